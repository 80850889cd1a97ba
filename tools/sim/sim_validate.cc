// ValidateSimOptions: every rule of SimOptions, all failures reported together.
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "tools/sim/simulate.h"

namespace sacfuse {
namespace {

class Checker {
 public:
  template <typename T>
  void Rule(bool ok, const std::string& key, const T& value, const std::string& rule) {
    if (ok) return;
    std::ostringstream os;
    os << "sim." << key << " = " << value << ": " << rule;
    errors_.push_back(os.str());
  }
  void Positive(const std::string& key, double v) { Rule(std::isfinite(v) && v > 0.0, key, v, "must be > 0"); }
  void NonNegative(const std::string& key, double v) { Rule(std::isfinite(v) && v >= 0.0, key, v, "must be >= 0"); }
  void Range(const std::string& key, double v, double lo, double hi) {
    std::ostringstream rule;
    rule << "must be in [" << lo << ", " << hi << "]";
    Rule(std::isfinite(v) && v >= lo && v <= hi, key, v, rule.str());
  }
  void IntRange(const std::string& key, int v, int lo, int hi) {
    Rule(v >= lo && v <= hi, key, v, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  void ThrowIfFailed() const {
    if (errors_.empty()) return;
    std::string message = "invalid simulation options";
    for (const auto& e : errors_) message += "\n  " + e;
    throw ConfigError(message);
  }

 private:
  std::vector<std::string> errors_;
};

}  // namespace

void ValidateSimOptions(const SimOptions& o) {
  Checker c;
  c.Rule(o.scene == "city" || o.scene == "las", "scene", "\"" + o.scene + "\"", "must be one of {city, las}");
  if (o.scene == "las") {
    std::error_code ec;
    c.Rule(!o.from_las.empty(), "from_las", "\"\"", "scene \"las\" needs a LAS file (--from-las)");
    if (!o.from_las.empty()) {
      c.Rule(std::filesystem::is_regular_file(o.from_las, ec), "from_las", "\"" + o.from_las + "\"",
             "no such file");
    }
    c.Range("area_width_m", o.area_width_m, 0.0, 20000.0);
    c.Range("area_height_m", o.area_height_m, 0.0, 20000.0);
  } else {
    c.Range("area_width_m", o.area_width_m, 1.0, 20000.0);
    c.Range("area_height_m", o.area_height_m, 1.0, 20000.0);
  }
  c.Rule(std::isfinite(o.origin_east_m) && std::isfinite(o.origin_north_m), "origin_east_m", o.origin_east_m,
         "origin_east_m and origin_north_m must be finite");
  c.Range("ground_height_m", o.ground_height_m, -1000.0, 9000.0);
  if (o.obliques) c.Range("oblique_tilt_deg", o.oblique_tilt_deg, 5.0, 70.0);
  c.Range("gsd_m", o.gsd_m, 0.005, 10.0);
  c.IntRange("nadir_width_px", o.nadir_width_px, 16, 100000);
  c.IntRange("nadir_height_px", o.nadir_height_px, 16, 100000);
  c.Rule(static_cast<double>(o.nadir_width_px) * o.nadir_height_px <= 4.0e8, "nadir_width_px",
         std::to_string(o.nadir_width_px) + " x " + std::to_string(o.nadir_height_px),
         "images larger than 400 megapixels are not supported");
  c.Range("nadir_focal_mm", o.nadir_focal_mm, 1.0, 1000.0);
  c.Range("oblique_focal_mm", o.oblique_focal_mm, 1.0, 1000.0);
  c.Range("pixel_size_um", o.pixel_size_um, 0.5, 100.0);
  c.Range("forward_overlap", o.forward_overlap, 0.0, 0.95);
  c.Range("side_overlap", o.side_overlap, 0.0, 0.95);
  c.Rule(o.max_nadir_views >= 0, "max_nadir_views", o.max_nadir_views, "must be >= 0 (0 = no limit)");
  c.Rule(o.max_oblique_views >= 0, "max_oblique_views", o.max_oblique_views, "must be >= 0 (0 = no limit)");
  c.IntRange("depth_downsample", o.depth_downsample, 1, 16);
  c.Range("reference_density_pts_m2", o.reference_density_pts_m2, 0.01, 10000.0);
  c.NonNegative("eval_cell_m", o.eval_cell_m);
  c.Positive("sparse_area_per_point_m2", o.sparse_area_per_point_m2);
  c.IntRange("min_sparse_points", o.min_sparse_points, 0, 10000000);
  c.IntRange("jpeg_quality", o.jpeg_quality, 1, 100);
  c.Range("sun_azimuth_deg", o.sun_azimuth_deg, -360.0, 360.0);
  c.Range("sun_elevation_deg", o.sun_elevation_deg, 1.0, 90.0);
  c.Range("ambient", o.ambient, 0.0, 1.0);
  c.Rule(std::isfinite(o.city_rotation_deg), "city_rotation_deg", o.city_rotation_deg, "must be finite");
  c.Rule(o.las_cell_m == 0.0 || (o.las_cell_m >= 0.05 && o.las_cell_m <= 10.0), "las_cell_m", o.las_cell_m,
         "must be 0 (auto) or in [0.05, 10]");

  c.Rule(o.depth == "synthetic" || o.depth == "sgbm", "depth", "\"" + o.depth + "\"",
         "must be one of {synthetic, sgbm}");
  if (o.depth == "sgbm") {
    const sim::SgbmDepthOptions& g = o.sgbm;
    c.IntRange("sgbm.sources.max_sources", g.sources.max_sources, 1, 16);
    c.Range("sgbm.sources.min_baseline_ratio", g.sources.min_baseline_ratio, 0.0, 10.0);
    c.Rule(g.sources.max_baseline_ratio > g.sources.min_baseline_ratio, "sgbm.sources.max_baseline_ratio",
           g.sources.max_baseline_ratio, "must be > sgbm.sources.min_baseline_ratio");
    c.IntRange("sgbm.sources.min_shared_points", g.sources.min_shared_points, 1, 1000000);
    c.Range("sgbm.sources.max_axis_angle_deg", g.sources.max_axis_angle_deg, 0.0, 90.0);
    c.Rule(g.match.block_size % 2 == 1 && g.match.block_size >= 1 && g.match.block_size <= 11, "sgbm.match.block_size",
           g.match.block_size, "must be odd, in [1, 11]");
    c.IntRange("sgbm.match.p2_multiplier", g.match.p2_multiplier, 9, 1000);
    c.IntRange("sgbm.match.uniqueness_percent", g.match.uniqueness_percent, 0, 100);
    c.IntRange("sgbm.match.erode_px", g.match.erode_px, 0, 100);
    c.Range("sgbm.depth_percentile", g.depth_percentile, 0.0, 49.0);
    c.Range("sgbm.depth_margin", g.depth_margin, 0.0, 0.9);
    c.Range("sgbm.near_fraction", g.near_fraction, 0.01, 1.0);
    c.IntRange("sgbm.max_disparities", g.max_disparities, 16, 4096);
    c.Range("sgbm.merge_tolerance", g.merge_tolerance, 0.0, 1.0);
    c.IntRange("sgbm.min_agree", g.min_agree, 1, g.sources.max_sources);
  }

  const SimErrorOptions& e = o.errors;
  c.NonNegative("errors.pose_position_sigma_m", e.pose_position_sigma_m);
  c.NonNegative("errors.pose_rotation_sigma_deg", e.pose_rotation_sigma_deg);
  c.NonNegative("errors.disparity_sigma_px", e.disparity_sigma_px);
  c.NonNegative("errors.stereo_baseline_m", e.stereo_baseline_m);
  c.Range("errors.noise_correlation_px", e.noise_correlation_px, 0.0, 100.0);
  c.NonNegative("errors.bias_amplitude_m", e.bias_amplitude_m);
  c.IntRange("errors.fattening_px", e.fattening_px, 0, 100);
  c.Positive("errors.fattening_min_step_m", e.fattening_min_step_m);
  c.Range("errors.blunders_per_mpx", e.blunders_per_mpx, 0.0, 100000.0);
  c.Rule(e.blunders_per_mpx == 0.0 || (std::isfinite(e.blunder_radius_px) && e.blunder_radius_px > 0.0),
         "errors.blunder_radius_px", e.blunder_radius_px, "must be > 0 when errors.blunders_per_mpx > 0");
  c.NonNegative("errors.blunder_depth_sigma_m", e.blunder_depth_sigma_m);
  c.IntRange("errors.occlusion_strip_px", e.occlusion_strip_px, 0, 100);
  c.Range("errors.dropout_fraction", e.dropout_fraction, 0.0, 0.5);
  c.NonNegative("errors.oblique_factor", e.oblique_factor);
  c.Range("errors.scale", e.scale, 0.0, 100.0);
  c.NonNegative("errors.keypoint_sigma_px", e.keypoint_sigma_px);
  c.ThrowIfFailed();
}

}  // namespace sacfuse
