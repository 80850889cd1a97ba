#include "tools/sim/simulate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/colmap_array.h"
#include "io/colmap_model.h"
#include "io/colmap_workspace.h"
#include "io/crs_wkt.h"
#include "io/geo_mask_io.h"
#include "tools/sim/city_layout.h"
#include "tools/sim/city_scene.h"
#include "tools/sim/consistency_graphs.h"
#include "tools/sim/depth_errors.h"
#include "tools/sim/depth_normals.h"
#include "tools/sim/flight_plan.h"
#include "tools/sim/las_scene.h"
#include "tools/sim/reference_cloud.h"
#include "tools/sim/render.h"
#include "tools/sim/sgbm_workspace.h"
#include "tools/sim/sim_metadata.h"
#include "tools/sim/sim_random.h"
#include "tools/sim/sim_workspace.h"
#include "tools/sim/sparse_points.h"
#include "tools/sim/truth_ortho.h"
#include "tools/sim/visibility.h"
#include "io/json_text.h"

namespace sacfuse {
namespace sim {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

std::string Join(const std::string& dir, const std::string& relative) { return (fs::path(dir) / relative).string(); }

// One workspace on disk (the main one or truth/).
struct Workspace {
  std::string root;
  ColmapModel model;
  std::string Image(const std::string& name) const { return Join(root, "images/" + name); }
  std::string Depth(const std::string& name) const { return Join(root, "stereo/depth_maps/" + name + ".geometric.bin"); }
  std::string Normal(const std::string& name) const {
    return Join(root, "stereo/normal_maps/" + name + ".geometric.bin");
  }
  // Writes the depth map and, when `camera` is given, the normal map computed from it with that camera.
  void WriteMaps(const std::string& name, const DepthMap& depth, const PinholeCamera* camera) const {
    CreateParentDirs(Depth(name));
    WriteColmapArray(Depth(name), depth);
    if (camera == nullptr) return;
    CreateParentDirs(Normal(name));
    WriteColmapArray(Normal(name), NormalsFromDepth(depth, *camera));
  }
  void AddView(uint32_t index, const PlannedView& view, const Rigid3d& pose, std::vector<ColmapPoint2D> points2D) {
    ColmapCamera camera;
    camera.camera_id = index + 1;
    camera.model = "PINHOLE";
    camera.width = static_cast<uint64_t>(view.camera.width);
    camera.height = static_cast<uint64_t>(view.camera.height);
    camera.params = {view.camera.fx, view.camera.fy, view.camera.cx, view.camera.cy};
    model.cameras[camera.camera_id] = camera;
    ColmapImage image;
    image.image_id = index + 1;
    image.camera_id = camera.camera_id;
    image.cam_from_world_rotation = pose.rotation.normalized();
    image.cam_from_world_translation = pose.translation;
    image.name = view.name;
    image.points2D = std::move(points2D);
    model.images.push_back(std::move(image));
  }
  void Finish(const std::vector<std::string>& names) const {
    const std::string sparse = Join(root, "sparse");
    fs::create_directories(sparse);
    WriteColmapModelBinary(model, sparse);
    WriteColmapStereoConfigs(root, names);
  }
};

// The main workspace's views in images.bin order, i.e. the image indices COLMAP's consistency graphs store.
// Workspace::AddView appends loop view v as images[v] with image_id v + 1, WriteColmapModelBinary writes the
// images in vector order and fusion.cfg lists the same names in the same order: image index == view index.
std::vector<View> ModelViews(const ColmapModel& model) {
  std::vector<View> views;
  views.reserve(model.images.size());
  for (const ColmapImage& image : model.images) {
    const ColmapCamera& camera = model.cameras.at(image.camera_id);
    View view;
    view.index = static_cast<uint32_t>(views.size());
    if (image.image_id != view.index + 1) throw Error("sim: images.bin order differs from the view order");
    view.name = image.name;
    view.camera = {static_cast<int>(camera.width), static_cast<int>(camera.height), camera.params[0],
                   camera.params[1],                camera.params[2],                camera.params[3]};
    view.cam_from_world = {image.cam_from_world_rotation, image.cam_from_world_translation};
    views.push_back(std::move(view));
  }
  return views;
}

Json ViewJson(uint32_t index, const PlannedView& view, const Rigid3d& written, const PoseError& pose_error,
              const ViewErrorModel& model, const DepthErrorReport& report, const PinholeCamera& depth_camera,
              const RenderedView& rendered, const Workspace& ws, double ground_z, bool has_normals) {
  Json bias = Json::array();
  for (const CosineMode& m : report.bias_modes) {
    bias.push_back({{"fu", m.fu}, {"fv", m.fv}, {"phase", m.phase}, {"weight", m.weight}});
  }
  const double range = (view.cam_from_world.Inverse().translation.z() - ground_z) /
                       std::max(1e-9, -(view.cam_from_world.rotation.conjugate() * Eigen::Vector3d::UnitZ()).z());
  const Json true_pose = Json::parse(PoseJson(view.cam_from_world));
  const Json written_pose = Json::parse(PoseJson(written));
  const auto rel = [&](const std::string& path) { return fs::path(path).lexically_relative(ws.root).string(); };
  return Json{
      {"index", index},
      {"image_id", index + 1},
      {"name", view.name},
      {"kind", ViewKindName(view.kind)},
      {"exposure", view.exposure},
      {"line", view.line},
      {"camera", Json::parse(CameraJson(view.camera))},
      {"depth_camera", Json::parse(CameraJson(depth_camera))},
      {"true_cam_from_world", true_pose},
      {"written_cam_from_world", written_pose},
      {"true_center", true_pose["center"]},
      {"written_center", written_pose["center"]},
      {"footprint_center", {view.footprint_center.x(), view.footprint_center.y()}},
      {"footprint_in_area_m2", view.footprint_in_area_m2},
      {"errors",
       {{"enabled", model.enabled},
        {"pose_center_delta_m", {pose_error.center_delta_m.x(), pose_error.center_delta_m.y(), pose_error.center_delta_m.z()}},
        {"pose_rotation_delta_deg",
         {pose_error.rotation_delta_rad.x() * 180.0 / M_PI, pose_error.rotation_delta_rad.y() * 180.0 / M_PI,
          pose_error.rotation_delta_rad.z() * 180.0 / M_PI}},
        {"disparity_sigma_px", model.disparity_sigma_px},
        {"baseline_m", model.baseline_m},
        {"stereo_sigma_at_center_m", model.enabled ? model.StereoSigma(range) : 0.0},
        {"bias_amplitude_m", model.bias_amplitude_m},
        {"bias_modes", bias},
        {"blunder_count", report.blunder_count},
        {"blunder_pixels", report.blunder_pixels},
        {"fattened_pixels", report.fattened_pixels},
        {"occluded_pixels", report.occluded_pixels},
        {"dropout_pixels", report.dropout_pixels},
        {"true_valid_pixels", report.valid_in},
        {"valid_pixels", report.valid_out}}},
      {"render", {{"tiles", rendered.tiles}, {"triangles", rendered.triangles}}},
      {"files",
       {{"image", rel(ws.Image(view.name))}, {"depth", rel(ws.Depth(view.name))}, {"normal", has_normals ? Json(rel(ws.Normal(view.name))) : Json(nullptr)}}},
  };
}

Json SgbmPassJson(const SgbmPassSummary& pass) {
  Json views = Json::array();
  double valid_sum = 0.0, error_sum = 0.0, over_sum = 0.0;
  for (const SgbmViewReport& v : pass.views) {
    views.push_back({{"name", v.name},
                     {"sources", v.sources},
                     {"pair_valid_fraction", v.pair_valid_fraction},
                     {"valid_fraction", v.valid_fraction},
                     {"median_abs_error_m", v.median_abs_error_m},
                     {"p90_abs_error_m", v.p90_abs_error_m},
                     {"share_over_1m", v.share_over_1m},
                     {"seconds", v.seconds}});
    valid_sum += v.valid_fraction;
    error_sum += v.median_abs_error_m;
    over_sum += v.share_over_1m;
  }
  const double n = std::max<double>(1.0, static_cast<double>(pass.views.size()));
  return Json{{"pairs", pass.pairs},
              {"valid_pixels", pass.valid_pixels},
              {"mean_valid_fraction", valid_sum / n},
              {"mean_median_abs_error_m", error_sum / n},
              {"mean_share_over_1m", over_sum / n},
              {"match_seconds", pass.match_seconds},
              {"seconds", pass.seconds},
              {"views", views}};
}

}  // namespace

SimSummary SimulateScene(const SimOptions& o, const SceneSpec& scene, const std::string& out_dir,
                         const SimProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  auto report = [&](const std::string& stage, size_t done, size_t total) {
    if (progress) progress(stage, done, total);
  };
  if (scene.surface == nullptr) throw Error("SimulateScene: no surface");
  const Surface& surface = *scene.surface;
  const Box2d area{scene.area_x0, scene.area_y0, scene.area_x1, scene.area_y1};
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw Error(out_dir + ": cannot create the output folder: " + ec.message());

  const FlightPlan plan = PlanFlight(o, area, scene.ground_z);
  if (plan.views.empty()) throw ConfigError("sim: no view of the flight plan sees the area; check the area and overlaps");
  report("plan", 1, 1);

  SimSummary summary;
  summary.workspace_dir = out_dir;
  summary.reference_las = Join(out_dir, "reference.las");
  summary.eval_mask_png = Join(out_dir, "eval_mask.png");
  summary.metadata_json = Join(out_dir, "metadata.json");
  const ReferenceProgress ref_progress = [&](size_t done, size_t total) { report("reference", done, total); };
  summary.reference_points =
      scene.kind == "las" ? WriteLasReference(o.from_las, surface, area, summary.reference_las)
                          : WriteSampledReference(surface, area, o.reference_density_pts_m2,
                                                  StreamKey(o.seed, Stream::kReference), summary.reference_las,
                                                  ref_progress);

  const Lighting lighting = Lighting::FromAngles(o.sun_azimuth_deg, o.sun_elevation_deg, o.ambient);
  const double cell = EvalCellSize(o.eval_cell_m, area);
  CoverageCounter coverage(surface, area, cell);
  const int sparse_count = std::max(
      o.min_sparse_points, static_cast<int>(std::ceil(area.Width() * area.Height() / o.sparse_area_per_point_m2)));
  SparsePointBuilder sparse(surface, area, sparse_count, lighting, StreamKey(o.seed, Stream::kSparse));

  Workspace main_ws{out_dir, {}};
  Workspace truth_ws{Join(out_dir, "truth"), {}};
  Json views = Json::array();
  std::vector<std::string> names;
  const int ds = std::max(1, o.depth_downsample);
  const double keypoint_sigma = o.errors.enabled ? o.errors.keypoint_sigma_px * o.errors.scale : 0.0;
  const bool sgbm = o.depth == "sgbm";
  auto depth_camera_of = [&](const PlannedView& view) {
    const int dw = std::max(1, view.camera.width / ds), dh = std::max(1, view.camera.height / ds);
    return ds == 1 ? view.camera : view.camera.Scaled(dw, dh);
  };
  for (size_t v = 0; v < plan.views.size(); ++v) {
    const auto i = static_cast<uint32_t>(v);
    const PlannedView& view = plan.views[v];
    const bool oblique = view.kind != ViewKind::kNadir;
    const PoseError pose_error = DrawPoseError(o.errors, StreamKey(o.seed, Stream::kPose, i));
    const Rigid3d written = ApplyPoseError(view.cam_from_world, pose_error);
    const PinholeCamera depth_camera = depth_camera_of(view);
    const int dw = depth_camera.width, dh = depth_camera.height;

    RenderRequest request;
    request.surface = &surface;
    request.camera = view.camera;
    request.cam_from_world = view.cam_from_world;
    request.depth_width = dw;
    request.depth_height = dh;
    request.lighting = lighting;
    RenderedView rendered = RenderView(request);
    WriteJpeg(main_ws.Image(view.name), rendered.image, o.jpeg_quality);
    RgbImage().data.swap(rendered.image.data);  // free the image before the depth stages

    coverage.AddView(rendered.depth, depth_camera, view.cam_from_world);
    std::vector<ColmapPoint2D> written_points2D, true_points2D;
    sparse.ObserveView(i, rendered.depth, depth_camera, view.camera, view.cam_from_world, written, keypoint_sigma,
                       &written_points2D, o.write_truth ? &true_points2D : nullptr);

    // Flight direction (world +x) in the image decides the stereo baseline axis.
    const Eigen::Vector3d flight_in_cam = view.cam_from_world.rotation * Eigen::Vector3d::UnitX();
    const ViewErrorModel error_model = MakeViewErrorModel(o.errors, oblique, view.camera.fx, plan.baseline_m, ds,
                                                          std::abs(flight_in_cam.x()) >= std::abs(flight_in_cam.y()));
    DepthErrorReport error_report;
    if (!sgbm) {  // with --depth sgbm the maps are matched from the images once all are rendered (below)
      const DepthMap depth = ApplyDepthErrors(rendered.depth, error_model, StreamKey(o.seed, Stream::kStereoNoise, i),
                                              &error_report);
      main_ws.WriteMaps(view.name, depth, o.write_normal_maps ? &depth_camera : nullptr);
    }
    summary.depth_pixels += error_report.valid_out;
    main_ws.AddView(i, view, written, std::move(written_points2D));
    if (o.write_truth) {
      truth_ws.WriteMaps(view.name, rendered.depth, o.write_normal_maps ? &depth_camera : nullptr);
      CreateRelativeSymlink(main_ws.Image(view.name), truth_ws.Image(view.name));
      truth_ws.AddView(i, view, view.cam_from_world, std::move(true_points2D));
    }
    views.push_back(ViewJson(i, view, written, pose_error, error_model, error_report, depth_camera, rendered, main_ws,
                             scene.ground_z, o.write_normal_maps));
    names.push_back(view.name);
    (oblique ? summary.num_oblique : summary.num_nadir) += 1;
    report("views", v + 1, plan.views.size());
  }
  summary.num_views = static_cast<int>(plan.views.size());

  summary.sparse_points = sparse.Finish(&main_ws.model);
  main_ws.Finish(names);
  if (o.write_truth) {
    sparse.Finish(&truth_ws.model);
    truth_ws.Finish(names);
  }
  report("sparse", 1, 1);
  WriteGeoMask(summary.eval_mask_png, coverage.Mask(2), scene.crs);
  if (o.truth_ortho_cell_m > 0) {
    std::string wkt;
    try {
      wkt = ProjectCrsWkt(scene.crs, CrsWktDialect::kGdal);
    } catch (const std::exception&) {
      wkt = scene.crs;  // a LiDAR scene's CRS is WKT already
    }
    WriteTruthOrtho(surface, area, lighting, o.truth_ortho_cell_m, wkt, Join(out_dir, "truth_ortho.tif"));
  }

  Json sgbm_json = nullptr;
  if (sgbm) {
    SgbmPassIo io;
    io.images_dir = Join(out_dir, "images");
    io.depth_downsample = ds;
    io.true_depth = [&](uint32_t v) {  // rendered again (depth only) for the error statistics
      RenderRequest request;
      request.surface = &surface;
      request.camera = plan.views[v].camera;
      request.cam_from_world = plan.views[v].cam_from_world;
      request.depth_width = depth_camera_of(plan.views[v]).width;
      request.depth_height = depth_camera_of(plan.views[v]).height;
      request.render_image = false;
      return RenderView(request).depth;
    };
    io.write_maps = [&](uint32_t v, const DepthMap& depth) {
      const PinholeCamera depth_camera = depth_camera_of(plan.views[v]);
      main_ws.WriteMaps(names[v], depth, o.write_normal_maps ? &depth_camera : nullptr);
    };
    io.progress = [&](size_t done, size_t total) { report("sgbm", done, total); };
    const SgbmPassSummary pass = RunSgbmPass(main_ws.model, o.sgbm, io);
    summary.depth_pixels = pass.valid_pixels;
    // patch-match.cfg names each view's partners, as a pipeline of stereo pairs does (fusion's independent support).
    std::vector<std::vector<std::string>> sources;
    for (const SgbmViewReport& v : pass.views) sources.push_back(v.sources);
    WriteColmapStereoConfigs(out_dir, names, sources);
    sgbm_json = SgbmPassJson(pass);
  }

  Json consistency = nullptr;
  if (o.write_consistency_graphs) {  // main workspace only: truth/ stays as it was
    const auto cg_start = std::chrono::steady_clock::now();
    report("consistency", 0, names.size());
    const ConsistencyGraphSummary cg = WriteConsistencyGraphs(
        out_dir, ModelViews(main_ws.model), {}, [&](size_t done, size_t total) { report("consistency", done, total); });
    summary.consistency_graphs = static_cast<int>(cg.num_graphs);
    consistency = {
        {"graphs", cg.num_graphs},
        {"valid_pixels", cg.valid_pixels},
        {"pixels_with_views", cg.pixels_with_views},
        {"entries", cg.entries},
        {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - cg_start).count()}};
  }

  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Json meta{
      {"generator", "sacfuse simulate"},
      {"preset", o.preset},
      {"seed", o.seed},
      {"scene", {{"kind", scene.kind}, {"description", surface.Describe()}, {"from_las", o.from_las}}},
      {"crs", scene.crs},
      {"gsd_m", o.gsd_m},
      {"area",
       {{"x0", area.min.x()}, {"y0", area.min.y()}, {"x1", area.max.x()}, {"y1", area.max.y()}, {"width_m", area.Width()},
        {"height_m", area.Height()}}},
      {"ground_z_m", scene.ground_z},
      {"options", Json::parse(SimOptionsJson(o))},
      {"flight",
       {{"nadir_focal_px", plan.nadir_focal_px},
        {"oblique_focal_px", plan.oblique_focal_px},
        {"flying_height_m", plan.flying_height_m},
        {"camera_z_m", plan.camera_z_m},
        {"baseline_m", plan.baseline_m},
        {"line_spacing_m", plan.line_spacing_m},
        {"num_exposures", plan.num_exposures},
        {"candidate_nadir_views", plan.candidate_nadir},
        {"candidate_oblique_views", plan.candidate_oblique}}},
      {"files",
       {{"workspace", "."},
        {"depth_type", "geometric"},
        {"reference_las", "reference.las"},
        {"eval_mask", "eval_mask.png"},
        {"truth_workspace", o.write_truth ? Json("truth") : Json(nullptr)},
        {"consistency_graphs", o.write_consistency_graphs ? Json("stereo/consistency_graphs") : Json(nullptr)}}},
      {"eval_mask", {{"cell_m", cell}, {"min_views", 2}, {"fraction_of_area", coverage.FractionSeen(2)}}},
      {"summary",
       {{"num_views", summary.num_views},
        {"num_nadir", summary.num_nadir},
        {"num_oblique", summary.num_oblique},
        {"depth_pixels", summary.depth_pixels},
        {"reference_points", summary.reference_points},
        {"sparse_candidates", sparse.num_candidates()},
        {"sparse_points", summary.sparse_points},
        {"seconds", summary.seconds}}},
      {"consistency_graphs", consistency},
      {"views", views},
  };
  if (sgbm) {
    meta["depth_mode"] = "sgbm";
    meta["sgbm"] = sgbm_json;
  }
  WriteFileAtomically(summary.metadata_json, JsonText(meta, 1) + "\n");
  report("done", 1, 1);
  return summary;
}

}  // namespace sim

