#pragma once
// Point sinks that sit between a fusion method and the writer: counting, keeping a tile's own points, timing the
// writer.
#include <cstdint>
#include <vector>

#include "core/fusion_method.h"
#include "core/point.h"

namespace sacfuse {

// Forwards every point, counting them in total and per source view (FusedPoint::view_index).
class CountingSink : public PointSink {
 public:
  explicit CountingSink(PointSink& next) : next_(next) {}
  void Write(const FusedPoint* points, size_t count) override;
  uint64_t count() const { return count_; }
  // Points per FusedPoint::view_index (the block's view index), as long as the largest index seen (views beyond
  // it: none).
  const std::vector<uint64_t>& per_view() const { return per_view_; }

 private:
  PointSink& next_;
  uint64_t count_ = 0;
  std::vector<uint64_t> per_view_;
};

// Forwards the points `owns` contains and counts the rest.
class OwnedPointsSink : public PointSink {
 public:
  OwnedPointsSink(const OwnedRegion& owns, PointSink& next) : owns_(owns), next_(next) {}
  void Write(const FusedPoint* points, size_t count) override;
  uint64_t rejected() const { return rejected_; }

 private:
  OwnedRegion owns_;
  PointSink& next_;
  std::vector<FusedPoint> kept_;
  uint64_t rejected_ = 0;
};

// Forwards every point and sums the wall time spent in the next sink (an untiled run's LAS/LAZ writing, which
// happens inside the fusion stage).
class TimedSink : public PointSink {
 public:
  explicit TimedSink(PointSink& next) : next_(next) {}
  void Write(const FusedPoint* points, size_t count) override;
  double seconds() const { return seconds_; }

 private:
  PointSink& next_;
  double seconds_ = 0.0;
};

}  // namespace sacfuse
