// Our LAS and LAZ files read by independent readers: the npm package @loaders.gl/las (tests/las_js, installed by
// tools/install_deps.sh with `npm ci --prefix tests/las_js`). Files written by LasWriter (LAS 1.2 and 1.4, UTM-size
// coordinates, colours, source IDs, CRS records) and by `sacfuse run` on a simulated tiny block (crs EPSG:25832;
// LAS 1.4 tiled: tile files + merged fused.las; LAS 1.2 untiled) are read by tests/las_js/read_las.mjs and
// compared with what we wrote: count, header bounds, every coordinate (to half a scale step), 8-bit colours,
// point source IDs, the CRS record; each file must also pass `sacfuse validate`.
// Skips with a message when node or tests/las_js/node_modules is missing, except under CI (CI=true), where that
// is a failure: CI installs them (tests/support/las_js_readers.h). COPC files: tests/copc_js_reader_test.cc.
// LAZ (LasWriterOptions::compressed): tests/las_js/decode_laz.mjs decodes our LAZ files with laz-perf (npm, the
// LASzip C++ code in WASM) and laz-rs (the WASM build inside @loaders.gl/las); both must give, byte for byte, the
// point records of the LAS file written from the same points (every attribute), for point formats 0-3 (LAS 1.2
// and 1.4) and 6-8 (LAS 1.4), multi-chunk, empty and 1-point files; LAZRsLoader must read the same positions.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/crs.h"
#include "io/crs_wkt.h"
#include "io/las_copy.h"
#include "io/las_crs.h"
#include "io/las_reader.h"
#include "io/las_writer.h"
#include "io/wkt1.h"
#include "tests/support/las_js_readers.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;
using testing::TempDir;
using testing::las_js::DecodeLaz;
using testing::las_js::ExpectValid;
using testing::las_js::LasJsDir;
using testing::las_js::LasPointRecords;
using testing::las_js::SortedPointRecords;

// Runs tests/las_js/read_las.mjs on `las` and returns its JSON.
json ReadWithLoadersGl(const fs::path& las, size_t max_points) {
  const fs::path out = fs::path(las).replace_extension(".js.json");
  const fs::path err = fs::path(las).replace_extension(".js.err");
  const std::string cmd = "node " + ShellQuote(LasJsDir() / "read_las.mjs") + " " + ShellQuote(las) +
                          " --max-points " + std::to_string(max_points) + " > " + ShellQuote(out) + " 2> " +
                          ShellQuote(err);
  std::string ignored;
  const int rc = RunCommand(cmd, &ignored);
  EXPECT_EQ(rc, 0) << cmd << "\n" << testing::ReadFileBytes(err);
  std::ifstream in(out);
  return json::parse(in);
}

// What a comparison found; printed by the tests.
struct Comparison {
  size_t points_compared = 0;
  double max_coordinate_diff_steps = 0.0;  // in scale steps
};

// Compares one loader's view of `las` with our reader's (and, when given, with the points we meant to write).
Comparison CompareLoader(const json& seen, const fs::path& las, const std::vector<LasPoint>* written = nullptr) {
  LasHeader h;
  const std::vector<LasPoint> ours = ReadAllLasPoints(las.string(), &h);
  Comparison c;
  EXPECT_FALSE(seen.contains("error")) << seen.value("error", "");
  if (seen.contains("error")) return c;
  EXPECT_EQ(seen.at("count").get<uint64_t>(), ours.size());
  EXPECT_EQ(seen.at("point_format").get<int>(), h.point_format);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(seen.at("scale")[a].get<double>(), h.scale[a]);
    EXPECT_EQ(seen.at("offset")[a].get<double>(), h.offset[a]);
    EXPECT_EQ(seen.at("header_min")[a].get<double>(), h.min[a]);
    EXPECT_EQ(seen.at("header_max")[a].get<double>(), h.max[a]);
    // The box of the positions it decoded equals the header box (ours is made from the stored integers).
    EXPECT_NEAR(seen.at("bounding_box")[0][a].get<double>(), h.min[a], h.scale[a] / 2);
    EXPECT_NEAR(seen.at("bounding_box")[1][a].get<double>(), h.max[a], h.scale[a] / 2);
  }
  const size_t stride = seen.at("stride").get<size_t>();
  const json& xs = seen.at("x");
  const json& ys = seen.at("y");
  const json& zs = seen.at("z");
  const json& rgb = seen.at("rgb");
  EXPECT_EQ(xs.size(), (ours.size() + stride - 1) / stride);
  size_t bad = 0;
  for (size_t j = 0; j < xs.size() && j * stride < ours.size(); ++j) {
    const LasPoint& p = ours[j * stride];
    const double js[3] = {xs[j].get<double>(), ys[j].get<double>(), zs[j].get<double>()};
    for (int a = 0; a < 3; ++a) {
      // Against what our reader decodes (the same integers: expected identical) ...
      const double d = std::abs(js[a] - p.xyz[a]) / h.scale[a];
      c.max_coordinate_diff_steps = std::max(c.max_coordinate_diff_steps, d);
      if (d > 0.5 && bad++ < 5) ADD_FAILURE() << "point " << j * stride << " axis " << a << " off by " << d;
      // ... and against the coordinate we meant to write (within the rounding to the scale).
      if (written != nullptr) {
        const double dw = std::abs(js[a] - (*written)[j * stride].xyz[a]) / h.scale[a];
        if (dw > 0.5 + 1e-6 && bad++ < 5) ADD_FAILURE() << "point " << j * stride << " axis " << a << " off by " << dw;
      }
    }
    if (seen.at("has_color").get<bool>()) {
      for (int k = 0; k < 3; ++k) {
        if (rgb[j][k].get<int>() != p.rgb[k] / 256 && bad++ < 5) {
          ADD_FAILURE() << "point " << j * stride << " colour " << k << ": " << rgb[j][k] << " vs " << p.rgb[k] / 256;
        }
      }
    }
    ++c.points_compared;
  }
  EXPECT_EQ(bad, 0u);
  return c;
}

