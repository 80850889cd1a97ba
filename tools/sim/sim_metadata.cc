#include "tools/sim/sim_metadata.h"

#include <nlohmann/json.hpp>

namespace sacfuse::sim {

std::string SimOptionsJson(const SimOptions& o) {
  const SimErrorOptions& e = o.errors;
  nlohmann::ordered_json errors = {
      {"enabled", e.enabled},
      {"pose_position_sigma_m", e.pose_position_sigma_m},
      {"pose_rotation_sigma_deg", e.pose_rotation_sigma_deg},
      {"disparity_sigma_px", e.disparity_sigma_px},
      {"stereo_baseline_m", e.stereo_baseline_m},
      {"noise_correlation_px", e.noise_correlation_px},
      {"bias_amplitude_m", e.bias_amplitude_m},
      {"fattening_px", e.fattening_px},
      {"fattening_min_step_m", e.fattening_min_step_m},
      {"blunders_per_mpx", e.blunders_per_mpx},
      {"blunder_radius_px", e.blunder_radius_px},
      {"blunder_depth_sigma_m", e.blunder_depth_sigma_m},
      {"occlusion_strip_px", e.occlusion_strip_px},
      {"dropout_fraction", e.dropout_fraction},
      {"oblique_factor", e.oblique_factor},
      {"scale", e.scale},
      {"keypoint_sigma_px", e.keypoint_sigma_px},
  };
  nlohmann::ordered_json j = {
      {"preset", o.preset},
      {"seed", o.seed},
      {"scene", o.scene},
      {"from_las", o.from_las},
      {"area_width_m", o.area_width_m},
      {"area_height_m", o.area_height_m},
      {"origin_east_m", o.origin_east_m},
      {"origin_north_m", o.origin_north_m},
      {"ground_height_m", o.ground_height_m},
      {"crs", o.crs},
      {"obliques", o.obliques},
      {"oblique_tilt_deg", o.oblique_tilt_deg},
      {"gsd_m", o.gsd_m},
      {"nadir_width_px", o.nadir_width_px},
      {"nadir_height_px", o.nadir_height_px},
      {"nadir_focal_mm", o.nadir_focal_mm},
      {"oblique_focal_mm", o.oblique_focal_mm},
      {"pixel_size_um", o.pixel_size_um},
      {"forward_overlap", o.forward_overlap},
      {"side_overlap", o.side_overlap},
      {"max_nadir_views", o.max_nadir_views},
      {"max_oblique_views", o.max_oblique_views},
      {"depth_downsample", o.depth_downsample},
      {"reference_density_pts_m2", o.reference_density_pts_m2},
      {"errors", errors},
      {"write_truth", o.write_truth},
      {"eval_cell_m", o.eval_cell_m},
      {"sparse_area_per_point_m2", o.sparse_area_per_point_m2},
      {"min_sparse_points", o.min_sparse_points},
      {"jpeg_quality", o.jpeg_quality},
      {"sun_azimuth_deg", o.sun_azimuth_deg},
      {"sun_elevation_deg", o.sun_elevation_deg},
      {"ambient", o.ambient},
      {"city_rotation_deg", o.city_rotation_deg},
      {"las_cell_m", o.las_cell_m},
      {"write_consistency_graphs", o.write_consistency_graphs},
      {"depth", o.depth},
  };
  if (o.depth == "sgbm") {
    const SgbmDepthOptions& g = o.sgbm;
    j["sgbm"] = {{"max_sources", g.sources.max_sources},
                 {"min_baseline_ratio", g.sources.min_baseline_ratio},
                 {"max_baseline_ratio", g.sources.max_baseline_ratio},
                 {"min_shared_points", g.sources.min_shared_points},
                 {"max_axis_angle_deg", g.sources.max_axis_angle_deg},
                 {"block_size", g.match.block_size},
                 {"p2_multiplier", g.match.p2_multiplier},
                 {"left_right_max_diff", g.match.left_right_max_diff},
                 {"uniqueness_percent", g.match.uniqueness_percent},
                 {"speckle_window_px", g.match.speckle_window_px},
                 {"speckle_range", g.match.speckle_range},
                 {"erode_px", g.match.erode_px},
                 {"depth_percentile", g.depth_percentile},
                 {"depth_margin", g.depth_margin},
                 {"near_fraction", g.near_fraction},
                 {"max_disparities", g.max_disparities},
                 {"merge_tolerance", g.merge_tolerance},
                 {"min_agree", g.min_agree}};
  }
  return j.dump();
}

std::string PoseJson(const Rigid3d& cam_from_world) {
  const Eigen::Quaterniond q = cam_from_world.rotation.normalized();
  const Eigen::Vector3d t = cam_from_world.translation;
  const Eigen::Vector3d c = cam_from_world.Inverse().translation;
  nlohmann::ordered_json j = {{"qw", q.w()}, {"qx", q.x()}, {"qy", q.y()}, {"qz", q.z()},
                              {"tx", t.x()}, {"ty", t.y()}, {"tz", t.z()}, {"center", {c.x(), c.y(), c.z()}}};
  return j.dump();
}

std::string CameraJson(const PinholeCamera& c) {
  nlohmann::ordered_json j = {{"model", "PINHOLE"}, {"width", c.width}, {"height", c.height},
                              {"fx", c.fx},         {"fy", c.fy},       {"cx", c.cx},
                              {"cy", c.cy}};
  return j.dump();
}

}  // namespace sacfuse::sim
