#include "core/sac_fusion.h"

#include <chrono>
#include <utility>

#include <tbb/task_group.h>

#include "core/consulted_views.h"
#include "core/correspondences.h"
#include "core/redundancy.h"
#include "core/sac_nodes.h"
#include "core/view_neighbors.h"
#include "core/view_noise.h"

namespace sacfuse {
namespace {

class StageTimer {
 public:
  explicit StageTimer(SacStats* stats) : stats_(stats), start_(std::chrono::steady_clock::now()) {}
  void Mark(const std::string& stage) {
    const auto now = std::chrono::steady_clock::now();
    stats_->stage_seconds.emplace_back(stage, std::chrono::duration<double>(now - start_).count());
    start_ = now;
  }

 private:
  SacStats* stats_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

SacStats RunSacFusion(const std::vector<SacView>& views, const SacOptions& options, PointSink& sink,
                      const SacProgress& progress, const OwnedRegion& owner, const ViewColours* colours) {
  ValidateSacOptions(options);
  SacStats stats;
  StageTimer timer(&stats);
  const NodeTable nodes = BuildNodes(views);
  stats.nodes = nodes.nodes.size();
  stats.valid_nodes = nodes.num_valid();
  const auto neighbors = SelectNeighborViews(views, nodes, options);
  ConsultOptions consult;
  consult.max_views = options.combine_max_views;
  consult.max_view_angle_deg = options.combine_max_view_angle_deg;
  consult.min_overlap = options.min_footprint_overlap;
  consult.region_m = options.combine_region_m;
  // With `combine: select` nothing is combined, and the neighbours judge free space.
  const bool average = options.combine == "average";
  const ConsultedViews combine_views =
      average ? ConsultedViews::Select(views, nodes, consult) : ConsultedViews(neighbors);
  timer.Mark("nodes");
  std::vector<double> noise_factor;
  if (average) {
    ViewNoiseOptions noise_options;
    noise_options.slope_step_sigmas = options.combine_slope_step_sigmas;
    noise_factor = EstimateViewNoiseFactors(views, combine_views, noise_options);
    stats.noise_factor = noise_factor;
    timer.Mark("noise");
  }
  // Correspondences, Netlets and their labels: on demand during the collapse with the defaults (core/sac_labeling.h).
  const CorrespondenceFinder finder(views, nodes, neighbors, options, noise_factor);
  const NodeLabels labels(views, nodes, finder, options);
  timer.Mark("labelling");
  const ConsultedViews redundancy_judges = RedundancySearchOrder(views, combine_views, noise_factor);
  // Judged on demand by the collapse (core/point_verdicts.h): their time is part of the collapse stage.
  const PointVerdicts verdicts(views, neighbors, combine_views, noise_factor, options);
  stats.emitted_per_view.assign(views.size(), 0);
  // With `colours`, only the emitting view's colours are held, and the next view's are loaded (decoded) while it
  // emits, so that the loading does not hold up the collapse (FusionNeeds::colours_one_view_at_a_time).
  RgbImage current, next;
  if (colours != nullptr && !views.empty()) current = colours->Load(0);
  for (uint32_t v = 0; v < views.size(); ++v) {
    tbb::task_group loading;
    if (colours != nullptr && v + 1 < views.size()) loading.run([&, v] { next = colours->Load(v + 1); });
    CollapseStats s;
    try {
      s = EmitView(v, views, nodes, labels, redundancy_judges, combine_views, noise_factor, verdicts, options,
                   owner, colours != nullptr ? &current : views[v].image, sink);
    } catch (...) {
      try {
        loading.wait();
      } catch (...) {  // the emission's error is the one to report
      }
      throw;
    }
    loading.wait();  // rethrows a loading error
    current = std::exchange(next, RgbImage{});
    stats.emitted_per_view[v] = s.emitted;
    stats.collapse += s;
    if (progress) progress("collapse", v + 1, views.size());
  }
  timer.Mark("collapse");
  stats.labeling = labels.Stats();
  return stats;
}

}  // namespace sacfuse
