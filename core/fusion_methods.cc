#include "core/fusion_methods.h"

#include <functional>
#include <utility>

#include "core/union_fusion.h"

namespace sacfuse {
namespace {

using FuseFunction = std::function<FusionStats(const std::vector<SacView>&, const FusionScope&, PointSink&)>;

// A method given by its name, needs and fusing function.
class FunctionMethod : public FusionMethod {
 public:
  FunctionMethod(std::string name, FusionNeeds needs, FuseFunction fuse)
      : name_(std::move(name)), needs_(needs), fuse_(std::move(fuse)) {}
  std::string name() const override { return name_; }
  FusionNeeds needs() const override { return needs_; }
  FusionStats Fuse(const std::vector<SacView>& views, const FusionScope& scope, PointSink& sink) const override {
    return fuse_(views, scope, sink);
  }

 private:
  std::string name_;
  FusionNeeds needs_;
  FuseFunction fuse_;
};

// The comparison methods reproject into the block's neighbour views in the block's order (FusionScope::plan).
FusionNeeds ComparisonNeeds() {
  FusionNeeds needs;
  needs.block_geometry = true;
  return needs;
}

// SAC's own statistics under the names of the one stats type.
FusionStats FromSacStats(const SacStats& s) {
  FusionStats out;
  out.emitted = s.collapse.emitted;
  out.emitted_per_view = s.emitted_per_view;
  out.Count("nodes", s.nodes);
  out.Count("valid_nodes", s.valid_nodes);
  out.Count("labelled_nodes", s.labeling.labelled_nodes);
  out.Count("correspondences", s.labeling.correspondences);
  out.Count("netlets", s.labeling.netlets);
  out.Count("netlets_proven_optimal", s.labeling.proven_optimal);
  out.Count("nodes_keeping_own_view", s.labeling.nodes_keeping_own_view);
  out.Count("nodes_relabelled", s.labeling.nodes_relabelled);
  out.Count("pixels_in", s.collapse.input_pixels);
  out.Count("pixels_collapsed", s.collapse.collapsed);
  out.Count("pixels_kept_uncovered", s.collapse.kept_uncovered);
  out.Count("pixels_redundant", s.collapse.redundant);
  out.Count("pixels_free_space", s.collapse.free_space);
  out.Count("pixels_outliers", s.collapse.outliers);
  out.Count("pixels_not_owned", s.collapse.not_owned);
  out.Count("points_interpolated", s.collapse.interpolated);
  out.AddHistogram("netlet_size",
                   std::vector<uint64_t>(s.labeling.size_histogram.begin(), s.labeling.size_histogram.end()));
  if (!s.noise_factor.empty()) out.view_values.emplace_back("noise_factor", s.noise_factor);
  out.stage_seconds = s.stage_seconds;
  return out;
}

}  // namespace

std::unique_ptr<FusionMethod> MakeSacMethod(const SacOptions& options, const SacProgress& progress) {
  FusionNeeds needs;
  needs.superpixels = true;
  needs.consistency_graphs = options.correspondence == "dense";
  needs.owns_pixels = true;
  needs.colours_one_view_at_a_time = true;  // the collapse emits view after view (core/collapse.h)
  return std::make_unique<FunctionMethod>(
      "sac", needs, [options, progress](const std::vector<SacView>& views, const FusionScope& scope, PointSink& sink) {
        return FromSacStats(RunSacFusion(views, options, sink, progress, scope.owns, scope.colours));
      });
}

std::unique_ptr<FusionMethod> MakeUnionMethod() {
  return std::make_unique<FunctionMethod>(
      "union", FusionNeeds{},
      [](const std::vector<SacView>& views, const FusionScope&, PointSink& sink) { return RunUnionFusion(views, sink); });
}

std::unique_ptr<FusionMethod> MakeConsistencyMethod(const ConsistencyOptions& options) {
  return std::make_unique<FunctionMethod>(
      "consistency", ComparisonNeeds(),
      [options](const std::vector<SacView>& views, const FusionScope& scope, PointSink& sink) {
        return RunConsistencyFusion(views, options, sink, scope.plan);
      });
}

std::unique_ptr<FusionMethod> MakeDisparityNormalMethod(const DisparityNormalOptions& options) {
  return std::make_unique<FunctionMethod>(
      "disparity_normal", ComparisonNeeds(),
      [options](const std::vector<SacView>& views, const FusionScope& scope, PointSink& sink) {
        return RunDisparityNormalFusion(views, options, sink, scope.plan);
      });
}

std::unique_ptr<FusionMethod> MakeTsdfMethod(const TsdfOptions& options) {
  return std::make_unique<FunctionMethod>(
      "tsdf", ComparisonNeeds(), [options](const std::vector<SacView>& views, const FusionScope& scope, PointSink& sink) {
        return RunTsdfFusion(views, options, sink, scope.gsd_m, scope.region_xy);
      });
}

std::unique_ptr<FusionMethod> MakeMultirayMethod(const MultirayOptions& options) {
  return std::make_unique<FunctionMethod>(
      "multiray", ComparisonNeeds(),
      [options](const std::vector<SacView>& views, const FusionScope& scope, PointSink& sink) {
        return RunMultirayFusion(views, options, sink, scope.plan);
      });
}

}  // namespace sacfuse
