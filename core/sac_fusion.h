#pragma once
// Select-and-Combine depth fusion over a set of views held in memory (the caller loads rasters; tiling decides
// which). Stages: nodes -> neighbour views -> noise -> correspondences, Netlets and labelling (on demand during the
// collapse with the defaults, core/sac_labeling.h) -> collapse + point tests.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/collapse.h"
#include "core/fusion_method.h"
#include "core/point.h"
#include "core/sac_labeling.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

struct SacStats {
  size_t nodes = 0;
  size_t valid_nodes = 0;
  LabelingStats labeling;
  CollapseStats collapse;
  std::vector<uint64_t> emitted_per_view;  // indexed like the input views
  // fusion.combine: average: the estimated depth noise factor k per view (sigma = k z^2 / focal, metres;
  // core/view_noise.h), indexed like the input views; empty otherwise.
  std::vector<double> noise_factor;
  std::vector<std::pair<std::string, double>> stage_seconds;
};

using SacProgress = std::function<void(const std::string& stage, size_t done, size_t total)>;

// Fuses `views` and streams the points to `sink`, view by view in input order. Deterministic for any thread count.
// `owner` (core/owned_region.h) is judged on each pixel's own back-projected point (before the averaging combine
// moves it along its ray), so that tiles sharing a halo emit every pixel exactly once although their averages
// differ slightly. `colours`: where each view's colours come from while it emits (core/fusion_method.h); null =
// SacView::image.
SacStats RunSacFusion(const std::vector<SacView>& views, const SacOptions& options, PointSink& sink,
                      const SacProgress& progress = {}, const OwnedRegion& owner = {},
                      const ViewColours* colours = nullptr);

}  // namespace sacfuse
