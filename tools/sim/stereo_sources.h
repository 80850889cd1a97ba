#pragma once
// Which views a view is matched with (the source views of its stereo pairs), chosen as a two-view pipeline does
// from the sparse model: among the views that look the same way (optical axes within max_axis_angle_deg: nadir with
// nadir, each oblique direction with itself) and share at least min_shared_points sparse points with it, those whose
// baseline over the median depth of the shared points lies in [min_baseline_ratio, max_baseline_ratio] (wide enough
// for depth precision, narrow enough to match), most shared points first (ties to the lower index), at most
// max_sources.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/camera.h"
#include "core/rigid3.h"

namespace sacfuse::sim {

struct StereoSourceOptions {
  int max_sources = 4;
  double min_baseline_ratio = 0.15;  // baseline / median depth of the shared sparse points
  double max_baseline_ratio = 0.75;
  int min_shared_points = 20;
  double max_axis_angle_deg = 30.0;  // between the two optical axes, degrees
};

// A view as the matcher sees it: its pose and the sparse points it observes.
struct StereoView {
  std::string name;
  PinholeCamera camera;              // at the resolution matched (the depth raster's)
  Rigid3d cam_from_world;            // the pose written to the workspace (errors included)
  std::vector<uint64_t> point_ids;   // sparse points it observes, sorted, no duplicates
};

using SparsePoints = std::map<uint64_t, Eigen::Vector3d>;  // id -> world position

// Per view, its source views (indices into `views`) in the order above.
std::vector<std::vector<uint32_t>> ChooseStereoSources(const std::vector<StereoView>& views,
                                                       const SparsePoints& points, const StereoSourceOptions& options);

}  // namespace sacfuse::sim
