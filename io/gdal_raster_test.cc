// Raster product files through GDAL (io/gdal_raster.h) and the assembly of a product block by block
// (io/raster_assembly.h): values, nodata, CRS and georeference read back; a mosaic reads across files; a COG built
// block by block equals the blocks; the VRT layout names its blocks relative to itself; no temporary file stays.
#include "io/gdal_raster.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/crs_wkt.h"
#include "io/raster_assembly.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

CellWindow Window(int64_t col0, int64_t row0, int64_t cols, int64_t rows, double cell = 0.25) {
  CellWindow w;
  w.cell_m = cell;
  w.col0 = col0;
  w.row0 = row0;
  w.cols = cols;
  w.rows = rows;
  return w;
}

std::vector<float> Ramp(const CellWindow& w) {
  std::vector<float> v(w.size());
  for (int64_t row = w.row0; row < w.row0 + w.rows; ++row) {
    for (int64_t col = w.col0; col < w.col0 + w.cols; ++col) v[w.Index(col, row)] = 100.0f + col + 0.001f * row;
  }
  return v;
}

size_t TemporaryFiles(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.path().string().find(".tmp") != std::string::npos;
  return n;
}

TEST(GdalRasterTest, IntermediateAndCogFilesReadBackWithTheirGeoreferenceNodataAndCrs) {
  testing::TempDir dir;
  const CellWindow w = Window(3082000, 25110200, 37, 23);  // UTM-sized coordinates, 0.25 m cells
  std::vector<float> v = Ramp(w);
  v[w.Index(w.col0 + 5, w.row0 + 7)] = kNan;
  RasterFormat format;
  format.nodata = kNan;
  format.crs_wkt = ProjectCrsWkt("EPSG:25832", CrsWktDialect::kGdal);
  for (const RasterLayout layout : {RasterLayout::kIntermediate, RasterLayout::kCog}) {
    const std::string path = (dir / (layout == RasterLayout::kCog ? "cog.tif" : "raw.tif")).string();
    WriteRasterFile(path, w, format, v.data(), layout);
    const RasterFile r(path);
    EXPECT_EQ(r.window(), w);
    EXPECT_DOUBLE_EQ(r.window().west(), 770500.0);
    ASSERT_TRUE(r.nodata().has_value());
    EXPECT_TRUE(std::isnan(*r.nodata()));
    EXPECT_NE(r.crs_wkt().find("25832"), std::string::npos) << r.crs_wkt();
    const std::vector<float> back = r.ReadFloat(w);
    for (size_t i = 0; i < v.size(); ++i) {
      ASSERT_TRUE((std::isnan(v[i]) && std::isnan(back[i])) || v[i] == back[i]) << i;
    }
    // A window reaching beyond the file: the outside reads as no value.
    const std::vector<float> wider = r.ReadFloat(w.Grown(2));
    EXPECT_TRUE(std::isnan(wider[0]));
    EXPECT_EQ(wider[w.Grown(2).Index(w.col0, w.row0)], v[w.Index(w.col0, w.row0)]);
  }
  EXPECT_EQ(TemporaryFiles(dir.path()), 0u);
}