// Point source IDs and CRS records as the script read them.
void CompareRaw(const json& raw, const fs::path& las, const Crs& crs) {
  LasHeader h;
  const std::vector<LasPoint> ours = ReadAllLasPoints(las.string(), &h);
  const json& ids = raw.at("point_source_id");
  const size_t stride = ids.size() > 0 ? (ours.size() + ids.size() - 1) / ids.size() : 1;
  size_t bad = 0;
  for (size_t j = 0; j < ids.size() && j * stride < ours.size(); ++j) {
    if (ids[j].get<int>() != ours[j * stride].point_source_id && bad++ < 5) {
      ADD_FAILURE() << "point " << j * stride << " source ID " << ids[j] << " vs " << ours[j * stride].point_source_id;
    }
  }
  EXPECT_EQ(bad, 0u);
  const bool wkt_bit = (raw.at("global_encoding").get<int>() & 0x10) != 0;
  if (h.version_minor == 4) {
    EXPECT_EQ(wkt_bit, crs.georeferenced());
    if (crs.georeferenced()) {
      ASSERT_TRUE(raw.at("wkt").is_string());
      EXPECT_EQ(raw.at("wkt").get<std::string>(), ProjectCrsWkt(crs.text(), CrsWktDialect::kLas14));
      EXPECT_EQ(WktHorizontalEpsg(ParseWkt1(raw.at("wkt").get<std::string>())), crs.horizontal_epsg());
    }
    EXPECT_TRUE(raw.at("geokeys").is_null());
  } else {
    EXPECT_FALSE(wkt_bit);
    EXPECT_TRUE(raw.at("wkt").is_null());
    if (crs.kind() == Crs::Kind::kProjected) {
      const std::vector<int> keys = raw.at("geokeys").get<std::vector<int>>();
      bool found = false;
      for (size_t k = 4; k + 3 < keys.size(); k += 4) {
        found = found || (keys[k] == 3072 && keys[k + 1] == 0 && keys[k + 3] == crs.horizontal_epsg());
      }
      EXPECT_TRUE(found) << "no ProjectedCSTypeGeoKey = " << crs.horizontal_epsg();
      EXPECT_NE(raw.at("geo_ascii").get<std::string>().find(crs.Name()), std::string::npos);
    }
  }
}

std::vector<LasPoint> KnownPoints(size_t n) {
  std::vector<LasPoint> pts(n);
  for (size_t i = 0; i < n; ++i) {
    LasPoint& p = pts[i];
    // UTM zone 32 coordinates (Dortmund), spread over ~2 km so that all digits vary.
    p.xyz = {391234.567 + 1.731 * i + 0.0004 * (i % 3), 5706543.21 + 0.917 * i, 87.5 + 0.013 * (i % 997)};
    p.rgb = {static_cast<uint16_t>(256 * (i % 256)), static_cast<uint16_t>(256 * ((7 * i) % 256)),
             static_cast<uint16_t>(256 * ((13 * i + 5) % 256))};
    p.point_source_id = static_cast<uint16_t>(1 + (i * 37) % 65535);
  }
  return pts;
}

