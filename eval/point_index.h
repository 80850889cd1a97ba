#pragma once
// k-d tree (nanoflann) over float points in a local metric frame, for nearest-neighbour queries of the
// evaluation. The points are not copied: they must outlive the index and stay unchanged. Memory: ~4 bytes per
// point plus the tree nodes (~1 byte per point with 10-point leaves).
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace sacfuse {

class PointIndex {
 public:
  explicit PointIndex(const std::vector<Eigen::Vector3f>& points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  size_t size() const;
  // Nearest point to q: its index and squared distance. False when the index is empty.
  bool Nearest(const Eigen::Vector3f& q, uint32_t* index, float* squared_distance) const;
  // Up to k nearest points, closest first; returns how many were found.
  size_t Knn(const Eigen::Vector3f& q, size_t k, uint32_t* indices, float* squared_distances) const;
  // Calls visit(index, squared_distance) for every point closer to q than `radius` (any order).
  void ForEachWithin(const Eigen::Vector3f& q, float radius,
                     const std::function<void(uint32_t, float)>& visit) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Distance from each query (where `use` is null or non-zero) to its nearest indexed point, in parallel; queries
// that are skipped, or an empty index, give +infinity.
std::vector<float> NearestDistances(const PointIndex& index, const std::vector<Eigen::Vector3f>& queries,
                                    const std::vector<uint8_t>* use = nullptr);

}  // namespace sacfuse
