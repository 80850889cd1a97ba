#pragma once
// The result of `sacfuse colmap-fusion` as a short text summary and as JSON (colmap_fusion.json): what ran, wall
// time, peak RSS, points, and the scores (F1, accuracy, completeness per threshold, fractions in [0, 1]).
#include <string>

#include "tools/bench/colmap_fusion.h"
#include "eval/eval.h"

namespace sacfuse {

struct ColmapFusionScoring {
  const EvalReport* report = nullptr;  // null: the config has no evaluation.reference
  std::string reference;
  std::string eval_json;               // the full report written by the scoring step
  double gsd_m = 0.0;
};

std::string ColmapFusionToJson(const ColmapFusionRequest& request, const ColmapFusionResult& result,
                               const ColmapFusionScoring& scoring, int indent = 2);
// Writes ColmapFusionToJson atomically; throws Error on I/O failure.
void WriteColmapFusionJson(const ColmapFusionRequest& request, const ColmapFusionResult& result,
                           const ColmapFusionScoring& scoring, const std::string& path);
// A few lines for the console: time, memory, points, F1 per threshold.
std::string FormatColmapFusionSummary(const ColmapFusionResult& result, const ColmapFusionScoring& scoring);

}  // namespace sacfuse
