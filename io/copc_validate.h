#pragma once
// The COPC 1.0 rules `sacfuse validate` checks (io/las_validate.h) for a file whose first VLR is the COPC info VLR
// or that is named *.copc.laz, reading the bytes itself; each finding is "COPC: <what is wrong>":
//   - LAS 1.4, point format 6, 7 or 8, compressed; the info VLR first (offset 375), 160 bytes, reserved words 0, a
//     cube of positive size and a positive spacing; the "laszip encoded" VLR with variable chunk sizes
//   - exactly one hierarchy EVLR (copc/1000); the root page (from the info VLR) and every child page inside it, a
//     whole number of 32-byte entries, none referenced twice, no key listed twice, every key valid
//   - the root node present and every other node's parent present (every node reachable from the root)
//   - every node with points: its offset and size inside the point data (after the chunk table offset, before the
//     chunk table), exactly one chunk of the chunk table, with the chunk table's point count; no chunk that no
//     node addresses; the nodes' counts add up to the header's count
//   - the header's bounds inside the cube
//   - every node's chunk decodes to its point count, every point inside its node's cube (closed bounds, as
//     COPC readers compute them) and its GPS time inside the info VLR's range
// Bounds are compared with half a scale step of slack: a point on a node's face may round either way. (sacfuse's
// own files keep every point strictly inside its node: io/copc_octree.h.) PDAL's and laspy's COPC test files
// (../shared/research-data/las_compat) pass these rules.
#include <string>
#include <vector>

namespace sacfuse {

// Findings for `path` (empty when it is not COPC, or passes every rule above).
std::vector<std::string> ValidateCopc(const std::string& path);
// "COPC 1.0, 120 nodes in 6 levels, 2 hierarchy pages" for a COPC file whose hierarchy can be walked, else "".
std::string DescribeCopc(const std::string& path);

}  // namespace sacfuse
