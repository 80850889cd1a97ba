#include "io/colmap_consistency_graph.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

namespace sacfuse {
namespace {

static_assert(sizeof(int32_t) == 4, "int32 expected");

bool ParseHeader(const std::string& bytes, size_t* data_offset, int* width, int* height) {
  long fields[3] = {0, 0, 0};
  size_t pos = 0;
  for (int f = 0; f < 3; ++f) {
    size_t start = pos;
    while (pos < bytes.size() && bytes[pos] >= '0' && bytes[pos] <= '9') ++pos;
    if (pos == start || pos >= bytes.size() || bytes[pos] != '&' || pos - start > 9) return false;
    fields[f] = std::stol(bytes.substr(start, pos - start));
    ++pos;
  }
  *width = static_cast<int>(fields[0]);
  *height = static_cast<int>(fields[1]);
  *data_offset = pos;
  return fields[0] > 0 && fields[1] > 0 && fields[2] == 1;
}

int32_t ReadLe32(const char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);  // the host is little-endian (checked at build time by COLMAP-array code as well)
  return static_cast<int32_t>(v);
}

}  // namespace

ConsistencyGraph ReadColmapConsistencyGraph(const std::string& path) {
  std::ifstream in = OpenInputStream(path, "consistency graph");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ConsistencyGraph graph;
  size_t offset = 0;
  if (!ParseHeader(bytes, &offset, &graph.width, &graph.height)) {
    throw InputError(path, "malformed consistency-graph header (expected \"W&H&1&\")");
  }
  if ((bytes.size() - offset) % 4 != 0) throw InputError(path, "consistency-graph data is not a whole number of int32");
  const size_t n = (bytes.size() - offset) / 4;
  const char* data = bytes.data() + offset;
  const size_t pixels = static_cast<size_t>(graph.width) * graph.height;
  std::vector<uint32_t> counts(pixels, 0);
  std::vector<std::pair<size_t, size_t>> runs;  // (pixel, first value index)
  for (size_t i = 0; i < n;) {
    if (i + 3 > n) throw InputError(path, "consistency graph truncated inside a pixel record");
    const int32_t col = ReadLe32(data + 4 * i), row = ReadLe32(data + 4 * (i + 1)), num = ReadLe32(data + 4 * (i + 2));
    if (num < 0 || i + 3 + static_cast<size_t>(num) > n) throw InputError(path, "consistency graph record runs past the end");
    if (col < 0 || row < 0 || col >= graph.width || row >= graph.height) {
      throw InputError(path, "consistency graph pixel (" + std::to_string(col) + ", " + std::to_string(row) +
                                 ") outside " + std::to_string(graph.width) + "x" + std::to_string(graph.height));
    }
    const size_t pixel = static_cast<size_t>(row) * graph.width + col;
    counts[pixel] += num;
    runs.emplace_back(pixel, i);
    i += 3 + num;
  }
  graph.pixel_offsets.resize(pixels + 1, 0);
  for (size_t p = 0; p < pixels; ++p) graph.pixel_offsets[p + 1] = graph.pixel_offsets[p] + counts[p];
  graph.view_indices.resize(graph.pixel_offsets.back());
  std::vector<uint32_t> fill(graph.pixel_offsets.begin(), graph.pixel_offsets.end() - 1);
  for (const auto& [pixel, i] : runs) {
    const int32_t num = ReadLe32(data + 4 * (i + 2));
    for (int32_t k = 0; k < num; ++k) {
      const int32_t idx = ReadLe32(data + 4 * (i + 3 + k));
      if (idx < 0) throw InputError(path, "negative image index in the consistency graph");
      graph.view_indices[fill[pixel]++] = static_cast<uint32_t>(idx);
    }
  }
  return graph;
}

void WriteColmapConsistencyGraph(const std::string& path, const ConsistencyGraph& graph) {
  std::string bytes = std::to_string(graph.width) + "&" + std::to_string(graph.height) + "&1&";
  size_t records = 0;
  for (size_t p = 0; p + 1 < graph.pixel_offsets.size(); ++p) {
    records += graph.pixel_offsets[p + 1] > graph.pixel_offsets[p] ? 1 : 0;
  }
  bytes.reserve(bytes.size() + 4 * (3 * records + graph.view_indices.size()));
  auto put = [&bytes](int32_t v) {
    char b[4];
    std::memcpy(b, &v, 4);
    bytes.append(b, 4);
  };
  for (int row = 0; row < graph.height; ++row) {
    for (int col = 0; col < graph.width; ++col) {
      const auto [first, last] = graph.At(row, col);
      if (first == last) continue;
      put(col);
      put(row);
      put(static_cast<int32_t>(last - first));
      for (const uint32_t* it = first; it != last; ++it) put(static_cast<int32_t>(*it));
    }
  }
  WriteFileAtomically(path, bytes);
}

}  // namespace sacfuse
