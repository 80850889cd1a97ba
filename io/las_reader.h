#pragma once
// Streaming reader for LAS 1.0-1.4, point formats 0-10, uncompressed or LAZ (LASzip-compressed: point formats 0-3
// point-wise and 6-8 layered, see io/laz_point_reader.h; detected by the compression bit of the point format or the
// "laszip encoded" VLR, not by the file name). The laszip VLR is not listed in header().vlrs, and
// header().point_format is the format without the compression bits.
// Validates the header against the file (signature, header size, offsets, record length vs format,
// offset + count x length <= file size) and throws sacfuse::InputError naming the file on any inconsistency.
// Tolerated, as laspy/LASlib do: extra header bytes, extra bytes per record (skipped), an overstated VLR count
// when the VLRs read end exactly at the point data, and in LAS 1.4 a 64-bit count of 0 with a non-zero legacy
// count (the legacy one is used; otherwise the 64-bit count wins). LAS 1.4 EVLRs are returned in header().vlrs
// (payloads over 64 MiB, i.e. waveform data, are left empty).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/las_types.h"

namespace sacfuse {

class LasReader {
 public:
  explicit LasReader(const std::string& path);
  ~LasReader();
  LasReader(const LasReader&) = delete;
  LasReader& operator=(const LasReader&) = delete;

  const LasHeader& header() const;
  // Reads up to max_count further points into out (resized); returns how many were read (0 at the end).
  size_t Read(std::vector<LasPoint>* out, size_t max_count);
  // Back to the first point.
  void Rewind();

  // LAZ files: the payload of the "laszip encoded" VLR (empty for LAS files).
  const std::vector<uint8_t>& laszip_vlr() const;
  // LAZ files: the next chunk as stored, undecoded, and its point count, when the reading stands at a chunk's
  // start; Read continues after it. False for LAS files, at the end, or mid-chunk. (LasWriter::AppendLaz.)
  bool ReadStoredChunk(std::vector<uint8_t>* bytes, uint64_t* points);
  // LAZ files: passes over the next `chunks` chunks without reading or decoding them (as ReadStoredChunk would
  // read them); false, having moved nothing, under ReadStoredChunk's conditions or when fewer chunks are left.
  bool SkipStoredChunks(uint64_t chunks);
  // The path the reader was opened with.
  const std::string& path() const;
  // LAZ files: the file offset just past the chunk table, whose coded length is that of its entries coded again
  // (0 for LAS files). A file shorter than this lost the end of its table (which the decoder, like LASzip's,
  // fills with zeros), what `sacfuse validate` reports.
  uint64_t laz_chunk_table_end() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Convenience for small files and tests: every point of a file.
std::vector<LasPoint> ReadAllLasPoints(const std::string& path, LasHeader* header = nullptr);

}  // namespace sacfuse
