#include "tools/sim/depth_errors.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <tbb/parallel_for.h>

#include "tools/sim/sim_random.h"

namespace sacfuse::sim {
namespace {

constexpr float kFar = 3.0e38f;

int ScalePixels(double image_px, int downsample) {
  if (image_px <= 0.0) return 0;
  return std::max(1, static_cast<int>(std::lround(image_px / downsample)));
}

// Foreground side of depth edges: pixels with a 4-neighbour more than `step` behind them keep their depth, every
// other pixel is kFar. Min-filtering this map spreads only edge foregrounds (smooth slopes never count).
cv::Mat EdgeForeground(const DepthMap& depth, float step) {
  cv::Mat m(depth.height, depth.width, CV_32F, cv::Scalar(kFar));
  const int w = depth.width, h = depth.height;
  tbb::parallel_for(0, h, [&](int row) {
    float* out = m.ptr<float>(row);
    for (int col = 0; col < w; ++col) {
      const float d = depth.at(row, col);
      if (!IsValidDepth(d)) continue;
      const int nr[4] = {row - 1, row + 1, row, row};
      const int nc[4] = {col, col, col - 1, col + 1};
      for (int k = 0; k < 4; ++k) {
        if (!depth.Contains(nr[k], nc[k])) continue;
        const float q = depth.at(nr[k], nc[k]);
        if (IsValidDepth(q) && q - d > step) {
          out[col] = d;
          break;
        }
      }
    }
  });
  return m;
}

}  // namespace

ViewErrorModel MakeViewErrorModel(const SimErrorOptions& o, bool oblique, double focal_px, double baseline_m,
                                  int depth_downsample, bool baseline_along_columns) {
  ViewErrorModel m;
  m.enabled = o.enabled;
  if (!o.enabled) return m;
  const int ds = std::max(1, depth_downsample);
  const double k = o.scale;
  const double f = oblique ? o.oblique_factor : 1.0;
  m.disparity_sigma_px = o.disparity_sigma_px * k * f;
  m.focal_px = focal_px;
  m.baseline_m = o.stereo_baseline_m > 0.0 ? o.stereo_baseline_m : baseline_m;
  m.noise_correlation_px = o.noise_correlation_px / ds;
  m.bias_amplitude_m = o.bias_amplitude_m * k * f;
  m.fattening_px = ScalePixels(o.fattening_px * k, ds);
  m.fattening_min_step_m = o.fattening_min_step_m;
  m.blunders_per_mpx = o.blunders_per_mpx * k * f;
  m.blunder_radius_px = o.blunder_radius_px / ds;
  m.blunder_depth_sigma_m = o.blunder_depth_sigma_m * k;
  m.occlusion_strip_px = ScalePixels(o.occlusion_strip_px * k, ds);
  m.baseline_along_columns = baseline_along_columns;
  m.dropout_fraction = std::min(0.5, o.dropout_fraction * k);
  return m;
}

DepthMap ApplyDepthErrors(const DepthMap& true_depth, const ViewErrorModel& m, uint64_t key,
                          DepthErrorReport* report) {
  DepthErrorReport local;
  DepthErrorReport& rep = report != nullptr ? *report : local;
  rep = DepthErrorReport();
  const int w = true_depth.width, h = true_depth.height;
  DepthMap d = true_depth;
  for (float& v : d.data) {
    if (!IsValidDepth(v)) v = 0.0f;
  }
  rep.valid_in = static_cast<size_t>(std::count_if(d.data.begin(), d.data.end(), [](float v) { return v > 0.0f; }));
  if (!m.enabled || w == 0 || h == 0) {
    rep.valid_out = rep.valid_in;
    return d;
  }

  // Fattening and occlusion strips, both from the true depth's foreground minima.
  if (m.fattening_px > 0 || m.occlusion_strip_px > 0) {
    const float step = static_cast<float>(m.fattening_min_step_m);
    const cv::Mat fg = EdgeForeground(true_depth, step);
    cv::Mat fat_min, occ_min;
    if (m.fattening_px > 0) {
      const int r = m.fattening_px;
      cv::erode(fg, fat_min, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
    }
    if (m.occlusion_strip_px > 0) {
      const int len = 2 * (m.fattening_px + m.occlusion_strip_px) + 1;
      const cv::Size size = m.baseline_along_columns ? cv::Size(len, 1) : cv::Size(1, len);
      cv::erode(fg, occ_min, cv::getStructuringElement(cv::MORPH_RECT, size));
    }
    std::atomic<size_t> fattened{0}, occluded{0};  // pixel counts, any order
    tbb::parallel_for(0, h, [&](int row) {
      for (int col = 0; col < w; ++col) {
        const float t = true_depth.at(row, col);
        if (!IsValidDepth(t)) continue;
        if (!fat_min.empty()) {
          const float near = fat_min.ptr<float>(row)[col];
          if (t - near > step) {
            d.at(row, col) = near;
            ++fattened;
            continue;
          }
        }
        if (!occ_min.empty() && t - occ_min.ptr<float>(row)[col] > step) {
          d.at(row, col) = 0.0f;
          ++occluded;
        }
      }
    });
    rep.fattened_pixels = fattened;
    rep.occluded_pixels = occluded;
  }

  // Correlated stereo noise and the smooth bias field.
  if (m.disparity_sigma_px > 0.0 || m.bias_amplitude_m > 0.0) {
    std::vector<float> noise;
    if (m.disparity_sigma_px > 0.0) noise = CorrelatedGaussianField(w, h, m.noise_correlation_px, HashCombine(key, 1));
    if (m.bias_amplitude_m > 0.0) rep.bias_modes = DrawCosineModes(HashCombine(key, 2), 3, 1.2);
    // cos(a_col + b_row) = cos a cos b - sin a sin b: per-mode column and row tables instead of per-pixel cosines.
    const size_t nm = rep.bias_modes.size();
    std::vector<double> cos_u(nm * w), sin_u(nm * w), cos_v(nm * h), sin_v(nm * h);
    for (size_t k = 0; k < nm; ++k) {
      const CosineMode& mode = rep.bias_modes[k];
      for (int col = 0; col < w; ++col) {
        const double a = 2.0 * M_PI * mode.fu * (col + 0.5) / w;
        cos_u[k * w + col] = mode.weight * std::cos(a), sin_u[k * w + col] = mode.weight * std::sin(a);
      }
      for (int row = 0; row < h; ++row) {
        const double b = 2.0 * M_PI * mode.fv * (row + 0.5) / h + mode.phase;
        cos_v[k * h + row] = std::cos(b), sin_v[k * h + row] = std::sin(b);
      }
    }
    tbb::parallel_for(0, h, [&](int row) {
      for (int col = 0; col < w; ++col) {
        float& v = d.at(row, col);
        if (v <= 0.0f) continue;
        double z = v;
        if (!noise.empty()) z += m.StereoSigma(v) * noise[static_cast<size_t>(row) * w + col];
        double bias = 0.0;
        for (size_t k = 0; k < nm; ++k) {
          bias += cos_u[k * w + col] * cos_v[k * h + row] - sin_u[k * w + col] * sin_v[k * h + row];
        }
        z += m.bias_amplitude_m * bias;
        v = z > 1e-3 ? static_cast<float>(z) : 0.0f;
      }
    });
  }

  // Blunder blobs.
  if (m.blunders_per_mpx > 0.0 && m.blunder_radius_px > 0.0) {
    Rng rng(HashCombine(key, 3));
    rep.blunder_count = rng.Poisson(m.blunders_per_mpx * 1e-6 * static_cast<double>(w) * h);
    std::vector<uint8_t> hit(static_cast<size_t>(w) * h, 0);
    for (int b = 0; b < rep.blunder_count; ++b) {
      const double cu = rng.Uniform(0.0, w), cv = rng.Uniform(0.0, h);
      const double radius = m.blunder_radius_px * rng.Uniform(0.5, 1.5);
      const double sign = rng.Bernoulli(0.5) ? 1.0 : -1.0;
      const float offset = static_cast<float>(sign * m.blunder_depth_sigma_m * (0.5 + std::abs(rng.Normal())));
      const int r0 = std::max(0, static_cast<int>(std::floor(cv - radius)));
      const int r1 = std::min(h - 1, static_cast<int>(std::ceil(cv + radius)));
      const int c0 = std::max(0, static_cast<int>(std::floor(cu - radius)));
      const int c1 = std::min(w - 1, static_cast<int>(std::ceil(cu + radius)));
      for (int row = r0; row <= r1; ++row) {
        for (int col = c0; col <= c1; ++col) {
          const double du = col + 0.5 - cu, dv = row + 0.5 - cv;
          if (du * du + dv * dv > radius * radius) continue;
          float& v = d.at(row, col);
          if (v <= 0.0f) continue;
          v = v + offset > 1e-3f ? v + offset : 0.0f;
          hit[static_cast<size_t>(row) * w + col] = 1;
        }
      }
    }
    rep.blunder_pixels = static_cast<size_t>(std::count(hit.begin(), hit.end(), 1));
  }

  // Dropout clusters.
  if (m.dropout_fraction > 0.0) {
    const std::vector<float> field = CorrelatedGaussianField(w, h, 1.5, HashCombine(key, 4));
    const auto threshold = static_cast<float>(InverseNormalCdf(1.0 - m.dropout_fraction));
    std::atomic<size_t> dropped{0};
    tbb::parallel_for(0, h, [&](int row) {
      for (int col = 0; col < w; ++col) {
        float& v = d.at(row, col);
        if (v > 0.0f && field[static_cast<size_t>(row) * w + col] > threshold) {
          v = 0.0f;
          ++dropped;
        }
      }
    });
    rep.dropout_pixels = dropped;
  }
  rep.valid_out = static_cast<size_t>(std::count_if(d.data.begin(), d.data.end(), [](float v) { return v > 0.0f; }));
  return d;
}

PoseError DrawPoseError(const SimErrorOptions& o, uint64_t key) {
  PoseError e;
  if (!o.enabled) return e;
  Rng rng(key);
  const double sp = o.pose_position_sigma_m * o.scale;
  const double sr = o.pose_rotation_sigma_deg * o.scale * M_PI / 180.0;
  for (int k = 0; k < 3; ++k) e.center_delta_m[k] = sp * rng.Normal();
  for (int k = 0; k < 3; ++k) e.rotation_delta_rad[k] = sr * rng.Normal();
  return e;
}

Rigid3d ApplyPoseError(const Rigid3d& true_cam_from_world, const PoseError& e) {
  if (e.center_delta_m.isZero(0.0) && e.rotation_delta_rad.isZero(0.0)) return true_cam_from_world;  // bit-exact
  const Rigid3d world_from_cam = true_cam_from_world.Inverse();
  Rigid3d written = world_from_cam;
  written.translation += e.center_delta_m;
  const double angle = e.rotation_delta_rad.norm();
  if (angle > 0.0) {
    const Eigen::Quaterniond delta(Eigen::AngleAxisd(angle, e.rotation_delta_rad / angle));
    written.rotation = (world_from_cam.rotation * delta).normalized();
  }
  return written.Inverse();
}

}  // namespace sacfuse::sim
