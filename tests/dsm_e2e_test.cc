// End-to-end: the DSM product on the simulated tiny block (crs EPSG:25832, so output.dsm: auto writes it).
// (a) an untiled run writes DIR/dsm.tif: GDAL's COG validator accepts it, GDAL's Python bindings (an independent
//     reader, test-time only) read the same cells, nodata and CRS as we do; run_report.json and eval.json carry
//     the DSM; the report shows its thumbnail;
// (b) a tiled run (20 m tiles, output.raster_layout: tiles, so DIR/dsm.vrt over COG blocks): its DSM equals
//     `sacfuse dsm` of its own fused.laz on the same extent cell for cell (the tiles' windows, their edge points
//     and the hole filling across them leave no seam); each tile's done marker covers its DSM files;
// (c) `sacfuse dsm` on a LAS takes the file's CRS, refuses bad arguments, and `sacfuse eval --dsm` scores a DSM;
// (d) the true orthophoto (output.ortho: auto, on with the DSM): DIR/ortho.tif on the DSM's cells, RGBA, read back
//     by GDAL's own gdalinfo (a reader independent of our code) as a COG with red, green, blue and alpha bands and
//     the CRS; scored by `sacfuse eval --ortho` against the simulator's reference ortho (simulate
//     --truth-ortho-cell) it covers more, has a higher PSNR and SSIM and sharper edges than the ortho of the
//     points' colours; the tiled run's ortho (VRT layout) agrees
//     with the untiled run's wherever their clouds give the cell the same height and view;
// (e) `sacfuse merge` of the tiled run's tiles on 1 and 4 threads writes the same DSM and ortho bytes as the run.
// The Python checks skip with a message when /usr/bin/python3 has no GDAL bindings (Debian's python3-gdal).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/gdal_raster.h"
#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::ReadJsonFile;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;

constexpr const char* kPython = "/usr/bin/python3";

bool PythonHasGdal() { return RunCommand(std::string(kPython) + " -c 'from osgeo import gdal' >/dev/null 2>&1") == 0; }

class DsmEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    SimulateBlock("--truth-ortho-cell 0.25");
    const double gsd = BlockGsd();
    for (const auto& [name, tiling, layout] : {std::tuple<std::string, double, std::string>{"untiled", 0.0, "auto"},
                                              {"tiled", 20.0, "tiles"}}) {
      std::ofstream(Config(name)) << "crs: \"EPSG:25832\"\n"
                                  << "input: {path: " << Block().string() << "}\n"
                                  << "output: {dir: " << Out(name).string() << ", raster_layout: " << layout << "}\n"
                                  << "tiling: {tile_size_m: " << tiling << ", halo_m: 5}\n"
                                  << "evaluation: {reference: " << (Block() / "reference.las").string()
                                  << ", mask: " << (Block() / "eval_mask.png").string() << ", gsd_m: " << gsd
                                  << "}\n";
    }
    for (const std::string name : {"untiled", "tiled"}) {
      std::string out;
      ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config(name)), &out), 0) << out;
    }
  }

  // The extent of a DSM as --extent for `sacfuse dsm`: the centres of its corner cells.
  static std::string ExtentArg(const CellWindow& w) {
    char buf[256];
    std::snprintf(buf, sizeof(buf), "%.6f,%.6f,%.6f,%.6f", w.west() + 0.5 * w.cell_m, w.south() + 0.5 * w.cell_m,
                  w.east() - 0.5 * w.cell_m, w.north() - 0.5 * w.cell_m);
    return buf;
  }
};

