#pragma once
// A sparse truncated-signed-distance volume (Curless & Levoy; as Open3D's ScalableTSDFVolume / VoxelBlockGrid):
// a hash map of 4 x 4 x 4 voxel blocks, allocated only around observed surface points, so memory follows the
// surface area seen, not the bounding box. Pure data structure + integration + zero-crossing extraction.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "core/box2d.h"
#include "core/fusion_stats.h"
#include "core/method_views.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

struct TsdfVoxel {  // 8 bytes
  float tsdf = 1.0f;       // running mean of the truncated signed distance / truncation, in [-1, 1]; + in front
  uint16_t weight = 0;     // observations averaged (capped at 65535)
  uint16_t view = 0;       // 1 + position of the view giving colour and source id; 0 = none yet
};

// Voxels per block edge: 4 keeps the allocated band around a surface thin (a +-4 voxel band spans 2-3 blocks
// of 4 voxels, against 2 of 8), at 64 B of hash-map overhead per 512 B block.
constexpr int kTsdfBlockEdge = 4;
constexpr int kTsdfBlockVoxels = kTsdfBlockEdge * kTsdfBlockEdge * kTsdfBlockEdge;

class TsdfVolume {
 public:
  // voxel_m: voxel edge, metres; truncation_m: truncation distance, metres; max_bytes: the volume refuses to
  // grow beyond this (Error naming tsdf.max_memory_gb).
  TsdfVolume(double voxel_m, double truncation_m, uint64_t max_bytes);

  // Integrates view `v` (position in `views`): allocates the blocks each valid depth pixel's ray crosses within
  // +-truncation of its point (sampled every half block), then updates every voxel of those blocks that projects onto a valid
  // depth d of the view: sdf = (d - z) * |p| / z (the distance along the pixel's ray; z the voxel's depth, p its
  // position in the camera frame), skipped when sdf < -truncation (hidden behind the surface), else
  // tsdf <- (tsdf * w + min(1, sdf / truncation)) / (w + 1), w <- w + 1 (free space in front counts as +1).
  // Source view: where |sdf| < truncation, the observing view with the smallest expected depth error at the
  // voxel (z^2 / focal, ties to the earlier one) is recorded; it gives the points near the voxel their source id
  // and colour.
  // Voxels are updated in parallel, each by one thread, views in call order: deterministic.
  void Integrate(const std::vector<SacView>& views, uint32_t v);

  // Zero crossings: for each voxel a and its +x, +y, +z neighbour b (also across blocks), both with weight >=
  // min_weight and |tsdf| < 0.98, and tsdf of opposite signs, one point at the linear interpolation
  // a + tsdf_a / (tsdf_a - tsdf_b) along the edge (at most 3 points per voxel); colour and source view from the
  // voxel nearer to the crossing (the other one when it has none): the colour is that view's pixel the point
  // projects onto (clamped to its raster). A crossing within 1 % of a voxel of a voxel
  // centre is put at that centre and emitted once (several edges of the voxel would give it). Blocks in ascending key order, voxels x
  // fastest: deterministic. Adds emitted / emitted_per_view (by view position) to *stats.
  void ExtractPoints(const std::vector<SacView>& views, double min_weight, PointSink& sink, FusionStats* stats) const;

  // Allocates no block whose XY extent misses `region` (a tile's halo: what lies outside cannot reach its core).
  // Voxels inside keep exactly the values they would have without it.
  void RestrictTo(const Box2d& region) { region_ = region; }

  size_t num_blocks() const { return blocks_.size(); }
  uint64_t bytes() const;
  double voxel_m() const { return voxel_m_; }

 private:
  struct Key {
    int32_t x = 0, y = 0, z = 0;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
    bool operator<(const Key& o) const { return x != o.x ? x < o.x : (y != o.y ? y < o.y : z < o.z); }
  };
  struct KeyHash {
    size_t operator()(const Key& k) const {
      return (static_cast<size_t>(static_cast<uint32_t>(k.x)) * 73856093u) ^
             (static_cast<size_t>(static_cast<uint32_t>(k.y)) * 19349663u) ^
             (static_cast<size_t>(static_cast<uint32_t>(k.z)) * 83492791u);
    }
  };
  using Block = std::array<TsdfVoxel, kTsdfBlockVoxels>;

  Key KeyOf(const Eigen::Vector3d& p) const;
  Eigen::Vector3d VoxelCentre(const Key& block, int i, int j, int k) const;
  const TsdfVoxel* FindVoxel(int64_t vx, int64_t vy, int64_t vz) const;  // global voxel index
  // Whether one of the edges 0 .. edge-1 of voxel v at global index g (-x, -y, -z, +x, +y, +z) has a zero
  // crossing within the snap distance of v's centre (then that edge emits the point at the centre).
  bool EarlierEdgeSnapsAt(int64_t gx, int64_t gy, int64_t gz, const TsdfVoxel& v, int edge, double min_weight) const;
  std::vector<uint32_t> AllocateAround(const SacView& view);

  bool InRegion(const Key& key) const;

  double voxel_m_, truncation_m_, block_m_;
  std::optional<Box2d> region_;
  uint64_t max_bytes_;
  std::unordered_map<Key, uint32_t, KeyHash> index_;
  std::vector<Key> keys_;
  std::vector<std::unique_ptr<Block>> blocks_;
};

}  // namespace sacfuse
