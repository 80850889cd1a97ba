#include "core/ortho_rule.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sacfuse {

OrthoRule OrthoRuleForCell(double cell_m) {
  OrthoRule r;
  r.occlusion_tolerance_m = cell_m;
  r.self_distance_m = 1.5 * cell_m;
  r.step_m = 0.5 * cell_m;
  r.wall_step_m = 2.0 * cell_m;
  return r;
}

int64_t OrthoHaloCells(const OrthoRule& rule, double cell_m) {
  return static_cast<int64_t>(std::ceil(rule.max_ray_m / cell_m)) + 1;
}

OrthoView OrthoViewOf(uint32_t index, const PinholeCamera& camera, const Rigid3d& cam_from_world) {
  OrthoView v;
  v.index = index;
  v.camera = camera;
  v.cam_from_world = cam_from_world;
  v.centre = cam_from_world.Inverse().translation;
  return v;
}

DsmPatch MakeDsmPatch(const CellWindow& window, std::vector<float> z) {
  DsmPatch p;
  p.window = window;
  p.z = std::move(z);
  p.z_max = std::numeric_limits<float>::lowest();
  for (const float h : p.z) {
    if (std::isfinite(h)) p.z_max = std::max(p.z_max, h);
  }
  return p;
}

bool ProjectsInside(const OrthoView& view, const Eigen::Vector3d& x, Eigen::Vector2d* uv) {
  const Eigen::Vector3d in_cam = view.cam_from_world * x;
  if (!(in_cam.z() > 0)) return false;
  *uv = view.camera.Project(in_cam);
  return uv->x() >= 0 && uv->y() >= 0 && uv->x() < view.camera.width && uv->y() < view.camera.height;
}

bool RayClearOfDsm(const Eigen::Vector3d& x, const Eigen::Vector3d& centre, const DsmPatch& dsm,
                   const OrthoRule& rule) {
  const Eigen::Vector3d d = centre - x;
  const double horizontal = d.head<2>().norm();
  if (!(horizontal > 1e-9)) return true;  // straight up: the cell's own column
  const double reach = std::min(horizontal, rule.max_ray_m);
  const double dz_per_m = d.z() / horizontal;
  const Eigen::Vector2d dir = d.head<2>() / horizontal;
  const double cell = dsm.window.cell_m;
  for (double s = rule.self_distance_m; s <= reach; s += rule.step_m) {
    const double ray_z = x.z() + s * dz_per_m;
    if (ray_z > dsm.z_max + rule.occlusion_tolerance_m) return true;  // above everything the patch holds
    const Eigen::Vector2d p = x.head<2>() + s * dir;
    const int64_t col = CellIndexOf(p.x(), cell), row = CellIndexOf(p.y(), cell);
    if (!dsm.window.Contains(col, row)) return true;  // beyond the patch: not tested
    const float h = dsm.z[dsm.window.Index(col, row)];
    if (std::isfinite(h) && h > ray_z + rule.occlusion_tolerance_m) return false;
  }
  return true;
}

namespace {

bool Sees(const OrthoView& view, const Eigen::Vector3d& x, const DsmPatch& dsm, const OrthoRule& rule) {
  Eigen::Vector2d uv;
  return ProjectsInside(view, x, &uv) && RayClearOfDsm(x, view.centre, dsm, rule);
}

// Whether one of the cell's 8 neighbours (inside the patch) is higher than z by more than the wall step.
bool AtWall(const DsmPatch& dsm, int64_t col, int64_t row, float z, const OrthoRule& rule) {
  for (int64_t dr = -1; dr <= 1; ++dr) {
    for (int64_t dc = -1; dc <= 1; ++dc) {
      if ((dr == 0 && dc == 0) || !dsm.window.Contains(col + dc, row + dr)) continue;
      const float h = dsm.z[dsm.window.Index(col + dc, row + dr)];
      if (std::isfinite(h) && h - z > rule.wall_step_m) return true;
    }
  }
  return false;
}

// Cosine of the angle between X -> centre and the vertical (larger = more nadir).
double NadirCosine(const OrthoView& view, const Eigen::Vector3d& x) {
  const Eigen::Vector3d d = view.centre - x;
  const double n = d.norm();
  return n > 0 ? d.z() / n : -1.0;
}

}  // namespace

