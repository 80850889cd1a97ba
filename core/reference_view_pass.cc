#include "core/reference_view_pass.h"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "core/error.h"

namespace sacfuse {
namespace {

constexpr int kRowsPerBlock = 16;
constexpr int kBlocksPerBatch = 64;

}  // namespace

PixelMarks::PixelMarks(const std::vector<SacView>& views) {
  flags_.reserve(views.size());
  for (const SacView& v : views) {
    const size_t n = v.depth->num_pixels();
    flags_.emplace_back(new std::atomic<uint8_t>[n]);
    for (size_t i = 0; i < n; ++i) flags_.back()[i].store(0, std::memory_order_relaxed);
    widths_.push_back(v.depth->width);
  }
}

void RunReferenceViewPasses(const std::vector<SacView>& views, const ViewPlan& plan,
                            const std::vector<std::string>& counter_names, const ReferencePixelFn& fn,
                            PointSink& sink, FusionStats* stats) {
  CheckViewPlan(plan, views.size());
  if (counter_names.size() > kMaxPassCounters) throw Error("too many pass counters");
  PixelMarks marks(views);
  stats->emitted_per_view.assign(views.size(), 0);
  stats->input_per_view.assign(views.size(), 0);
  PassCounters totals{};
  uint64_t skipped = 0;
  struct Block {
    std::vector<FusedPoint> points;
    PassCounters counters{};
    uint64_t input = 0, skipped = 0;
  };
  std::vector<Block> blocks(kBlocksPerBatch);
  for (const uint32_t v : plan.order) {
    const SacView& view = views[v];
    const DepthMap& depth = *view.depth;
    const int num_blocks = (depth.height + kRowsPerBlock - 1) / kRowsPerBlock;
    auto process = [&](int block, Block& out) {
      out.points.clear();
      out.counters = PassCounters{};
      out.input = out.skipped = 0;
      const int row_end = std::min(depth.height, (block + 1) * kRowsPerBlock);
      for (int row = block * kRowsPerBlock; row < row_end; ++row) {
        for (int col = 0; col < depth.width; ++col) {
          const float d = depth.at(row, col);
          if (!IsValidDepth(d)) continue;
          ++out.input;
          if (marks.marked(v, row, col)) {
            ++out.skipped;
            continue;
          }
          FusedPoint p;
          if (fn(v, row, col, d, PixelPoint(view, row, col, d), marks, &p, &out.counters)) out.points.push_back(p);
        }
      }
    };
    for (int first = 0; first < num_blocks; first += kBlocksPerBatch) {
      const int count = std::min(kBlocksPerBatch, num_blocks - first);
      tbb::parallel_for(0, count, [&](int i) { process(first + i, blocks[i]); });
      for (int i = 0; i < count; ++i) {
        const Block& b = blocks[i];
        if (!b.points.empty()) sink.Write(b.points.data(), b.points.size());
        stats->input_pixels += b.input;
        stats->input_per_view[v] += b.input;
        stats->emitted += b.points.size();
        stats->emitted_per_view[v] += b.points.size();
        skipped += b.skipped;
        for (size_t c = 0; c < kMaxPassCounters; ++c) totals[c] += b.counters[c];
      }
    }
  }
  for (size_t c = 0; c < counter_names.size(); ++c) stats->Count(counter_names[c], totals[c]);
  stats->Count("skipped_marked", skipped);
}

}  // namespace sacfuse