SimSummary SimulateBlock(const SimOptions& o, const std::string& out_dir, const SimProgress& progress) {
  ValidateSimOptions(o);
  if (progress) progress("scene", 0, 1);
  sim::SceneSpec spec;
  std::unique_ptr<sim::Surface> surface;
  if (o.scene == "las") {
    sim::LasSceneOptions lo;
    lo.path = o.from_las;
    lo.area_width_m = o.area_width_m;
    lo.area_height_m = o.area_height_m;
    lo.cell_m = o.las_cell_m;
    lo.seed = o.seed;
    auto las = std::make_unique<sim::LasScene>(lo);
    spec.area_x0 = las->area().min.x(), spec.area_y0 = las->area().min.y();
    spec.area_x1 = las->area().max.x(), spec.area_y1 = las->area().max.y();
    spec.ground_z = las->ground_z();
    spec.crs = las->crs_wkt();
    spec.kind = "las";
    surface = std::move(las);
  } else {
    sim::CityParams p;
    p.area_width_m = o.area_width_m;
    p.area_height_m = o.area_height_m;
    p.center_x = o.origin_east_m + 0.5 * o.area_width_m;
    p.center_y = o.origin_north_m + 0.5 * o.area_height_m;
    p.ground_z = o.ground_height_m;
    p.rotation_deg = o.city_rotation_deg;
    p.margin_m = std::clamp(0.3 * std::max(o.area_width_m, o.area_height_m), 60.0, 300.0);
    p.seed = o.seed;
    surface = std::make_unique<sim::CityScene>(sim::GenerateCityLayout(p));
    spec.area_x0 = o.origin_east_m, spec.area_y0 = o.origin_north_m;
    spec.area_x1 = o.origin_east_m + o.area_width_m, spec.area_y1 = o.origin_north_m + o.area_height_m;
    spec.ground_z = o.ground_height_m;
    spec.crs = o.crs;
    spec.kind = "city";
  }
  spec.surface = surface.get();
  if (progress) progress("scene", 1, 1);
  return sim::SimulateScene(o, spec, out_dir, progress);
}

}  // namespace sacfuse
