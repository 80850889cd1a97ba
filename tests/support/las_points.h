#pragma once
// Comparing decoded LAS points field by field (round trips: LAS <-> LAZ, copies, twins).
#include <vector>

#include <gtest/gtest.h>

#include "io/las_types.h"

namespace sacfuse::testing {

// Every field of every point equal, in order; reports at most three differing points.
inline void ExpectSamePoints(const std::vector<LasPoint>& a, const std::vector<LasPoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  size_t bad = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const LasPoint& p = a[i];
    const LasPoint& q = b[i];
    const bool same = p.xyz == q.xyz && p.intensity == q.intensity && p.return_number == q.return_number &&
                      p.number_of_returns == q.number_of_returns && p.classification == q.classification &&
                      p.flags == q.flags && p.scanner_channel == q.scanner_channel &&
                      p.scan_direction == q.scan_direction && p.edge_of_flight_line == q.edge_of_flight_line &&
                      p.scan_angle_deg == q.scan_angle_deg && p.user_data == q.user_data &&
                      p.point_source_id == q.point_source_id && p.gps_time == q.gps_time && p.rgb == q.rgb &&
                      p.nir == q.nir;
    if (!same && bad++ < 3) ADD_FAILURE() << "point " << i << " differs";
  }
  EXPECT_EQ(bad, 0u);
}

}  // namespace sacfuse::testing
