#pragma once
// The loop shared by the per-pixel comparison methods (consistency [15], disparity_normal [13], multiray [35]):
// views are visited one after another in the plan's order; each valid pixel of the current (reference) view that
// no earlier view has marked is handed to the method, which may emit one point and mark pixels of other views
// (removed as redundant or occluded, or used by a fused point) so that they are skipped when their view's turn
// comes.
//
// Determinism: a view's own marks are only written while other views are processed, so they are frozen during
// its pass; marks written during a pass land in other views and are idempotent (a flag set to 1). Rows are
// processed in parallel blocks and the points written in row order, so the output is identical for any thread
// count.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/fusion_stats.h"
#include "core/method_views.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

// One flag per depth pixel of every view, settable from several threads.
class PixelMarks {
 public:
  explicit PixelMarks(const std::vector<SacView>& views);
  bool marked(uint32_t view, int row, int col) const {
    return flags_[view][static_cast<size_t>(row) * widths_[view] + col].load(std::memory_order_relaxed) != 0;
  }
  void Mark(uint32_t view, int row, int col) {
    flags_[view][static_cast<size_t>(row) * widths_[view] + col].store(1, std::memory_order_relaxed);
  }

 private:
  std::vector<std::unique_ptr<std::atomic<uint8_t>[]>> flags_;
  std::vector<int> widths_;
};

// Per-block counters of a method (index -> name given to RunReferenceViewPasses).
constexpr size_t kMaxPassCounters = 4;
using PassCounters = std::array<uint64_t, kMaxPassCounters>;

// Called for every valid, unmarked pixel of the reference view `view` (its world point given); fills *out and
// returns true to emit a point. May Mark pixels of other views and count into *counters.
using ReferencePixelFn = std::function<bool(uint32_t view, int row, int col, float depth_m,
                                            const Eigen::Vector3d& point_in_world, PixelMarks& marks,
                                            FusedPoint* out, PassCounters* counters)>;

// Runs the passes; fills stats->input_pixels (all valid pixels), emitted, emitted_per_view, the counters named
// in counter_names (plus "skipped_marked": valid pixels skipped because an earlier view marked them).
void RunReferenceViewPasses(const std::vector<SacView>& views, const ViewPlan& plan,
                            const std::vector<std::string>& counter_names, const ReferencePixelFn& fn,
                            PointSink& sink, FusionStats* stats);

}  // namespace sacfuse
