#include "io/openmvs_dmap.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

// OpenMVS writes its structs and arrays with raw fwrite on little-endian machines; we decode them with memcpy,
// which is only correct on a little-endian host.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "sacfuse's .dmap I/O assumes a little-endian host");
static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559, "float must be IEEE-754 binary32");
static_assert(sizeof(double) == 8 && std::numeric_limits<double>::is_iec559, "double must be IEEE-754 binary64");

namespace sacfuse {
namespace {

constexpr uint64_t kFixedHeaderBytes = 28;  // sizeof(HeaderDepthDataRaw)
constexpr uint64_t kCameraBytes = 21 * sizeof(double);
constexpr uint32_t kMaxViewIds = 255;
constexpr uint8_t kKnownFlags = kDmapDepth | kDmapNormals | kDmapConfidence | kDmapViews;

std::string Hex2(unsigned value) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "0x%02x", value & 0xffu);
  return buf;
}

std::string Printable(const char* bytes, size_t n) {
  std::string out;
  for (size_t i = 0; i < n; ++i) {
    const auto u = static_cast<unsigned char>(bytes[i]);
    if (u >= 0x20 && u < 0x7f) {
      out += static_cast<char>(u);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\x%02x", u);
      out += buf;
    }
  }
  return "\"" + out + "\"";
}

std::ifstream OpenForReading(const std::string& path) { return OpenInputStream(path, "depth map"); }

// Reads `bytes` at `offset`, which the caller has checked lie inside the file; a short read means the file
// shrank while we read it.
void ReadAt(std::ifstream& in, const std::string& path, uint64_t offset, char* dst, uint64_t bytes) {
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(dst, static_cast<std::streamsize>(bytes));
  if (!in || static_cast<uint64_t>(in.gcount()) != bytes) {
    throw InputError(path, "read of " + std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                               " failed (file truncated while reading?)");
  }
}

// Sequential reader of the variable-length header: every read is checked against the file size first, so a
// truncated file says which part it ends in.
class HeaderCursor {
 public:
  HeaderCursor(std::ifstream& in, const std::string& path, uint64_t file_size)
      : in_(in), path_(path), file_size_(file_size) {}

  void Read(void* dst, uint64_t bytes, const std::string& what) {
    if (pos_ + bytes > file_size_) {
      throw InputError(path_, "truncated depth map: the file (" + std::to_string(file_size_) +
                                  " bytes) ends inside the " + what + " (bytes " + std::to_string(pos_) + ".." +
                                  std::to_string(pos_ + bytes) + ")");
    }
    ReadAt(in_, path_, pos_, static_cast<char*>(dst), bytes);
    pos_ += bytes;
  }
  uint64_t pos() const { return pos_; }

 private:
  std::ifstream& in_;
  const std::string& path_;
  uint64_t file_size_;
  uint64_t pos_ = 0;
};

