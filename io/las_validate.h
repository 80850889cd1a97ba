#pragma once
// A LAS validator checking what LAStools' lasvalidate checks (../shared/reference/jobs-and-las.md B8) that a
// writer can get wrong, reading the bytes itself (so it reports what LasReader would refuse, instead of
// throwing). Points are streamed in chunks: memory stays bounded for any file size.
//
// Each finding is one line "<rule>: <what is wrong>", rules:
//   file            cannot open / read, bad signature, version
//   header size     smaller than the version's header (227 / 235 / 375)
//   offset to point data   smaller than header + VLRs (a VLR flows into the points), or beyond the file
//   point format    not allowed for the version (1.0-1.1: 0-1, 1.2: 0-3, 1.3: 0-5, 1.4: 0-10)
//   record length   smaller than the format's fields; extra bytes before 1.4 or without a LASF_Spec/4 record
//   file size       != offset to point data + count x record length (+ EVLRs / waveform data): truncated or
//                   trailing bytes
//   legacy counts   LAS 1.4: legacy count and points by return must be 0 for PDRF >= 6 (or counts > 2^32-1),
//                   else equal to the 64-bit ones
//   points by return   the header's array differs from the counted return numbers (includes sum != count)
//   zero points     a file before LAS 1.4 without points
//   bounds          header min/max vs the stored points' extent, beyond half a scale step (or min > max)
//   return numbers  return number 0, number of returns 0, return > number of returns, number of returns above
//                   the format's maximum (5 for PDRF 0-5, 15 for 6-10)
//   global encoding bits not defined for the version/format; WKT bit (4) set iff LAS 1.4 with a WKT record;
//                   GPS bit (0) clear while GPS times lie outside one week [0, 604800] s; waveform bits vs start
//   scale           not > 0 or not 10^k x {1, 0.5, 0.25}
//   offset          not finite or not a multiple of the scale ("translation fluff")
//   system identifier / generating software   not NUL-terminated and NUL-padded
//   creation date   not set (year 0), or in the future
//   CRS             GeoTIFF records in a PDRF 6-10 file, both GeoTIFF and WKT, several WKT records, malformed
//                   WKT or GeoKeys
//   COPC            for a COPC file (first VLR the COPC info VLR, or named *.copc.laz): its octree, hierarchy,
//                   chunks and nodes' points (io/copc_validate.h)
// A file without any CRS is not a finding (sacfuse writes none when config `crs` is empty).
#include <string>
#include <vector>

namespace sacfuse {

// Every finding for the file at `path`; empty when it passes every rule.
std::vector<std::string> ValidateLasFile(const std::string& path);

}  // namespace sacfuse
