#pragma once
// Select-and-Combine depth fusion over a set of views held in memory (the caller loads rasters; tiling decides
// which). Stages: nodes -> neighbour views -> correspondences -> Netlets -> labelling -> collapse + outliers.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/collapse.h"
#include "core/point.h"
#include "core/sac_labeling.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

struct SacStats {
  size_t nodes = 0;
  size_t valid_nodes = 0;
  double mean_correspondences = 0.0;   // per valid node
  LabelingStats labeling;
  CollapseStats collapse;
  std::vector<uint64_t> emitted_per_view;  // indexed like the input views
  std::vector<std::pair<std::string, double>> stage_seconds;
};

using SacProgress = std::function<void(const std::string& stage, size_t done, size_t total)>;

// Fuses `views` and streams the points to `sink`, view by view in input order. Deterministic for any thread count.
SacStats RunSacFusion(const std::vector<SacView>& views, const SacOptions& options, PointSink& sink,
                      const SacProgress& progress = {});

}  // namespace sacfuse
