#include "io/colmap_array.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

// COLMAP writes the floats with a raw native write on little-endian machines; we read them with memcpy, which
// is only a little-endian decode on a little-endian host. Big-endian hosts are not supported.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "sacfuse's COLMAP array I/O assumes a little-endian host");
static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559, "float must be IEEE-754 binary32");

namespace sacfuse {
namespace {

// Longest header we accept: three fields of at most 10 digits plus three '&'.
constexpr size_t kMaxHeaderBytes = 3 * 10 + 3;

std::string ShapeText(uint64_t w, uint64_t h, uint64_t c) {
  return std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(c);
}

std::string Quote(const std::string& bytes) {
  std::string out;
  for (const char ch : bytes) {
    const auto u = static_cast<unsigned char>(ch);
    if (u >= 0x20 && u < 0x7f) {
      out += ch;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\x%02x", u);
      out += buf;
    }
  }
  return "\"" + out + "\"";
}

void ReadExactly(std::ifstream& in, const std::string& path, char* dst, size_t bytes, uint64_t offset) {
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(dst, static_cast<std::streamsize>(bytes));
  if (!in || static_cast<size_t>(in.gcount()) != bytes) {
    throw InputError(path, "read of " + std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                               " failed (file truncated while reading?)");
  }
}

std::ifstream OpenForReading(const std::string& path) { return OpenInputStream(path, "dense array"); }

// Copies `rows` rows of one channel plane (row-major floats) into the interleaved raster starting at `row0`.
void ScatterPlane(const std::vector<float>& plane, int channel, int row0, int rows, Raster<float>* out) {
  const size_t n = static_cast<size_t>(rows) * out->width;
  const size_t base = static_cast<size_t>(row0) * out->width;
  if (out->channels == 1) {
    std::memcpy(out->data.data() + base, plane.data(), n * sizeof(float));
    return;
  }
  float* dst = out->data.data() + base * out->channels + channel;
  for (size_t i = 0; i < n; ++i) dst[i * out->channels] = plane[i];
}

// Columns [col_begin, col_begin + width) of each of `rows` (checked by the caller), every channel: row i of the
// result is rows[i]. One seek + read per row and channel; windows and row lists both read through here.
Raster<float> ReadRowSpans(const std::string& path, const ColmapArrayShape& shape, const std::vector<int>& rows,
                           int col_begin, int width) {
  Raster<float> out = Raster<float>::Uninitialized(width, static_cast<int>(rows.size()), shape.channels);  // all read
  std::ifstream in = OpenForReading(path);
  const uint64_t plane_floats = static_cast<uint64_t>(shape.width) * shape.height;
  std::vector<float> row(static_cast<size_t>(width));
  for (int c = 0; c < shape.channels; ++c) {
    for (size_t i = 0; i < rows.size(); ++i) {
      const uint64_t offset = shape.data_offset + (c * plane_floats + static_cast<uint64_t>(rows[i]) * shape.width +
                                                   static_cast<uint64_t>(col_begin)) * sizeof(float);
      ReadExactly(in, path, reinterpret_cast<char*>(row.data()), row.size() * sizeof(float), offset);
      ScatterPlane(row, c, static_cast<int>(i), 1, &out);
    }
  }
  return out;
}

}  // namespace

ColmapArrayShape ReadColmapArrayShape(const std::string& path) {
  std::ifstream in = OpenForReading(path);
  in.seekg(0, std::ios::end);
  const auto end = in.tellg();
  if (end < 0) throw InputError(path, "cannot determine the file size");
  const uint64_t file_size = static_cast<uint64_t>(end);
  in.seekg(0);
  std::string head(static_cast<size_t>(std::min<uint64_t>(file_size, kMaxHeaderBytes)), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  if (static_cast<size_t>(in.gcount()) != head.size()) throw InputError(path, "cannot read the dense array header");

  // Strict "W&H&C&": exactly three non-empty decimal fields, each terminated by '&'.
  uint64_t fields[3] = {0, 0, 0};
  size_t pos = 0;
  for (int f = 0; f < 3; ++f) {
    const size_t start = pos;
    while (pos < head.size() && head[pos] >= '0' && head[pos] <= '9') {
      if (pos - start >= 10) {
        throw InputError(path, "garbage dense array header " + Quote(head) + ": field " + std::to_string(f + 1) +
                                   " has too many digits");
      }
      fields[f] = fields[f] * 10 + static_cast<uint64_t>(head[pos] - '0');
      ++pos;
    }
    if (pos == start || pos >= head.size() || head[pos] != '&') {
      if (pos >= head.size() && file_size <= kMaxHeaderBytes) {
        throw InputError(path, "truncated dense array: the file (" + std::to_string(file_size) +
                                   " bytes) ends inside the header " + Quote(head) +
                                   " (expected \"W&H&C&\" then float32 data)");
      }
      throw InputError(path, "garbage dense array header " + Quote(head.substr(0, std::min<size_t>(pos + 1, head.size()))) +
                                 ": expected \"W&H&C&\" with three decimal fields, failed at field " +
                                 std::to_string(f + 1));
    }
    ++pos;  // '&'
  }
  const uint64_t w = fields[0], h = fields[1], c = fields[2];
  if (w == 0 || h == 0 || c == 0) {
    throw InputError(path, "invalid dense array header " + Quote(head.substr(0, pos)) + ": width " +
                               std::to_string(w) + ", height " + std::to_string(h) + ", channels " +
                               std::to_string(c) + " (all must be > 0)");
  }
  constexpr uint64_t kIntMax = static_cast<uint64_t>(std::numeric_limits<int>::max());
  if (w > kIntMax || h > kIntMax || c > kIntMax) {
    throw InputError(path, "invalid dense array header: shape " + ShapeText(w, h, c) + " is too large");
  }
  const uint64_t header_bytes = pos;
  // W*H*C*4 can exceed 64 bits for absurd headers (each field < 2^31).
  const unsigned __int128 expected_data = static_cast<unsigned __int128>(w * h) * c * 4;
  const unsigned __int128 expected_size = expected_data + header_bytes;
  if (expected_size != file_size) {
    // A fourth field ("W&H&C&X&") makes the size disagree; say so rather than just "mismatched". (Checked only
    // after the size test: the first data bytes may legitimately look like "5&".)
    if (pos < head.size() && head[pos] >= '0' && head[pos] <= '9') {
      size_t p = pos;
      while (p < head.size() && head[p] >= '0' && head[p] <= '9') ++p;
      if (p < head.size() && head[p] == '&') {
        throw InputError(path, "garbage dense array header " + Quote(head.substr(0, p + 1)) +
                                   ": more than 3 fields (expected \"W&H&C&\"); the file size (" +
                                   std::to_string(file_size) + " bytes) does not match a 3-field header either");
      }
    }
    const bool huge = expected_size > std::numeric_limits<uint64_t>::max();
    const std::string data_text = huge ? std::string("W*H*C*4") : std::to_string(static_cast<uint64_t>(expected_data));
    const std::string size_text = huge ? std::string("more than 2^64") : std::to_string(static_cast<uint64_t>(expected_size));
    throw InputError(path, std::string(expected_size > file_size ? "truncated" : "mismatched") +
                               " dense array: header " + Quote(head.substr(0, pos)) + " (" + ShapeText(w, h, c) +
                               " float32) needs " + std::to_string(header_bytes) + " + " + data_text + " = " +
                               size_text + " bytes but the file has " + std::to_string(file_size) + " bytes");
  }
  ColmapArrayShape shape;
  shape.width = static_cast<int>(w);
  shape.height = static_cast<int>(h);
  shape.channels = static_cast<int>(c);
  shape.data_offset = static_cast<size_t>(header_bytes);
  return shape;
}

Raster<float> ReadColmapArray(const std::string& path) {
  const ColmapArrayShape shape = ReadColmapArrayShape(path);
  return ReadColmapArrayRows(path, 0, shape.height);
}

Raster<float> ReadColmapArrayRows(const std::string& path, int row_begin, int row_end) {
  const ColmapArrayShape shape = ReadColmapArrayShape(path);
  if (row_begin < 0 || row_end < row_begin || row_end > shape.height) {
    throw InputError(path, "requested rows [" + std::to_string(row_begin) + ", " + std::to_string(row_end) +
                               ") are outside the array's " + std::to_string(shape.height) + " rows");
  }
  const int rows = row_end - row_begin;
  Raster<float> out = Raster<float>::Uninitialized(shape.width, rows, shape.channels);  // every value read below
  if (rows == 0) return out;
  std::ifstream in = OpenForReading(path);
  const uint64_t plane_floats = static_cast<uint64_t>(shape.width) * shape.height;
  // Read in row blocks of at most ~16 MB so a wide multi-channel window does not need a second full copy.
  const int rows_per_block = std::max(1, static_cast<int>((16u << 20) / (sizeof(float) * shape.width)));
  std::vector<float> plane;
  for (int c = 0; c < shape.channels; ++c) {
    for (int r0 = 0; r0 < rows; r0 += rows_per_block) {
      const int n_rows = std::min(rows_per_block, rows - r0);
      const size_t n = static_cast<size_t>(n_rows) * shape.width;
      const uint64_t offset = shape.data_offset +
                              (c * plane_floats + static_cast<uint64_t>(row_begin + r0) * shape.width) * sizeof(float);
      if (shape.channels == 1) {  // the plane is the raster: read in place
        float* dst = out.data.data() + static_cast<size_t>(r0) * shape.width;
        ReadExactly(in, path, reinterpret_cast<char*>(dst), n * sizeof(float), offset);
        continue;
      }
      plane.resize(n);
      ReadExactly(in, path, reinterpret_cast<char*>(plane.data()), n * sizeof(float), offset);
      ScatterPlane(plane, c, r0, n_rows, &out);
    }
  }
  return out;
}

Raster<float> ReadColmapArrayWindow(const std::string& path, const PixelWindow& window) {
  const ColmapArrayShape shape = ReadColmapArrayShape(path);
  if (!window.FitsIn(shape.width, shape.height)) {
    throw Error(path + ": window " + PixelWindowText(window) + " is not inside the array's " +
                std::to_string(shape.width) + "x" + std::to_string(shape.height) + " pixels");
  }
  std::vector<int> rows(static_cast<size_t>(window.height()));
  for (int r = 0; r < window.height(); ++r) rows[static_cast<size_t>(r)] = window.row_begin + r;
  return ReadRowSpans(path, shape, rows, window.col_begin, window.width());
}

Raster<float> ReadColmapArrayRowList(const std::string& path, const std::vector<int>& rows) {
  const ColmapArrayShape shape = ReadColmapArrayShape(path);
  for (const int r : rows) {
    if (r < 0 || r >= shape.height) {
      throw Error(path + ": row " + std::to_string(r) + " is outside the array's " + std::to_string(shape.height) +
                  " rows");
    }
  }
  return ReadRowSpans(path, shape, rows, 0, shape.width);
}

void WriteColmapArray(const std::string& path, const Raster<float>& raster) {
  if (raster.width <= 0 || raster.height <= 0 || raster.channels <= 0) {
    throw Error(path + ": cannot write an empty dense array (" + std::to_string(raster.width) + "x" +
                std::to_string(raster.height) + "x" + std::to_string(raster.channels) + ")");
  }
  const size_t n_pixels = raster.num_pixels();
  if (raster.data.size() != n_pixels * raster.channels) {
    throw Error(path + ": raster data size " + std::to_string(raster.data.size()) + " does not match " +
                std::to_string(raster.width) + "x" + std::to_string(raster.height) + "x" +
                std::to_string(raster.channels));
  }
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string tmp = TemporaryPathFor(path);
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) throw Error(path + ": cannot create " + tmp + ": " + std::strerror(errno));
  const std::string header = std::to_string(raster.width) + "&" + std::to_string(raster.height) + "&" +
                             std::to_string(raster.channels) + "&";
  bool ok = std::fwrite(header.data(), 1, header.size(), f) == header.size();
  if (raster.channels == 1) {
    ok = ok && std::fwrite(raster.data.data(), sizeof(float), n_pixels, f) == n_pixels;
  } else {
    // Interleaved -> planar, through a bounded buffer.
    constexpr size_t kChunk = 1 << 20;
    std::vector<float> buffer(std::min(kChunk, n_pixels));
    for (int c = 0; ok && c < raster.channels; ++c) {
      for (size_t start = 0; ok && start < n_pixels; start += kChunk) {
        const size_t n = std::min(kChunk, n_pixels - start);
        for (size_t i = 0; i < n; ++i) buffer[i] = raster.data[(start + i) * raster.channels + c];
        ok = std::fwrite(buffer.data(), sizeof(float), n, f) == n;
      }
    }
  }
  CloseAndCommitTemporaryFile(f, ok, tmp, path);
}

}  // namespace sacfuse
