#include "eval/eval_options.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse {
namespace {

TEST(EvalOptionsTest, DefaultsAreValidAndDeriveFromGsd) {
  EvalOptions o;
  EXPECT_NO_THROW(ValidateEvalOptions(o));
  EXPECT_EQ(EvalThresholds(o), (std::vector<double>{0.2, 0.5}));
  EXPECT_DOUBLE_EQ(EvalVoxelSize(o), 0.1);
  EXPECT_DOUBLE_EQ(EvalTopCellSize(o), 0.4);
  o.tau_m = {2.0, 1.0, 1.0};
  o.voxel_m = 0.5;
  o.top_cell_m = 1.0;
  EXPECT_EQ(EvalThresholds(o), (std::vector<double>{1.0, 2.0}));  // explicit, sorted, unique
  EXPECT_DOUBLE_EQ(EvalVoxelSize(o), 0.5);
  EXPECT_DOUBLE_EQ(EvalTopCellSize(o), 1.0);
}

TEST(EvalOptionsTest, EveryBrokenRuleIsNamed) {
  EvalOptions o;
  o.gsd_m = -1;
  o.tau_m = {0.2, 0.0};
  o.align_mode = "icp";
  o.align_trim_fraction = 1.5;
  try {
    ValidateEvalOptions(o);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("eval.gsd_m = -1: must be > 0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("eval.tau_m[1] = 0: must be > 0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("eval.align_mode = \"icp\": must be one of"), std::string::npos) << msg;
    EXPECT_NE(msg.find("eval.align_trim_fraction = 1.5: must be in (0, 1]"), std::string::npos) << msg;
  }
  EvalOptions none;
  none.tau_gsd.clear();
  EXPECT_THROW(ValidateEvalOptions(none), ConfigError);
  EvalOptions few;
  few.align_max_points = 10;
  EXPECT_THROW(ValidateEvalOptions(few), ConfigError);
}

}  // namespace
}  // namespace sacfuse