TEST_F(DsmEndToEndTest, UntiledRunWritesAValidCogThatGdalReadsLikeWeDo) {
  const fs::path dsm = Out("untiled") / "dsm.tif";
  ASSERT_TRUE(fs::exists(dsm));
  const RasterFile ours(dsm.string());
  const CellWindow w = ours.window();
  // The automatic cell: 2 x the GSD of the block's depth maps (0.175 m here, a little finer than the simulator's
  // nominal 0.2 m), rounded to 1, 2, 2.5 or 5 x 10^k: 0.25 m.
  EXPECT_DOUBLE_EQ(w.cell_m, 0.25);
  const nlohmann::json report = ReadJsonFile(Out("untiled") / "run_report.json");
  ASSERT_TRUE(report.contains("dsm")) << report.dump(2);
  EXPECT_DOUBLE_EQ(report.at("dsm").at("cell_m").get<double>(), w.cell_m);
  // Over the whole extent (the block's thinly seen margins included); inside the evaluation mask, below, nearly all.
  const double filled = report.at("dsm").at("cells_with_value").get<double>() / static_cast<double>(w.size());
  EXPECT_GT(filled, 0.6);
  const nlohmann::json eval = ReadJsonFile(Out("untiled") / "eval.json");
  ASSERT_TRUE(eval.contains("dsm")) << eval.dump(2);
  EXPECT_GT(eval.at("dsm").at("all").at("completeness").get<double>(), 0.95);
  EXPECT_LT(eval.at("dsm").at("all").at("nmad_m").get<double>(), 3 * BlockGsd());
  EXPECT_TRUE(fs::exists(Out("untiled") / "report" / "dsm.png"));
  EXPECT_NE(testing::ReadFileBytes(Out("untiled") / "report" / "index.html").find("dsm.png"), std::string::npos);

  if (!PythonHasGdal()) GTEST_SKIP() << kPython << " has no GDAL bindings (Debian: python3-gdal): COG validator and "
                                     << "independent reader not run";
  std::string out;
  // GDAL's COG validator on both rasters of the run: the DSM and the true orthophoto.
  for (const fs::path& raster : {fs::path(dsm), Out("untiled") / "ortho.tif"}) {
    const int code = RunCommand(std::string(kPython) + " -m osgeo_utils.samples.validate_cloud_optimized_geotiff " +
                                    ShellQuote(raster) + " 2>&1",
                                &out);
    EXPECT_EQ(code, 0) << raster << ": " << out;
    EXPECT_NE(out.find("is a valid cloud optimized GeoTIFF"), std::string::npos) << raster << ": " << out;
  }
  // GDAL's own reading: size, georeference, nodata, CRS (EPSG:25832), compression and predictor, tiles, overviews,
  // and every cell's value as a sum and count over the cells with a value.
  const fs::path script = Dir() / "read_dsm.py";
  std::ofstream(script) << "import json, sys\nfrom osgeo import gdal, osr\nimport numpy as np\n"
                           "d = gdal.Open(sys.argv[1]); b = d.GetRasterBand(1)\n"
                           "a = b.ReadAsArray().astype(np.float64); nd = b.GetNoDataValue()\n"
                           "ok = a != nd\n"
                           "s = osr.SpatialReference(wkt=d.GetProjection()); s.AutoIdentifyEPSG()\n"
                           "md = d.GetMetadata('IMAGE_STRUCTURE')\n"
                           "print(json.dumps({'size': [d.RasterXSize, d.RasterYSize], 'gt': d.GetGeoTransform(),\n"
                           "  'nodata': nd, 'epsg': s.GetAuthorityCode('PROJCS'), 'type': gdal.GetDataTypeName(b.DataType),\n"
                           "  'compression': md.get('COMPRESSION'), 'predictor': md.get('PREDICTOR'),\n"
                           "  'block': b.GetBlockSize(), 'overviews': b.GetOverviewCount(),\n"
                           "  'count': int(ok.sum()), 'sum': float(a[ok].sum())}))\n";
  ASSERT_EQ(RunCommand(std::string(kPython) + " " + ShellQuote(script) + " " + ShellQuote(dsm), &out), 0) << out;
  const nlohmann::json g = nlohmann::json::parse(out);
  EXPECT_EQ(g.at("size").at(0).get<int64_t>(), w.cols);
  EXPECT_EQ(g.at("size").at(1).get<int64_t>(), w.rows);
  EXPECT_DOUBLE_EQ(g.at("gt").at(0).get<double>(), w.west());
  EXPECT_DOUBLE_EQ(g.at("gt").at(3).get<double>(), w.north());
  EXPECT_DOUBLE_EQ(g.at("gt").at(1).get<double>(), w.cell_m);
  EXPECT_DOUBLE_EQ(g.at("gt").at(5).get<double>(), -w.cell_m);
  EXPECT_DOUBLE_EQ(g.at("nodata").get<double>(), -9999.0);
  EXPECT_EQ(g.at("epsg").get<std::string>(), "25832");
  EXPECT_EQ(g.at("type").get<std::string>(), "Float32");
  EXPECT_EQ(g.at("compression").get<std::string>(), "DEFLATE");
  EXPECT_EQ(g.at("predictor").get<std::string>(), "3");
  EXPECT_EQ(g.at("block").at(0).get<int>(), 512);
  const std::vector<float> v = ours.ReadFloat(w);
  double sum = 0;
  int64_t count = 0;
  for (const float x : v) {
    if (!std::isnan(x)) sum += x, ++count;
  }
  EXPECT_EQ(g.at("count").get<int64_t>(), count);
  EXPECT_NEAR(g.at("sum").get<double>(), sum, 1e-6 * std::abs(sum));
}

