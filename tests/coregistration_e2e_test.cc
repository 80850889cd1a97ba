// End-to-end: the co-registration stage of `sacfuse run` (jobs/coregistered_block.h) on the tiny simulated block,
// whose written poses carry the simulator's pose errors. (a) a run writes DIR/coregistration.json and the
// run_report's coregistration section, with the residuals between views smaller after than before; (b) a rerun
// reuses the file and writes the same cloud; (c) other coregistration.* options, or a damaged file, compute the
// poses again (the same poses for the same options); (d) tiled and untiled runs fuse the same corrected poses;
// (e) coregistration.enabled: false fuses the written poses (another cloud).
#include <filesystem>
#include <fstream>
#include <string>

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

class CoregistrationEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void Write(const std::string& name, const std::string& extra) {
    std::ofstream(Config(name)) << "input: {path: " << Block().string() << "}\n"
                                << "output: {dir: " << Out(name).string() << "}\n"
                                << extra;
  }
  static std::string Run(const std::string& name) {
    std::string out;
    EXPECT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config(name)), &out), 0) << out;
    return out;
  }
  static std::string Fused(const std::string& name) {
    return WithoutLasCreationDate(ReadFileBytes(Out(name) / "fused.laz"));
  }
};

TEST_F(CoregistrationEndToEndTest, CorrectsReusesAndRecomputes) {
  Write("a", "");
  const std::string first = Run("a");
  EXPECT_NE(first.find("co-registration of"), std::string::npos) << first;
  EXPECT_NE(first.find("computed"), std::string::npos) << first;
  const nlohmann::json file = ReadJsonFile(Out("a") / "coregistration.json");
  ASSERT_TRUE(file.contains("views"));
  size_t improved = 0;
  for (const auto& v : file["views"]) {
    EXPECT_GT(v["samples"].get<size_t>(), 0u);
    improved += v["rms_after_m"].get<double>() < v["rms_before_m"].get<double>();
  }
  EXPECT_GT(improved, file["views"].size() * 3 / 4) << file.dump(1);
  const nlohmann::json report = ReadJsonFile(Out("a") / "run_report.json");
  ASSERT_TRUE(report.contains("coregistration")) << report.dump(1);
  EXPECT_FALSE(report["coregistration"]["reused"].get<bool>());
  EXPECT_LT(report["coregistration"]["median_rms_after_m"].get<double>(),
            report["coregistration"]["median_rms_before_m"].get<double>());
  EXPECT_GT(report["coregistration"]["median_rotation_deg"].get<double>(), 0.0);
  const std::string cloud = Fused("a");

  // (b) A rerun reads the file: same poses, same cloud.
  const std::string second = Run("a");
  EXPECT_NE(second.find("reused"), std::string::npos) << second;
  EXPECT_TRUE(Fused("a") == cloud);

  // (c) Other options: computed again, other poses; back to the first options after a damaged file: the first
  // poses and cloud again.
  Write("a", "coregistration: {iterations: 3}\n");
  const std::string other = Run("a");
  EXPECT_NE(other.find("other coregistration.* options"), std::string::npos) << other;
  EXPECT_NE(ReadJsonFile(Out("a") / "coregistration.json")["views"], file["views"]);
  Write("a", "");
  std::ofstream(Out("a") / "coregistration.json") << "{\"format\": \"sacfuse-coregistration-1\", \"views\": [";
  const std::string repaired = Run("a");
  EXPECT_NE(repaired.find("cannot be read"), std::string::npos) << repaired;
  EXPECT_EQ(ReadJsonFile(Out("a") / "coregistration.json")["views"], file["views"]);
  EXPECT_TRUE(Fused("a") == cloud);

  // (d) Tiled: the same corrected poses in every tile (the stage runs before tiling).
  Write("tiled", "tiling: {tile_size_m: 20, halo_m: 5}\n");
  Run("tiled");
  EXPECT_EQ(ReadJsonFile(Out("tiled") / "coregistration.json")["views"], file["views"]);

  // (e) Disabled: the written poses, another cloud, no file.
  Write("off", "coregistration: {enabled: false}\n");
  const std::string off = Run("off");
  EXPECT_EQ(off.find("co-registration of"), std::string::npos) << off;
  EXPECT_FALSE(fs::exists(Out("off") / "coregistration.json"));
  EXPECT_FALSE(Fused("off") == cloud);
}

TEST_F(CoregistrationEndToEndTest, RejectsBadOptionsNamingTheKey) {
  Write("bad", "coregistration: {iterations: 0, huber_gsd: -1}\n");
  std::string out;
  EXPECT_NE(RunCommand(SacfuseBinary() + " run " + ShellQuote(Config("bad")), &out), 0);
  EXPECT_NE(out.find("coregistration.iterations"), std::string::npos) << out;
  EXPECT_NE(out.find("coregistration.huber_gsd"), std::string::npos) << out;
}

}  // namespace
}  // namespace sacfuse
