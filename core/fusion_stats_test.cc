#include "core/fusion_stats.h"

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

FusionStats TileStats() {
  FusionStats s;
  s.input_pixels = 30;
  s.emitted = 12;
  s.input_per_view = {10, 20};
  s.emitted_per_view = {4, 8};
  s.Count("netlets", 3);
  s.AddHistogram("netlet_size", {0, 2, 1});
  s.view_values.emplace_back("noise_factor", std::vector<double>{0.5, 0.7});
  s.AddStageSeconds("collapse", 1.5);
  return s;
}

TEST(FusionStatsTest, AddMapsTilePositionsToBlockViews) {
  FusionStats total;
  total.Add(TileStats(), {3, 1}, 5);  // the tile's view 0 is block view 3, its view 1 block view 1
  total.Add(TileStats(), {1, 4}, 5);
  EXPECT_EQ(total.input_pixels, 60u);
  EXPECT_EQ(total.emitted, 24u);
  EXPECT_EQ(total.input_per_view, (std::vector<uint64_t>{0, 30, 0, 10, 20}));
  EXPECT_EQ(total.emitted_per_view, (std::vector<uint64_t>{0, 12, 0, 4, 8}));
  EXPECT_EQ(total.counter("netlets"), 6u);
  EXPECT_EQ(total.counter("absent"), 0u);
  ASSERT_NE(total.histogram("netlet_size"), nullptr);
  EXPECT_EQ(*total.histogram("netlet_size"), (std::vector<uint64_t>{0, 4, 2}));
  // A view's value is the first tile's that has one.
  ASSERT_NE(total.view_value("noise_factor"), nullptr);
  EXPECT_EQ(*total.view_value("noise_factor"), (std::vector<double>{0.0, 0.7, 0.0, 0.5, 0.7}));
  ASSERT_EQ(total.stage_seconds.size(), 1u);
  EXPECT_DOUBLE_EQ(total.stage_seconds[0].second, 3.0);
}

TEST(FusionStatsTest, HistogramsOfDifferentLengthsAddBinByBin) {
  FusionStats s;
  s.AddHistogram("h", {1});
  s.AddHistogram("h", {1, 2, 3});
  s.AddHistogram("h", {1, 1});
  EXPECT_EQ(*s.histogram("h"), (std::vector<uint64_t>{3, 3, 3}));
  EXPECT_EQ(s.histogram("other"), nullptr);
}

}  // namespace
}  // namespace sacfuse