TEST_F(DsmEndToEndTest, TiledDsmEqualsTheDsmOfItsOwnCloudAndTheVrtLayoutHoldsTheSameCells) {
  ASSERT_TRUE(fs::exists(Out("tiled") / "dsm.vrt"));
  EXPECT_FALSE(fs::exists(Out("tiled") / "dsm.tif"));
  EXPECT_GE(testing::CountFilesNamedWith(Out("tiled") / "dsm", ".tif"), 1u);
  const RasterFile tiled((Out("tiled") / "dsm.vrt").string());
  const CellWindow w = tiled.window();
  const CellWindow untiled = RasterFile((Out("untiled") / "dsm.tif").string()).window();
  EXPECT_EQ(w.cell_m, untiled.cell_m);
  // One lattice, nearly one extent (the bounds of two slightly different clouds within the same project area).
  EXPECT_GT(w.Intersection(untiled).size(), 95 * std::min(w.size(), untiled.size()) / 100);
  std::string out;
  const fs::path regridded = Dir() / "regridded.tif";
  ASSERT_EQ(RunCommand(SacfuseBinary() + " dsm " + ShellQuote(Out("tiled") / "fused.laz") + " --cell " +
                           std::to_string(w.cell_m) + " --extent " + ExtentArg(w) + " --out " + ShellQuote(regridded),
                       &out),
            0)
      << out;
  const std::vector<float> a = tiled.ReadFloat(w);
  const RasterFile again(regridded.string());
  ASSERT_EQ(again.window(), w);
  const std::vector<float> b = again.ReadFloat(w);
  // Cell for cell, including the cells along tile edges that got points from two tiles (SAC's fused points may land
  // beyond their tile's core: the tiles' edge files and the recomputation at the assembly).
  size_t same = 0, with_value = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    same += (std::isnan(a[i]) && std::isnan(b[i])) || std::memcmp(&a[i], &b[i], sizeof(float)) == 0;
    with_value += !std::isnan(a[i]);
  }
  EXPECT_EQ(same, w.size()) << "of " << w.size() << " cells, " << with_value << " with a value";
  // Each tile's raw window is covered by its done marker.
  size_t with_dsm = 0, with_edge = 0;
  for (const auto& e : fs::directory_iterator(Out("tiled") / "tiles")) {
    const std::string name = e.path().filename().string();
    if (name.find(".done.json") == std::string::npos) continue;
    const nlohmann::json m = ReadJsonFile(e.path());
    for (const auto& p : m.value("products", nlohmann::json::array())) {
      with_dsm += p.at("suffix").get<std::string>() == "dsm.tif" ? 1 : 0;
      with_edge += p.at("suffix").get<std::string>() == "dsm_edge.bin" ? 1 : 0;
    }
  }
  EXPECT_GT(with_dsm, 4u);
  EXPECT_GT(with_edge, 0u);  // the tiny block's tiles do fuse points beyond their cores
}

// gdalinfo -json of a raster, or null when gdalinfo (Debian's gdal-bin) is absent.
nlohmann::json GdalInfo(const fs::path& path) {
  std::string out;
  if (RunCommand("gdalinfo -json " + ShellQuote(path) + " 2>/dev/null", &out) != 0) return nullptr;
  return nlohmann::json::parse(out, nullptr, false);
}

