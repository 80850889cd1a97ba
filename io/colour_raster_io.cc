#include "io/colour_raster_io.h"

#include <sys/types.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/unique_file.h"

namespace sacfuse {
namespace {

constexpr char kMagic[8] = {'S', 'A', 'C', 'R', 'G', 'B', '0', '1'};
constexpr uint64_t kHeaderBytes = 24;

using File = UniqueFile;

void PutU32(unsigned char* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
uint32_t GetU32(const unsigned char* p) {
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 | static_cast<uint32_t>(p[2]) << 16 |
         static_cast<uint32_t>(p[3]) << 24;
}

void ReadAt(std::FILE* f, const std::string& path, uint64_t offset, void* data, size_t bytes, const char* what) {
  if (bytes == 0) return;
  if (::fseeko(f, static_cast<off_t>(offset), SEEK_SET) != 0 || std::fread(data, 1, bytes, f) != bytes) {
    throw InputError(path, std::string("cannot read ") + what + " (truncated or unreadable file)");
  }
}

File OpenChecked(const std::string& path, ColourRasterInfo* info) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw InputError(path, std::string("cannot open colour raster: ") + std::strerror(errno));
  std::FILE* f = file.get();
  if (::fseeko(f, 0, SEEK_END) != 0) throw InputError(path, "cannot seek in colour raster");
  const off_t end = ::ftello(f);
  if (end < 0) throw InputError(path, "cannot determine the file size");
  const auto size = static_cast<uint64_t>(end);
  if (size < kHeaderBytes) throw InputError(path, "too short for a colour raster header");
  unsigned char header[kHeaderBytes];
  ReadAt(f, path, 0, header, kHeaderBytes, "the header");
  if (std::memcmp(header, kMagic, sizeof(kMagic)) != 0) {
    throw InputError(path, "not a colour raster (magic is not SACRGB01)");
  }
  const uint32_t width = GetU32(header + 8), height = GetU32(header + 12), channels = GetU32(header + 16);
  if (width == 0 || height == 0 || width > static_cast<uint32_t>(INT_MAX) || height > static_cast<uint32_t>(INT_MAX) ||
      (channels != 1 && channels != 3)) {
    throw InputError(path, "invalid colour raster shape " + std::to_string(width) + "x" + std::to_string(height) +
                               "x" + std::to_string(channels));
  }
  const uint64_t expected = kHeaderBytes + static_cast<uint64_t>(width) * height * channels;
  if (expected != size) {
    throw InputError(path, "file size " + std::to_string(size) + " bytes does not match " + std::to_string(width) +
                               "x" + std::to_string(height) + "x" + std::to_string(channels) +
                               " pixels (truncated or corrupt)");
  }
  info->width = static_cast<int>(width);
  info->height = static_cast<int>(height);
  info->channels = static_cast<int>(channels);
  return file;
}

}  // namespace

void WriteColourRaster(const std::string& path, const RgbImage& image) {
  if (image.empty() || (image.channels != 1 && image.channels != 3) ||
      image.data.size() != image.num_pixels() * image.channels) {
    throw Error(path + ": WriteColourRaster: needs a non-empty 1- or 3-channel raster");
  }
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string tmp = TemporaryPathFor(path);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) throw Error(path + ": cannot create " + tmp + ": " + std::strerror(errno));
  unsigned char header[kHeaderBytes] = {};
  std::memcpy(header, kMagic, sizeof(kMagic));
  PutU32(header + 8, static_cast<uint32_t>(image.width));
  PutU32(header + 12, static_cast<uint32_t>(image.height));
  PutU32(header + 16, static_cast<uint32_t>(image.channels));
  bool ok = std::fwrite(header, 1, kHeaderBytes, f) == kHeaderBytes;
  ok = ok && std::fwrite(image.data.data(), 1, image.data.size(), f) == image.data.size();
  CloseAndCommitTemporaryFile(f, ok, tmp, path);
}

ColourRasterInfo ReadColourRasterInfo(const std::string& path) {
  ColourRasterInfo info;
  OpenChecked(path, &info);
  return info;
}

RgbImage ReadColourRasterWindow(const std::string& path, const PixelWindow& window) {
  ColourRasterInfo info;
  const File file = OpenChecked(path, &info);
  if (!window.FitsIn(info.width, info.height)) {
    throw Error(path + ": window " + PixelWindowText(window) + " is not inside the raster's " +
                std::to_string(info.width) + "x" + std::to_string(info.height) + " pixels");
  }
  RgbImage out(window.width(), window.height(), info.channels);
  const size_t row_bytes = static_cast<size_t>(window.width()) * info.channels;
  for (int r = 0; r < window.height(); ++r) {
    const uint64_t offset =
        kHeaderBytes +
        ((static_cast<uint64_t>(window.row_begin) + r) * info.width + window.col_begin) * info.channels;
    ReadAt(file.get(), path, offset, out.data.data() + r * row_bytes, row_bytes, "the colour rows");
  }
  return out;
}

}  // namespace sacfuse
