#include "io/superpixel_io.h"

#include <sys/types.h>

#include <algorithm>
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
#include "io/unique_file.h"

namespace sacfuse {
namespace {

constexpr char kMagicInt32[8] = {'S', 'A', 'C', 'S', 'P', 'X', '0', '1'};  // int32 labels
constexpr char kMagicBanded[8] = {'S', 'A', 'C', 'S', 'P', 'X', '0', '2'};  // u16 offsets in row bands
constexpr uint64_t kHeaderBytes = 32;
constexpr uint64_t kClusterBytes = 20;
// The bands are SuperpixelLabels' (core/superpixel_labels.h: banded(), band_base()).
constexpr int kBandRows = SuperpixelLabels::kBandRows;

uint64_t NumBands(uint64_t height) { return (height + kBandRows - 1) / kBandRows; }

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

using File = UniqueFile;

// An open superpixel file with a validated header.
struct OpenFile {
  File file;
  SuperpixelFileInfo info;
  bool banded = false;                // SACSPX02
  std::vector<uint32_t> band_base;    // banded: the label base of each band of kBandRows rows
  uint64_t labels_offset = 0;         // byte offset of label (row 0, col 0)
  uint64_t label_bytes = 4;           // 4 (int32) or 2 (u16 offset from the band's base)
  uint64_t LabelOffset(uint64_t row, uint64_t col) const {
    return labels_offset + (row * static_cast<uint64_t>(info.width) + col) * label_bytes;
  }
  uint64_t ClusterTableOffset() const {
    return labels_offset + static_cast<uint64_t>(info.width) * info.height * label_bytes;
  }
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
  if (std::memcmp(header, kMagicBanded, sizeof(kMagicBanded)) == 0) {
    open.banded = true;
  } else if (std::memcmp(header, kMagicInt32, sizeof(kMagicInt32)) != 0) {
    throw InputError(path, "not a superpixel file (magic is not SACSPX01 or SACSPX02)");
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
  open.label_bytes = open.banded ? 2 : 4;
  const uint64_t bands = open.banded ? NumBands(height) : 0;
  open.labels_offset = kHeaderBytes + bands * 4;
  const bool counts_plausible = pixels <= size / open.label_bytes && clusters <= size / kClusterBytes;
  if (!counts_plausible || open.labels_offset + pixels * open.label_bytes + clusters * kClusterBytes != size) {
    throw InputError(path, "file size " + std::to_string(size) + " bytes does not match " + std::to_string(width) +
                               "x" + std::to_string(height) + " labels and " + std::to_string(clusters) +
                               " clusters (truncated or corrupt)");
  }
  if (clusters > static_cast<uint64_t>(INT32_MAX) || clusters > pixels || (pixels > 0 && clusters == 0)) {
    throw InputError(path, "invalid cluster count " + std::to_string(clusters) + " for " + std::to_string(pixels) +
                               " pixels");
  }
  if (open.banded) {
    std::vector<unsigned char> raw(bands * 4);
    ReadExactly(f, path, kHeaderBytes, raw.data(), raw.size(), "the band bases");
    open.band_base.resize(bands);
    for (uint64_t b = 0; b < bands; ++b) {
      open.band_base[b] = GetU32(raw.data() + b * 4);
      if (open.band_base[b] >= clusters) {
        throw InputError(path, "band " + std::to_string(b) + " base " + std::to_string(open.band_base[b]) +
                                   " is not below the " + std::to_string(clusters) + " clusters");
      }
    }
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
  ReadExactly(open.file.get(), path, open.ClusterTableOffset(), raw.data(), raw.size(), "the cluster table");
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

// Reads `count` labels of row `row` from column `col` into `out`, decodes them and range-checks them.
void ReadLabelRun(const OpenFile& open, const std::string& path, uint64_t row, uint64_t col, size_t count,
                  int32_t* out) {
  std::vector<unsigned char> raw(count * open.label_bytes);
  ReadExactly(open.file.get(), path, open.LabelOffset(row, col), raw.data(), raw.size(), "the label rows");
  const auto n = static_cast<int64_t>(open.info.num_clusters);
  const int64_t base = open.banded ? open.band_base[row / kBandRows] : 0;
  for (size_t i = 0; i < count; ++i) {
    const unsigned char* p = raw.data() + i * open.label_bytes;
    const int64_t label = open.banded ? base + (p[0] | (p[1] << 8)) : static_cast<int32_t>(GetU32(p));
    if (label < 0 || label >= n) {
      throw InputError(path, "label " + std::to_string(label) + " at row " + std::to_string(row) + ", col " +
                                 std::to_string(col + i) + " is outside [0, " + std::to_string(n) + ")");
    }
    out[i] = static_cast<int32_t>(label);
  }
}

// Reads rows [row_begin, row_end) into map->labels and range-checks them.
void ReadLabelRows(const OpenFile& open, const std::string& path, int row_begin, int row_end, SuperpixelMap* map) {
  const auto width = static_cast<size_t>(open.info.width);
  std::vector<int32_t> labels(width * static_cast<size_t>(row_end - row_begin));
  // One read per band (banded) or for all rows (int32): contiguous on disk either way.
  for (int row = row_begin; row < row_end;) {
    const int band_end = open.banded ? std::min(row_end, (row / kBandRows + 1) * kBandRows) : row_end;
    ReadLabelRun(open, path, static_cast<uint64_t>(row), 0, width * static_cast<size_t>(band_end - row),
                 labels.data() + width * static_cast<size_t>(row - row_begin));
    row = band_end;
  }
  map->labels = SuperpixelLabels(open.info.width, row_end - row_begin, labels);
}

void WriteAll(std::FILE* f, const void* data, size_t bytes, const std::string& path, const std::string& tmp) {
  if (bytes > 0 && std::fwrite(data, 1, bytes, f) != bytes) {
    throw Error(path + ": cannot write " + tmp + ": " + std::strerror(errno));
  }
}

}  // namespace

void WriteSuperpixels(const std::string& path, const SuperpixelMap& map, uint64_t options_hash) {
  if (map.width < 0 || map.height < 0 || (map.width == 0) != (map.height == 0) ||
      map.labels.width() != map.width || map.labels.height() != map.height) {
    throw Error(path + ": WriteSuperpixels: labels do not match " + std::to_string(map.width) + "x" +
                std::to_string(map.height));
  }
  if (map.clusters.size() > static_cast<size_t>(INT32_MAX)) throw Error(path + ": WriteSuperpixels: too many clusters");
  const auto n = static_cast<int64_t>(map.clusters.size());
  std::vector<int32_t> labels(static_cast<size_t>(map.width));
  for (int r = 0; r < map.height; ++r) {
    map.labels.CopyRow(r, labels.data());
    for (const int32_t label : labels) {
      if (label < 0 || label >= n) {
        throw Error(path + ": WriteSuperpixels: label " + std::to_string(label) + " out of range [0, " +
                    std::to_string(n) + ")");
      }
    }
  }

  // Banded when the labels fit that layout (SuperpixelLabels::banded), else int32.
  const bool banded = map.labels.banded();
  const std::vector<uint32_t>& band_base = map.labels.band_base();
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string tmp = TemporaryPathFor(path);
  File file(std::fopen(tmp.c_str(), "wb"));
  if (!file) throw Error(path + ": cannot create " + tmp + ": " + std::strerror(errno));
  try {
    std::FILE* f = file.get();
    unsigned char header[kHeaderBytes];
    std::memcpy(header, banded ? kMagicBanded : kMagicInt32, sizeof(kMagicBanded));
    PutU32(header + 8, static_cast<uint32_t>(map.width));
    PutU32(header + 12, static_cast<uint32_t>(map.height));
    PutU64(header + 16, map.clusters.size());
    PutU64(header + 24, options_hash);
    WriteAll(f, header, sizeof(header), path, tmp);
    if (banded) {
      std::vector<unsigned char> raw(band_base.size() * 4);
      for (size_t b = 0; b < band_base.size(); ++b) PutU32(raw.data() + b * 4, band_base[b]);
      WriteAll(f, raw.data(), raw.size(), path, tmp);
    }
    // Labels row by row, little-endian: u16 offsets from the row's band base, or int32.
    const size_t label_bytes = banded ? 2 : 4;
    std::vector<unsigned char> row(static_cast<size_t>(map.width) * label_bytes);
    std::vector<int32_t> labels_row(static_cast<size_t>(map.width));
    for (int r = 0; r < map.height; ++r) {
      map.labels.CopyRow(r, labels_row.data());
      const uint32_t base = banded ? band_base[static_cast<size_t>(r / kBandRows)] : 0;
      for (int c = 0; c < map.width; ++c) {
        unsigned char* p = row.data() + static_cast<size_t>(c) * label_bytes;
        const uint32_t value = static_cast<uint32_t>(labels_row[static_cast<size_t>(c)]) - base;
        if (banded) {
          p[0] = static_cast<unsigned char>(value);
          p[1] = static_cast<unsigned char>(value >> 8);
        } else {
          PutU32(p, value);
        }
      }
      WriteAll(f, row.data(), row.size(), path, tmp);
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
  std::vector<int32_t> row(static_cast<size_t>(map.width));
  for (int r = 0; r < map.height; ++r) {
    map.labels.CopyRow(r, row.data());
    for (const int32_t label : row) ++counts[static_cast<size_t>(label)];
  }
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
  const size_t row_values = static_cast<size_t>(window.width());
  std::vector<int32_t> labels(window.num_pixels());
  for (int r = 0; r < window.height(); ++r) {
    ReadLabelRun(open, path, static_cast<uint64_t>(window.row_begin) + r, static_cast<uint64_t>(window.col_begin),
                 row_values, labels.data() + r * row_values);
  }
  return labels;
}

std::vector<SuperpixelCluster> ReadSuperpixelClusters(const std::string& path) {
  const OpenFile open = Open(path);
  return ReadClusterTable(open, path);
}

}  // namespace sacfuse