TEST_F(DsmEndToEndTest, UntiledRunWritesATrueOrthoOnTheDsmCells) {
  const fs::path ortho = Out("untiled") / "ortho.tif";
  ASSERT_TRUE(fs::exists(ortho));
  const RasterFile o(ortho.string());
  const RasterFile dsm((Out("untiled") / "dsm.tif").string());
  EXPECT_EQ(o.window(), dsm.window());
  EXPECT_EQ(o.bands(), 4);
  EXPECT_NE(o.crs_wkt().find("25832"), std::string::npos);
  const nlohmann::json report = ReadJsonFile(Out("untiled") / "run_report.json");
  ASSERT_TRUE(report.contains("ortho")) << report.dump(2);
  const nlohmann::json& r = report.at("ortho");
  // Coloured: nearly every cell with a height; mostly from the view SAC selected.
  const double with_height = report.at("dsm").at("cells_with_value").get<double>();
  EXPECT_GT(r.at("cells_coloured").get<double>(), 0.97 * with_height) << r.dump();
  EXPECT_GT(r.at("cells_selected_view").get<double>(), 0.8 * r.at("cells_coloured").get<double>()) << r.dump();
  EXPECT_GT(r.at("cells_other_view").get<uint64_t>(), 0u) << r.dump();  // occluded selections and filled holes
  // Alpha marks the coloured cells, and they are those the report counts.
  const std::vector<float> alpha = o.ReadFloat(o.window(), 4);
  uint64_t opaque = 0;
  for (const float a : alpha) opaque += a == 255.0f ? 1 : 0;
  EXPECT_EQ(opaque, r.at("cells_coloured").get<uint64_t>());
  EXPECT_TRUE(fs::exists(Out("untiled") / "report" / "ortho.png"));
  EXPECT_NE(testing::ReadFileBytes(Out("untiled") / "report" / "index.html").find("ortho.png"), std::string::npos);

  const nlohmann::json info = GdalInfo(ortho);
  if (info.is_null() || info.is_discarded()) GTEST_SKIP() << "gdalinfo (Debian: gdal-bin) absent: GDAL's reading not run";
  EXPECT_EQ(info.at("size").at(0).get<int64_t>(), o.window().cols);
  EXPECT_EQ(info.at("size").at(1).get<int64_t>(), o.window().rows);
  const nlohmann::json& bands = info.at("bands");
  ASSERT_EQ(bands.size(), 4u);
  const char* interp[] = {"Red", "Green", "Blue", "Alpha"};
  for (size_t b = 0; b < 4; ++b) {
    EXPECT_EQ(bands[b].at("type").get<std::string>(), "Byte");
    EXPECT_EQ(bands[b].at("colorInterpretation").get<std::string>(), interp[b]);
  }
  const nlohmann::json& structure = info.at("metadata").at("IMAGE_STRUCTURE");
  EXPECT_EQ(structure.value("LAYOUT", ""), "COG") << structure.dump();
  EXPECT_EQ(structure.value("COMPRESSION", ""), "DEFLATE") << structure.dump();
  EXPECT_NE(info.at("coordinateSystem").at("wkt").get<std::string>().find("25832"), std::string::npos);
  EXPECT_DOUBLE_EQ(info.at("geoTransform").at(0).get<double>(), o.window().west());
  EXPECT_DOUBLE_EQ(info.at("geoTransform").at(3).get<double>(), o.window().north());
}

// The scores `sacfuse eval --ortho` prints for one ortho: PSNR, SSIM, edge displacement median (cells).
struct PrintedOrthoScores {
  double coverage = 0, psnr = 0, ssim = 0, edge_median = 0, edge_p90 = 0, edge_mean = 0;
};
PrintedOrthoScores ParseOrthoLine(const std::string& out, const std::string& name) {
  PrintedOrthoScores s;
  const size_t at = out.find("  " + name + " ");
  if (at == std::string::npos) return s;
  unsigned long long cells = 0;
  std::sscanf(out.c_str() + at + 2 + name.size(), " %llu %lf%% %lf %lf %lf cells %*f m %lf cells %*f m %lf", &cells,
              &s.coverage, &s.psnr, &s.ssim, &s.edge_median, &s.edge_p90, &s.edge_mean);
  return s;
}

