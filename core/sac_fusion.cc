#include "core/sac_fusion.h"

#include <chrono>

#include "core/correspondences.h"
#include "core/netlets.h"
#include "core/sac_nodes.h"
#include "core/view_neighbors.h"

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
                      const SacProgress& progress) {
  ValidateSacOptions(options);
  SacStats stats;
  StageTimer timer(&stats);
  const NodeTable nodes = BuildNodes(views);
  stats.nodes = nodes.nodes.size();
  stats.valid_nodes = nodes.num_valid();
  const auto neighbors = SelectNeighborViews(views, nodes, options);
  timer.Mark("nodes");
  const Correspondences correspondences = FindCorrespondences(views, nodes, neighbors, options);
  stats.mean_correspondences =
      stats.valid_nodes > 0 ? static_cast<double>(correspondences.node_ids.size()) / stats.valid_nodes : 0.0;
  timer.Mark("correspondences");
  const bool per_node = options.netlets == "node";
  const Netlets netlets = per_node ? BuildNodeNetlets(nodes, correspondences, options.tau_m)
                                   : BuildNetlets(nodes, correspondences, options.tau_m);
  timer.Mark("netlets");
  const std::vector<uint32_t> chosen = LabelNetlets(views, nodes, netlets, options, &stats.labeling);
  timer.Mark("labelling");
  stats.emitted_per_view.assign(views.size(), 0);
  for (uint32_t v = 0; v < views.size(); ++v) {
    const CollapseStats s = EmitView(v, views, nodes, chosen, neighbors, options, sink);
    stats.emitted_per_view[v] = s.emitted;
    stats.collapse += s;
    if (progress) progress("collapse", v + 1, views.size());
  }
  timer.Mark("collapse");
  return stats;
}

}  // namespace sacfuse
