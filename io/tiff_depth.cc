#include "io/tiff_depth.h"

#include <tiffio.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "io/input_warnings.h"

namespace sacfuse {
namespace {

constexpr ttag_t kGdalNodataTag = 42113;
constexpr uint64_t kMaxPixels = uint64_t{1} << 31;      // 8 GiB of float32: anything larger is a corrupt header
constexpr uint64_t kMaxBlockBytes = uint64_t{1} << 31;  // one strip or tile

// GDAL's private ASCII tag, registered so libtiff reads it as a named field (and does not warn about it).
TIFFExtendProc g_parent_extender = nullptr;
void TagExtender(TIFF* tif) {
  static const TIFFFieldInfo kFields[] = {
      {kGdalNodataTag, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, const_cast<char*>("GDALNoDataValue")},
      {42112, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, const_cast<char*>("GDALMetadata")},
  };
  TIFFMergeFieldInfo(tif, kFields, sizeof(kFields) / sizeof(kFields[0]));
  if (g_parent_extender != nullptr) g_parent_extender(tif);
}

void SilentGlobalHandler(const char*, const char*, va_list) {}

// Process-wide libtiff setup, once: the tag extender, and global handlers that print nothing (messages about a
// file reach its per-handle handlers below; the global ones only see messages without a file).
void InitLibTiff() {
  static std::once_flag once;
  std::call_once(once, [] {
    g_parent_extender = TIFFSetTagExtender(TagExtender);
    TIFFSetErrorHandler(SilentGlobalHandler);
    TIFFSetWarningHandler(SilentGlobalHandler);
  });
}

std::string Format(const char* module, const char* fmt, va_list ap) {
  char buf[1024];
  std::vsnprintf(buf, sizeof(buf), fmt, ap);
  std::string text = buf;
  if (module != nullptr && *module != '\0') text = std::string(module) + ": " + text;
  return text;
}

// libtiff messages of one open file.
struct Messages {
  std::string errors, warnings;
};

int CollectError(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
  auto* m = static_cast<Messages*>(user);
  m->errors += (m->errors.empty() ? "" : "; ") + Format(module, fmt, ap);
  return 1;  // handled: do not call the global handler
}

int CollectWarning(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
  auto* m = static_cast<Messages*>(user);
  if (m->warnings.size() < 2000) m->warnings += (m->warnings.empty() ? "" : "; ") + Format(module, fmt, ap);
  return 1;
}

// An open TIFF whose libtiff messages are collected (never printed).
class TiffFile {
 public:
  TiffFile(const std::string& path, const char* mode) : path_(path) {
    InitLibTiff();
    TIFFOpenOptions* opts = TIFFOpenOptionsAlloc();
    TIFFOpenOptionsSetErrorHandlerExtR(opts, CollectError, messages_.get());
    TIFFOpenOptionsSetWarningHandlerExtR(opts, CollectWarning, messages_.get());
    tif_ = TIFFOpenExt(path.c_str(), mode, opts);
    TIFFOpenOptionsFree(opts);
  }
  ~TiffFile() {
    if (tif_ != nullptr) TIFFClose(tif_);
  }
  TiffFile(const TiffFile&) = delete;
  TiffFile& operator=(const TiffFile&) = delete;

  TIFF* get() const { return tif_; }
  // Closes (flushing a file being written); false when libtiff reported an error.
  bool Close() {
    if (tif_ == nullptr) return false;
    TIFFClose(tif_);  // flushes and writes the directory; errors go to the handlers
    tif_ = nullptr;
    return messages_->errors.empty();
  }
  // " (libtiff: ...)" or "" when libtiff said nothing.
  std::string Details() const {
    std::string d = messages_->errors;
    if (!messages_->warnings.empty()) d += (d.empty() ? "" : "; ") + std::string("warnings: ") + messages_->warnings;
    return d.empty() ? "" : " (libtiff: " + d + ")";
  }
  [[noreturn]] void Fail(const std::string& what) const { throw InputError(path_, what + Details()); }
  // libtiff's warnings about a file that was read anyway become warnings naming it (io/input_warnings.h).
  void ReportWarnings() {
    if (messages_->warnings.empty()) return;
    WarnAboutInput(path_, "libtiff warnings: " + messages_->warnings);
    messages_->warnings.clear();
  }

