#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/geo_mask_io.h"
#include "io/las_reader.h"
#include "io/las_writer.h"
#include "tests/support/test_support.h"
#include "eval/eval.h"
#include "eval/eval_test_scene.h"

namespace sacfuse {
namespace {

using Points = std::vector<Eigen::Vector3d>;
const Eigen::Vector3d kUtm(390000.0, 5705000.0, 100.0);

void WriteLas(const std::string& path, const Points& points, bool with_ids) {
  LasWriterOptions o;
  o.offset = Eigen::Vector3d(390000.0, 5705000.0, 0.0);
  LasWriter writer(path, o);
  std::vector<LasPoint> las(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    las[i].xyz = points[i];
    if (with_ids) las[i].point_source_id = static_cast<uint16_t>(1 + i % 4);
  }
  writer.WritePoints(las.data(), las.size());
  writer.Close();
}

Points XyzOf(const std::vector<LasPoint>& las) {
  Points out;
  for (const auto& p : las) out.push_back(p.xyz);
  return out;
}

class EvaluateLasFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto scene = eval_test::BoxScene();
    reference_ = eval_test::Shifted(eval_test::SampleGrid(scene), kUtm);
    result_ = eval_test::Shifted(eval_test::SampleRandom(scene, 20.0, 0.05, 9), kUtm);
    ref_path_ = (dir_ / "reference.las").string();
    res_path_ = (dir_ / "result.las").string();
    WriteLas(ref_path_, reference_, false);
    WriteLas(res_path_, result_, true);
  }
  testing::TempDir dir_;
  Points reference_, result_;
  std::string ref_path_, res_path_;
};

TEST_F(EvaluateLasFilesTest, SameNumbersAsInMemory) {
  EvalOptions o;
  o.tau_m = {0.1, 0.2, 0.5};
  const EvalReport from_files = EvaluateLasFiles(res_path_, ref_path_, o);
  // Exactly what the files hold (1 mm quantised) through the pure API...
  const auto las_res = ReadAllLasPoints(res_path_);
  std::vector<uint16_t> ids;
  for (const auto& p : las_res) ids.push_back(p.point_source_id);
  const EvalReport same = EvaluateClouds(XyzOf(las_res), ids, XyzOf(ReadAllLasPoints(ref_path_)), nullptr, o);
  // ...and the unquantised clouds, which may differ only by points within 1 mm of a threshold.
  const EvalReport close = EvaluateClouds(result_, {}, reference_, nullptr, o);
  ASSERT_EQ(from_files.scores.size(), 3u);
  for (size_t t = 0; t < 3; ++t) {
    EXPECT_DOUBLE_EQ(from_files.scores[t].accuracy, same.scores[t].accuracy);
    EXPECT_DOUBLE_EQ(from_files.scores[t].completeness, same.scores[t].completeness);
    EXPECT_DOUBLE_EQ(from_files.scores[t].raw_f1, same.scores[t].raw_f1);
    EXPECT_NEAR(from_files.scores[t].f1, close.scores[t].f1, 0.01);
  }
  EXPECT_EQ(from_files.result_points, result_.size());
  EXPECT_EQ(from_files.reference_points, reference_.size());
  EXPECT_DOUBLE_EQ(from_files.mean_abs_distance_m, same.mean_abs_distance_m);
  ASSERT_EQ(from_files.source_id_histogram.size(), 4u);
  EXPECT_EQ(from_files.source_id_histogram, same.source_id_histogram);
  EXPECT_EQ(from_files.source_id_histogram.at(1), (result_.size() + 3) / 4);
}

TEST_F(EvaluateLasFilesTest, MaskFileIsRead) {
  GeoMask mask;  // UTM x in [390000, 390020)
  mask.origin_x = kUtm.x();
  mask.origin_y = kUtm.y() + 40.0;
  mask.cell_size_m = 0.5;
  mask.width = 40;
  mask.height = 82;
  mask.cells.assign(40 * 82, 255);
  EvalOptions o;
  o.mask_path = (dir_ / "mask.png").string();
  WriteGeoMask(o.mask_path, mask);
  const EvalReport r = EvaluateLasFiles(res_path_, ref_path_, o);
  EXPECT_GT(r.result_points_outside_mask, result_.size() / 3);
  EXPECT_DOUBLE_EQ(r.area_m2, 40 * 82 * 0.25);
  o.mask_path = (dir_ / "missing_mask.png").string();
  try {
    EvaluateLasFiles(res_path_, ref_path_, o);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {  // the PNG or its JSON sidecar
    EXPECT_NE(std::string(e.what()).find("missing_mask."), std::string::npos) << e.what();
  }
}

void ExpectInputErrorNaming(const std::string& result, const std::string& reference, const std::string& bad) {
  try {
    EvaluateLasFiles(result, reference, EvalOptions{});
    ADD_FAILURE() << "expected InputError for " << bad;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), bad);
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}

