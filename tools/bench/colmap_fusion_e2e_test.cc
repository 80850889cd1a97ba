// End-to-end: `sacfuse colmap-fusion` on a simulated tiny block. The COLMAP run needs the colmap binary (Debian
// package colmap) and skips without it; the missing-binary error is checked always.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/las_reader.h"
#include "tests/support/block_suite.h"
#include "tools/bench/child_process.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::ReadJsonFile;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;

class ColmapFusionEndToEndTest : public testing::TinyBlockSuite {};

TEST_F(ColmapFusionEndToEndTest, MissingColmapIsAConfigErrorWithAdvice) {
  std::string out;
  const fs::path dest = Dir() / "no_colmap";
  const int code = RunCommand(SacfuseBinary() + " colmap-fusion " + ShellQuote(Block() / "sacfuse.yaml") +
                                  " --colmap /no/such/colmap --out " + ShellQuote(dest),
                              &out);
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("COLMAP not found"), std::string::npos) << out;
  EXPECT_NE(out.find("--colmap"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(dest)) << "nothing is written before the binary is found";
}

TEST_F(ColmapFusionEndToEndTest, FailingColmapIsAFailedRunShowingItsLog) {
  const fs::path fake = Dir() / "fake_colmap";
  {
    std::ofstream(fake) << "#!/bin/sh\n"
                           "if [ \"$1\" = -h ]; then echo 'COLMAP 0.0 -- fake'; exit 0; fi\n"
                           "echo \"fusing with $*\"; echo 'F0101 fake failure: out of luck' >&2; exit 3\n";
  }
  fs::permissions(fake, fs::perms::owner_all);
  std::string out;
  const fs::path dest = Dir() / "fake";
  EXPECT_EQ(RunCommand(SacfuseBinary() + " colmap-fusion " + ShellQuote(Block() / "sacfuse.yaml") + " --colmap " +
                           ShellQuote(fake) + " --out " + ShellQuote(dest) +
                           " --threads 3 --stereo-fusion max_normal_error=180",
                       &out),
            1)
      << out;
  EXPECT_NE(out.find("exit code 3"), std::string::npos) << out;
  EXPECT_NE(out.find("fake failure: out of luck"), std::string::npos) << "the log's tail is shown: " << out;
  const std::string log = testing::ReadFileBytes(dest / "colmap.log");
  EXPECT_NE(log.find("COLMAP 0.0"), std::string::npos) << log;
  EXPECT_NE(log.find("stereo_fusion --workspace_path"), std::string::npos) << log;
  EXPECT_NE(log.find("--StereoFusion.num_threads 3"), std::string::npos) << log;
  EXPECT_NE(log.find("--StereoFusion.cache_size 4"), std::string::npos) << log;  // resources.memory_gb
  EXPECT_NE(log.find("--StereoFusion.max_normal_error 180"), std::string::npos) << log;
  EXPECT_TRUE(fs::is_symlink(dest / "workspace" / "stereo"));
  // A malformed extra option is a command-line error.
  EXPECT_EQ(RunCommand(SacfuseBinary() + " colmap-fusion " + ShellQuote(Block() / "sacfuse.yaml") + " --colmap " +
                           ShellQuote(fake) + " --out " + ShellQuote(dest) + " --stereo-fusion max_normal_error",
                       &out),
            2)
      << out;
  EXPECT_NE(out.find("NAME=VALUE"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(dest / "fused.las"));
}

TEST_F(ColmapFusionEndToEndTest, FusesWithColmapAndScoresLikeRun) {
  if (FindExecutable("colmap").empty()) {
    GTEST_SKIP() << "colmap not on PATH (Debian package colmap); skipping the COLMAP stereo_fusion run";
  }
  std::string out;
  const fs::path dest = Dir() / "colmap";
  ASSERT_EQ(RunCommand(SacfuseBinary() + " colmap-fusion " + ShellQuote(Block() / "sacfuse.yaml") + " --out " +
                           ShellQuote(dest) + " --threads 2",
                       &out),
            0)
      << out;
  EXPECT_NE(out.find("COLMAP F1 @"), std::string::npos) << out;
  for (const char* f : {"fused.las", "colmap.log", "eval.json", "colmap_fusion.json", "workspace/fused.ply",
                        "workspace/sparse/images.bin"}) {
    EXPECT_TRUE(fs::exists(dest / f)) << f;
  }
  const nlohmann::json j = ReadJsonFile(dest / "colmap_fusion.json");
  EXPECT_EQ(j.at("exit_code").get<int>(), 0);
  EXPECT_GT(j.at("wall_s").get<double>(), 0.0);
  EXPECT_GT(j.at("peak_rss_mib").get<double>(), 5.0);
  const uint64_t points = j.at("points").get<uint64_t>();
  EXPECT_GT(points, 3000u);  // tiny, seed 3: ~9,200

  // The LAS is back in the block's frame: centred on the reference (the views see beyond its 60 m, so the bounds
  // differ by tens of metres), heights within the reference's range.
  LasReader fused((dest / "fused.las").string());
  LasReader reference((Block() / "reference.las").string());
  EXPECT_EQ(fused.header().point_count, points);
  const Eigen::Vector3d fused_centre = 0.5 * (fused.header().min + fused.header().max);
  const Eigen::Vector3d reference_centre = 0.5 * (reference.header().min + reference.header().max);
  EXPECT_LT((fused_centre - reference_centre).head<2>().norm(), 30.0)
      << fused_centre.transpose() << " vs " << reference_centre.transpose();
  EXPECT_GT(fused.header().min.z(), reference.header().min.z() - 10.0);
  EXPECT_LT(fused.header().max.z(), reference.header().max.z() + 10.0);

  // Scored as `sacfuse run` scores: two thresholds. A correct georeference is accurate at 5 x GSD (measured 99.99 %;
  // a frame error of a metre would score near 0). COLMAP's default fusion (2 px reprojection tolerance) leaves about
  // one point per 2-pixel radius, so its completeness and F1 stay lower (tiny, seed 3: F1 ~0.89 at 5 x GSD).
  const auto& scores = j.at("evaluation").at("scores");
  ASSERT_EQ(scores.size(), 2u);
  EXPECT_NEAR(scores[0].at("tau_gsd").get<double>(), 2.0, 1e-9);
  EXPECT_GT(scores[1].at("accuracy").get<double>(), 0.97);
  EXPECT_GT(scores[1].at("f1").get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(scores[1].at("f1").get<double>(), testing::EvalF1(dest / "eval.json", 1));
}

}  // namespace
}  // namespace sacfuse