 private:
  std::string path_;
  std::unique_ptr<Messages> messages_ = std::make_unique<Messages>();  // stable address for the handlers
  TIFF* tif_ = nullptr;
};

std::string SampleFormatName(uint16_t format) {
  switch (format) {
    case SAMPLEFORMAT_UINT:
      return "unsigned integer";
    case SAMPLEFORMAT_INT:
      return "signed integer";
    case SAMPLEFORMAT_IEEEFP:
      return "floating point";
    case SAMPLEFORMAT_COMPLEXINT:
      return "complex integer";
    case SAMPLEFORMAT_COMPLEXIEEEFP:
      return "complex floating point";
    default:
      return "sample format " + std::to_string(format);
  }
}

std::optional<double> ParseNodata(const std::string& path, const char* text) {
  std::string s(text);
  const size_t b = s.find_first_not_of(" \t\r\n");
  const size_t e = s.find_last_not_of(" \t\r\n");
  s = b == std::string::npos ? "" : s.substr(b, e - b + 1);
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0') {
    throw InputError(path, "GDAL_NODATA tag (42113) \"" + s + "\" is not a number");
  }
  return v;
}

// Opens for reading and checks that the first image is a single-band float32 raster of a sane size.
struct OpenedDepth {
  std::unique_ptr<TiffFile> file;
  TiffDepthInfo info;
};

OpenedDepth OpenDepth(const std::string& path) {
  CheckInputFile(path, "depth raster");
  OpenedDepth out;
  // "m": no memory mapping (a file truncated under us must fail with an error, not a bus error).
  out.file = std::make_unique<TiffFile>(path, "rm");
  TiffFile& f = *out.file;
  TIFF* tif = f.get();
  if (tif == nullptr) f.Fail("not a readable TIFF file");
  uint32_t w = 0, h = 0;
  uint16_t bits = 0, spp = 1, format = SAMPLEFORMAT_UINT, orientation = ORIENTATION_TOPLEFT, compression = 1;
  if (!TIFFGetField(tif, TIFFTAG_IMAGEWIDTH, &w) || !TIFFGetField(tif, TIFFTAG_IMAGELENGTH, &h)) {
    f.Fail("TIFF without image width/height");
  }
  TIFFGetFieldDefaulted(tif, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(tif, TIFFTAG_SAMPLESPERPIXEL, &spp);
  TIFFGetFieldDefaulted(tif, TIFFTAG_SAMPLEFORMAT, &format);
  TIFFGetFieldDefaulted(tif, TIFFTAG_COMPRESSION, &compression);
  if (TIFFGetField(tif, TIFFTAG_ORIENTATION, &orientation) && orientation != ORIENTATION_TOPLEFT) {
    f.Fail("Orientation tag is " + std::to_string(orientation) +
           "; only 1 (row 0 at the top, column 0 at the left) "
           "is supported for depth rasters");
  }
  if (spp != 1) {
    f.Fail(std::to_string(spp) + " bands (samples per pixel); a depth raster must have exactly one float32 band");
  }
  if (format != SAMPLEFORMAT_IEEEFP || bits != 32) {
    f.Fail("not float32: samples are " + std::to_string(bits) + "-bit " + SampleFormatName(format) +
           "; a depth raster must be 32-bit floating point (metres)");
  }
  if (w == 0 || h == 0 || static_cast<uint64_t>(w) * h > kMaxPixels) {
    f.Fail("implausible size " + std::to_string(w) + "x" + std::to_string(h));
  }
  TiffDepthInfo& info = out.info;
  info.width = static_cast<int>(w);
  info.height = static_cast<int>(h);
  info.compression = compression;
  info.tiled = TIFFIsTiled(tif) != 0;
  if (info.tiled) {
    uint32_t tw = 0, th = 0;
    if (!TIFFGetField(tif, TIFFTAG_TILEWIDTH, &tw) || !TIFFGetField(tif, TIFFTAG_TILELENGTH, &th) || tw == 0 ||
        th == 0 || static_cast<uint64_t>(tw) * th * 4 > kMaxBlockBytes) {
      f.Fail("tiled TIFF with a missing or implausible tile size");
    }
    info.block_width = static_cast<int>(tw);
    info.block_height = static_cast<int>(th);
  } else {
    uint32_t rps = 0;
    TIFFGetFieldDefaulted(tif, TIFFTAG_ROWSPERSTRIP, &rps);
    rps = std::clamp<uint32_t>(rps, 1, h);
    if (static_cast<uint64_t>(rps) * w * 4 > kMaxBlockBytes) f.Fail("implausible strip size");
    info.block_width = info.width;
    info.block_height = static_cast<int>(rps);
  }
  char* nodata_text = nullptr;
  if (TIFFGetField(tif, kGdalNodataTag, &nodata_text) && nodata_text != nullptr) {
    info.nodata = ParseNodata(path, nodata_text);
  }
  f.ReportWarnings();
  return out;
}

float CleanDepth(float v, const std::optional<double>& nodata) {
  if (!std::isfinite(v) || v <= 0.0f) return 0.0f;
  if (nodata && static_cast<double>(v) == *nodata) return 0.0f;
  return v;
}

// Reads rows [r0, r1) x cols [c0, c1) of an opened raster into `out` (sized (c1-c0) x (r1-r0)).
void ReadBlocks(const OpenedDepth& d, const PixelWindow& w, DepthMap* out) {
  TIFF* tif = d.file->get();
  const TiffDepthInfo& info = d.info;
  const int bw = info.block_width, bh = info.block_height;
  std::vector<float> block(static_cast<size_t>(bw) * bh);
  const tmsize_t block_bytes = static_cast<tmsize_t>(block.size() * sizeof(float));
  for (int by = w.row_begin / bh; by * bh < w.row_end; ++by) {
    const int y0 = by * bh;
    for (int bx = w.col_begin / bw; bx * bw < w.col_end; ++bx) {
      const int x0 = bx * bw;
      // Rows of this block that hold image data (the last strip may be short; tiles are always full size).
      const int block_rows = info.tiled ? bh : std::min(bh, info.height - y0);
      tmsize_t got = 0;
      std::string what;
      if (info.tiled) {
        const uint32_t tile = TIFFComputeTile(tif, static_cast<uint32_t>(x0), static_cast<uint32_t>(y0), 0, 0);
        got = TIFFReadEncodedTile(tif, tile, block.data(), block_bytes);
        what = "tile " + std::to_string(tile) + " (rows " + std::to_string(y0) + "+, cols " + std::to_string(x0) + "+)";
      } else {
        const uint32_t strip = TIFFComputeStrip(tif, static_cast<uint32_t>(y0), 0);
        got = TIFFReadEncodedStrip(tif, strip, block.data(), static_cast<tmsize_t>(block_rows) * bw * 4);
        what = "strip " + std::to_string(strip) + " (rows " + std::to_string(y0) + "+)";
      }
      const tmsize_t expected = static_cast<tmsize_t>(block_rows) * bw * 4;
      if (got < expected) d.file->Fail("cannot decode " + what + " (file truncated or corrupt)");
      const int r_begin = std::max(w.row_begin, y0), r_end = std::min(w.row_end, y0 + block_rows);
      const int c_begin = std::max(w.col_begin, x0), c_end = std::min(w.col_end, x0 + bw);
      for (int r = r_begin; r < r_end; ++r) {
        const float* src = block.data() + static_cast<size_t>(r - y0) * bw + (c_begin - x0);
        float* dst = &out->at(r - w.row_begin, c_begin - w.col_begin);
        for (int c = 0; c < c_end - c_begin; ++c) dst[c] = CleanDepth(src[c], info.nodata);
      }
    }
  }
}

uint16_t CompressionTag(TiffDepthWriteOptions::Compression c) {
  switch (c) {
    case TiffDepthWriteOptions::Compression::kNone:
      return COMPRESSION_NONE;
    case TiffDepthWriteOptions::Compression::kLzw:
      return COMPRESSION_LZW;
    case TiffDepthWriteOptions::Compression::kDeflate:
      return COMPRESSION_ADOBE_DEFLATE;
  }
  return COMPRESSION_NONE;
}

std::string NodataText(float v) {
  if (std::isnan(v)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.9g", static_cast<double>(v));
  return buf;
}

}  // namespace

struct TiffDepthReader::Impl {
  OpenedDepth opened;
};

TiffDepthReader::TiffDepthReader(const std::string& path) : path_(path), impl_(std::make_unique<Impl>()) {
  impl_->opened = OpenDepth(path);
  info_ = impl_->opened.info;
}

TiffDepthReader::~TiffDepthReader() = default;

DepthMap TiffDepthReader::ReadWindow(const PixelWindow& window) {
  if (!window.FitsIn(info_.width, info_.height)) {
    throw Error(path_ + ": window " + PixelWindowText(window) + " is not inside the raster's " +
                std::to_string(info_.width) + "x" + std::to_string(info_.height) + " pixels");
  }
  DepthMap out(window.width(), window.height(), 1, 0.0f);
  ReadBlocks(impl_->opened, window, &out);
  impl_->opened.file->ReportWarnings();
  return out;
}

TiffDepthInfo ReadTiffDepthInfo(const std::string& path) { return OpenDepth(path).info; }

DepthMap ReadTiffDepth(const std::string& path) {
  TiffDepthReader reader(path);
  return reader.ReadWindow(PixelWindow{0, reader.info().height, 0, reader.info().width});
}

DepthMap ReadTiffDepthWindow(const std::string& path, const PixelWindow& window) {
  return TiffDepthReader(path).ReadWindow(window);
}

void WriteTiffDepth(const std::string& path, const DepthMap& depth, const TiffDepthWriteOptions& options) {
  if (depth.empty() || depth.channels != 1) throw Error(path + ": cannot write an empty or multi-channel depth raster");
  if (options.tiled && (options.tile_size_px < 16 || options.tile_size_px % 16 != 0)) {
    throw Error(path + ": TIFF tile size " + std::to_string(options.tile_size_px) +
                " is not a positive multiple of 16");
  }
  if (!options.tiled && options.rows_per_strip < 1) throw Error(path + ": rows per strip must be >= 1");
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string tmp = TemporaryPathFor(path);
  const bool big = static_cast<uint64_t>(depth.num_pixels()) * 4 > (uint64_t{1} << 31);
  const auto fail = [&](const std::string& what, const TiffFile* f) {
    std::remove(tmp.c_str());
    throw Error(path + ": " + what + (f != nullptr ? f->Details() : std::string()));
  };
  {
    TiffFile f(tmp, big ? "w8" : "w");
    TIFF* tif = f.get();
    if (tif == nullptr) fail("cannot create " + tmp, &f);
    const uint16_t compression = CompressionTag(options.compression);
    bool ok = TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, static_cast<uint32_t>(depth.width)) &&
              TIFFSetField(tif, TIFFTAG_IMAGELENGTH, static_cast<uint32_t>(depth.height)) &&
              TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, uint16_t{32}) &&
              TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, uint16_t{1}) &&
              TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT, uint16_t{SAMPLEFORMAT_IEEEFP}) &&
              TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, uint16_t{PHOTOMETRIC_MINISBLACK}) &&
              TIFFSetField(tif, TIFFTAG_PLANARCONFIG, uint16_t{PLANARCONFIG_CONTIG}) &&
              TIFFSetField(tif, TIFFTAG_COMPRESSION, compression);
    if (ok && compression != COMPRESSION_NONE) {
      ok = TIFFSetField(tif, TIFFTAG_PREDICTOR, uint16_t{PREDICTOR_FLOATINGPOINT});
    }
    if (ok && options.tiled) {
      ok = TIFFSetField(tif, TIFFTAG_TILEWIDTH, static_cast<uint32_t>(options.tile_size_px)) &&
           TIFFSetField(tif, TIFFTAG_TILELENGTH, static_cast<uint32_t>(options.tile_size_px));
    } else if (ok) {
      ok = TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP,
                        static_cast<uint32_t>(std::min(options.rows_per_strip, depth.height)));
    }
    if (ok && options.nodata) ok = TIFFSetField(tif, kGdalNodataTag, NodataText(*options.nodata).c_str());
    if (!ok) fail("cannot set the TIFF tags", &f);
    const auto value = [&](int row, int col) {
      const float v = depth.at(row, col);
      return options.nodata && !IsValidDepth(v) ? *options.nodata : v;
    };
    if (options.tiled) {
      const int t = options.tile_size_px;
      std::vector<float> tile(static_cast<size_t>(t) * t);
      for (int y0 = 0; y0 < depth.height; y0 += t) {
        for (int x0 = 0; x0 < depth.width; x0 += t) {
          // Pixels beyond the image edge are padding (written as nodata, else 0).
          std::fill(tile.begin(), tile.end(), options.nodata ? *options.nodata : 0.0f);
          for (int r = 0; r < t && y0 + r < depth.height; ++r) {
            for (int c = 0; c < t && x0 + c < depth.width; ++c)
              tile[static_cast<size_t>(r) * t + c] = value(y0 + r, x0 + c);
          }
          const uint32_t index = TIFFComputeTile(tif, static_cast<uint32_t>(x0), static_cast<uint32_t>(y0), 0, 0);
          if (TIFFWriteEncodedTile(tif, index, tile.data(), static_cast<tmsize_t>(tile.size() * 4)) < 0) {
            fail("cannot write tile " + std::to_string(index), &f);
          }
        }
      }
    } else {
      const int rps = std::min(options.rows_per_strip, depth.height);
      std::vector<float> strip;
      for (int y0 = 0, s = 0; y0 < depth.height; y0 += rps, ++s) {
        const int rows = std::min(rps, depth.height - y0);
        strip.resize(static_cast<size_t>(rows) * depth.width);
        for (int r = 0; r < rows; ++r) {
          for (int c = 0; c < depth.width; ++c) strip[static_cast<size_t>(r) * depth.width + c] = value(y0 + r, c);
        }
        if (TIFFWriteEncodedStrip(tif, static_cast<uint32_t>(s), strip.data(),
                                  static_cast<tmsize_t>(strip.size() * 4)) < 0) {
          fail("cannot write strip " + std::to_string(s), &f);
        }
      }
    }
    if (!f.Close()) fail("write failed (disk full?)", &f);
  }
  try {
    CommitTemporaryFile(tmp, path);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

}  // namespace sacfuse