TEST(LasJsReaderTest, ReadsOurWriterFilesExactly) {
  REQUIRE_READER();
  TempDir dir;
  const Crs crs = ParseProjectCrs("EPSG:25832");
  const std::vector<LasPoint> pts = KnownPoints(1500);
  for (int minor : {2, 4}) {
    SCOPED_TRACE("LAS 1." + std::to_string(minor));
    const fs::path path = dir / ("ours_1" + std::to_string(minor) + ".las");
    LasWriterOptions o;
    o.version_minor = minor;
    AddCrsToLasOptions(crs, &o);
    {
      LasWriter w(path.string(), o);
      w.WritePoints(pts.data(), pts.size());
      w.Close();
    }
    const json seen = ReadWithLoadersGl(path, 100000);  // every point
    const Comparison c = CompareLoader(seen.at("loaders").at("laz-rs"), path, &pts);
    EXPECT_EQ(c.points_compared, pts.size());
    std::printf("[ las_js   ] %s: laz-rs read %zu points, max coordinate difference %.3g scale steps\n",
                path.filename().c_str(), c.points_compared, c.max_coordinate_diff_steps);
    const json& perf = seen.at("loaders").at("laz-perf");
    if (minor == 2) {
      CompareLoader(perf, path, &pts);
    } else {
      // The package's default loader (laz-perf) reads LAS <= 1.3 only: it must refuse, not misread.
      ASSERT_TRUE(perf.contains("error")) << "laz-perf read a LAS 1.4 file; compare it like laz-rs";
      std::printf("[ las_js   ] %s: laz-perf (the default LASLoader) refuses LAS 1.4: %s\n", path.filename().c_str(),
                  perf.at("error").get<std::string>().c_str());
    }
    CompareRaw(seen.at("raw"), path, crs);
    ExpectValid(path);
  }
}

// laz-perf and laz-rs decode `laz` to exactly `expected` (point records of its LAS twin).
void ExpectDecodersGive(const fs::path& laz, const std::string& expected) {
  const json seen = DecodeLaz(laz);
  for (const char* decoder : {"laz-perf", "laz-rs"}) {
    const json& d = seen.at("decoders").at(decoder);
    ASSERT_FALSE(d.contains("error")) << decoder << ": " << d.value("error", "");
    const std::string got = testing::ReadFileBytes(laz.string() + "." + decoder + ".bin");
    EXPECT_GT(got.size(), 0u) << decoder;
    EXPECT_EQ(got.size(), expected.size()) << decoder;
    EXPECT_TRUE(got == expected) << decoder << " decoded other records than the LAS twin's";
  }
}

