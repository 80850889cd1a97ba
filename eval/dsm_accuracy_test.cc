// DSM accuracy (eval/dsm_accuracy.h) on a hand-made reference and DSM with known errors: completeness, median,
// NMAD, RMSE, the split by class, the mask, and the reference's empty cells filled from their neighbours.
#include "eval/dsm_accuracy.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "io/gdal_raster.h"
#include "io/geo_mask_io.h"
#include "io/las_writer.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

// Reference: 10 x 10 cells of 1 m at (1000, 2000); the western half ground (class 2, z 100), the eastern half a
// building (class 6, z 110); one point per cell at its centre, except cell (3, 3) (empty: filled from its
// neighbours) and a noise return (class 7) high above cell (1, 1), which must be ignored.
void WriteReference(const std::string& path) {
  std::vector<LasPoint> points;
  for (int r = 0; r < 10; ++r) {
    for (int c = 0; c < 10; ++c) {
      if (r == 3 && c == 3) continue;
      LasPoint p;
      p.xyz = {1000.5 + c, 2000.5 + r, c < 5 ? 100.0 : 110.0};
      p.classification = c < 5 ? 2 : 6;
      points.push_back(p);
    }
  }
  LasPoint noise;
  noise.xyz = {1001.5, 2001.5, 150.0};
  noise.classification = 7;
  points.push_back(noise);
  LasWriterOptions o;
  LasWriter w(path, o);
  w.WritePoints(points.data(), points.size());
  w.Close();
}

TEST(DsmAccuracyTest, KnownErrorsGiveKnownStatisticsOverallAndByClass) {
  testing::TempDir dir;
  WriteReference((dir / "ref.las").string());
  CellWindow w;
  w.cell_m = 1.0;
  w.col0 = 1000;
  w.row0 = 2000;
  w.cols = w.rows = 10;
  std::vector<float> dsm(w.size());
  for (int r = 0; r < 10; ++r) {
    for (int c = 0; c < 10; ++c) {
      // Ground +0.1 m everywhere; building -0.2 m, and a 10 x 1 column of +1 m errors at c = 9.
      float z = c < 5 ? 100.1f : 109.8f;
      if (c == 9) z = 111.0f;
      dsm[w.Index(1000 + c, 2000 + r)] = z;
    }
  }
  for (int r = 0; r < 5; ++r) dsm[w.Index(1000, 2000 + r)] = kNan;  // 5 ground cells without a value
  RasterFormat format;
  format.nodata = -9999.0;
  WriteRasterFile((dir / "dsm.tif").string(), w, format, dsm.data(), RasterLayout::kIntermediate);
  DsmAccuracyRequest req;
  req.dsm_path = (dir / "dsm.tif").string();
  req.reference_las = (dir / "ref.las").string();
  req.gsd_m = 0.1;
  const DsmAccuracy a = EvaluateDsm(req);
  EXPECT_DOUBLE_EQ(a.cell_m, 1.0);
  EXPECT_EQ(a.all.cells, 100u);
  EXPECT_EQ(a.all.cells_with_value, 95u);
  EXPECT_DOUBLE_EQ(a.all.completeness, 0.95);
  // Errors: 45 x +0.1 (ground), 40 x -0.2, 10 x +1.0; sorted, the 48th of 95 is +0.1.
  EXPECT_NEAR(a.all.median_m, 0.1, 1e-4);
  // |e - 0.1|: 45 x 0, 40 x 0.3, 10 x 0.9 -> median 0.3 -> NMAD 0.44478.
  EXPECT_NEAR(a.all.nmad_m, 1.4826 * 0.3, 1e-4);
  EXPECT_NEAR(a.all.rmse_m, std::sqrt((45 * 0.01 + 40 * 0.04 + 10 * 1.0) / 95.0), 1e-4);
  EXPECT_NEAR(a.all.within_2gsd, 85.0 / 100.0, 1e-9);  // |e| <= 0.2 m: ground and building, not the 1 m column
  ASSERT_EQ(a.by_class.size(), 2u);
  EXPECT_EQ(a.by_class[0].first, "building");
  EXPECT_EQ(a.by_class[0].second.cells, 50u);
  EXPECT_NEAR(a.by_class[0].second.median_m, -0.2, 1e-4);
  EXPECT_EQ(a.by_class[1].first, "ground");
  EXPECT_EQ(a.by_class[1].second.cells_with_value, 45u);
  EXPECT_NEAR(a.by_class[1].second.nmad_m, 0.0, 1e-4);
  EXPECT_NE(FormatDsmAccuracy(a).find("ground"), std::string::npos);

  // A mask keeping the northern half only (rows 5-9): 50 cells, all with a value.
  GeoMask mask;
  mask.origin_x = 1000.0;
  mask.origin_y = 2010.0;
  mask.cell_size_m = 1.0;
  mask.width = mask.height = 10;
  mask.cells.assign(100, 0);
  for (int r = 0; r < 5; ++r) {
    for (int c = 0; c < 10; ++c) mask.cells[r * 10 + c] = 255;  // mask row 0 is north
  }
  WriteGeoMask((dir / "mask.png").string(), mask);
  req.mask_png = (dir / "mask.png").string();
  const DsmAccuracy m = EvaluateDsm(req);
  EXPECT_EQ(m.all.cells, 50u);
  EXPECT_DOUBLE_EQ(m.all.completeness, 1.0);
}

TEST(DsmAccuracyTest, ErrorStatisticsOfKnownSamples) {
  const DsmErrorStats s = DsmErrorStatsOf({-1.0, 0.0, 0.5, 2.0}, 8, 0.5);
  EXPECT_DOUBLE_EQ(s.completeness, 0.5);
  EXPECT_DOUBLE_EQ(s.median_m, 0.25);
  EXPECT_DOUBLE_EQ(s.nmad_m, 1.4826 * 0.75);  // |e - 0.25| = 1.25, 0.25, 0.25, 1.75 -> median 0.75
  EXPECT_DOUBLE_EQ(s.rmse_m, std::sqrt((1.0 + 0.0 + 0.25 + 4.0) / 4.0));
  EXPECT_DOUBLE_EQ(s.within_2gsd, 3.0 / 8.0);
}

}  // namespace
}  // namespace sacfuse
