#include "tools/sim/stereo_sources.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace sacfuse::sim {

std::vector<std::vector<uint32_t>> ChooseStereoSources(const std::vector<StereoView>& views,
                                                       const SparsePoints& points, const StereoSourceOptions& options) {
  const double min_axis_cos = std::cos(options.max_axis_angle_deg * M_PI / 180.0);
  std::vector<std::vector<uint32_t>> sources(views.size());
  for (uint32_t i = 0; i < views.size(); ++i) {
    const StereoView& ref = views[i];
    const Eigen::Vector3d ref_axis = ref.cam_from_world.rotation.conjugate() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d ref_center = ref.cam_from_world.Inverse().translation;
    struct Candidate {
      uint32_t view;
      size_t shared;
    };
    std::vector<Candidate> candidates;
    for (uint32_t j = 0; j < views.size(); ++j) {
      if (j == i) continue;
      const StereoView& src = views[j];
      const Eigen::Vector3d src_axis = src.cam_from_world.rotation.conjugate() * Eigen::Vector3d::UnitZ();
      if (ref_axis.dot(src_axis) < min_axis_cos) continue;
      std::vector<uint64_t> shared;
      std::set_intersection(ref.point_ids.begin(), ref.point_ids.end(), src.point_ids.begin(), src.point_ids.end(),
                            std::back_inserter(shared));
      if (static_cast<int>(shared.size()) < options.min_shared_points) continue;
      std::vector<double> depths;
      depths.reserve(shared.size());
      for (const uint64_t id : shared) {
        const auto it = points.find(id);
        if (it != points.end()) depths.push_back((ref.cam_from_world * it->second).z());
      }
      if (depths.empty()) continue;
      std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
      const double median_depth = depths[depths.size() / 2];
      if (!(median_depth > 0.0)) continue;
      const double ratio = (src.cam_from_world.Inverse().translation - ref_center).norm() / median_depth;
      if (ratio < options.min_baseline_ratio || ratio > options.max_baseline_ratio) continue;
      candidates.push_back({j, shared.size()});
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.shared > b.shared; });
    for (size_t k = 0; k < candidates.size() && static_cast<int>(k) < options.max_sources; ++k) {
      sources[i].push_back(candidates[k].view);
    }
  }
  return sources;
}

}  // namespace sacfuse::sim
