// Text helpers of the report: escaping, number formats, axis ticks.
#include "report/report_text.h"

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

TEST(ReportTextTest, EscapesMarkup) {
  EXPECT_EQ(EscapeHtml("a<b & 'c' \"d\">"), "a&lt;b &amp; &#39;c&#39; &quot;d&quot;&gt;");
}

TEST(ReportTextTest, FormatsNumbers) {
  EXPECT_EQ(GroupedInteger(0), "0");
  EXPECT_EQ(GroupedInteger(1234567), "1,234,567");
  EXPECT_EQ(GroupedInteger(100000), "100,000");
  EXPECT_EQ(ShortCount(999), "999");
  EXPECT_EQ(ShortCount(45600), "45.6 k");
  EXPECT_EQ(ShortCount(1234567), "1.23 M");
  EXPECT_EQ(ShortCount(391581885), "392 M");
  EXPECT_EQ(Percent(0.61, 1), "61.0 %");
  EXPECT_EQ(Duration(12.34), "12.3 s");
  EXPECT_EQ(Duration(245), "4 min 05 s");
  EXPECT_EQ(Duration(3720), "1 h 02 min");
  EXPECT_EQ(HexColour(255, 16, 0), "#ff1000");
}

TEST(ReportTextTest, TicksAreRoundAndInsideTheRange) {
  const std::vector<double> t = NiceTicks(97.3, 131.8, 5);
  ASSERT_EQ(t, (std::vector<double>{100, 110, 120, 130}));
  EXPECT_EQ(TickLabel(120, 10), "120");
  // The step is the first of 1, 2, 5 x 10^k at least range / target: 0.25 -> 0.5.
  const std::vector<double> f = NiceTicks(0.0, 1.0, 4);
  ASSERT_EQ(f, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(TickLabel(f[1], f[1] - f[0]), "0.5");
  EXPECT_EQ(TickLabel(0.25, 0.05), "0.25");
  EXPECT_TRUE(NiceTicks(5.0, 5.0, 4).empty());
}

}  // namespace
}  // namespace sacfuse
