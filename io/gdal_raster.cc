#include "io/gdal_raster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <mutex>

#include <gdal_priv.h>
#include <gdal_utils.h>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "io/atomic_file.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

constexpr float kMissing = std::numeric_limits<float>::quiet_NaN();

void CPL_STDCALL LogGdalMessage(CPLErr level, CPLErrorNum, const char* message) {
  if (level == CE_Warning) spdlog::debug("GDAL: {}", message);
}

// GDAL's drivers, a bounded block cache, no .aux.xml side files, GDAL's messages into our log (errors are
// turned into exceptions where they happen).
void InitGdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    if (GDALGetCacheMax64() > kGdalCacheBytes) GDALSetCacheMax64(kGdalCacheBytes);
    CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");
    CPLSetErrorHandler(LogGdalMessage);
  });
}

std::string LastGdalError() {
  const char* m = CPLGetLastErrorMsg();
  return (m != nullptr && *m != '\0') ? std::string(m) : std::string("GDAL reported no reason");
}

GDALDataType GdalType(RasterSampleType type) {
  return type == RasterSampleType::kFloat32 ? GDT_Float32 : GDT_Byte;
}

struct DatasetCloser {
  void operator()(GDALDataset* d) const {
    if (d != nullptr) GDALClose(GDALDataset::ToHandle(d));
  }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

// Closes a dataset written to `path` and reports GDAL's errors of the close (the last blocks are flushed there).
void CloseWritten(DatasetPtr* dataset, const std::string& path) {
  CPLErrorReset();
  GDALDataset* d = dataset->release();
  if (d == nullptr) return;
  GDALClose(GDALDataset::ToHandle(d));  // void in GDAL 3.6: errors of the final flush are in the error state
  if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal) {
    throw Error(path + ": GDAL could not finish the file: " + LastGdalError());
  }
}

class CslOptions {
 public:
  CslOptions(std::initializer_list<std::pair<const char*, std::string>> items) {
    for (const auto& [key, value] : items) list_ = CSLSetNameValue(list_, key, value.c_str());
  }
  ~CslOptions() { CSLDestroy(list_); }
  void Set(const char* key, const std::string& value) { list_ = CSLSetNameValue(list_, key, value.c_str()); }
  CslOptions(const CslOptions&) = delete;
  CslOptions& operator=(const CslOptions&) = delete;
  char** get() const { return list_; }

 private:
  char** list_ = nullptr;
};