TEST_F(DsmEndToEndTest, TrueOrthoBeatsThePointColourOrthoAgainstTheSimulatorsReference) {
  ASSERT_TRUE(fs::exists(Block() / "truth_ortho.tif"));
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " eval " + ShellQuote(Out("untiled") / "fused.laz") + " --reference " +
                           ShellQuote(Block() / "reference.las") + " --gsd " + std::to_string(BlockGsd()) +
                           " --ortho " + ShellQuote(Out("untiled") / "ortho.tif") + " --ortho-reference " +
                           ShellQuote(Block() / "truth_ortho.tif"),
                       &out),
            0)
      << out;
  const PrintedOrthoScores ortho = ParseOrthoLine(out, "true ortho"), points = ParseOrthoLine(out, "point colours");
  // Measured on this block: coverage 98.8 % against 96.2 %, PSNR 23.8 against 22.9 dB, SSIM 0.842 against 0.836,
  // edge displacement median 0 against 1 cell, mean 0.50 against 0.58 cells (docs/dsm-and-ortho.md).
  EXPECT_GT(ortho.coverage, 97.0) << out;
  EXPECT_GT(ortho.coverage, points.coverage) << out;
  EXPECT_GT(ortho.psnr, points.psnr + 0.2) << out;
  EXPECT_GT(ortho.ssim, points.ssim) << out;
  EXPECT_LT(ortho.edge_mean, points.edge_mean) << out;
  EXPECT_LE(ortho.edge_median, points.edge_median) << out;
  EXPECT_LE(ortho.edge_p90, points.edge_p90) << out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " eval " + ShellQuote(Out("untiled") / "fused.laz") + " --reference " +
                           ShellQuote(Block() / "reference.las") + " --ortho " +
                           ShellQuote(Out("untiled") / "ortho.tif"),
                       &out),
            2)
      << out;
  EXPECT_NE(out.find("--ortho-reference"), std::string::npos) << out;
}

TEST_F(DsmEndToEndTest, TiledOrthoIsOnTheTiledDsmAndAgreesWithTheUntiledOne) {
  ASSERT_TRUE(fs::exists(Out("tiled") / "ortho.vrt"));
  EXPECT_FALSE(fs::exists(Out("tiled") / "ortho.tif"));
  const RasterFile tiled((Out("tiled") / "ortho.vrt").string());
  const RasterFile tiled_dsm((Out("tiled") / "dsm.vrt").string());
  EXPECT_EQ(tiled.window(), tiled_dsm.window());
  const RasterFile untiled((Out("untiled") / "ortho.tif").string());
  const RasterFile untiled_dsm((Out("untiled") / "dsm.tif").string());
  const CellWindow w = tiled.window().Intersection(untiled.window());
  // The two runs' clouds differ a little (SAC decides per tile with the tile's views), so their DSMs and selected
  // views do; where the two DSMs agree within 1 cm, the orthos show the same colours up to the choice of view.
  const std::vector<float> za = tiled_dsm.ReadFloat(w), zb = untiled_dsm.ReadFloat(w);
  std::vector<std::vector<float>> a, b;
  for (int band = 1; band <= 4; ++band) a.push_back(tiled.ReadFloat(w, band)), b.push_back(untiled.ReadFloat(w, band));
  uint64_t both = 0, same_height = 0, identical = 0, close = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    if (std::isnan(za[i]) || std::isnan(zb[i])) continue;
    ++both;
    if (std::abs(za[i] - zb[i]) > 0.01f) continue;
    ++same_height;
    bool same = true;
    double diff = 0;
    for (int band = 0; band < 4; ++band) {
      same = same && a[band][i] == b[band][i];
      if (band < 3) diff += std::abs(a[band][i] - b[band][i]) / 3.0;
    }
    identical += same ? 1 : 0;
    close += diff <= 16 ? 1 : 0;
  }
  EXPECT_GT(same_height, both / 4) << same_height << " of " << both;  // 37 % of the cells on this block
  EXPECT_GT(identical, 0.8 * same_height) << identical << " of " << same_height;
  EXPECT_GT(close, 0.95 * same_height) << close << " of " << same_height;
}

