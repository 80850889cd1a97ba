// COPC files (output.format copc) read by independent readers: tests/las_js/read_copc.mjs reads fused.copc.laz and
// the COPC tile files of `sacfuse run` on a simulated tiny block (crs EPSG:25832, tiled and untiled) with the npm
// package copc (copc.js), node by node from the hierarchy, to the records of the same run written as LAS; laz-perf
// and laz-rs decode them; DIR/tiles.vpc matches the tile files. Skips with a message when node or
// tests/las_js/node_modules is missing, except under CI (tests/support/las_js_readers.h).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/crs.h"
#include "io/crs_wkt.h"
#include "io/las_copy.h"
#include "io/las_reader.h"
#include "tests/support/las_js_readers.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;
using testing::las_js::DecodeLaz;
using testing::las_js::ExpectValid;
using testing::las_js::LasJsDir;
using testing::las_js::LasPointRecords;
using testing::las_js::SortedPointRecords;

class CopcJsRunTest : public testing::las_js::RunSuite {};

// Runs tests/las_js/read_copc.mjs on `copc`: the npm package copc (copc.js) walks the hierarchy from the info VLR's
// root page and decodes every node's chunk alone; returns its JSON (the records, node after node, are in
// <copc>.copc.bin).
json ReadWithCopcJs(const fs::path& copc) {
  const fs::path out = fs::path(copc).replace_extension(".copcjs.json");
  const fs::path err = fs::path(copc).replace_extension(".copcjs.err");
  const std::string cmd = "cd " + ShellQuote(LasJsDir()) + " && node read_copc.mjs " + ShellQuote(copc) + " " +
                          ShellQuote(copc) + " > " + ShellQuote(out) + " 2> " + ShellQuote(err);
  std::string ignored;
  EXPECT_EQ(RunCommand(cmd, &ignored), 0) << cmd << "\n" << testing::ReadFileBytes(err);
  std::ifstream in(out);
  return json::parse(in);
}

// Sorted records of a buffer of `length`-byte records.
std::string Sorted(const std::string& all, size_t length) {
  std::vector<std::string> records;
  for (size_t at = 0; at + length <= all.size(); at += length) records.push_back(all.substr(at, length));
  std::sort(records.begin(), records.end());
  std::string sorted;
  for (const std::string& r : records) sorted += r;
  return sorted;
}

// copc.js reads `copc` node by node: every node's points inside the node's cube, the nodes' points the header's
// count, and their records, in any order, those of `las` (the same run written as LAS; none: not compared);
// laz-rs decodes every node's chunk to the records copc.js (laz-perf's chunk decoder) decoded; laz-perf decodes the
// file front to back (chunk table, variable chunks) to the records our reader decodes. The laz-rs build inside
// @loaders.gl/las reads fixed-size chunks only: front to back it must fail, not misread (tests/las_js/laz_rs.mjs).
// `sacfuse validate` passes.
void ExpectCopcReadByIndependentReaders(const fs::path& copc, const fs::path* las) {
  SCOPED_TRACE(copc.string());
  LasHeader h;
  {
    LasReader reader(copc.string());
    h = reader.header();
  }
  const json seen = ReadWithCopcJs(copc);
  ASSERT_FALSE(seen.contains("error")) << seen.value("error", "");
  EXPECT_EQ(seen.at("count").get<uint64_t>(), h.point_count);
  EXPECT_EQ(seen.at("point_format").get<int>(), 7);
  EXPECT_EQ(seen.at("points_in_nodes").get<uint64_t>(), h.point_count);
  EXPECT_EQ(seen.at("wkt").get<std::string>(), h.Wkt());
  uint64_t outside = 0;
  for (const json& node : seen.at("nodes")) outside += node.at("outside").get<uint64_t>();
  EXPECT_EQ(outside, 0u) << "copc.js finds points outside their node's cube";
  const std::string nodes_records = testing::ReadFileBytes(copc.string() + ".copc.bin");
  EXPECT_EQ(nodes_records.size(), h.point_count * h.point_record_length);
  if (las != nullptr) {
    EXPECT_TRUE(Sorted(nodes_records, h.point_record_length) == SortedPointRecords(*las))
        << "copc.js's nodes do not hold the points of " << las->string();
  }
  EXPECT_TRUE(testing::ReadFileBytes(copc.string() + ".laz-rs-nodes.bin") == nodes_records)
      << "laz-rs decodes the nodes' chunks to other records than copc.js";
  const fs::path twin = fs::path(copc).replace_extension(".twin.las");
  CopyLasFile(copc.string(), twin.string(), /*compressed=*/false);
  const std::string file_order = LasPointRecords(twin);
  const json decoded = DecodeLaz(copc);
  const json& perf = decoded.at("decoders").at("laz-perf");
  ASSERT_FALSE(perf.contains("error")) << perf.value("error", "");
  EXPECT_TRUE(testing::ReadFileBytes(copc.string() + ".laz-perf.bin") == file_order);
  const json& rs = decoded.at("decoders").at("laz-rs");
  if (rs.contains("error")) {
    EXPECT_NE(rs.at("error").get<std::string>().find("Error decompressing points"), std::string::npos) << rs;
  } else {
    EXPECT_TRUE(testing::ReadFileBytes(copc.string() + ".laz-rs.bin") == file_order);
  }
  EXPECT_TRUE(Sorted(nodes_records, h.point_record_length) == SortedPointRecords(twin));
  ExpectValid(copc);
  std::printf("[ las_js   ] %s: copc.js walked %d hierarchy pages, %zu nodes, %ju points (levels %s); laz-rs "
              "decodes its chunks, laz-perf the file%s\n",
              copc.filename().c_str(), seen.at("pages").get<int>(), seen.at("nodes").size(),
              static_cast<uintmax_t>(h.point_count), seen.at("points_per_level").dump().c_str(),
              las != nullptr ? "; the same records as the LAS run" : "");
}

