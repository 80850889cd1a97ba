#include "eval/point_index.h"

#include <cmath>
#include <limits>
#include <string>

#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"

namespace sacfuse {
namespace {

struct CloudAdaptor {
  const std::vector<Eigen::Vector3f>* points;
  size_t kdtree_get_point_count() const { return points->size(); }
  float kdtree_get_pt(size_t i, size_t dim) const { return (*points)[i][static_cast<int>(dim)]; }
  template <class Bbox>
  bool kdtree_get_bbox(Bbox&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>, CloudAdaptor,
                                                 3, uint32_t>;

}  // namespace

struct PointIndex::Impl {
  CloudAdaptor adaptor;
  std::unique_ptr<Tree> tree;
};

PointIndex::PointIndex(const std::vector<Eigen::Vector3f>& points) : impl_(std::make_unique<Impl>()) {
  if (points.size() >= static_cast<size_t>(std::numeric_limits<uint32_t>::max())) {
    throw Error("PointIndex: " + std::to_string(points.size()) +
                " points exceed the 32-bit index; tile the evaluation");
  }
  impl_->adaptor.points = &points;
  impl_->tree = std::make_unique<Tree>(3, impl_->adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
}

PointIndex::~PointIndex() = default;

size_t PointIndex::size() const { return impl_->adaptor.points->size(); }

bool PointIndex::Nearest(const Eigen::Vector3f& q, uint32_t* index, float* squared_distance) const {
  if (size() == 0) return false;
  return impl_->tree->knnSearch(q.data(), 1, index, squared_distance) == 1;
}

size_t PointIndex::Knn(const Eigen::Vector3f& q, size_t k, uint32_t* indices, float* squared_distances) const {
  if (size() == 0 || k == 0) return 0;
  return impl_->tree->knnSearch(q.data(), k, indices, squared_distances);
}

namespace {

// nanoflann result set that hands each point within the radius to a callback instead of collecting it.
class VisitWithin {
 public:
  VisitWithin(float squared_radius, const std::function<void(uint32_t, float)>& visit)
      : squared_radius_(squared_radius), visit_(visit) {}
  bool full() const { return true; }
  float worstDist() const { return squared_radius_; }
  size_t size() const { return count_; }
  bool addPoint(float squared_distance, uint32_t index) {
    if (squared_distance < squared_radius_) {
      visit_(index, squared_distance);
      ++count_;
    }
    return true;
  }

 private:
  float squared_radius_;
  const std::function<void(uint32_t, float)>& visit_;
  size_t count_ = 0;
};

}  // namespace

void PointIndex::ForEachWithin(const Eigen::Vector3f& q, float radius,
                               const std::function<void(uint32_t, float)>& visit) const {
  if (size() == 0 || !(radius > 0)) return;
  VisitWithin within(radius * radius, visit);
  impl_->tree->findNeighbors(within, q.data(), nanoflann::SearchParams());
}

std::vector<float> NearestDistances(const PointIndex& index, const std::vector<Eigen::Vector3f>& queries,
                                    const std::vector<uint8_t>* use) {
  std::vector<float> out(queries.size(), std::numeric_limits<float>::infinity());
  if (index.size() == 0) return out;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, queries.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      if (use != nullptr && (*use)[i] == 0) continue;
      uint32_t j = 0;
      float d2 = 0.0f;
      if (index.Nearest(queries[i], &j, &d2)) out[i] = std::sqrt(d2);
    }
  });
  return out;
}

}  // namespace sacfuse
