// Test-time only (tests/las_js_laz_test.cc): decodes a LAZ file with two independent LASzip implementations and
// writes the uncompressed point records each produced, so that the test can compare them byte for byte with the
// point data of the LAS file written from the same points.
//
//   node decode_laz.mjs FILE.laz OUT_PREFIX
//
// "laz-perf": the npm package laz-perf (LASzip in C++ compiled to WASM), its LASZip reader.
// "laz-rs":   laz-rs compiled to WASM as shipped inside @loaders.gl/las (the decoder behind its LAZRsLoader),
//             its WasmLasZipDecompressor (tests/las_js/laz_rs.mjs; fixed-size chunks only, so it fails on COPC).
// Each writes OUT_PREFIX.<decoder>.bin (count x record length bytes) and reports {count, record_length,
// point_format} or {error} in the JSON printed on stdout. Exit code 0 unless the file cannot be read at all.
import { readFileSync, writeFileSync } from 'node:fs';
import lazPerfPackage from 'laz-perf';
import { decodeFile } from './laz_rs.mjs';

const [file, prefix] = process.argv.slice(2);
if (!file || !prefix) {
  console.error('usage: node decode_laz.mjs FILE.laz OUT_PREFIX');
  process.exit(2);
}
const bytes = readFileSync(file);
const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
const minor = view.getUint8(25);
const recordLength = view.getUint16(105, true);
const pointFormat = view.getUint8(104) & 0x3f;
const count = minor >= 4 ? Number(view.getBigUint64(247, true)) || view.getUint32(107, true) : view.getUint32(107, true);

async function lazPerf() {
  const LazPerf = await lazPerfPackage.createLazPerf();
  const filePtr = LazPerf._malloc(bytes.length);
  LazPerf.HEAPU8.set(bytes, filePtr);
  const reader = new LazPerf.LASZip();
  try {
    reader.open(filePtr, bytes.length);
    const n = reader.getCount();
    const length = reader.getPointLength();
    const out = Buffer.alloc(n * length);
    const pointPtr = LazPerf._malloc(length);
    for (let i = 0; i < n; i++) {
      reader.getPoint(pointPtr);
      out.set(LazPerf.HEAPU8.subarray(pointPtr, pointPtr + length), i * length);
    }
    LazPerf._free(pointPtr);
    writeFileSync(`${prefix}.laz-perf.bin`, out);
    return { count: n, record_length: length, point_format: reader.getPointFormat() };
  } finally {
    reader.delete();
    LazPerf._free(filePtr);
  }
}

async function lazRs() {
  const out = decodeFile(bytes, count, recordLength);
  writeFileSync(`${prefix}.laz-rs.bin`, out);
  return { count, record_length: recordLength, point_format: pointFormat };
}

const result = { file, decoders: {} };
for (const [name, run] of [['laz-perf', lazPerf], ['laz-rs', lazRs]]) {
  try {
    result.decoders[name] = await run();
  } catch (e) {
    result.decoders[name] = { error: String(e && e.message ? e.message : e) };
  }
}
process.stdout.write(JSON.stringify(result) + '\n');
