#include "core/tsdf_volume.h"

#include <algorithm>
#include <cmath>

#include <sstream>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/method_views.h"

namespace sacfuse {
namespace {

constexpr uint64_t kBlockOverheadBytes = 64;  // map node, key, pointer
constexpr float kMaxExtractTsdf = 0.98f;
constexpr double kSnapFraction = 0.01;  // crossings within 1 % of a voxel of a voxel centre are at that centre
constexpr int kRowsPerTask = 16;
constexpr size_t kBlocksPerExtractTask = 256;
constexpr size_t kTasksPerBatch = 64;

int64_t FloorDiv(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Colour of the pixel a world point projects onto in a view (clamped to the raster).
std::array<uint8_t, 3> ColourAt(const SacView& view, const Eigen::Vector3d& point_in_world) {
  const Eigen::Vector3d p = view.view.cam_from_world * point_in_world;
  if (p.z() <= 0) return PixelColour(view, 0, 0);
  const Eigen::Vector2d uv = view.depth_camera.Project(p);
  const int col = std::clamp(static_cast<int>(std::floor(uv.x())), 0, view.depth->width - 1);
  const int row = std::clamp(static_cast<int>(std::floor(uv.y())), 0, view.depth->height - 1);
  return PixelColour(view, row, col);
}

}  // namespace

TsdfVolume::TsdfVolume(double voxel_m, double truncation_m, uint64_t max_bytes)
    : voxel_m_(voxel_m), truncation_m_(truncation_m), block_m_(voxel_m * kTsdfBlockEdge), max_bytes_(max_bytes) {
  if (!(voxel_m > 0) || !(truncation_m > 0)) throw Error("tsdf: voxel size and truncation must be > 0");
}

bool TsdfVolume::InRegion(const Key& key) const {
  if (!region_) return true;
  const double x0 = key.x * block_m_, y0 = key.y * block_m_;
  return x0 + block_m_ >= region_->min.x() && x0 <= region_->max.x() && y0 + block_m_ >= region_->min.y() &&
         y0 <= region_->max.y();
}

uint64_t TsdfVolume::bytes() const { return blocks_.size() * (sizeof(Block) + kBlockOverheadBytes); }

TsdfVolume::Key TsdfVolume::KeyOf(const Eigen::Vector3d& p) const {
  return {static_cast<int32_t>(std::floor(p.x() / block_m_)), static_cast<int32_t>(std::floor(p.y() / block_m_)),
          static_cast<int32_t>(std::floor(p.z() / block_m_))};
}

Eigen::Vector3d TsdfVolume::VoxelCentre(const Key& b, int i, int j, int k) const {
  return {(static_cast<double>(b.x) * kTsdfBlockEdge + i + 0.5) * voxel_m_,
          (static_cast<double>(b.y) * kTsdfBlockEdge + j + 0.5) * voxel_m_,
          (static_cast<double>(b.z) * kTsdfBlockEdge + k + 0.5) * voxel_m_};
}

bool TsdfVolume::EarlierEdgeSnapsAt(int64_t gx, int64_t gy, int64_t gz, const TsdfVoxel& v, int edge,
                                    double min_weight) const {
  for (int e = 0; e < edge; ++e) {
    const int axis = e % 3;
    const int dir = e < 3 ? -1 : 1;
    const TsdfVoxel* n = FindVoxel(gx + dir * (axis == 0), gy + dir * (axis == 1), gz + dir * (axis == 2));
    if (n == nullptr || n->weight < min_weight || !(std::abs(n->tsdf) < kMaxExtractTsdf)) continue;
    if (!(v.tsdf * n->tsdf < 0.0f)) continue;
    if (v.tsdf / (static_cast<double>(v.tsdf) - n->tsdf) < kSnapFraction) return true;
  }
  return false;
}

const TsdfVoxel* TsdfVolume::FindVoxel(int64_t vx, int64_t vy, int64_t vz) const {
  const Key key{static_cast<int32_t>(FloorDiv(vx, kTsdfBlockEdge)), static_cast<int32_t>(FloorDiv(vy, kTsdfBlockEdge)),
                static_cast<int32_t>(FloorDiv(vz, kTsdfBlockEdge))};
  const auto it = index_.find(key);
  if (it == index_.end()) return nullptr;
  const int i = static_cast<int>(vx - int64_t{key.x} * kTsdfBlockEdge);
  const int j = static_cast<int>(vy - int64_t{key.y} * kTsdfBlockEdge);
  const int k = static_cast<int>(vz - int64_t{key.z} * kTsdfBlockEdge);
  return &(*blocks_[it->second])[(k * kTsdfBlockEdge + j) * kTsdfBlockEdge + i];
}

std::vector<uint32_t> TsdfVolume::AllocateAround(const SacView& view) {
  // The blocks the view's pixel rays cross within +-truncation of their points, sampled every half block.
  const DepthMap& depth = *view.depth;
  const int tasks = (depth.height + kRowsPerTask - 1) / kRowsPerTask;
  std::vector<std::vector<Key>> task_keys(static_cast<size_t>(tasks));
  const Eigen::Vector3d centre = view.world_from_cam.translation;
  const int steps = static_cast<int>(std::ceil(2.0 * truncation_m_ / (0.5 * block_m_)));
  const double step_m = 2.0 * truncation_m_ / steps;
  tbb::parallel_for(0, tasks, [&](int t) {
    std::vector<Key>& keys = task_keys[static_cast<size_t>(t)];
    const int row_end = std::min(depth.height, (t + 1) * kRowsPerTask);
    for (int row = t * kRowsPerTask; row < row_end; ++row) {
      for (int col = 0; col < depth.width; ++col) {
        const float d = depth.at(row, col);
        if (!IsValidDepth(d)) continue;
        const Eigen::Vector3d p = PixelPoint(view, row, col, d);
        const Eigen::Vector3d r = (p - centre).normalized();
        for (int k = 0; k <= steps; ++k) {
          const Key key = KeyOf(p + (k * step_m - truncation_m_) * r);
          if (keys.empty() || !(keys.back() == key)) keys.push_back(key);
        }
      }
      if (keys.size() > (1u << 16)) {  // keep the task's list short: neighbouring rays share most blocks
        std::sort(keys.begin(), keys.end());
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
      }
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  });
  std::vector<Key> all;
  for (const auto& k : task_keys) all.insert(all.end(), k.begin(), k.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  std::vector<uint32_t> touched;
  touched.reserve(all.size());
  for (const Key& key : all) {
    if (!InRegion(key)) continue;
    const auto it = index_.find(key);
    if (it != index_.end()) {
      touched.push_back(it->second);
      continue;
    }
    if ((blocks_.size() + 1) * (sizeof(Block) + kBlockOverheadBytes) > max_bytes_) {
      std::ostringstream msg;
      msg << "tsdf: the voxel grid would exceed tsdf.max_memory_gb ("
          << static_cast<double>(max_bytes_) / static_cast<double>(uint64_t{1} << 30) << " GiB: " << blocks_.size()
          << " blocks of " << kTsdfBlockVoxels << " voxels of " << voxel_m_
          << " m); use smaller tiles (tiling.tile_size_m), a larger tsdf.voxel_size_gsd or a larger "
             "tsdf.max_memory_gb";
      throw Error(msg.str());
    }
    const uint32_t id = static_cast<uint32_t>(blocks_.size());
    index_.emplace(key, id);
    keys_.push_back(key);
    blocks_.push_back(std::make_unique<Block>());
    touched.push_back(id);
  }
  return touched;
}

void TsdfVolume::Integrate(const std::vector<SacView>& views, uint32_t v) {
  const SacView& view = views[v];
  const std::vector<uint32_t> touched = AllocateAround(view);
  const Eigen::Matrix3d rot = view.view.cam_from_world.rotation.toRotationMatrix();
  const Eigen::Vector3d trans = view.view.cam_from_world.translation;
  const PinholeCamera& cam = view.depth_camera;
  const DepthMap& depth = *view.depth;
  const double mu = truncation_m_;
  tbb::parallel_for(size_t{0}, touched.size(), [&](size_t t) {
    const uint32_t id = touched[t];
    const Key key = keys_[id];
    Block& block = *blocks_[id];
    for (int k = 0; k < kTsdfBlockEdge; ++k) {
      for (int j = 0; j < kTsdfBlockEdge; ++j) {
        for (int i = 0; i < kTsdfBlockEdge; ++i) {
          const Eigen::Vector3d c = VoxelCentre(key, i, j, k);
          const Eigen::Vector3d p = rot * c + trans;
          if (p.z() <= 0) continue;
          const double u = cam.fx * p.x() / p.z() + cam.cx;
          const double w = cam.fy * p.y() / p.z() + cam.cy;
          if (!(u >= 0 && w >= 0 && u < depth.width && w < depth.height)) continue;
          const int col = static_cast<int>(u), row = static_cast<int>(w);
          const float d = depth.at(row, col);
          if (!IsValidDepth(d)) continue;
          const double sdf = (d - p.z()) * p.norm() / p.z();
          if (sdf < -mu) continue;
          TsdfVoxel& voxel = block[(k * kTsdfBlockEdge + j) * kTsdfBlockEdge + i];
          const double obs = std::min(1.0, sdf / mu);
          voxel.tsdf = static_cast<float>((voxel.tsdf * voxel.weight + obs) / (voxel.weight + 1.0));
          if (voxel.weight < UINT16_MAX) ++voxel.weight;
          if (std::abs(sdf) >= mu) continue;
          bool take = voxel.view == 0;
          if (!take) {
            const SacView& best = views[voxel.view - 1u];
            const double zb = (best.view.cam_from_world * c).z();
            // Strictly smaller by a relative margin, so equal precisions tie to the earlier view whatever the
            // rounding of the two projections.
            take = p.z() * p.z() / cam.fx < (1.0 - 1e-9) * zb * zb / best.depth_camera.fx;
          }
          if (take) voxel.view = static_cast<uint16_t>(v + 1);
        }
      }
    }
  });
}

void TsdfVolume::ExtractPoints(const std::vector<SacView>& views, double min_weight, PointSink& sink,
                               FusionStats* stats) const {
  std::vector<uint32_t> order(blocks_.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys_[a] < keys_[b]; });
  if (stats->emitted_per_view.size() < views.size()) stats->emitted_per_view.resize(views.size(), 0);
  const auto usable = [&](const TsdfVoxel* v) {
    return v != nullptr && v->weight >= min_weight && std::abs(v->tsdf) < kMaxExtractTsdf;
  };
  const size_t tasks = (order.size() + kBlocksPerExtractTask - 1) / kBlocksPerExtractTask;
  std::vector<std::vector<FusedPoint>> out(kTasksPerBatch);
  std::vector<std::vector<uint32_t>> out_views(kTasksPerBatch);
  // One task: kBlocksPerExtractTask blocks into out[slot]; batches of tasks bound the points held at once.
  const auto extract = [&](size_t task, size_t slot) {
    out[slot].clear();
    out_views[slot].clear();
    for (size_t o = task * kBlocksPerExtractTask; o < std::min(order.size(), (task + 1) * kBlocksPerExtractTask);
         ++o) {
      const uint32_t id = order[o];
      const Key key = keys_[id];
      const Block& block = *blocks_[id];
      for (int k = 0; k < kTsdfBlockEdge; ++k) {
        for (int j = 0; j < kTsdfBlockEdge; ++j) {
          for (int i = 0; i < kTsdfBlockEdge; ++i) {
            const TsdfVoxel* a = &block[(k * kTsdfBlockEdge + j) * kTsdfBlockEdge + i];
            if (!usable(a)) continue;
            const int64_t gx = int64_t{key.x} * kTsdfBlockEdge + i, gy = int64_t{key.y} * kTsdfBlockEdge + j,
                          gz = int64_t{key.z} * kTsdfBlockEdge + k;
            for (int axis = 0; axis < 3; ++axis) {
              const bool inside = (axis == 0 ? i : axis == 1 ? j : k) + 1 < kTsdfBlockEdge;
              const TsdfVoxel* b =
                  inside ? &block[((k + (axis == 2)) * kTsdfBlockEdge + j + (axis == 1)) * kTsdfBlockEdge + i +
                                  (axis == 0)]
                         : FindVoxel(gx + (axis == 0), gy + (axis == 1), gz + (axis == 2));
              if (!usable(b) || !(a->tsdf * b->tsdf < 0.0f)) continue;
              double t_cross = a->tsdf / (static_cast<double>(a->tsdf) - b->tsdf);
              // A crossing at a voxel centre is shared by that voxel's edges: emit it once, from the first of
              // its six edges (-x, -y, -z, +x, +y, +z) that has it.
              if (t_cross < kSnapFraction) {
                if (EarlierEdgeSnapsAt(gx, gy, gz, *a, 3 + axis, min_weight)) continue;
                t_cross = 0.0;
              } else if (t_cross > 1.0 - kSnapFraction) {
                if (EarlierEdgeSnapsAt(gx + (axis == 0), gy + (axis == 1), gz + (axis == 2), *b, axis, min_weight)) {
                  continue;
                }
                t_cross = 1.0;
              }
              const TsdfVoxel* src = t_cross < 0.5 ? a : b;
              if (src->view == 0) src = src == a ? b : a;
              if (src->view == 0) continue;
              Eigen::Vector3d p = VoxelCentre(key, i, j, k);
              p[axis] += t_cross * voxel_m_;
              FusedPoint fp;
              fp.point_in_world = p;
              fp.rgb = ColourAt(views[src->view - 1u], p);
              fp.view_index = views[src->view - 1u].view.index;
              out[slot].push_back(fp);
              out_views[slot].push_back(src->view - 1u);
            }
          }
        }
      }
    }
  };
  for (size_t first = 0; first < tasks; first += kTasksPerBatch) {
    const size_t count = std::min(kTasksPerBatch, tasks - first);
    tbb::parallel_for(size_t{0}, count, [&](size_t i) { extract(first + i, i); });
    for (size_t i = 0; i < count; ++i) {
      if (!out[i].empty()) sink.Write(out[i].data(), out[i].size());
      stats->emitted += out[i].size();
      for (const uint32_t v : out_views[i]) ++stats->emitted_per_view[v];
    }
  }
}

}  // namespace sacfuse