// Beyond max_result_points accuracy is scored on every k-th point, but completeness still sees every point: a
// dense plane thinned 16-fold leaves reference points without a result point within 5 cm, the whole plane does not.
TEST(EvaluateLasFilesThinned, CompletenessAgainstEveryPoint) {
  testing::TempDir dir;
  Points dense, reference;
  for (int r = 0; r < 200; ++r) {
    for (int c = 0; c < 200; ++c) dense.push_back(kUtm + Eigen::Vector3d(0.05 * c, 0.05 * r, 0.0));
  }
  for (int r = 0; r < 33; ++r) {
    for (int c = 0; c < 33; ++c) reference.push_back(kUtm + Eigen::Vector3d(0.3 * c + 0.01, 0.3 * r + 0.01, 0.0));
  }
  const std::string res_path = (dir / "dense.las").string(), ref_path = (dir / "reference.las").string();
  WriteLas(res_path, dense, false);
  WriteLas(ref_path, reference, false);
  EvalOptions o;
  o.tau_m = {0.05, 0.5};
  const EvalReport whole = EvaluateLasFiles(res_path, ref_path, o);
  o.max_result_points = dense.size() / 16.0;
  const EvalReport thinned = EvaluateLasFiles(res_path, ref_path, o);
  EXPECT_EQ(whole.result_stride, 1u);
  EXPECT_FALSE(whole.completeness_from_all_points);
  EXPECT_EQ(thinned.result_stride, 16u);
  EXPECT_EQ(thinned.result_points, dense.size() / 16);
  EXPECT_TRUE(thinned.completeness_from_all_points);
  ASSERT_EQ(thinned.scores.size(), 2u);
  EXPECT_GT(whole.scores[0].completeness, 0.99);
  for (size_t t = 0; t < 2; ++t) {
    EXPECT_DOUBLE_EQ(thinned.scores[t].completeness, whole.scores[t].completeness) << t;
    EXPECT_EQ(thinned.scores[t].reference_complete, whole.scores[t].reference_complete) << t;
  }
  // The thinned points alone (the old behaviour) miss most reference points at 5 cm.
  const Points stored = XyzOf(ReadAllLasPoints(res_path));
  Points every16th;
  for (size_t i = 0; i < stored.size(); i += 16) every16th.push_back(stored[i]);
  const EvalReport alone = EvaluateClouds(every16th, {}, XyzOf(ReadAllLasPoints(ref_path)), nullptr, o);
  EXPECT_LT(alone.scores[0].completeness, 0.5);
  EXPECT_DOUBLE_EQ(alone.scores[0].accuracy, thinned.scores[0].accuracy);
}

TEST_F(EvaluateLasFilesTest, BadFilesAreNamed) {
  const std::string missing = (dir_ / "nope.las").string();
  ExpectInputErrorNaming(missing, ref_path_, missing);
  ExpectInputErrorNaming(res_path_, missing, missing);
  const std::string garbage = (dir_ / "garbage.las").string();
  std::ofstream(garbage) << "this is not a LAS file at all, just some text that is long enough to be read";
  ExpectInputErrorNaming(garbage, ref_path_, garbage);
  const std::string truncated = (dir_ / "truncated.las").string();
  std::filesystem::copy_file(ref_path_, truncated);
  std::filesystem::resize_file(truncated, std::filesystem::file_size(truncated) / 2);
  ExpectInputErrorNaming(res_path_, truncated, truncated);
  const std::string empty = (dir_ / "empty.las").string();
  WriteLas(empty, {}, false);
  ExpectInputErrorNaming(res_path_, empty, empty);  // a reference without points
}

// Issue 50: a FIFO, a folder and a symbolic-link loop were all "no such LAS file"; the one gate for inputs
// (io/input_file.h) says what each is, and a FIFO never blocks.
TEST_F(EvaluateLasFilesTest, WhatIsNotALasFileIsNamedForWhatItIs) {
  const auto message = [&](const std::string& bad) {
    try {
      EvaluateLasFiles(bad, ref_path_, EvalOptions{});
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), bad);
      return std::string(e.what());
    }
    ADD_FAILURE() << "no InputError for " << bad;
    return std::string();
  };
  const std::string fifo = (dir_ / "fifo.las").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_NE(message(fifo).find("it is a FIFO (named pipe), not a regular file"), std::string::npos);
  const std::string folder = (dir_ / "folder.las").string();
  std::filesystem::create_directory(folder);
  EXPECT_NE(message(folder).find("it is a directory, not a regular file"), std::string::npos);
  const std::string loop = (dir_ / "loop.las").string();
  std::filesystem::create_symlink(loop, loop);
  EXPECT_NE(message(loop).find("Too many levels of symbolic links"), std::string::npos) << message(loop);
  EXPECT_NE(message((dir_ / "nope.las").string()).find("missing LAS file: it does not exist"), std::string::npos);
}

}  // namespace
}  // namespace sacfuse
