// End-to-end: "never stale, never lost" (issue 14), on copies of the tiny block (each case changes its own copy).
// Stale inputs: after a depth map, an image or a pose changes, a rerun recomputes exactly the superpixels of the
// changed views and exactly the tiles whose windows read them, logs which views changed and why, and ends
// byte-identical (but the LAS creation date) to a fresh run in a new folder. Never lost: a run failing mid-way
// leaves the previous fused cloud byte for byte and run_state.json "failed" (`sacfuse status` exits 1 and says
// so); temporary files of killed runs are removed by the next run; a corrupt superpixel cache is recomputed.
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::ReadFileBytes;
using testing::ReadJsonFile;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;
using testing::WithoutLasCreationDate;

constexpr const char* kDepthView = "nadir/0010.jpg";

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// Scales the valid depths of the second half of a COLMAP depth array ("w&h&c&" + float32) by 1.01.
void ChangeDepthMap(const fs::path& path) {
  std::string bytes = ReadFileBytes(path);
  size_t header = 0;
  for (int amp = 0; amp < 3; ++header) amp += bytes.at(header) == '&' ? 1 : 0;
  const size_t n = (bytes.size() - header) / 4;
  for (size_t i = n / 2; i < n; ++i) {
    float z;
    std::memcpy(&z, &bytes[header + 4 * i], 4);
    if (z > 0) z *= 1.01f;
    std::memcpy(&bytes[header + 4 * i], &z, 4);
  }
  WriteBytes(path, bytes);
}

// Moves the first image of sparse/images.bin (view 0) by 5 cm in x; returns its name. Layout: u64 count, then
// u32 id, 4 x f64 quaternion, 3 x f64 translation, u32 camera id, name (NUL-terminated), ...
std::string ShiftFirstPose(const fs::path& images_bin) {
  std::string bytes = ReadFileBytes(images_bin);
  const size_t tx = 8 + 4 + 32;
  double x;
  std::memcpy(&x, &bytes[tx], 8);
  x += 0.05;
  std::memcpy(&bytes[tx], &x, 8);
  WriteBytes(images_bin, bytes);
  return std::string(bytes.c_str() + tx + 24 + 4);
}

class RunStateEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static fs::path BlockCopy(const std::string& name) { return Dir() / ("block_" + name); }
  // A copy of the block and a config for it; `out` defaults to the case's name.
  static void MakeCase(const std::string& name, bool tiled) {
    fs::copy(Block(), BlockCopy(name), fs::copy_options::recursive);
    WriteConfig(name, name, tiled);
  }
  static void WriteConfig(const std::string& config, const std::string& block_case, bool tiled) {
    std::ofstream(Config(config)) << "input: {path: " << BlockCopy(block_case).string() << "}\n"
                                  << "output: {dir: " << Out(config).string() << ", format: las}\n"
                                  << (tiled ? "tiling: {tile_size_m: 20, halo_m: 5}\n" : "")
                                  // Tiled cases count which tiles a changed view recomputes; co-registration
                                  // solves every pose together, so with it any changed view moves every pose a
                                  // little and every tile is recomputed (jobs/coregistered_block.h).
                                  << (tiled ? "coregistration: {enabled: false}\n" : "");
  }
  static std::string Run(const std::string& name, int* code, const std::string& extra = "") {
    std::string out;
    *code = RunCommand(SacfuseBinary() + " run " + ShellQuote(Config(name)) + extra, &out);
    return out;
  }
  static std::string RunOk(const std::string& name, const std::string& extra = "") {
    int code = 0;
    std::string out = Run(name, &code, extra);
    EXPECT_EQ(code, 0) << out;
    return out;
  }
  static std::string Fused(const std::string& name) { return ReadFileBytes(Out(name) / "fused.las"); }
  // A fresh run of the case's (changed) block into a new folder gives the same cloud as the rerun did.
  static void ExpectSameAsFreshRun(const std::string& name, bool tiled) {
    WriteConfig(name + "_fresh", name, tiled);
    RunOk(name + "_fresh");
    const std::string rerun = WithoutLasCreationDate(Fused(name));
    EXPECT_GT(rerun.size(), 100000u);
    EXPECT_TRUE(rerun == WithoutLasCreationDate(Fused(name + "_fresh")))
        << name << ": the rerun's fused.las differs from a fresh run's";
  }
  // Done markers by tile id.
  static std::map<std::string, nlohmann::json> Markers(const std::string& name) {
    std::map<std::string, nlohmann::json> markers;
    for (const auto& e : fs::directory_iterator(Out(name) / "tiles")) {
      const std::string file = e.path().filename().string();
      const auto pos = file.find(".done.json");
      if (pos != std::string::npos) markers[file.substr(0, pos)] = ReadJsonFile(e.path());
    }
    return markers;
  }
  static bool ReadsView(const nlohmann::json& marker, const std::set<std::string>& views) {
    for (const auto& v : marker.at("inputs").at("views")) {
      if (views.count(v.at("name").get<std::string>())) return true;
    }
    return false;
  }
  // Exactly the tiles that read one of `views` (before or after the change) were recomputed.
  static void ExpectOnlyTilesReading(const std::map<std::string, nlohmann::json>& before,
                                     const std::map<std::string, nlohmann::json>& after,
                                     const std::set<std::string>& views, const std::string& out) {
    ASSERT_EQ(before.size(), after.size());
    size_t recomputed = 0, skipped = 0;
    for (const auto& [id, marker] : before) {
      const bool reads = ReadsView(marker, views) || ReadsView(after.at(id), views);
      const bool changed = marker.at("finished_unix_ns") != after.at(id).at("finished_unix_ns");
      EXPECT_EQ(changed, reads) << "tile " << id << (reads ? " reads" : " does not read") << " a changed view";
      if (reads) {
        EXPECT_NE(out.find("tile " + id + ": recomputed: inputs changed: view "), std::string::npos) << id;
      } else {
        EXPECT_NE(out.find("tile " + id + ": done, skipped"), std::string::npos) << id;
      }
      (changed ? recomputed : skipped) += 1;
    }
    EXPECT_GT(recomputed, 0u);
    EXPECT_GT(skipped, 0u);
    EXPECT_NE(out.find(std::to_string(recomputed) + " tiles rerun because their inputs changed: "), std::string::npos)
        << out;
  }
  static void Truncate(const fs::path& path, uintmax_t size) { fs::resize_file(path, size); }
};

