#pragma once
// Every fusion method behind the one interface of core/fusion_method.h, each made from its own options (the job
// picks one by fusion.method: jobs/fusion_methods.h).
#include <memory>

#include "core/consistency_fusion.h"
#include "core/disparity_normal_fusion.h"
#include "core/fusion_method.h"
#include "core/multiray_fusion.h"
#include "core/sac_fusion.h"
#include "core/tsdf_fusion.h"

namespace sacfuse {

// Select-and-Combine (core/sac_fusion.h). Its FusionStats carry SAC's counters under the names of the run report
// ("nodes", "valid_nodes", "labelled_nodes", "correspondences" (total over the labelled nodes), "netlets",
// "netlets_proven_optimal", "nodes_keeping_own_view", "nodes_relabelled", "pixels_in", "pixels_collapsed",
// "pixels_kept_uncovered", "pixels_outliers", "pixels_not_owned", "points_interpolated"), the histogram "netlet_size" and, with fusion.combine: average, the
// per-view "noise_factor". `progress` reports the collapse view by view.
std::unique_ptr<FusionMethod> MakeSacMethod(const SacOptions& options, const SacProgress& progress = {});
// Every valid depth pixel becomes a point (core/union_fusion.h).
std::unique_ptr<FusionMethod> MakeUnionMethod();
std::unique_ptr<FusionMethod> MakeConsistencyMethod(const ConsistencyOptions& options);
std::unique_ptr<FusionMethod> MakeDisparityNormalMethod(const DisparityNormalOptions& options);
std::unique_ptr<FusionMethod> MakeTsdfMethod(const TsdfOptions& options);
std::unique_ptr<FusionMethod> MakeMultirayMethod(const MultirayOptions& options);

}  // namespace sacfuse