TEST(LasJsReaderTest, LazPerfAndLazRsDecodeOurLazToTheLasRecords) {
  REQUIRE_READER();
  TempDir dir;
  struct Case {
    int minor, pdrf;
    size_t n;
  };
  const Case cases[] = {{2, 0, 1500}, {2, 1, 1500}, {2, 2, 1500}, {2, 3, 1500}, {4, 1, 1500}, {4, 6, 1500},
                        {4, 7, 1500}, {4, 8, 1500}, {2, 3, 120001}, {4, 7, 120001}, {2, 3, 0}, {4, 7, 0},
                        {2, 3, 1}, {4, 7, 1}, {4, 8, 1}};
  for (const Case& c : cases) {
    const std::string name = "f" + std::to_string(c.pdrf) + "_1" + std::to_string(c.minor) + "_" + std::to_string(c.n);
    SCOPED_TRACE(name);
    std::vector<LasPoint> pts = KnownPoints(c.n);
    for (size_t i = 0; i < pts.size(); ++i) {
      LasPoint& p = pts[i];
      p.intensity = static_cast<uint16_t>(i * 7);
      p.number_of_returns = static_cast<uint8_t>(1 + i % 5);
      p.return_number = static_cast<uint8_t>(1 + i % p.number_of_returns);
      p.classification = static_cast<uint8_t>(i % 19);
      p.scan_direction = i % 3 == 0;
      p.edge_of_flight_line = i % 17 == 0;
      p.scan_angle_deg = c.pdrf >= 6 ? 0.006f * static_cast<float>(i % 900) : static_cast<float>(i % 40) - 20.0f;
      p.user_data = static_cast<uint8_t>(i / 50);
      if (c.pdrf >= 6) p.scanner_channel = static_cast<uint8_t>((i / 100) % 4);
      if (c.pdrf >= 6) p.flags = static_cast<uint8_t>(i % 16);
      if (c.pdrf != 0 && c.pdrf != 2) p.gps_time = 271828.0 + 0.0001 * static_cast<double>(i / 2);
      if (c.pdrf == 0 || c.pdrf == 1 || c.pdrf == 6) p.rgb = {0, 0, 0};
      if (c.pdrf == 8) p.nir = static_cast<uint16_t>(i * 3);
    }
    for (bool compressed : {false, true}) {
      LasWriterOptions o;
      o.version_minor = c.minor;
      o.point_format = c.pdrf;
      o.compressed = compressed;
      LasWriter w((dir / (name + (compressed ? ".laz" : ".las"))).string(), o);
      w.WritePoints(pts.data(), pts.size());
      w.Close();
    }
    const fs::path laz = dir / (name + ".laz");
    const std::string expected = LasPointRecords(dir / (name + ".las"));
    const json seen = DecodeLaz(laz);
    for (const char* decoder : {"laz-perf", "laz-rs"}) {
      const json& d = seen.at("decoders").at(decoder);
      ASSERT_FALSE(d.contains("error")) << decoder << ": " << d.value("error", "");
      EXPECT_EQ(d.at("count").get<size_t>(), c.n) << decoder;
      EXPECT_EQ(d.at("point_format").get<int>(), c.pdrf) << decoder;
      const std::string got = testing::ReadFileBytes(laz.string() + "." + decoder + ".bin");
      EXPECT_EQ(got.size(), expected.size()) << decoder;
      EXPECT_TRUE(got == expected) << decoder << " decoded other records than the LAS twin's";
    }
    if (c.n == 1500 || c.n == 120001) {
      // And @loaders.gl/las' LAZRsLoader reads the positions and colours our reader reads.
      const Comparison cmp = CompareLoader(ReadWithLoadersGl(laz, 200000).at("loaders").at("laz-rs"), laz, &pts);
      EXPECT_EQ(cmp.points_compared, c.n);
    }
    std::printf("[ las_js   ] %s: laz-perf and laz-rs decode the %zu records of the LAS twin byte for byte (%ju -> %ju bytes)\n",
                laz.filename().c_str(), c.n, static_cast<uintmax_t>(fs::file_size(dir / (name + ".las"))),
                static_cast<uintmax_t>(fs::file_size(laz)));
  }
}

// A file whose chunks were copied from other LAZ files (LasWriter::AppendLaz, the tile merge) between chunks of
// points written before: laz-perf and laz-rs decode it to the records our reader decodes, for LAS 1.4 and 1.2.
TEST(LasJsReaderTest, LazPerfAndLazRsDecodeAFileOfCopiedChunks) {
  REQUIRE_READER();
  TempDir dir;
  for (int minor : {4, 2}) {
    SCOPED_TRACE(minor);
    LasWriterOptions o;
    o.version_minor = minor;
    o.compressed = true;
    o.offset = Eigen::Vector3d(391000, 5706000, 0);
    const std::vector<LasPoint> pts = KnownPoints(120001);
    const std::vector<LasPoint> head(pts.begin(), pts.begin() + 20001), rest(pts.begin() + 20001, pts.end());
    {
      LasWriter w((dir / "part.laz").string(), o);
      w.WritePoints(rest.data(), rest.size());  // 100,000 points: 2 full chunks
      w.Close();
    }
    const fs::path merged = dir / ("merged_1" + std::to_string(minor) + ".laz");
    {
      LasWriter w(merged.string(), o);
      w.WritePoints(head.data(), head.size());
      LasReader part((dir / "part.laz").string());
      ASSERT_TRUE(w.AppendLaz(part));
      w.WritePoints(head.data(), 999);
      w.Close();
    }
    const fs::path twin = dir / ("merged_1" + std::to_string(minor) + ".twin.las");
    CopyLasFile(merged.string(), twin.string(), /*compressed=*/false);
    EXPECT_EQ(ReadAllLasPoints(twin.string()).size(), 120001u + 999u);
    ExpectDecodersGive(merged, LasPointRecords(twin));
  }
}

class LasJsRunTest : public testing::las_js::RunSuite {
 protected:
  static void CheckFile(const fs::path& las, const Crs& crs, int minor) {
    SCOPED_TRACE(las.string());
    LasHeader h;
    {
      LasReader reader(las.string());
      h = reader.header();
    }
    EXPECT_EQ(h.version_minor, minor);
    EXPECT_EQ(ReadLasCrs(h).epsg, crs.horizontal_epsg());
    const json seen = ReadWithLoadersGl(las, 20000);
    const Comparison c = CompareLoader(seen.at("loaders").at("laz-rs"), las);
    if (minor == 2) CompareLoader(seen.at("loaders").at("laz-perf"), las);
    CompareRaw(seen.at("raw"), las, crs);
    ExpectValid(las);
    std::printf("[ las_js   ] %s (%llu points): laz-rs agrees on %zu sampled points, max difference %.3g steps\n",
                las.filename().c_str(), static_cast<unsigned long long>(h.point_count), c.points_compared,
                c.max_coordinate_diff_steps);
  }
};