template <typename T>
T Load(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

std::string SizeText(uint64_t w, uint64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

// Reads `count` elements of `element_bytes` each, contiguous from `offset`, into `dst`, in bounded chunks.
void ReadBlock(const std::string& path, uint64_t offset, uint64_t bytes, char* dst) {
  std::ifstream in = OpenForReading(path);
  constexpr uint64_t kChunk = 16u << 20;
  for (uint64_t done = 0; done < bytes; done += kChunk) {
    const uint64_t n = std::min(kChunk, bytes - done);
    ReadAt(in, path, offset + done, dst + done, n);
  }
}

}  // namespace

DmapHeader ReadDmapHeader(const std::string& path) {
  std::ifstream in = OpenForReading(path);
  in.seekg(0, std::ios::end);
  const auto end = in.tellg();
  if (end < 0) throw InputError(path, "cannot determine the file size");
  DmapHeader h;
  h.file_size = static_cast<uint64_t>(end);
  if (h.file_size < kFixedHeaderBytes) {
    throw InputError(path, "truncated depth map header: the file has " + std::to_string(h.file_size) +
                               " bytes, the fixed header alone needs " + std::to_string(kFixedHeaderBytes));
  }
  HeaderCursor cursor(in, path, h.file_size);
  unsigned char fixed[kFixedHeaderBytes];
  cursor.Read(fixed, kFixedHeaderBytes, "fixed header");
  if (fixed[0] != 'D' || fixed[1] != 'R') {
    throw InputError(path, "not an OpenMVS depth map: magic bytes " +
                               Printable(reinterpret_cast<const char*>(fixed), 2) + " (expected \"DR\")");
  }
  h.flags = fixed[2];
  if (!h.has(kDmapDepth)) {
    throw InputError(path, "header flags " + Hex2(h.flags) + " declare no depth map (flag 1 must be set)");
  }
  h.image_width = Load<uint32_t>(fixed + 4);
  h.image_height = Load<uint32_t>(fixed + 8);
  h.depth_width = Load<uint32_t>(fixed + 12);
  h.depth_height = Load<uint32_t>(fixed + 16);
  h.depth_min = Load<float>(fixed + 20);
  h.depth_max = Load<float>(fixed + 24);
  if (h.depth_width == 0 || h.depth_height == 0) {
    throw InputError(path, "invalid header: depth size " + SizeText(h.depth_width, h.depth_height) +
                               " (both must be > 0)");
  }
  if (h.image_width < h.depth_width || h.image_height < h.depth_height) {
    throw InputError(path, "invalid header: depth size " + SizeText(h.depth_width, h.depth_height) +
                               " is larger than the image size " + SizeText(h.image_width, h.image_height));
  }
  constexpr uint32_t kIntMax = static_cast<uint32_t>(std::numeric_limits<int>::max());
  if (h.image_width > kIntMax || h.image_height > kIntMax) {
    throw InputError(path, "invalid header: image size " + SizeText(h.image_width, h.image_height) + " is too large");
  }

  uint16_t name_bytes = 0;
  cursor.Read(&name_bytes, sizeof(name_bytes), "image path length");
  h.image_path.assign(name_bytes, '\0');  // at most 65535 bytes
  cursor.Read(h.image_path.data(), name_bytes, "image path");

  uint32_t num_ids = 0;
  cursor.Read(&num_ids, sizeof(num_ids), "view ID count");
  if (num_ids == 0 || num_ids > kMaxViewIds) {
    throw InputError(path, "invalid header: " + std::to_string(num_ids) + " view IDs (must be 1.." +
                               std::to_string(kMaxViewIds) + ": the reference view and its neighbours)");
  }
  h.view_ids.resize(num_ids);
  cursor.Read(h.view_ids.data(), uint64_t{num_ids} * sizeof(uint32_t), "view IDs");

  unsigned char camera[kCameraBytes];
  cursor.Read(camera, kCameraBytes, "camera (K, R, C)");
  for (int i = 0; i < 9; ++i) h.camera.K[i] = Load<double>(camera + 8 * i);
  for (int i = 0; i < 9; ++i) h.camera.R[i] = Load<double>(camera + 72 + 8 * i);
  for (int i = 0; i < 3; ++i) h.camera.C[i] = Load<double>(camera + 144 + 8 * i);
  h.depth_offset = cursor.pos();

  // Sizes of the maps the flags declare; 128-bit so absurd headers cannot overflow.
  const unsigned __int128 pixels = static_cast<unsigned __int128>(h.depth_width) * h.depth_height;
  unsigned __int128 expected = h.depth_offset + pixels * 4;
  if (h.has(kDmapNormals)) {
    h.normals_offset = static_cast<uint64_t>(std::min<unsigned __int128>(expected, UINT64_MAX));
    expected += pixels * 12;
  }
  if (h.has(kDmapConfidence)) {
    h.confidence_offset = static_cast<uint64_t>(std::min<unsigned __int128>(expected, UINT64_MAX));
    expected += pixels * 4;
  }
  if (h.has(kDmapViews)) {
    h.views_offset = static_cast<uint64_t>(std::min<unsigned __int128>(expected, UINT64_MAX));
    expected += pixels * 4;
  }
  if (expected != h.file_size) {
    std::string maps = "depth";
    if (h.has(kDmapNormals)) maps += " + normals";
    if (h.has(kDmapConfidence)) maps += " + confidence";
    if (h.has(kDmapViews)) maps += " + views";
    const std::string unknown =
        (h.flags & ~kKnownFlags) != 0 ? " (the flags also have unknown bits " + Hex2(h.flags & ~kKnownFlags) + ")" : "";
    const std::string needs = expected > UINT64_MAX ? std::string("more than 2^64")
                                                    : std::to_string(static_cast<uint64_t>(expected));
    throw InputError(path, std::string(expected > h.file_size ? "truncated" : "mismatched") + " depth map: " +
                               SizeText(h.depth_width, h.depth_height) + " pixels of " + maps + " (flags " +
                               Hex2(h.flags) + ") from byte " + std::to_string(h.depth_offset) + " need " + needs +
                               " bytes in all, but the file has " + std::to_string(h.file_size) + unknown);
  }
  return h;
}

DepthMap ReadDmapDepth(const std::string& path) {
  const DmapHeader h = ReadDmapHeader(path);
  DepthMap out(static_cast<int>(h.depth_width), static_cast<int>(h.depth_height), 1);
  ReadBlock(path, h.depth_offset, static_cast<uint64_t>(out.data.size()) * sizeof(float),
            reinterpret_cast<char*>(out.data.data()));
  return out;
}

DepthMap ReadDmapDepthWindow(const std::string& path, const PixelWindow& window) {
  return ReadDmapDepthWindow(path, ReadDmapHeader(path), window);
}

DepthMap ReadDmapDepthWindow(const std::string& path, const DmapHeader& h, const PixelWindow& window) {
  const int width = static_cast<int>(h.depth_width), height = static_cast<int>(h.depth_height);
  if (!window.FitsIn(width, height)) {
    throw Error(path + ": window " + PixelWindowText(window) + " is not inside the depth map's " +
                SizeText(h.depth_width, h.depth_height) + " pixels");
  }
  DepthMap out(window.width(), window.height(), 1);
  std::ifstream in = OpenForReading(path);
  const uint64_t row_bytes = static_cast<uint64_t>(window.width()) * sizeof(float);
  for (int r = 0; r < window.height(); ++r) {
    const uint64_t offset =
        h.depth_offset + (static_cast<uint64_t>(window.row_begin + r) * h.depth_width + window.col_begin) * sizeof(float);
    ReadAt(in, path, offset, reinterpret_cast<char*>(&out.at(r, 0)), row_bytes);
  }
  return out;
}

NormalMap ReadDmapNormals(const std::string& path) {
  const DmapHeader h = ReadDmapHeader(path);
  if (!h.has(kDmapNormals)) throw InputError(path, "has no normal map (header flags " + Hex2(h.flags) + ")");
  NormalMap out(static_cast<int>(h.depth_width), static_cast<int>(h.depth_height), 3);
  ReadBlock(path, h.normals_offset, static_cast<uint64_t>(out.data.size()) * sizeof(float),
            reinterpret_cast<char*>(out.data.data()));
  return out;
}

Raster<float> ReadDmapConfidence(const std::string& path) {
  const DmapHeader h = ReadDmapHeader(path);
  if (!h.has(kDmapConfidence)) throw InputError(path, "has no confidence map (header flags " + Hex2(h.flags) + ")");
  Raster<float> out(static_cast<int>(h.depth_width), static_cast<int>(h.depth_height), 1);
  ReadBlock(path, h.confidence_offset, static_cast<uint64_t>(out.data.size()) * sizeof(float),
            reinterpret_cast<char*>(out.data.data()));
  return out;
}

Raster<uint8_t> ReadDmapViews(const std::string& path) {
  const DmapHeader h = ReadDmapHeader(path);
  if (!h.has(kDmapViews)) throw InputError(path, "has no views map (header flags " + Hex2(h.flags) + ")");
  Raster<uint8_t> out(static_cast<int>(h.depth_width), static_cast<int>(h.depth_height), 4);
  ReadBlock(path, h.views_offset, static_cast<uint64_t>(out.data.size()), reinterpret_cast<char*>(out.data.data()));
  return out;
}

void WriteDmap(const std::string& path, const DmapContents& c) {
  const DepthMap& d = c.depth;
  auto fail = [&](const std::string& what) { throw Error(path + ": cannot write depth map: " + what); };
  if (d.width <= 0 || d.height <= 0 || d.channels != 1 || d.data.size() != d.num_pixels()) {
    fail("the depth raster must be non-empty with 1 channel (got " + SizeText(d.width, d.height) + "x" +
         std::to_string(d.channels) + ")");
  }
  if (c.image_width < static_cast<uint32_t>(d.width) || c.image_height < static_cast<uint32_t>(d.height)) {
    fail("image size " + SizeText(c.image_width, c.image_height) + " is smaller than the depth map " +
         SizeText(d.width, d.height));
  }
  if (c.image_path.size() > std::numeric_limits<uint16_t>::max()) fail("image path longer than 65535 bytes");
  if (c.view_ids.empty() || c.view_ids.size() > kMaxViewIds) {
    fail(std::to_string(c.view_ids.size()) + " view IDs (must be 1.." + std::to_string(kMaxViewIds) + ")");
  }
  auto check_map = [&](const auto& map, int channels, const char* name) {
    if (map.empty()) return false;
    if (map.width != d.width || map.height != d.height || map.channels != channels ||
        map.data.size() != map.num_pixels() * channels) {
      fail(std::string(name) + " map is " + SizeText(map.width, map.height) + "x" + std::to_string(map.channels) +
           ", expected " + SizeText(d.width, d.height) + "x" + std::to_string(channels));
    }
    return true;
  };
  const bool normals = check_map(c.normals, 3, "normal");
  const bool confidence = check_map(c.confidence, 1, "confidence");
  const bool views = check_map(c.views, 4, "views");

  unsigned char fixed[kFixedHeaderBytes] = {};
  fixed[0] = 'D';
  fixed[1] = 'R';
  fixed[2] = static_cast<uint8_t>(kDmapDepth | (normals ? kDmapNormals : 0) | (confidence ? kDmapConfidence : 0) |
                                  (views ? kDmapViews : 0));
  const uint32_t sizes[4] = {c.image_width, c.image_height, static_cast<uint32_t>(d.width),
                             static_cast<uint32_t>(d.height)};
  std::memcpy(fixed + 4, sizes, sizeof(sizes));
  std::memcpy(fixed + 20, &c.depth_min, sizeof(float));
  std::memcpy(fixed + 24, &c.depth_max, sizeof(float));

  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string tmp = TemporaryPathFor(path);
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) throw Error(path + ": cannot create " + tmp + ": " + std::strerror(errno));
  auto put = [&](const void* data, size_t bytes) { return bytes == 0 || std::fwrite(data, 1, bytes, f) == bytes; };
  const uint16_t name_bytes = static_cast<uint16_t>(c.image_path.size());
  const uint32_t num_ids = static_cast<uint32_t>(c.view_ids.size());
  bool ok = put(fixed, sizeof(fixed)) && put(&name_bytes, sizeof(name_bytes)) &&
            put(c.image_path.data(), name_bytes) && put(&num_ids, sizeof(num_ids)) &&
            put(c.view_ids.data(), num_ids * sizeof(uint32_t)) && put(c.camera.K.data(), 9 * sizeof(double)) &&
            put(c.camera.R.data(), 9 * sizeof(double)) && put(c.camera.C.data(), 3 * sizeof(double)) &&
            put(d.data.data(), d.data.size() * sizeof(float));
  if (ok && normals) ok = put(c.normals.data.data(), c.normals.data.size() * sizeof(float));
  if (ok && confidence) ok = put(c.confidence.data.data(), c.confidence.data.size() * sizeof(float));
  if (ok && views) ok = put(c.views.data.data(), c.views.data.size());
  CloseAndCommitTemporaryFile(f, ok, tmp, path);
}

}  // namespace sacfuse