// The DSM and the ortho are made on the job's threads, and their bytes do not depend on how many: `sacfuse merge`
// of a copy of the tiled run's tiles on 1 thread writes the run's block files (made on every core) byte for byte,
// and on 1 and 4 threads into one COG each (output.raster_layout: single) the same dsm.tif and ortho.tif.
TEST_F(DsmEndToEndTest, DsmAndOrthoAreTheSameBytesOnAnyThreadCount) {
  const fs::path copy = Dir() / "threads";
  fs::copy(Out("tiled"), copy, fs::copy_options::recursive);
  const auto merge = [&](int threads, const std::string& layout) {
    std::string out;
    ASSERT_EQ(RunCommand(SacfuseBinary() + " merge " + ShellQuote(Config("tiled")) + " --output-dir " +
                             ShellQuote(copy) + " --set resources.threads=" + std::to_string(threads) +
                             " --set output.raster_layout=" + layout,
                         &out),
              0)
        << out;
  };
  merge(1, "tiles");
  size_t blocks = 0;
  for (const std::string product : {"dsm", "ortho"}) {
    for (const auto& e : fs::directory_iterator(Out("tiled") / product)) {
      const fs::path again = copy / product / e.path().filename();
      ASSERT_TRUE(fs::exists(again)) << again;
      EXPECT_TRUE(testing::ReadFileBytes(e.path()) == testing::ReadFileBytes(again)) << again;
      ++blocks;
    }
  }
  EXPECT_GE(blocks, 2u);
  std::vector<std::string> one_thread;
  for (const int threads : {1, 4}) {
    merge(threads, "single");
    std::vector<std::string> files;
    for (const std::string name : {"dsm.tif", "ortho.tif"}) files.push_back(testing::ReadFileBytes(copy / name));
    if (threads == 1) {
      one_thread = files;
    } else {
      EXPECT_TRUE(files == one_thread) << "dsm.tif or ortho.tif differs between 1 and 4 threads";
    }
  }
}

TEST_F(DsmEndToEndTest, DsmCommandTakesTheLasCrsAndEvalScoresADsm) {
  std::string out;
  const fs::path dsm = Dir() / "cmd.tif";
  ASSERT_EQ(RunCommand(SacfuseBinary() + " dsm " + ShellQuote(Out("untiled") / "fused.laz") + " --cell 0.5 --out " +
                           ShellQuote(dsm),
                       &out),
            0)
      << out;
  EXPECT_NE(out.find("cells of 0.5 m"), std::string::npos) << out;
  const RasterFile r(dsm.string());
  EXPECT_DOUBLE_EQ(r.window().cell_m, 0.5);
  EXPECT_NE(r.crs_wkt().find("25832"), std::string::npos);
  ASSERT_EQ(RunCommand(SacfuseBinary() + " eval " + ShellQuote(Out("untiled") / "fused.laz") + " --reference " +
                           ShellQuote(Block() / "reference.las") + " --mask " + ShellQuote(Block() / "eval_mask.png") +
                           " --gsd " + std::to_string(BlockGsd()) + " --dsm " + ShellQuote(dsm) + " --json " +
                           ShellQuote(Dir() / "eval_cmd.json"),
                       &out),
            0)
      << out;
  EXPECT_NE(out.find("NMAD"), std::string::npos) << out;
  EXPECT_DOUBLE_EQ(ReadJsonFile(Dir() / "eval_cmd.json").at("dsm").at("cell_m").get<double>(), 0.5);
  // Bad arguments: exit 2 naming the option.
  EXPECT_EQ(RunCommand(SacfuseBinary() + " dsm " + ShellQuote(Out("untiled") / "fused.laz") + " --cell -1 --out " +
                           ShellQuote(Dir() / "x.tif"),
                       &out),
            2);
  EXPECT_NE(out.find("--cell"), std::string::npos) << out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " dsm " + ShellQuote(Block() / "metadata.json") + " --cell 1 --out " +
                           ShellQuote(Dir() / "x.tif"),
                       &out),
            1);
  EXPECT_NE(out.find("not a LAS, LAZ or PLY"), std::string::npos) << out;
}

}  // namespace
}  // namespace sacfuse