// output.format copc, tiled (30 m tiles) and untiled: DIR/fused.copc.laz holds, node by node as copc.js reads it,
// exactly the points of the same run written as LAS; the tiles are COPC files too, and DIR/tiles.vpc lists them
// with the counts, bounds and CRS our reader reads from each.
TEST_F(CopcJsRunTest, CopcRunsAreReadByCopcJsAsTheLasRuns) {
  REQUIRE_READER();
  std::string out;
  const std::string crs_wkt = ProjectCrsWkt("EPSG:25832", CrsWktDialect::kLas14);
  // The four runs share one superpixel cache (the same views, the same superpixels).
  const std::string cache = "fusion: {superpixel_cache_dir: " + (Dir() / "copc_superpixels").string() + "}\n";
  for (const bool tiled : {true, false}) {
    SCOPED_TRACE(tiled ? "tiled" : "untiled");
    const std::string tiling = cache + (tiled ? "tiling: {tile_size_m: 30}\n" : "");  // tiny fits: untiled
    const std::string copc_run = tiled ? "copc_tiled" : "copc_untiled", las_run = tiled ? "las_tiled" : "las_untiled";
    const fs::path copc_config = WriteConfig(copc_run, ", format: copc", tiling);
    const fs::path las_config = WriteConfig(las_run, ", format: las", tiling);
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(copc_config), &out), 0) << out;
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(las_config), &out), 0) << out;
    const fs::path las = Out(las_run) / "fused.las";
    ExpectCopcReadByIndependentReaders(Out(copc_run) / "fused.copc.laz", &las);
    EXPECT_FALSE(fs::exists(Out(copc_run) / "fused.laz"));
    if (!tiled) {
      EXPECT_FALSE(fs::exists(Out(copc_run) / "tiles.vpc"));
      continue;
    }
    // The tile index: one feature per tile file with points, as our reader reads the file.
    std::ifstream in(Out(copc_run) / "tiles.vpc");
    const json vpc = json::parse(in);
    ASSERT_EQ(vpc.at("type"), "FeatureCollection");
    size_t tile_files = 0;
    for (const auto& e : fs::directory_iterator(Out(copc_run) / "tiles")) {
      const std::string name = e.path().filename().string();
      tile_files += name.size() > 9 && name.compare(name.size() - 9, 9, ".copc.laz") == 0 ? 1 : 0;
    }
    ASSERT_EQ(vpc.at("features").size(), tile_files);
    uint64_t total = 0;
    for (const json& f : vpc.at("features")) {
      const std::string href = f.at("assets").at("data").at("href");
      ASSERT_EQ(href.rfind("./tiles/", 0), 0u) << href;
      const fs::path file = Out(copc_run) / href.substr(2);
      LasHeader h;
      {
        LasReader reader(file.string());
        h = reader.header();
      }
      const json& p = f.at("properties");
      EXPECT_EQ(p.at("pc:count").get<uint64_t>(), h.point_count) << href;
      EXPECT_EQ(p.at("proj:bbox").get<std::vector<double>>(),
                (std::vector<double>{h.min.x(), h.min.y(), h.min.z(), h.max.x(), h.max.y(), h.max.z()}));
      EXPECT_EQ(p.at("proj:wkt2").get<std::string>(), crs_wkt);
      EXPECT_EQ(p.at("proj:epsg").get<int>(), 25832);
      const std::vector<double> wgs84 = f.at("bbox");
      EXPECT_NEAR(wgs84[0], 7.43, 0.1);  // the tiny block lies at UTM 32N 390000 / 5705000: 7.4 E, 51.5 N
      EXPECT_NEAR(wgs84[1], 51.5, 0.1);
      total += h.point_count;
    }
    LasHeader fused;
    {
      LasReader reader((Out(copc_run) / "fused.copc.laz").string());
      fused = reader.header();
    }
    EXPECT_EQ(total, fused.point_count);
    // A tile file itself, as copc.js reads it.
    const std::string first = vpc.at("features")[0].at("assets").at("data").at("href");
    ExpectCopcReadByIndependentReaders(Out(copc_run) / first.substr(2), nullptr);
  }
}

}  // namespace
}  // namespace sacfuse