std::vector<int32_t> OrthoCellViews(const DsmPatch& dsm, const CellWindow& inner, const std::vector<int32_t>& selected,
                                    const std::vector<OrthoView>& views, const OrthoRule& rule) {
  std::vector<int32_t> out(inner.size(), -1);
  // Every cell on its own (its view depends only on the patch): rows on the job's threads.
  tbb::parallel_for(tbb::blocked_range<int64_t>(inner.row0, inner.row0 + inner.rows, 8),
                    [&](const tbb::blocked_range<int64_t>& rows) {
    std::vector<std::pair<double, uint32_t>> candidates;
    for (int64_t row = rows.begin(); row < rows.end(); ++row) {
      for (int64_t col = inner.col0; col < inner.col0 + inner.cols; ++col) {
        if (!dsm.window.Contains(col, row)) continue;
        const float z = dsm.z[dsm.window.Index(col, row)];
        if (!std::isfinite(z)) continue;
        const Eigen::Vector3d x = CellPoint(col, row, inner.cell_m, z);
        const size_t i = inner.Index(col, row);
        const int32_t sel = selected.empty() || AtWall(dsm, col, row, z, rule) ? -1 : selected[i];
        if (sel >= 0 && static_cast<size_t>(sel) < views.size() && Sees(views[sel], x, dsm, rule)) {
          out[i] = sel;
          continue;
        }
        candidates.clear();
        Eigen::Vector2d uv;
        for (const OrthoView& v : views) {
          if (static_cast<int32_t>(v.index) == sel || !ProjectsInside(v, x, &uv)) continue;
          candidates.emplace_back(-NadirCosine(v, x), v.index);
        }
        std::sort(candidates.begin(), candidates.end());
        for (const auto& [unused, index] : candidates) {
          if (RayClearOfDsm(x, views[index].centre, dsm, rule)) {
            out[i] = static_cast<int32_t>(index);
            break;
          }
        }
      }
    }
  });
  return out;
}

std::array<uint8_t, 3> SampleBilinear(const RgbImage& image, double u, double v) {
  const double x = std::clamp(u - 0.5, 0.0, image.width - 1.0), y = std::clamp(v - 0.5, 0.0, image.height - 1.0);
  const int x0 = std::min(static_cast<int>(x), image.width - 1), y0 = std::min(static_cast<int>(y), image.height - 1);
  const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
  const double fx = x - x0, fy = y - y0;
  std::array<uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) {
    const double top = (1 - fx) * image.at(y0, x0, c) + fx * image.at(y0, x1, c);
    const double bottom = (1 - fx) * image.at(y1, x0, c) + fx * image.at(y1, x1, c);
    out[c] = static_cast<uint8_t>(std::clamp(std::lround((1 - fy) * top + fy * bottom), 0L, 255L));
  }
  return out;
}

std::array<uint8_t, 3> CellColour(const RgbImage& image, const PinholeCamera& camera, const Rigid3d& cam_from_world,
                                  const Eigen::Vector3d& x, double cell_m) {
  const Eigen::Vector3d centre_in_cam = cam_from_world * x;
  const double pixel_m = centre_in_cam.z() > 0 ? centre_in_cam.z() / camera.fx : cell_m;  // the image's GSD at X
  const int n = std::clamp(static_cast<int>(std::ceil(cell_m / pixel_m - 1e-9)), kMinCellSamples, kMaxCellSamples);
  double sum[3] = {0, 0, 0};
  int samples = 0;
  for (int sy = 0; sy < n; ++sy) {
    for (int sx = 0; sx < n; ++sx) {
      const double dx = (sx + 0.5) / n - 0.5, dy = (sy + 0.5) / n - 0.5;
      const Eigen::Vector3d in_cam = cam_from_world * (x + Eigen::Vector3d(dx * cell_m, dy * cell_m, 0.0));
      if (!(in_cam.z() > 0)) continue;
      const Eigen::Vector2d uv = camera.Project(in_cam);
      const std::array<uint8_t, 3> rgb = SampleBilinear(image, uv.x(), uv.y());
      for (int c = 0; c < 3; ++c) sum[c] += rgb[c];
      ++samples;
    }
  }
  std::array<uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) out[c] = samples > 0 ? static_cast<uint8_t>(std::lround(sum[c] / samples)) : 0;
  return out;
}

}  // namespace sacfuse
