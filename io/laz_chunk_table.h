#pragma once
// The LAZ chunk table (LASzip compressed data format): stored after the last chunk, its position written in the
// 8 bytes that open the point data. Layout: u32 version (0), u32 number of chunks, then one arithmetic-coded
// stream in which each chunk's byte size (and, for variable-size chunks, its point count) is coded with the
// integer compressor against the previous chunk's. Private to io/.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sacfuse::laz {

struct ChunkEntry {
  uint32_t points = 0;  // coded only for variable-size chunks
  uint32_t bytes = 0;
};

constexpr size_t kChunkTableHeaderSize = 8;

// The whole table (header and stream).
std::vector<uint8_t> EncodeChunkTable(const std::vector<ChunkEntry>& chunks, bool variable_size);
// The entries from the stream after the header (`count` from the header); fixed-size tables leave points 0.
// Throws laz::DataError on corrupt data.
std::vector<ChunkEntry> DecodeChunkTable(const uint8_t* data, size_t size, uint32_t count, bool variable_size);

}  // namespace sacfuse::laz