TEST_F(LasJsRunTest, TiledLas14RunWithCrsIsReadByLoadersGl) {
  REQUIRE_READER();
  std::string out;
  const fs::path config = WriteConfig("run14", ", format: las", "tiling: {tile_size_m: 30}\n");
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &out), 0) << out;
  const Crs crs = ParseProjectCrs("EPSG:25832");
  CheckFile(Out("run14") / "fused.las", crs, 4);
  size_t tiles = 0;
  // Tile files are LAZ: their LAS twin (our reader's point-for-point copy) is read as fused.las is, and laz-perf
  // and laz-rs decode the tile to the twin's records.
  for (const auto& e : fs::directory_iterator(Out("run14") / "tiles")) {
    if (e.path().extension() != ".laz" || tiles++ >= 2) continue;
    const fs::path twin = Out("run14") / (e.path().stem().string() + ".twin.las");
    CopyLasFile(e.path().string(), twin.string(), /*compressed=*/false);
    CheckFile(twin, crs, 4);
    ExpectDecodersGive(e.path(), LasPointRecords(twin));
  }
  EXPECT_GT(tiles, 1u);
  // `sacfuse merge` again writes the same CRS.
  fs::remove(Out("run14") / "fused.las");
  ASSERT_EQ(RunCommand(SacfuseBinary() + " merge " + ShellQuote(config), &out), 0) << out;
  CheckFile(Out("run14") / "fused.las", crs, 4);
}

TEST_F(LasJsRunTest, Las12RunWithCrsIsReadByLoadersGl) {
  REQUIRE_READER();
  std::string out;
  const fs::path config = WriteConfig("run12", ", las_version: \"1.2\", format: las", "");
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &out), 0) << out;
  CheckFile(Out("run12") / "fused.las", ParseProjectCrs("EPSG:25832"), 2);
}

// The default output, DIR/fused.laz (tiled: merged from tiles), is decoded by laz-perf and laz-rs to exactly the
// point records of the same run written as LAS, for LAS 1.4 and 1.2.
TEST_F(LasJsRunTest, DefaultFusedLazDecodesToTheRecordsOfTheLasRun) {
  REQUIRE_READER();
  for (const char* version : {"1.4", "1.2"}) {
    SCOPED_TRACE(version);
    const std::string v = std::string(", las_version: \"") + version + "\"";
    const std::string laz_run = std::string("default_laz_") + version, las_run = std::string("as_las_") + version;
    std::string out;
    const fs::path laz_config = WriteConfig(laz_run, v, "tiling: {tile_size_m: 30}\n");
    const fs::path las_config = WriteConfig(las_run, v + ", format: las", "tiling: {tile_size_m: 30}\n");
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(laz_config), &out), 0) << out;
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(las_config), &out), 0) << out;
    const fs::path laz = Out(laz_run) / "fused.laz";
    ASSERT_TRUE(fs::exists(laz));
    EXPECT_FALSE(fs::exists(Out(laz_run) / "fused.las"));
    // The LAZ merge copies the tiles' full chunks (LasWriter::AppendLaz), so its point order differs from the
    // LAS merge's: the decoders give our reader's records, and those are the LAS run's points.
    const fs::path twin = Out(laz_run) / "fused.twin.las";
    CopyLasFile(laz.string(), twin.string(), /*compressed=*/false);
    ExpectDecodersGive(laz, LasPointRecords(twin));
    EXPECT_TRUE(SortedPointRecords(twin) == SortedPointRecords(Out(las_run) / "fused.las"));
    // Our own reader too (merge, eval, report and validate read it).
    EXPECT_EQ(ReadAllLasPoints(laz.string()).size(), ReadAllLasPoints((Out(las_run) / "fused.las").string()).size());
    std::printf("[ las_js   ] run LAS %s: fused.laz %ju bytes, fused.las %ju bytes; laz-perf and laz-rs agree\n",
                version, static_cast<uintmax_t>(fs::file_size(laz)),
                static_cast<uintmax_t>(fs::file_size(Out(las_run) / "fused.las")));
  }
}

}  // namespace
}  // namespace sacfuse
