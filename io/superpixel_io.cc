#include "io/superpixel_io.h"

#include <sys/types.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/error.h"
#include "io/atomic_file.h"

namespace sacfuse {
namespace {

constexpr char kMagic[8] = {'S', 'A', 'C', 'S', 'P', 'X', '0', '1'};
constexpr uint64_t kHeaderBytes = 32;
constexpr uint64_t kClusterBytes = 20;

bool HostIsLittleEndian() {
  const uint32_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

void PutU32(unsigned char* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void PutU64(unsigned char* p, uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void PutF32(unsigned char* p, float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, 4);
  PutU32(p, bits);
}
uint32_t GetU32(const unsigned char* p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(p[i]) << (8 * i);
  return v;
}
uint64_t GetU64(const unsigned char* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(p[i]) << (8 * i);
  return v;
}
float GetF32(const unsigned char* p) {
  const uint32_t bits = GetU32(p);
  float v;
  std::memcpy(&v, &bits, 4);
  return v;
}

// Labels are stored little-endian; on big-endian hosts they are swapped in place (before writing / after
// reading).
void SwapLabelsIfBigEndian(int32_t* labels, size_t n) {
  if (HostIsLittleEndian()) return;
  for (size_t i = 0; i < n; ++i) {
    unsigned char b[4];
    PutU32(b, static_cast<uint32_t>(labels[i]));
    std::memcpy(&labels[i], b, 4);
  }
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// An open superpixel file with a validated header.
struct OpenFile {
  File file;
  SuperpixelFileInfo info;
};

void ReadExactly(std::FILE* f, const std::string& path, uint64_t offset, void* data, size_t bytes, const char* what) {
  if (bytes == 0) return;
  if (::fseeko(f, static_cast<off_t>(offset), SEEK_SET) != 0 || std::fread(data, 1, bytes, f) != bytes) {
    throw InputError(path, std::string("cannot read ") + what + " (truncated or unreadable file)");
  }
}

OpenFile Open(const std::string& path) {
  OpenFile open;
  open.file.reset(std::fopen(path.c_str(), "rb"));
  if (!open.file) throw InputError(path, std::string("cannot open superpixel file: ") + std::strerror(errno));
  std::FILE* f = open.file.get();
  if (::fseeko(f, 0, SEEK_END) != 0) throw InputError(path, "cannot seek in superpixel file");
  const off_t end = ::ftello(f);
  if (end < 0) throw InputError(path, "cannot determine the file size");
  const auto size = static_cast<uint64_t>(end);
  if (size < kHeaderBytes) {
    throw InputError(path, "too short for a superpixel file header (" + std::to_string(size) + " bytes)");
  }
  unsigned char header[kHeaderBytes];
  ReadExactly(f, path, 0, header, kHeaderBytes, "the header");
  if (std::memcmp(header, kMagic, sizeof(kMagic)) != 0) {
    throw InputError(path, "not a superpixel file (magic is not SACSPX01)");
  }
  const uint32_t width = GetU32(header + 8);
  const uint32_t height = GetU32(header + 12);
  const uint64_t clusters = GetU64(header + 16);
  const uint64_t hash = GetU64(header + 24);
  if (width > static_cast<uint32_t>(INT_MAX) || height > static_cast<uint32_t>(INT_MAX) ||
      (width == 0) != (height == 0)) {
    throw InputError(path, "invalid raster size " + std::to_string(width) + "x" + std::to_string(height));
  }
  const uint64_t pixels = static_cast<uint64_t>(width) * height;
  const bool counts_plausible = pixels <= size / 4 && clusters <= size / kClusterBytes;
  if (!counts_plausible || kHeaderBytes + pixels * 4 + clusters * kClusterBytes != size) {
    throw InputError(path, "file size " + std::to_string(size) + " bytes does not match " + std::to_string(width) +
                               "x" + std::to_string(height) + " labels and " + std::to_string(clusters) +
                               " clusters (truncated or corrupt)");
  }
  if (clusters > static_cast<uint64_t>(INT32_MAX) || clusters > pixels || (pixels > 0 && clusters == 0)) {
    throw InputError(path, "invalid cluster count " + std::to_string(clusters) + " for " + std::to_string(pixels) +
                               " pixels");
  }
  open.info.width = static_cast<int>(width);
  open.info.height = static_cast<int>(height);
  open.info.num_clusters = clusters;
  open.info.options_hash = hash;
  return open;
}

std::vector<SuperpixelCluster> ReadClusterTable(const OpenFile& open, const std::string& path) {
  const SuperpixelFileInfo& info = open.info;
  const uint64_t pixels = static_cast<uint64_t>(info.width) * info.height;
  std::vector<unsigned char> raw(info.num_clusters * kClusterBytes);
  ReadExactly(open.file.get(), path, kHeaderBytes + pixels * 4, raw.data(), raw.size(), "the cluster table");
  std::vector<SuperpixelCluster> clusters(info.num_clusters);
  uint64_t total = 0;
  for (size_t i = 0; i < clusters.size(); ++i) {
    const unsigned char* p = raw.data() + i * kClusterBytes;
    SuperpixelCluster& c = clusters[i];
    c.centroid_col = GetF32(p);
    c.centroid_row = GetF32(p + 4);
    c.depth_m = GetF32(p + 8);
    c.pixel_count = GetU32(p + 12);
    c.valid_count = GetU32(p + 16);
    const bool ok = std::isfinite(c.centroid_col) && std::isfinite(c.centroid_row) && c.centroid_col >= 0.0f &&
                    c.centroid_row >= 0.0f && c.centroid_col <= info.width && c.centroid_row <= info.height &&
                    std::isfinite(c.depth_m) && c.depth_m >= 0.0f && c.pixel_count > 0 &&
                    c.valid_count <= c.pixel_count;
    if (!ok) throw InputError(path, "cluster " + std::to_string(i) + " has invalid values (corrupt cluster table)");
    total += c.pixel_count;
  }
  if (total != pixels) {
    throw InputError(path, "cluster pixel counts sum to " + std::to_string(total) + ", not " + std::to_string(pixels));
  }
  return clusters;
}

// Reads rows [row_begin, row_end) into map->labels and range-checks them.
void ReadLabelRows(const OpenFile& open, const std::string& path, int row_begin, int row_end, SuperpixelMap* map) {
  const uint64_t width = static_cast<uint64_t>(open.info.width);
  const size_t count = static_cast<size_t>(width * static_cast<uint64_t>(row_end - row_begin));
  map->labels.resize(count);
  ReadExactly(open.file.get(), path, kHeaderBytes + static_cast<uint64_t>(row_begin) * width * 4, map->labels.data(),
              count * 4, "the label rows");
  SwapLabelsIfBigEndian(map->labels.data(), count);
  const auto n = static_cast<int64_t>(open.info.num_clusters);
  for (size_t i = 0; i < count; ++i) {
    const int32_t label = map->labels[i];
    if (label < 0 || label >= n) {
      throw InputError(path, "label " + std::to_string(label) + " at row " +
                                 std::to_string(row_begin + static_cast<int64_t>(i / width)) + ", col " +
                                 std::to_string(i % width) + " is outside [0, " + std::to_string(n) + ")");
    }
  }
}

void WriteAll(std::FILE* f, const void* data, size_t bytes, const std::string& path, const std::string& tmp) {
  if (bytes > 0 && std::fwrite(data, 1, bytes, f) != bytes) {
    throw Error(path + ": cannot write " + tmp + ": " + std::strerror(errno));
  }
}

}  // namespace

void WriteSuperpixels(const std::string& path, const SuperpixelMap& map, uint64_t options_hash) {
  if (map.width < 0 || map.height < 0 || (map.width == 0) != (map.height == 0) ||
      map.labels.size() != static_cast<size_t>(map.width) * static_cast<size_t>(map.height)) {
    throw Error(path + ": WriteSuperpixels: labels do not match " + std::to_string(map.width) + "x" +
                std::to_string(map.height));
  }
  if (map.clusters.size() > static_cast<size_t>(INT32_MAX)) throw Error(path + ": WriteSuperpixels: too many clusters");
  const auto n = static_cast<int64_t>(map.clusters.size());
  for (size_t i = 0; i < map.labels.size(); ++i) {
    if (map.labels[i] < 0 || map.labels[i] >= n) {
      throw Error(path + ": WriteSuperpixels: label " + std::to_string(map.labels[i]) + " out of range [0, " +
                  std::to_string(n) + ")");
    }
  }

  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string tmp = TemporaryPathFor(path);
  File file(std::fopen(tmp.c_str(), "wb"));
  if (!file) throw Error(path + ": cannot create " + tmp + ": " + std::strerror(errno));
  try {
    std::FILE* f = file.get();
    unsigned char header[kHeaderBytes];
    std::memcpy(header, kMagic, sizeof(kMagic));
    PutU32(header + 8, static_cast<uint32_t>(map.width));
    PutU32(header + 12, static_cast<uint32_t>(map.height));
    PutU64(header + 16, map.clusters.size());
    PutU64(header + 24, options_hash);
    WriteAll(f, header, sizeof(header), path, tmp);
    if (HostIsLittleEndian()) {
      WriteAll(f, map.labels.data(), map.labels.size() * 4, path, tmp);
    } else {
      std::vector<int32_t> row(static_cast<size_t>(map.width));
      for (int r = 0; r < map.height; ++r) {
        std::memcpy(row.data(), map.labels.data() + static_cast<size_t>(r) * map.width, row.size() * 4);
        SwapLabelsIfBigEndian(row.data(), row.size());
        WriteAll(f, row.data(), row.size() * 4, path, tmp);
      }
    }
    std::vector<unsigned char> table(map.clusters.size() * kClusterBytes);
    for (size_t i = 0; i < map.clusters.size(); ++i) {
      unsigned char* p = table.data() + i * kClusterBytes;
      const SuperpixelCluster& c = map.clusters[i];
      PutF32(p, c.centroid_col);
      PutF32(p + 4, c.centroid_row);
      PutF32(p + 8, c.depth_m);
      PutU32(p + 12, c.pixel_count);
      PutU32(p + 16, c.valid_count);
    }
    WriteAll(f, table.data(), table.size(), path, tmp);
    if (std::fclose(file.release()) != 0) throw Error(path + ": cannot close " + tmp + ": " + std::strerror(errno));
    CommitTemporaryFile(tmp, path);
  } catch (...) {
    file.reset();
    std::remove(tmp.c_str());
    throw;
  }
}

SuperpixelFileInfo ReadSuperpixelInfo(const std::string& path) { return Open(path).info; }

SuperpixelMap ReadSuperpixels(const std::string& path) {
  const OpenFile open = Open(path);
  SuperpixelMap map;
  map.width = open.info.width;
  map.height = open.info.height;
  map.clusters = ReadClusterTable(open, path);
  ReadLabelRows(open, path, 0, map.height, &map);
  std::vector<uint32_t> counts(map.clusters.size(), 0);
  for (const int32_t label : map.labels) ++counts[static_cast<size_t>(label)];
  for (size_t i = 0; i < counts.size(); ++i) {
    if (counts[i] != map.clusters[i].pixel_count) {
      throw InputError(path, "cluster " + std::to_string(i) + " has " + std::to_string(counts[i]) +
                                 " labelled pixels but its table entry says " +
                                 std::to_string(map.clusters[i].pixel_count));
    }
  }
  return map;
}

SuperpixelMap ReadSuperpixelRows(const std::string& path, int row_begin, int row_end) {
  const OpenFile open = Open(path);
  if (row_begin < 0 || row_end < row_begin || row_end > open.info.height) {
    throw Error(path + ": row window [" + std::to_string(row_begin) + ", " + std::to_string(row_end) +
                ") is outside the raster's " + std::to_string(open.info.height) + " rows");
  }
  SuperpixelMap map;
  map.width = open.info.width;
  map.height = row_end - row_begin;
  map.clusters = ReadClusterTable(open, path);
  ReadLabelRows(open, path, row_begin, row_end, &map);
  return map;
}

std::vector<int32_t> ReadSuperpixelLabelWindow(const std::string& path, const PixelWindow& window,
                                               SuperpixelFileInfo* info) {
  const OpenFile open = Open(path);
  if (!window.FitsIn(open.info.width, open.info.height)) {
    throw Error(path + ": window " + PixelWindowText(window) + " is not inside the raster's " +
                std::to_string(open.info.width) + "x" + std::to_string(open.info.height) + " pixels");
  }
  if (info != nullptr) *info = open.info;
  const uint64_t width = static_cast<uint64_t>(open.info.width);
  const size_t row_values = static_cast<size_t>(window.width());
  std::vector<int32_t> labels(window.num_pixels());
  for (int r = 0; r < window.height(); ++r) {
    const uint64_t offset = kHeaderBytes + ((static_cast<uint64_t>(window.row_begin) + r) * width + window.col_begin) * 4;
    ReadExactly(open.file.get(), path, offset, labels.data() + r * row_values, row_values * 4, "the label rows");
  }
  SwapLabelsIfBigEndian(labels.data(), labels.size());
  const auto n = static_cast<int64_t>(open.info.num_clusters);
  for (size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] < 0 || labels[i] >= n) {
      throw InputError(path, "label " + std::to_string(labels[i]) + " at row " +
                                 std::to_string(window.row_begin + static_cast<int64_t>(i / row_values)) + ", col " +
                                 std::to_string(window.col_begin + static_cast<int64_t>(i % row_values)) +
                                 " is outside [0, " + std::to_string(n) + ")");
    }
  }
  return labels;
}

std::vector<SuperpixelCluster> ReadSuperpixelClusters(const std::string& path) {
  const OpenFile open = Open(path);
  return ReadClusterTable(open, path);
}

}  // namespace sacfuse