// GDAL's compression threads for a file written now: the job's thread count (resources.threads caps TBB's
// parallelism, jobs/thread_limit.h). GDAL compresses the tiles in parallel and writes them in order, so the file's
// bytes do not depend on the count.
std::string CompressionThreads() {
  return std::to_string(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

std::string Predictor(RasterSampleType type) { return type == RasterSampleType::kFloat32 ? "3" : "2"; }

// GeoTIFF creation options of an RGBA product: RGB photometric with an unassociated alpha sample.
void AddColourOptions(const RasterFormat& format, CslOptions* options) {
  if (!format.rgba || format.bands != 4) return;
  options->Set("PHOTOMETRIC", "RGB");
  options->Set("ALPHA", "YES");
}

void Describe(GDALDataset& d, const CellWindow& window, const RasterFormat& format, const std::string& path) {
  std::array<double, 6> gt = {window.west(), window.cell_m, 0.0, window.north(), 0.0, -window.cell_m};
  if (d.SetGeoTransform(gt.data()) != CE_None) throw Error(path + ": cannot set the geotransform: " + LastGdalError());
  if (!format.crs_wkt.empty()) {
    OGRSpatialReference srs;
    if (srs.importFromWkt(format.crs_wkt.c_str()) != OGRERR_NONE) {
      throw Error(path + ": GDAL cannot read the CRS WKT: " + format.crs_wkt);
    }
    if (d.SetSpatialRef(&srs) != CE_None) throw Error(path + ": cannot set the CRS: " + LastGdalError());
  }
  for (int b = 1; b <= format.bands; ++b) {
    GDALRasterBand* band = d.GetRasterBand(b);
    if (format.nodata) band->SetNoDataValue(*format.nodata);
    if (static_cast<size_t>(b) <= format.band_descriptions.size()) {
      band->SetDescription(format.band_descriptions[b - 1].c_str());
    }
    if (format.rgba && format.bands == 4) {
      static constexpr GDALColorInterp kRgba[4] = {GCI_RedBand, GCI_GreenBand, GCI_BlueBand, GCI_AlphaBand};
      band->SetColorInterpretation(kRgba[b - 1]);
    }
  }
}

void WriteBands(GDALDataset& d, int x, int y, const CellWindow& window, const RasterFormat& format, const void* data,
                const std::string& path) {
  const size_t band_bytes = window.size() * SampleBytes(format.type);
  for (int b = 1; b <= format.bands; ++b) {
    void* band_data = const_cast<char*>(static_cast<const char*>(data) + (b - 1) * band_bytes);
    if (d.GetRasterBand(b)->RasterIO(GF_Write, x, y, static_cast<int>(window.cols), static_cast<int>(window.rows),
                                     band_data, static_cast<int>(window.cols), static_cast<int>(window.rows),
                                     GdalType(format.type), 0, 0, nullptr) != CE_None) {
      throw Error(path + ": cannot write band " + std::to_string(b) + ": " + LastGdalError());
    }
  }
}

void CheckSize(const CellWindow& window, const std::string& path) {
  if (window.empty() || window.cols > (int64_t{1} << 30) || window.rows > (int64_t{1} << 30)) {
    throw Error(path + ": raster of " + std::to_string(window.cols) + " x " + std::to_string(window.rows) +
                " cells cannot be written");
  }
}

// Overview factors of a raster: halving until its longer side fits one 512 tile (the COG driver's own rule).
std::vector<int> OverviewFactors(const CellWindow& window) {
  std::vector<int> factors;
  for (int64_t f = 2, side = std::max(window.cols, window.rows); side > 512; f *= 2) {
    factors.push_back(static_cast<int>(f));
    side = (side + 1) / 2;
  }
  return factors;
}

void BuildOverviews(GDALDataset& d, const CellWindow& window, const RasterFormat& format, const std::string& path) {
  std::vector<int> factors = OverviewFactors(window);
  if (factors.empty()) return;
  if (d.BuildOverviews(format.overview_resampling.c_str(), static_cast<int>(factors.size()), factors.data(), 0,
                       nullptr, nullptr, nullptr) != CE_None) {
    throw Error(path + ": cannot build overviews: " + LastGdalError());
  }
}

// The COG at `path` from `source` (whose overviews exist), through a temporary name.
void CopyToCog(GDALDataset& source, const RasterFormat& format, const std::string& path) {
  GDALDriver* cog = GetGDALDriverManager()->GetDriverByName("COG");
  if (cog == nullptr) throw Error(path + ": this GDAL has no COG driver (GDAL >= 3.1 is needed)");
  const CslOptions options{{"COMPRESS", "DEFLATE"},  {"PREDICTOR", "YES"},      {"BLOCKSIZE", "512"},
                           {"OVERVIEWS", "AUTO"},    {"BIGTIFF", "IF_SAFER"},   {"NUM_THREADS", CompressionThreads()},
                           {"RESAMPLING", format.overview_resampling}};
  const std::string temp = TemporaryPathFor(path);
  CPLErrorReset();
  DatasetPtr out(cog->CreateCopy(temp.c_str(), &source, FALSE, options.get(), nullptr, nullptr));
  try {
    if (!out) throw Error(path + ": GDAL's COG driver failed: " + LastGdalError());
    CloseWritten(&out, path);
    CommitTemporaryFile(temp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw;
  }
}

}  // namespace

size_t SampleBytes(RasterSampleType type) { return type == RasterSampleType::kFloat32 ? 4 : 1; }

void WriteRasterFile(const std::string& path, const CellWindow& window, const RasterFormat& format, const void* data,
                     RasterLayout layout) {
  InitGdal();
  CheckSize(window, path);
  if (!fs::path(path).parent_path().empty()) fs::create_directories(fs::path(path).parent_path());
  const int cols = static_cast<int>(window.cols), rows = static_cast<int>(window.rows);
  if (layout == RasterLayout::kCog) {
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    DatasetPtr d(mem->Create("", cols, rows, format.bands, GdalType(format.type), nullptr));
    if (!d) throw Error(path + ": cannot make an in-memory raster: " + LastGdalError());
    Describe(*d, window, format, path);
    WriteBands(*d, 0, 0, window, format, data, path);
    BuildOverviews(*d, window, format, path);
    CopyToCog(*d, format, path);
    return;
  }
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  CslOptions options{{"TILED", "YES"},       {"BLOCKXSIZE", "256"},
                           {"BLOCKYSIZE", "256"},  {"COMPRESS", "DEFLATE"},
                           {"PREDICTOR", Predictor(format.type)}, {"BIGTIFF", "IF_SAFER"},
                           {"NUM_THREADS", CompressionThreads()}};
  AddColourOptions(format, &options);
  const std::string temp = TemporaryPathFor(path);
  try {
    CPLErrorReset();
    DatasetPtr d(gtiff->Create(temp.c_str(), cols, rows, format.bands, GdalType(format.type), options.get()));
    if (!d) throw Error(path + ": GDAL cannot create it: " + LastGdalError());
    Describe(*d, window, format, path);
    WriteBands(*d, 0, 0, window, format, data, path);
    CloseWritten(&d, path);
    CommitTemporaryFile(temp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw;
  }
}

// ----------------------------------------------------------------------------------------------- CogBuilder

struct CogBuilder::Impl {
  std::string path, temp;
  CellWindow extent;
  RasterFormat format;
  DatasetPtr dataset;
  bool finished = false;
};

CogBuilder::CogBuilder(const std::string& path, const CellWindow& extent, const RasterFormat& format,
                       uint64_t uncompressed_temp_bytes)
    : impl_(std::make_unique<Impl>()) {
  InitGdal();
  CheckSize(extent, path);
  impl_->path = path;
  impl_->temp = TemporaryPathFor(path);
  impl_->extent = extent;
  impl_->format = format;
  if (!fs::path(path).parent_path().empty()) fs::create_directories(fs::path(path).parent_path());
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  // This file lives only until the COG is written: uncompressed when small (no pass that compresses it and one
  // that decompresses it again before the COG is coded: on one thread while GDAL's compression threads waited),
  // else fast compression.
  CslOptions options{{"TILED", "YES"},        {"BLOCKXSIZE", "512"},   {"BLOCKYSIZE", "512"},
                     {"BIGTIFF", "IF_SAFER"}, {"SPARSE_OK", "TRUE"}};
  if (extent.size() * SampleBytes(format.type) * static_cast<uint64_t>(format.bands) > uncompressed_temp_bytes) {
    options.Set("COMPRESS", "DEFLATE");
    options.Set("ZLEVEL", "1");
    options.Set("PREDICTOR", Predictor(format.type));
    options.Set("NUM_THREADS", CompressionThreads());
  }
  AddColourOptions(format, &options);
  CPLErrorReset();
  impl_->dataset.reset(gtiff->Create(impl_->temp.c_str(), static_cast<int>(extent.cols), static_cast<int>(extent.rows),
                                     format.bands, GdalType(format.type), options.get()));
  if (!impl_->dataset) throw Error(path + ": GDAL cannot create " + impl_->temp + ": " + LastGdalError());
  Describe(*impl_->dataset, extent, format, path);
  // Cells no block writes read as nodata (a sparse file's missing tiles read as the nodata value).
}

CogBuilder::~CogBuilder() {
  if (impl_ && !impl_->finished) {
    impl_->dataset.reset();
    std::error_code ec;
    fs::remove(impl_->temp, ec);
  }
}

void CogBuilder::Write(const CellWindow& block, const void* data) {
  if (block.Intersection(impl_->extent) != block) throw Error(impl_->path + ": block outside the raster's extent");
  WriteBands(*impl_->dataset, static_cast<int>(block.XOffsetIn(impl_->extent)),
             static_cast<int>(block.YOffsetIn(impl_->extent)), block, impl_->format, data, impl_->path);
}

void CogBuilder::Finish() {
  try {
    BuildOverviews(*impl_->dataset, impl_->extent, impl_->format, impl_->path);
    CPLErrorReset();
    impl_->dataset->FlushCache(false);
    if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal) {
      throw Error(impl_->path + ": cannot flush " + impl_->temp + ": " + LastGdalError());
    }
    CopyToCog(*impl_->dataset, impl_->format, impl_->path);
  } catch (...) {
    impl_->dataset.reset();
    std::error_code ec;
    fs::remove(impl_->temp, ec);
    impl_->finished = true;
    throw;
  }
  impl_->dataset.reset();
  std::error_code ec;
  fs::remove(impl_->temp, ec);
  impl_->finished = true;
}

// ----------------------------------------------------------------------------------------------- RasterFile

struct RasterFile::Impl {
  std::string path;
  DatasetPtr dataset;
  CellWindow window;
};

namespace {

CellWindow LatticeWindow(GDALDataset& d, const std::string& path, bool lattice) {
  std::array<double, 6> gt{};
  if (d.GetGeoTransform(gt.data()) != CE_None) throw InputError(path, "the raster has no geotransform");
  if (gt[2] != 0.0 || gt[4] != 0.0) throw InputError(path, "rotated rasters are not supported");
  const double cell = gt[1];
  if (!(cell > 0) || std::abs(-gt[5] - cell) > 1e-9 * cell) {
    throw InputError(path, "the raster's cells are not square and north-up (pixel size " + std::to_string(gt[1]) +
                               " x " + std::to_string(gt[5]) + ")");
  }
  CellWindow w;
  w.cell_m = cell;
  w.cols = d.GetRasterXSize();
  w.rows = d.GetRasterYSize();
  const double c = gt[0] / cell, n = gt[3] / cell;
  w.col0 = static_cast<int64_t>(std::llround(c));
  const int64_t north = static_cast<int64_t>(std::llround(n));
  if (lattice && (std::abs(c - static_cast<double>(w.col0)) > 1e-6 || std::abs(n - static_cast<double>(north)) > 1e-6)) {
    throw InputError(path, "the raster's origin is not on a multiple of its cell size");
  }
  if (!lattice) {
    w.col0 = CellIndexOf(gt[0] + 0.5 * cell, cell);
    w.row0 = CellIndexOf(gt[3] - 0.5 * cell, cell) - w.rows + 1;
    return w;
  }
  w.row0 = north - w.rows;
  return w;
}

}  // namespace

RasterFile::RasterFile(const std::string& path, bool lattice) : impl_(std::make_unique<Impl>()) {
  InitGdal();
  impl_->path = path;
  CPLErrorReset();
  impl_->dataset.reset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!impl_->dataset) throw InputError(path, "GDAL cannot open it as a raster: " + LastGdalError());
  impl_->window = LatticeWindow(*impl_->dataset, path, lattice);
}

RasterFile::~RasterFile() = default;
RasterFile::RasterFile(RasterFile&&) noexcept = default;
RasterFile& RasterFile::operator=(RasterFile&&) noexcept = default;

const std::string& RasterFile::path() const { return impl_->path; }
const CellWindow& RasterFile::window() const { return impl_->window; }
int RasterFile::bands() const { return impl_->dataset->GetRasterCount(); }

std::optional<double> RasterFile::nodata(int band) const {
  int has = 0;
  const double v = impl_->dataset->GetRasterBand(band)->GetNoDataValue(&has);
  return has ? std::optional<double>(v) : std::nullopt;
}

std::string RasterFile::crs_wkt() const {
  const OGRSpatialReference* srs = impl_->dataset->GetSpatialRef();
  if (srs == nullptr) return "";
  char* wkt = nullptr;
  srs->exportToWkt(&wkt);
  std::string out = wkt != nullptr ? wkt : "";
  CPLFree(wkt);
  return out;
}

std::vector<float> RasterFile::ReadFloat(const CellWindow& w, int band) const {
  std::vector<float> out(w.size(), kMissing);
  if (band < 1 || band > bands()) throw InputError(impl_->path, "has no band " + std::to_string(band));
  if (std::abs(w.cell_m - impl_->window.cell_m) > 1e-9 * w.cell_m) {
    throw InputError(impl_->path, "cell size " + std::to_string(impl_->window.cell_m) + " m, not the " +
                                      std::to_string(w.cell_m) + " m asked for");
  }
  CellWindow file = impl_->window;
  file.cell_m = w.cell_m;
  const CellWindow common = w.Intersection(file);
  if (common.empty()) return out;
  std::vector<float> buffer(common.size());
  CPLErrorReset();
  if (impl_->dataset->GetRasterBand(band)->RasterIO(
          GF_Read, static_cast<int>(common.XOffsetIn(file)), static_cast<int>(common.YOffsetIn(file)),
          static_cast<int>(common.cols), static_cast<int>(common.rows), buffer.data(), static_cast<int>(common.cols),
          static_cast<int>(common.rows), GDT_Float32, 0, 0, nullptr) != CE_None) {
    throw InputError(impl_->path, "cannot read band " + std::to_string(band) + ": " + LastGdalError());
  }
  const std::optional<double> nd = nodata(band);
  const float nd_value = nd ? static_cast<float>(*nd) : 0.0f;
  const int64_t x0 = common.XOffsetIn(w), y0 = common.YOffsetIn(w);
  for (int64_t r = 0; r < common.rows; ++r) {
    for (int64_t c = 0; c < common.cols; ++c) {
      const float v = buffer[static_cast<size_t>(r * common.cols + c)];
      const bool missing = !std::isfinite(v) || (nd && v == nd_value);
      out[static_cast<size_t>((y0 + r) * w.cols + x0 + c)] = missing ? kMissing : v;
    }
  }
  return out;
}

std::vector<float> RasterFile::ReadOverview(int max_side, int* cols, int* rows, int band) const {
  const int64_t side = std::max(impl_->window.cols, impl_->window.rows);
  const double scale = side > max_side ? static_cast<double>(max_side) / static_cast<double>(side) : 1.0;
  *cols = std::max(1, static_cast<int>(std::lround(static_cast<double>(impl_->window.cols) * scale)));
  *rows = std::max(1, static_cast<int>(std::lround(static_cast<double>(impl_->window.rows) * scale)));
  std::vector<float> out(static_cast<size_t>(*cols) * static_cast<size_t>(*rows));
  GDALRasterIOExtraArg extra;
  INIT_RASTERIO_EXTRA_ARG(extra);
  extra.eResampleAlg = GRIORA_Average;
  CPLErrorReset();
  if (impl_->dataset->GetRasterBand(band)->RasterIO(GF_Read, 0, 0, static_cast<int>(impl_->window.cols),
                                                    static_cast<int>(impl_->window.rows), out.data(), *cols, *rows,
                                                    GDT_Float32, 0, 0, &extra) != CE_None) {
    throw InputError(impl_->path, "cannot read an overview: " + LastGdalError());
  }
  const std::optional<double> nd = nodata(band);
  for (float& v : out) {
    if (!std::isfinite(v) || (nd && v == static_cast<float>(*nd))) v = kMissing;
  }
  return out;
}

void WriteVrt(const std::string& vrt_path, const std::vector<std::string>& sources) {
  InitGdal();
  if (sources.empty()) throw Error(vrt_path + ": a VRT needs at least one source raster");
  std::vector<std::string> absolute;
  for (const std::string& s : sources) absolute.push_back(fs::absolute(s).lexically_normal().string());
  std::vector<const char*> names;
  for (const std::string& s : absolute) names.push_back(s.c_str());
  const std::string final_path = fs::absolute(vrt_path).lexically_normal().string();
  const std::string temp = TemporaryPathFor(final_path);
  CPLErrorReset();
  GDALBuildVRTOptions* options = GDALBuildVRTOptionsNew(nullptr, nullptr);
  int usage_error = 0;
  GDALDatasetH vrt =
      GDALBuildVRT(temp.c_str(), static_cast<int>(names.size()), nullptr, names.data(), options, &usage_error);
  GDALBuildVRTOptionsFree(options);
  try {
    if (vrt == nullptr) throw Error(vrt_path + ": GDAL cannot build the VRT: " + LastGdalError());
    DatasetPtr d(GDALDataset::FromHandle(vrt));
    CloseWritten(&d, vrt_path);
    CommitTemporaryFile(temp, final_path);
  } catch (...) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw;
  }
}

}  // namespace sacfuse