TEST_F(RunStateEndToEndTest, TiledChangedDepthMapRecomputesItsTilesOnly) {
  MakeCase("tiled_depth", true);
  RunOk("tiled_depth");
  const auto before = Markers("tiled_depth");
  const fs::path depth = BlockCopy("tiled_depth") / "stereo/depth_maps" / (std::string(kDepthView) + ".geometric.bin");
  const auto size = fs::file_size(depth);
  ChangeDepthMap(depth);
  const std::string out = RunOk("tiled_depth");
  EXPECT_NE(out.find("input changed: view 10 (nadir/0010.jpg): depth map changed (size " + std::to_string(size) +
                     " -> " + std::to_string(size) + ", content hash differs)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("superpixels: 1 computed, 19 reused"), std::string::npos) << out;
  ExpectOnlyTilesReading(before, Markers("tiled_depth"), {kDepthView}, out);
  ExpectSameAsFreshRun("tiled_depth", true);
}

TEST_F(RunStateEndToEndTest, TiledSwappedImagesRecomputeTheirTilesOnly) {
  MakeCase("tiled_image", true);
  RunOk("tiled_image");
  const auto before = Markers("tiled_image");
  const fs::path a = BlockCopy("tiled_image") / "images/nadir/0005.jpg";
  const fs::path b = BlockCopy("tiled_image") / "images/nadir/0009.jpg";
  const std::string a_bytes = ReadFileBytes(a);
  WriteBytes(a, ReadFileBytes(b));
  WriteBytes(b, a_bytes);
  const std::string out = RunOk("tiled_image");
  EXPECT_NE(out.find("(nadir/0005.jpg): image changed (size "), std::string::npos) << out;
  EXPECT_NE(out.find("(nadir/0009.jpg): image changed (size "), std::string::npos) << out;
  EXPECT_NE(out.find("superpixels: 2 computed, 18 reused"), std::string::npos) << out;
  ExpectOnlyTilesReading(before, Markers("tiled_image"), {"nadir/0005.jpg", "nadir/0009.jpg"}, out);
  ExpectSameAsFreshRun("tiled_image", true);
}

TEST_F(RunStateEndToEndTest, TiledChangedPoseRecomputesItsTilesOnly) {
  MakeCase("tiled_pose", true);
  RunOk("tiled_pose");
  const auto before = Markers("tiled_pose");
  const std::string name = ShiftFirstPose(BlockCopy("tiled_pose") / "sparse/images.bin");
  const std::string out = RunOk("tiled_pose");
  EXPECT_NE(out.find("input changed: view 0 (" + name + "): camera changed (pose or intrinsics)"), std::string::npos)
      << out;
  EXPECT_NE(out.find("plan: the inputs changed"), std::string::npos) << out;
  EXPECT_NE(out.find("superpixels: 0 computed, 20 reused"), std::string::npos) << out;  // a pose moves no pixel
  ExpectOnlyTilesReading(before, Markers("tiled_pose"), {name}, out);
  ExpectSameAsFreshRun("tiled_pose", true);
}

TEST_F(RunStateEndToEndTest, UntiledChangedDepthMapAndImageRecomputeTheirSuperpixels) {
  MakeCase("untiled", false);
  RunOk("untiled");
  ChangeDepthMap(BlockCopy("untiled") / "stereo/depth_maps" / (std::string(kDepthView) + ".geometric.bin"));
  std::string out = RunOk("untiled");
  EXPECT_NE(out.find("view 10 (nadir/0010.jpg): depth map changed (size "), std::string::npos) << out;
  EXPECT_NE(out.find("superpixels: 1 computed, 19 reused"), std::string::npos) << out;
  ExpectSameAsFreshRun("untiled", false);
  const fs::path a = BlockCopy("untiled") / "images/nadir/0005.jpg";
  const fs::path b = BlockCopy("untiled") / "images/nadir/0009.jpg";
  const std::string a_bytes = ReadFileBytes(a);
  WriteBytes(a, ReadFileBytes(b));
  WriteBytes(b, a_bytes);
  out = RunOk("untiled");
  EXPECT_NE(out.find("(nadir/0005.jpg): image changed (size "), std::string::npos) << out;
  EXPECT_NE(out.find("superpixels: 2 computed, 18 reused"), std::string::npos) << out;
  fs::remove_all(Out("untiled_fresh"));
  ExpectSameAsFreshRun("untiled", false);
}

// A run that fails after planning (a depth map cut short: its header still reads) keeps the previous cloud and
// says so; fixing the input and rerunning succeeds.
TEST_F(RunStateEndToEndTest, FailedRunKeepsThePreviousCloudAndStatusSaysFailed) {
  for (const bool tiled : {true, false}) {
    const std::string name = tiled ? "fail_tiled" : "fail_untiled";
    MakeCase(name, tiled);
    RunOk(name);
    const std::string previous = Fused(name);
    const fs::path depth = BlockCopy(name) / "stereo/depth_maps" / (std::string(kDepthView) + ".geometric.bin");
    const std::string good = ReadFileBytes(depth);
    Truncate(depth, good.size() / 2);
    int code = 0;
    const std::string out = Run(name, &code);
    EXPECT_EQ(code, 1) << out;
    EXPECT_TRUE(Fused(name) == previous) << name << ": the failed run changed fused.las";
    EXPECT_EQ(testing::CountFilesNamedWith(Out(name), ".tmp-"), 0u) << name;
    const nlohmann::json state = ReadJsonFile(Out(name) / "run_state.json");
    EXPECT_EQ(state.at("status"), "failed") << state.dump();
    EXPECT_NE(state.at("error").get<std::string>().find("0010.jpg"), std::string::npos) << state.dump();
    std::string status;
    EXPECT_EQ(RunCommand(SacfuseBinary() + " status " + ShellQuote(Config(name)), &status), 1) << status;
    EXPECT_NE(status.find("last run FAILED at "), std::string::npos) << status;
    EXPECT_NE(status.find("fused.las is from the previous successful run at "), std::string::npos) << status;
    std::string report;
    EXPECT_EQ(RunCommand(SacfuseBinary() + " report --no-before " + ShellQuote(Config(name)), &report), 0) << report;
    EXPECT_NE(report.find("last run FAILED at "), std::string::npos) << report;
    WriteBytes(depth, good);
    RunOk(name);
    EXPECT_EQ(ReadJsonFile(Out(name) / "run_state.json").at("status"), "succeeded");
    EXPECT_TRUE(WithoutLasCreationDate(Fused(name)) == WithoutLasCreationDate(previous)) << name;
    EXPECT_EQ(RunCommand(SacfuseBinary() + " status " + ShellQuote(Config(name)), &status), 0) << status;
    EXPECT_NE(status.find("last run succeeded at "), std::string::npos) << status;
  }
}

// Temporary files of killed processes (our pattern only, only in our folders) go at the next run's start, logged:
// named by an older version (no host) or by another host, they go because the run is alone in the folder; one
// named with a live pid of this host (this test's) stays, whoever else is there.
TEST_F(RunStateEndToEndTest, NextRunRemovesTemporaryFilesOfKilledRuns) {
  MakeCase("temps", true);
  RunOk("temps");
  const std::vector<fs::path> ours = {Out("temps") / "fused.las.tmp-999999-0", Out("temps") / "tiles/3_4.las.tmp-999999-1",
                                      Out("temps") / "superpixels/nadir/0010.jpg.spx.tmp-999999-2",
                                      Out("temps") / "report/index.html.tmp-other-host-4321-3"};
  const fs::path foreign = Out("temps") / "notes.tmp-draft";
  char host[256] = {};
  ::gethostname(host, sizeof(host) - 1);
  const fs::path live = Out("temps") / ("run_report.json.tmp-" + std::string(host) + "-" +
                                        std::to_string(::getpid()) + "-0");
  for (const auto& p : ours) WriteBytes(p, "half-written");
  WriteBytes(foreign, "not ours");
  WriteBytes(live, "being written by a live process");
  const std::string out = RunOk("temps");
  for (const auto& p : ours) {
    EXPECT_FALSE(fs::exists(p)) << p;
    EXPECT_NE(out.find("removed " + p.string() + " (left by a process that is gone)"), std::string::npos) << out;
  }
  EXPECT_TRUE(fs::exists(foreign));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_NE(out.find("removed 4 temporary files left by processes that are gone"), std::string::npos) << out;
  EXPECT_NE(out.find("kept 1 temporary files whose writers may be alive"), std::string::npos) << out;
  fs::remove(live);
}

// A superpixel cache whose body is corrupt but whose size, time and sampled content look unchanged (the labels in
// the middle of the file overwritten, mtime restored) is recomputed with a warning (untiled: the whole file is read
// and validated); a cache file changed since written is recomputed by a tiled run's pass too.
TEST_F(RunStateEndToEndTest, CorruptSuperpixelCacheIsRecomputed) {
  MakeCase("corrupt", false);
  RunOk("corrupt");
  const std::string reference = WithoutLasCreationDate(Fused("corrupt"));
  const fs::path spx = Out("corrupt") / "superpixels" / (std::string(kDepthView) + ".spx");
  const auto mtime = fs::last_write_time(spx);
  std::string bytes = ReadFileBytes(spx);
  ASSERT_GT(bytes.size(), 64u * 1024);  // the 4 KiB overwritten mid-file lie in the label raster
  std::memset(&bytes[bytes.size() / 2], 0x7f, 4096);
  WriteBytes(spx, bytes);
  fs::last_write_time(spx, mtime);
  std::string out = RunOk("corrupt");
  EXPECT_NE(out.find("view 10 (nadir/0010.jpg): superpixel cache " + spx.string() + " is corrupt ("),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("superpixels: 1 computed, 19 reused"), std::string::npos) << out;
  EXPECT_TRUE(WithoutLasCreationDate(Fused("corrupt")) == reference);

  MakeCase("corrupt_tiled", true);
  RunOk("corrupt_tiled");
  const std::string tiled_reference = WithoutLasCreationDate(Fused("corrupt_tiled"));
  std::string tile;  // a tile that reads the view
  for (const auto& [id, marker] : Markers("corrupt_tiled")) {
    if (ReadsView(marker, {kDepthView})) tile = id;
  }
  ASSERT_FALSE(tile.empty());
  const fs::path tiled_spx = Out("corrupt_tiled") / "superpixels" / (std::string(kDepthView) + ".spx");
  bytes = ReadFileBytes(tiled_spx);
  std::memset(&bytes[bytes.size() / 2], 0x7f, 4096);
  WriteBytes(tiled_spx, bytes);
  out = RunOk("corrupt_tiled", " --tiles " + tile);
  EXPECT_NE(out.find("view 10 (nadir/0010.jpg): superpixels cache not reused (the cache file " + tiled_spx.string() +
                     " changed since it was written): recomputed"),
            std::string::npos)
      << out;
  EXPECT_TRUE(WithoutLasCreationDate(Fused("corrupt_tiled")) == tiled_reference);
}

}  // namespace
}  // namespace sacfuse