TEST(GdalRasterTest, AssemblyIntoOneCogOrBlocksWithAVrtGivesTheSameCells) {
  testing::TempDir dir;
  const CellWindow extent = Window(-100, 50, 2300, 70, 1.0);  // blocks [-2048, 0), [0, 2048), [2048, 4096)
  const std::vector<float> raw = Ramp(extent);
  const RawCellReader read = [&](const CellWindow& w) {
    std::vector<float> out(w.size(), kNan);
    const CellWindow c = w.Intersection(extent);
    for (int64_t row = c.row0; row < c.row0 + c.rows; ++row) {
      for (int64_t col = c.col0; col < c.col0 + c.cols; ++col) out[w.Index(col, row)] = raw[extent.Index(col, row)];
    }
    return out;
  };
  // A finisher reading the halo: each cell becomes the mean of its west and east neighbours (where both exist).
  const CellFinisher finish = [](const std::vector<float>& r, const CellWindow& outer, const CellWindow& inner) {
    std::vector<float> out(inner.size(), kNan);
    for (int64_t row = inner.row0; row < inner.row0 + inner.rows; ++row) {
      for (int64_t col = inner.col0; col < inner.col0 + inner.cols; ++col) {
        out[inner.Index(col, row)] = 0.5f * (r[outer.Index(col - 1, row)] + r[outer.Index(col + 1, row)]);
      }
    }
    return out;
  };
  RasterFormat format;
  format.nodata = -9999.0;
  RasterOutput single;
  single.single_path = (dir / "dsm.tif").string();
  const AssemblyStats one = AssembleRaster(extent, 1, read, finish, format, single);
  EXPECT_EQ(one.blocks, 3u);
  RasterOutput blocks;
  blocks.blocks = true;
  blocks.blocks_dir = (dir / "dsm").string();
  blocks.vrt_path = (dir / "dsm.vrt").string();
  const AssemblyStats two = AssembleRaster(extent, 1, read, finish, format, blocks);
  EXPECT_EQ(two.files.size(), 4u);  // the VRT and three blocks
  const std::vector<float> a = RasterFile(single.single_path).ReadFloat(extent);
  const std::vector<float> b = RasterFile(blocks.vrt_path).ReadFloat(extent);
  ASSERT_EQ(a.size(), b.size());
  size_t nan = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE((std::isnan(a[i]) && std::isnan(b[i])) || a[i] == b[i]) << i;
    nan += std::isnan(a[i]);
  }
  EXPECT_EQ(nan, 2u * extent.rows);  // the western and eastern columns lack a neighbour
  EXPECT_FLOAT_EQ(a[extent.Index(500, 60)], 100.0f + 500 + 0.06f);
  // The VRT names its blocks relative to itself: the folder can move.
  fs::rename(dir / "dsm", dir / "moved_dsm_folder_is_not_found");
  fs::create_directories(dir / "elsewhere");
  fs::rename(dir / "moved_dsm_folder_is_not_found", dir / "elsewhere" / "dsm");
  fs::rename(dir / "dsm.vrt", dir / "elsewhere" / "dsm.vrt");
  EXPECT_EQ(RasterFile((dir / "elsewhere" / "dsm.vrt").string()).ReadFloat(extent).size(), a.size());
  EXPECT_EQ(TemporaryFiles(dir.path()), 0u);
}

// CogBuilder keeps a small raster's temporary GeoTIFF uncompressed and compresses a large one's: the COG's bytes
// (values, overviews, layout) are the same either way, and no temporary file stays.
TEST(GdalRasterTest, CogBytesDoNotDependOnHowTheTemporaryFileWasStored) {
  testing::TempDir dir;
  const CellWindow extent = Window(10, -20, 1100, 700, 0.5);  // overviews of 2 and 4 (their averages cascade)
  std::vector<float> values = Ramp(extent);
  for (size_t i = 0; i < values.size(); i += 7) values[i] = -9999.0f;  // nodata cells left out of the averages
  RasterFormat format;
  format.nodata = -9999.0;
  format.band_descriptions = {"height (m)"};
  const CellWindow west = Window(10, -20, 512, 700, 0.5), east = Window(522, -20, 588, 700, 0.5);
  const auto part = [&](const CellWindow& w) {
    std::vector<float> v(w.size());
    for (int64_t row = w.row0; row < w.row0 + w.rows; ++row) {
      for (int64_t col = w.col0; col < w.col0 + w.cols; ++col) v[w.Index(col, row)] = values[extent.Index(col, row)];
    }
    return v;
  };
  for (const uint64_t uncompressed_up_to : {kCogUncompressedBytes, uint64_t{0}}) {
    CogBuilder cog((dir / ("cog_" + std::to_string(uncompressed_up_to) + ".tif")).string(), extent, format,
                   uncompressed_up_to);
    cog.Write(west, part(west).data());
    cog.Write(east, part(east).data());
    cog.Finish();
  }
  const std::string uncompressed =
      testing::ReadFileBytes(dir / ("cog_" + std::to_string(kCogUncompressedBytes) + ".tif"));
  EXPECT_GT(uncompressed.size(), 1000u);
  EXPECT_TRUE(uncompressed == testing::ReadFileBytes(dir / "cog_0.tif"));
  EXPECT_EQ(TemporaryFiles(dir.path()), 0u);
}

TEST(GdalRasterTest, UnreadableAndMissingFilesAreInputErrors) {
  testing::TempDir dir;
  std::FILE* f = std::fopen((dir / "junk.tif").c_str(), "wb");
  std::fputs("not a tiff", f);
  std::fclose(f);
  EXPECT_THROW(RasterFile((dir / "junk.tif").string()), InputError);
  EXPECT_THROW(RasterFile((dir / "missing.tif").string()), InputError);
}

}  // namespace
}  // namespace sacfuse
