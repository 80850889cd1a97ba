// Test-time only (tests/las_js_reader_test.cc): reads a LAS file with an independent reader, the npm package
// @loaders.gl/las through @loaders.gl/core, and prints JSON of what it saw.
//
//   node read_las.mjs FILE.las [--max-points N]
//
// Two loaders of @loaders.gl/las are run:
//   "laz-rs"   LAZRsLoader  (LAS 1.0-1.4, point formats 0-10, the 64-bit count of LAS 1.4)
//   "laz-perf" LASLoader    (the package's default export; formats 0-3 and the legacy 32-bit count only)
// For each: the point count, header fields, the bounding box of the decoded positions, and every point's x y z
// (fp64) and 8-bit RGB (colorDepth 16, i.e. the stored 16-bit value / 256) -- or every k-th point when the file
// has more than N points (k = ceil(count / N), "stride" in the output).
// loaders.gl exposes neither the point source ID nor the VLRs, so "raw" holds what this script reads itself with
// a DataView at the positions the loader reported (point offset and record length): point source IDs of the same
// points, the global encoding, the VLR list, the WKT text and the GeoKeys. Errors of a loader are reported, not
// thrown. Exit code 0 unless the file cannot be read at all.
import { readFileSync } from 'node:fs';
import { parse } from '@loaders.gl/core';
import { LASLoader, LAZRsLoader } from '@loaders.gl/las';

// laz-rs-wasm fetches its .wasm next to its module (a file: URL); Node's fetch has no file: scheme.
const realFetch = globalThis.fetch;
globalThis.fetch = async (url, ...rest) => {
  const text = String(url);
  if (text.startsWith('file:')) {
    return new Response(readFileSync(new URL(text)), { headers: { 'Content-Type': 'application/wasm' } });
  }
  return realFetch(url, ...rest);
};

const args = process.argv.slice(2);
if (args.length < 1) {
  console.error('usage: node read_las.mjs FILE.las [--max-points N]');
  process.exit(2);
}
const file = args[0];
let maxPoints = 50000;
const mi = args.indexOf('--max-points');
if (mi >= 0) maxPoints = Number(args[mi + 1]);

const bytes = readFileSync(file);
const arrayBuffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const view = new DataView(arrayBuffer);

function stride(count) {
  return Math.max(1, Math.ceil(count / maxPoints));
}

async function runLoader(loader) {
  try {
    const mesh = await parse(arrayBuffer, loader, {
      worker: false,
      las: { shape: 'mesh', fp64: true, skip: 1, colorDepth: 16 },
    });
    const h = mesh.loaderData;
    const count = mesh.header.vertexCount;
    const pos = mesh.attributes.POSITION.value;
    const col = mesh.attributes.COLOR_0 ? mesh.attributes.COLOR_0.value : null;
    const k = stride(count);
    const x = [], y = [], z = [], rgb = [];
    for (let i = 0; i < count; i += k) {
      x.push(pos[3 * i]);
      y.push(pos[3 * i + 1]);
      z.push(pos[3 * i + 2]);
      if (col) rgb.push([col[4 * i], col[4 * i + 1], col[4 * i + 2]]);
    }
    return {
      count,
      version: h.versionAsString ?? null,
      point_format: h.pointsFormatId,
      points_offset: h.pointsOffset,
      record_length: h.pointsStructSize,
      header_count: h.pointsCount,
      scale: h.scale,
      offset: h.offset,
      header_min: h.mins,
      header_max: h.maxs,
      bounding_box: mesh.header.boundingBox ?? null,
      has_color: Boolean(col),
      stride: k,
      x, y, z, rgb,
    };
  } catch (e) {
    return { error: String(e && e.message ? e.message : e) };
  }
}

function padded(offset, size) {
  let s = '';
  for (let i = 0; i < size; i++) {
    const c = view.getUint8(offset + i);
    if (c === 0) break;
    s += String.fromCharCode(c);
  }
  return s;
}

// What the script reads itself: VLRs, CRS records, point source IDs.
function readRaw(pointsOffset, recordLength, pointFormat, count) {
  const raw = { global_encoding: view.getUint16(6, true), vlrs: [], wkt: null, geokeys: null, geo_ascii: null };
  const headerSize = view.getUint16(94, true);
  const numVlrs = view.getUint32(100, true);
  let at = headerSize;
  for (let i = 0; i < numVlrs && at + 54 <= pointsOffset; i++) {
    const userId = padded(at + 2, 16);
    const recordId = view.getUint16(at + 18, true);
    const length = view.getUint16(at + 20, true);
    const data = new Uint8Array(arrayBuffer, at + 54, length);
    raw.vlrs.push({ user_id: userId, record_id: recordId, length, description: padded(at + 22, 32) });
    if (userId === 'LASF_Projection' && recordId === 2112) {
      let end = data.indexOf(0);
      if (end < 0) end = data.length;
      raw.wkt = Buffer.from(data.subarray(0, end)).toString('utf8');
    }
    if (userId === 'LASF_Projection' && recordId === 34735) {
      raw.geokeys = [];
      for (let j = 0; j + 1 < length; j += 2) raw.geokeys.push(view.getUint16(at + 54 + j, true));
    }
    if (userId === 'LASF_Projection' && recordId === 34737) {
      raw.geo_ascii = Buffer.from(data).toString('latin1');
    }
    at += 54 + length;
  }
  raw.point_source_id = null;
  if (view.getUint8(104) & 0x80) return raw;  // LAZ: the records are compressed (decode_laz.mjs checks them)
  const idOffset = pointFormat >= 6 ? 20 : 18;
  const k = stride(count);
  raw.point_source_id = [];
  for (let i = 0; i < count; i += k) {
    raw.point_source_id.push(view.getUint16(pointsOffset + i * recordLength + idOffset, true));
  }
  return raw;
}

const out = { file, max_points: maxPoints, loaders: {} };
out.loaders['laz-rs'] = await runLoader(LAZRsLoader);
out.loaders['laz-perf'] = await runLoader(LASLoader);
const ref = out.loaders['laz-rs'];
if (!ref.error) {
  out.raw = readRaw(ref.points_offset, ref.record_length, ref.point_format, ref.count);
}
process.stdout.write(JSON.stringify(out) + '\n');
