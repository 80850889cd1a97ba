#include "jobs/point_sinks.h"

#include <chrono>

namespace sacfuse {

void CountingSink::Write(const FusedPoint* points, size_t count) {
  for (size_t i = 0; i < count; ++i) {
    if (points[i].view_index >= per_view_.size()) per_view_.resize(points[i].view_index + 1, 0);
    ++per_view_[points[i].view_index];
  }
  count_ += count;
  next_.Write(points, count);
}

void OwnedPointsSink::Write(const FusedPoint* points, size_t count) {
  if (owns_.OwnsEverything()) {
    next_.Write(points, count);
    return;
  }
  kept_.clear();
  for (size_t i = 0; i < count; ++i) {
    if (owns_.Contains(points[i].point_in_world)) kept_.push_back(points[i]);
  }
  rejected_ += count - kept_.size();
  if (!kept_.empty()) next_.Write(kept_.data(), kept_.size());
}

void TimedSink::Write(const FusedPoint* points, size_t count) {
  const auto start = std::chrono::steady_clock::now();
  next_.Write(points, count);
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace sacfuse
