// Test-time only: laz-rs compiled to WASM as shipped inside @loaders.gl/las (the decoder behind its LAZRsLoader;
// not among the package's exports, so loaded by file URL from the installed package). Used by decode_laz.mjs and
// read_copc.mjs.
//
// This build's WasmLasZipDecompressor reads LAZ files with fixed-size chunks only (a COPC file, whose chunks vary
// in size, fails at its first chunk's end: "Error decompressing points!"), so decodeChunk decodes one chunk of
// any file by wrapping its bytes, unchanged, as a one-chunk LAZ file of that chunk's point count: the file's own
// header and VLRs, the count and the laszip VLR's chunk size set to the chunk's points, no EVLRs.
import { readFileSync } from 'node:fs';

const dir = new URL('./node_modules/@loaders.gl/las/dist/libs/laz-rs-wasm/', import.meta.url);
const mod = await import(new URL('laz_rs_wasm.js', dir));
mod.initSync({ module: readFileSync(new URL('laz_rs_wasm_bg.wasm', dir)) });

// The `count` point records (count x recordLength bytes) of the LAZ file `bytes`.
export function decodeFile(bytes, count, recordLength) {
  const decompressor = new mod.WasmLasZipDecompressor(new Uint8Array(bytes));
  try {
    const out = new Uint8Array(count * recordLength);
    if (count > 0) decompressor.decompress_many(out);
    return out;
  } finally {
    try {
      decompressor.free();
    } catch {
      // a decompressor whose last call failed stays borrowed; the error above is the one to report
    }
  }
}

// The `points` records of the chunk of `bytes` (a LAZ file) at [start, start + size).
export function decodeChunk(bytes, start, size, points) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const pointOffset = view.getUint32(96, true);
  const recordLength = view.getUint16(105, true);
  let at = view.getUint16(94, true);
  let laszip = -1;
  for (let i = 0, n = view.getUint32(100, true); i < n; i++) {
    const user = Buffer.from(bytes.subarray(at + 2, at + 18)).toString('latin1').replace(/\0.*$/s, '');
    if (user === 'laszip encoded') laszip = at + 54;
    at += 54 + view.getUint16(at + 20, true);
  }
  if (laszip < 0) throw new Error('no laszip VLR');
  const file = Buffer.alloc(pointOffset + 8 + size);
  file.set(bytes.subarray(0, pointOffset), 0);
  const w = new DataView(file.buffer, file.byteOffset, file.byteLength);
  w.setUint32(107, 0, true);                       // legacy count
  w.setBigUint64(247, BigInt(points), true);       // 64-bit count
  w.setBigUint64(235, 0n, true);                   // no EVLRs
  w.setUint32(243, 0, true);
  w.setUint32(laszip + 12, points, true);          // chunk size: this chunk's points
  w.setBigInt64(pointOffset, -1n, true);           // no chunk table (one chunk, read in order)
  file.set(bytes.subarray(start, start + size), pointOffset + 8);
  return decodeFile(file, points, recordLength);
}
