// Test-time only (tests/las_js_reader_test.cc): reads a COPC file with the npm package `copc` (copc.js, the COPC
// reader of viewers built on laz-perf), the way a streaming viewer does: the info VLR, then the hierarchy page by
// page from the root page, then every node's chunk alone, decompressed by laz-perf's ChunkDecoder.
//
//   node read_copc.mjs FILE.copc.laz OUT_PREFIX
//
// The same chunks are decoded by laz-rs too (tests/las_js/laz_rs.mjs decodeChunk: each node's chunk as stored, at
// the offset and size the hierarchy gives).
//
// Writes OUT_PREFIX.copc.bin (the point records of every node, node after node, as copc.js decoded them) and
// OUT_PREFIX.laz-rs-nodes.bin (the same nodes decoded by laz-rs), and prints JSON:
// header count, point format and record length, the info VLR (cube, spacing, GPS time range), the WKT, the pages
// walked, the nodes (key, point count, points outside the node's cube as copc.js computes it with
// Bounds.stepTo), points per level, and {error} when the file cannot be read.
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { decodeChunk } from './laz_rs.mjs';

const require = createRequire(import.meta.url);
const { Copc, Bounds, Key, Las } = require('copc');

const [file, prefix] = process.argv.slice(2);
if (!file || !prefix) {
  console.error('usage: node read_copc.mjs FILE.copc.laz OUT_PREFIX');
  process.exit(2);
}

async function read() {
  const copc = await Copc.create(file);
  const { header, info } = copc;
  const nodes = {};
  let pages = 0;
  const pending = [info.rootHierarchyPage];
  while (pending.length > 0) {
    const page = pending.pop();
    const h = await Copc.loadHierarchyPage(file, page);
    pages += 1;
    for (const [key, node] of Object.entries(h.nodes)) {
      if (key in nodes) throw new Error(`node ${key} listed twice`);
      nodes[key] = node;
    }
    for (const child of Object.values(h.pages)) pending.push(child);
  }
  const buffers = [];
  const lazRsBuffers = [];
  const bytes = readFileSync(file);
  const out = [];
  const perLevel = {};
  let points = 0;
  const keys = Object.keys(nodes).sort((a, b) => Key.compare(Key.parse(a), Key.parse(b)));
  for (const key of keys) {
    const node = nodes[key];
    const entry = { key, point_count: node.pointCount, outside: 0 };
    if (node.pointCount > 0) {
      const buffer = await Copc.loadPointDataBuffer(file, header, node);
      const view = Las.View.create(buffer, header, copc.eb);
      const [x, y, z] = ['X', 'Y', 'Z'].map((d) => view.getter(d));
      const [minx, miny, minz, maxx, maxy, maxz] = Bounds.stepTo(info.cube, Key.parse(key));
      for (let i = 0; i < view.pointCount; i++) {
        const px = x(i), py = y(i), pz = z(i);
        if (px < minx || px > maxx || py < miny || py > maxy || pz < minz || pz > maxz) entry.outside += 1;
      }
      buffers.push(Buffer.from(buffer.buffer, buffer.byteOffset, buffer.byteLength));
      const records = decodeChunk(bytes, node.pointDataOffset, node.pointDataLength, node.pointCount);
      lazRsBuffers.push(Buffer.from(records.buffer, records.byteOffset, records.byteLength));
      points += view.pointCount;
      const level = Key.parse(key)[0];
      perLevel[level] = (perLevel[level] || 0) + view.pointCount;
    }
    out.push(entry);
  }
  writeFileSync(`${prefix}.copc.bin`, Buffer.concat(buffers));
  writeFileSync(`${prefix}.laz-rs-nodes.bin`, Buffer.concat(lazRsBuffers));
  return {
    count: header.pointCount,
    point_format: header.pointDataRecordFormat,
    record_length: header.pointDataRecordLength,
    cube: info.cube,
    spacing: info.spacing,
    gps_time_range: info.gpsTimeRange,
    wkt: copc.wkt ?? null,
    pages,
    points_in_nodes: points,
    points_per_level: perLevel,
    nodes: out,
  };
}

let result;
try {
  result = await read();
} catch (e) {
  result = { error: String(e && e.message ? e.message : e) };
}
process.stdout.write(JSON.stringify(result) + '\n');
