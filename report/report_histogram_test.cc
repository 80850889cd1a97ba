// The points-per-view chart: order, proportional bar heights, labels, the half-of-points count.
#include "report/report_histogram.h"

#include <regex>

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

std::vector<ViewCounts> Counts() {
  return {{0, "nadir/a.jpg", 1000, 400}, {1, "oblique_fwd/b.jpg", 500, 800}, {2, "nadir/c.jpg", 2000, 0},
          {3, "oblique_left/d.jpg", 250, 800}};
}

TEST(ReportHistogramTest, SortsByAfterCountThenViewIndex) {
  const std::vector<ViewCounts> s = SortedByAfter(Counts());
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].view, 1u);  // 800, lower index first
  EXPECT_EQ(s[1].view, 3u);  // 800
  EXPECT_EQ(s[2].view, 0u);  // 400
  EXPECT_EQ(s[3].view, 2u);  // 0
}

TEST(ReportHistogramTest, BarHeightsAreProportionalToCounts) {
  const std::vector<ViewCounts> counts = Counts();  // kept: a reference into a temporary dangles (found by ASan)
  const HistogramLayout l = LayoutHistogram(counts, 600, 200);
  ASSERT_EQ(l.bars.size(), 4u);
  EXPECT_GE(l.max_count, 2000.0);  // the axis holds the largest count
  for (const HistogramBar& b : l.bars) {
    const ViewCounts& c = counts[b.view];
    EXPECT_NEAR(b.before_height, c.before / l.max_count * 200.0, 1e-9);
    EXPECT_NEAR(b.after_height, c.after / l.max_count * 200.0, 1e-9);
    EXPECT_LE(b.before_height, 200.0);
  }
  // Sorted slots: view 2 (2000 before) is last, view 3 (250 before) second: 8 times as tall.
  ASSERT_EQ(l.bars[3].view, 2u);
  ASSERT_EQ(l.bars[1].view, 3u);
  EXPECT_NEAR(l.bars[3].before_height / l.bars[1].before_height, 8.0, 1e-9);
  // Slots left to right in sorted order, inside the plot.
  for (size_t i = 1; i < l.bars.size(); ++i) EXPECT_GT(l.bars[i].x, l.bars[i - 1].x);
  EXPECT_LE(l.bars.back().x + l.slot, l.plot_left + l.plot_width + 1e-9);
  // Ticks are round numbers from 0 up to the top of the axis.
  EXPECT_EQ(l.ticks.front(), 0.0);
  EXPECT_DOUBLE_EQ(l.ticks.back(), l.max_count);
}

TEST(ReportHistogramTest, SvgHasOneBeforeAndOneAfterBarPerViewWithItsColourAndName) {
  const std::vector<Rgb> colours = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}};
  const std::string svg = HistogramSvg(Counts(), colours, 600, 200);
  const auto count = [&](const std::string& pattern) {
    const std::regex re(pattern);
    return std::distance(std::sregex_iterator(svg.begin(), svg.end(), re), std::sregex_iterator());
  };
  EXPECT_EQ(count("class='before'"), 4);
  EXPECT_EQ(count("class='after'"), 4);
  EXPECT_EQ(count("fill='#040506'"), 1);  // view 1's colour
  EXPECT_NE(svg.find("oblique_left/d.jpg"), std::string::npos);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(ReportHistogramTest, ViewsForHalfOfThePoints) {
  EXPECT_EQ(ViewsForHalfOfPoints(Counts()), 2u);  // 800 + 800 of 2000
  EXPECT_EQ(ViewsForHalfOfPoints({{0, "a", 1, 10}, {1, "b", 1, 10}, {2, "c", 1, 10}}), 2u);
  EXPECT_EQ(ViewsForHalfOfPoints({}), 0u);
}

}  // namespace
}  // namespace sacfuse
