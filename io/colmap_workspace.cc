#include "io/colmap_workspace.h"

#include "io/colmap_consistency_graph.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>


#include "core/error.h"
#include "io/atomic_file.h"
#include "io/colmap_array.h"
#include "io/colmap_patch_match_config.h"
#include "io/input_file.h"
#include "io/input_warnings.h"
#include "io/rgb_image_file.h"
#include "io/view_checks.h"

namespace sacfuse {
namespace {

std::string JoinPath(const std::string& dir, const std::string& relative) {
  if (dir.empty()) return relative;
  return dir.back() == '/' ? dir + relative : dir + "/" + relative;
}

// The sparse file that ReadColmapModel used (for error messages).
std::string SparseFile(const std::string& dir, const std::string& stem) {
  const std::string bin = JoinPath(dir, "sparse/" + stem + ".bin");
  std::error_code ec;
  return std::filesystem::exists(bin, ec) ? bin : JoinPath(dir, "sparse/" + stem + ".txt");
}

std::string Quoted(const std::string& s) { return "\"" + s + "\""; }

bool IsFisheye(const std::string& model) {
  return model == "OPENCV_FISHEYE" || model == "SIMPLE_RADIAL_FISHEYE" || model == "RADIAL_FISHEYE" ||
         model == "THIN_PRISM_FISHEYE" || model == "RAD_TAN_THIN_PRISM_FISHEYE";
}

// Pinhole intrinsics of a COLMAP camera without distortion. Every non-fisheye COLMAP model is
// f/fx,fy then cx,cy then distortion terms (FOV's omega = 0 is the pinhole case too).
PinholeCamera ToPinhole(const ColmapCamera& cam, const std::string& cameras_file, const std::string& image_name) {
  const std::string who = "camera_id " + std::to_string(cam.camera_id) + " (" + cam.model + ", used by image " +
                          Quoted(image_name) + ")";
  const std::string hint = "; the workspace must be undistorted (run colmap image_undistorter)";
  if (IsFisheye(cam.model)) {
    throw InputError(cameras_file, who + ": fisheye models are not pinhole even without distortion" + hint);
  }
  const int num_params = ColmapCameraModelNumParams(cam.model);
  if (num_params < 0) throw InputError(cameras_file, who + ": unknown camera model" + hint);
  if (static_cast<int>(cam.params.size()) != num_params) {
    throw InputError(cameras_file, who + ": expected " + std::to_string(num_params) + " parameters, got " +
                                       std::to_string(cam.params.size()));
  }
  const bool single_focal = cam.model == "SIMPLE_PINHOLE" || cam.model == "SIMPLE_RADIAL" || cam.model == "RADIAL";
  const size_t first_distortion = single_focal ? 3 : 4;
  for (size_t k = first_distortion; k < cam.params.size(); ++k) {
    if (cam.params[k] != 0.0) {
      throw InputError(cameras_file, who + ": nonzero distortion parameter " + std::to_string(k - first_distortion + 1) +
                                         " (" + std::to_string(cam.params[k]) + ")" + hint);
    }
  }
  constexpr uint64_t kIntMax = static_cast<uint64_t>(std::numeric_limits<int>::max());
  if (cam.width == 0 || cam.height == 0 || cam.width > kIntMax || cam.height > kIntMax) {
    throw InputError(cameras_file, who + ": invalid size " + std::to_string(cam.width) + "x" + std::to_string(cam.height));
  }
  PinholeCamera pinhole;
  pinhole.width = static_cast<int>(cam.width);
  pinhole.height = static_cast<int>(cam.height);
  pinhole.fx = cam.params[0];
  pinhole.fy = single_focal ? cam.params[0] : cam.params[1];
  pinhole.cx = cam.params[single_focal ? 1 : 2];
  pinhole.cy = cam.params[single_focal ? 2 : 3];
  if (!pinhole.IsValid() || !std::isfinite(pinhole.fx) || !std::isfinite(pinhole.fy) || !std::isfinite(pinhole.cx) ||
      !std::isfinite(pinhole.cy)) {
    throw InputError(cameras_file, who + ": focal length must be positive and all parameters finite");
  }
  return pinhole;
}

// fusion.cfg: one image name per line; surrounding whitespace and empty lines ignored (as COLMAP does).
std::vector<std::pair<std::string, int>> ReadFusionConfig(const std::string& path) {
  std::ifstream in = OpenInputStream(path, "fusion.cfg");
  std::vector<std::pair<std::string, int>> names;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t begin = line.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) continue;
    const size_t end = line.find_last_not_of(" \t\r\n");
    names.emplace_back(line.substr(begin, end - begin + 1), line_number);
  }
  return names;
}

// True when (w, h) is (W, H) scaled by one factor with each side rounded to within 1 px: the intervals of
// factors compatible with each side must overlap.
bool SizeMatchesAspect(int w, int h, int image_w, int image_h) {
  if (w <= 0 || h <= 0 || w > image_w || h > image_h) return false;
  const double lo = std::max((w - 1.0) / image_w, (h - 1.0) / image_h);
  const double hi = std::min((w + 1.0) / image_w, (h + 1.0) / image_h);
  return lo <= hi;
}

// Reads a dense array for `view`, checking its channel count and size; every error names the image.
Raster<float> ReadDenseForView(const std::string& path, const View& view, int channels, const char* kind) {
  const std::string for_image = " (" + std::string(kind) + " of image " + Quoted(view.name) + ")";
  Raster<float> raster;
  try {
    raster = ReadColmapArray(path);
  } catch (const InputError& e) {
    throw InputError(e.file(), e.message() + for_image);
  }
  if (raster.channels != channels) {
    throw InputError(path, std::to_string(raster.channels) + " channels, expected " + std::to_string(channels) +
                               for_image);
  }
  if (!SizeMatchesAspect(raster.width, raster.height, view.camera.width, view.camera.height)) {
    throw InputError(path, "size " + std::to_string(raster.width) + "x" + std::to_string(raster.height) +
                               " is not the image size " + std::to_string(view.camera.width) + "x" +
                               std::to_string(view.camera.height) + " or a downscale of it with the same aspect" +
                               for_image);
  }
  return raster;
}

std::string TypeSuffix(ColmapDepthType type) {
  return type == ColmapDepthType::kGeometric ? ".geometric.bin" : ".photometric.bin";
}

}  // namespace

ColmapWorkspace::ColmapWorkspace(const std::string& dir, ColmapDepthType depth_type)
    : dir_(dir), depth_type_(depth_type), model_(ReadColmapModel(JoinPath(dir, "sparse"))) {
  const std::string images_file = SparseFile(dir, "images");
  std::map<std::string, size_t> by_name;
  for (size_t i = 0; i < model_.images.size(); ++i) {
    if (!by_name.emplace(model_.images[i].name, i).second) {
      throw InputError(images_file, "image name " + Quoted(model_.images[i].name) + " appears more than once");
    }
  }
  std::vector<size_t> order;
  const std::string fusion_cfg = JoinPath(dir, "stereo/fusion.cfg");
  std::error_code ec;
  if (std::filesystem::exists(fusion_cfg, ec)) {
    std::set<std::string> seen;
    for (const auto& [name, line] : ReadFusionConfig(fusion_cfg)) {
      const auto it = by_name.find(name);
      if (it == by_name.end()) {
        throw InputError(fusion_cfg, "line " + std::to_string(line) + ": image " + Quoted(name) +
                                         " is not in the sparse model " + images_file);
      }
      if (!seen.insert(name).second) {
        throw InputError(fusion_cfg, "line " + std::to_string(line) + ": image " + Quoted(name) + " is listed twice");
      }
      order.push_back(it->second);
    }
  } else {
    for (size_t i = 0; i < model_.images.size(); ++i) order.push_back(i);
  }
  const std::string cameras_file = SparseFile(dir, "cameras");
  // Every listed image's camera is checked, with or without a depth map: a broken model is an error first.
  std::vector<View> listed;
  listed.reserve(order.size());
  for (const size_t i : order) {
    const ColmapImage& img = model_.images[i];
    View view;
    view.name = img.name;
    view.camera = ToPinhole(model_.cameras.at(img.camera_id), cameras_file, img.name);
    view.cam_from_world.rotation = img.cam_from_world_rotation.normalized();
    view.cam_from_world.translation = img.cam_from_world_translation;
    const std::string who = "image " + Quoted(img.name) + " (image_id " + std::to_string(img.image_id) + ")";
    CheckViewIntrinsics(view.camera, cameras_file, who + ", camera_id " + std::to_string(img.camera_id));
    CheckViewPose(view.cam_from_world, images_file, who);
    listed.push_back(std::move(view));
  }
  const std::vector<size_t> kept = WithDepthMaps(order);  // a subsequence of order
  views_.reserve(kept.size());
  model_index_to_view_.assign(model_.images.size(), UINT32_MAX);
  for (size_t j = 0, k = 0; j < order.size() && k < kept.size(); ++j) {
    if (order[j] != kept[k]) continue;
    ++k;
    model_index_to_view_[order[j]] = static_cast<uint32_t>(views_.size());
    listed[j].index = static_cast<uint32_t>(views_.size());
    views_.push_back(std::move(listed[j]));
  }
  ReadMatchingPartners();
}

void ColmapWorkspace::ReadMatchingPartners() {
  const std::string path = JoinPath(dir_, "stereo/patch-match.cfg");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return;
  std::vector<std::vector<uint32_t>> partners;
  try {
    partners = MatchingPartners(ReadPatchMatchConfig(path), views_);
  } catch (const InputError& e) {
    // The depth maps are still good: fuse them without knowing the pairs.
    WarnAboutInput(path, e.message() +
                             "; the views' matching partners are unknown (fusion.independent_support has no effect)");
    return;
  }
  for (size_t i = 0; i < views_.size(); ++i) views_[i].matching_partners = std::move(partners[i]);
}

std::vector<size_t> ColmapWorkspace::WithDepthMaps(const std::vector<size_t>& order) const {
  auto depth_path = [&](size_t i, ColmapDepthType type) {
    return JoinPath(dir_, "stereo/depth_maps/" + model_.images[i].name + TypeSuffix(type));
  };
  std::error_code ec;
  std::vector<size_t> kept, missing;
  for (const size_t i : order) (std::filesystem::exists(depth_path(i, depth_type_), ec) ? kept : missing).push_back(i);
  if (missing.empty()) return kept;
  const char* type = depth_type_ == ColmapDepthType::kGeometric ? "geometric" : "photometric";
  if (kept.empty()) {
    // Which maps the workspace has instead decides the fix.
    const ColmapDepthType other_type =
        depth_type_ == ColmapDepthType::kGeometric ? ColmapDepthType::kPhotometric : ColmapDepthType::kGeometric;
    const char* other = depth_type_ == ColmapDepthType::kGeometric ? "photometric" : "geometric";
    size_t others = 0;
    for (const size_t i : order) others += std::filesystem::exists(depth_path(i, other_type), ec) ? 1 : 0;
    std::string fix;
    if (others > 0) {
      fix = "; it has " + std::string(other) + " ones for " + std::to_string(others) + " of them" +
            (depth_type_ == ColmapDepthType::kGeometric
                 ? " (patch_match_stereo run with --PatchMatchStereo.geom_consistency false writes only those)"
                 : "") +
            ": set input.depth_type: " + other;
    } else {
      fix = "; run the dense matcher first (colmap patch_match_stereo, or a matcher writing "
            "stereo/depth_maps/<image>." + std::string(type) + ".bin)";
    }
    throw InputError(depth_path(missing.front(), depth_type_),
                     "missing: no " + std::string(type) + " depth map for any of the " + std::to_string(order.size()) +
                         " images to fuse" + fix);
  }
  // As COLMAP's stereo_fusion ("Ignoring image ..., because input does not exist"): the other views are fused.
  for (const size_t i : missing) {
    WarnAboutInput(depth_path(i, depth_type_),
                   "missing: image " + Quoted(model_.images[i].name) + " has no " + type +
                       " depth map and is left out (" + std::to_string(kept.size()) + " of " +
                       std::to_string(order.size()) + " images are fused); remove it from stereo/fusion.cfg, or "
                       "match it, to silence this");
  }
  return kept;
}

std::string ColmapWorkspace::ImagePath(const View& view) const { return JoinPath(dir_, "images/" + view.name); }

std::string ColmapWorkspace::DepthMapPath(const View& view) const {
  return JoinPath(dir_, "stereo/depth_maps/" + view.name + TypeSuffix(depth_type_));
}

std::string ColmapWorkspace::ConsistencyGraphPath(const View& view) const {
  return JoinPath(dir_, "stereo/consistency_graphs/" + view.name + TypeSuffix(depth_type_));
}

bool ColmapWorkspace::HasConsistencyGraph(const View& view) const {
  std::error_code ec;
  return std::filesystem::exists(ConsistencyGraphPath(view), ec);  // anything there is read (and checked)
}

ConsistencyGraph ColmapWorkspace::ReadConsistencyGraph(const View& view) const {
  const std::string path = ConsistencyGraphPath(view);
  ConsistencyGraph raw = ReadColmapConsistencyGraph(path);
  ConsistencyGraph graph;
  graph.width = raw.width;
  graph.height = raw.height;
  graph.pixel_offsets.assign(raw.pixel_offsets.size(), 0);
  graph.view_indices.reserve(raw.view_indices.size());
  for (size_t p = 0; p + 1 < raw.pixel_offsets.size(); ++p) {
    for (uint32_t k = raw.pixel_offsets[p]; k < raw.pixel_offsets[p + 1]; ++k) {
      const uint32_t idx = raw.view_indices[k];
      if (idx >= model_index_to_view_.size()) {
        throw InputError(path, "image index " + std::to_string(idx) + " beyond the " +
                                   std::to_string(model_index_to_view_.size()) + " images of the model (image " +
                                   Quoted(view.name) + ")");
      }
      if (model_index_to_view_[idx] != UINT32_MAX) graph.view_indices.push_back(model_index_to_view_[idx]);
    }
    graph.pixel_offsets[p + 1] = static_cast<uint32_t>(graph.view_indices.size());
  }
  return graph;
}

std::string ColmapWorkspace::NormalMapPath(const View& view) const {
  return JoinPath(dir_, "stereo/normal_maps/" + view.name + TypeSuffix(depth_type_));
}

DepthMap ColmapWorkspace::ReadDepthMap(const View& view) const {
  return WarnIfNoValidDepth(ReadDenseForView(DepthMapPath(view), view, 1, "depth map"), view, DepthMapPath(view));
}

DepthRasterSize ColmapWorkspace::DepthSize(const View& view) const {
  const ColmapArrayShape shape = ReadColmapArrayShape(DepthMapPath(view));
  return {shape.width, shape.height};
}

DepthMap ColmapWorkspace::ReadDepthWindow(const View& view, const PixelWindow& window) const {
  return ReadColmapArrayWindow(DepthMapPath(view), window);
}

DepthMap ColmapWorkspace::ReadDepthRows(const View& view, const std::vector<int>& rows) const {
  // A map that ReadDepthMap refuses goes through it, so that it is refused with the same message.
  const std::string path = DepthMapPath(view);
  ColmapArrayShape shape;
  try {
    shape = ReadColmapArrayShape(path);
  } catch (const InputError&) {
    return DepthBlock::ReadDepthRows(view, rows);
  }
  if (shape.channels != 1 || !SizeMatchesAspect(shape.width, shape.height, view.camera.width, view.camera.height)) {
    return DepthBlock::ReadDepthRows(view, rows);
  }
  return ReadColmapArrayRowList(path, rows);
}

std::vector<double> ColmapWorkspace::SceneHeights() const {
  std::vector<double> z;
  z.reserve(model_.points3D.size());
  for (const auto& [id, p] : model_.points3D) {
    if (std::isfinite(p.xyz.z())) z.push_back(p.xyz.z());
  }
  if (!z.empty()) return z;
  // Without sparse points the block's height range would fall back to the config's tiling.z_min_m/z_max_m, which
  // need not hold the scene (footprints, tiles and windows then miss parts of it): the depth maps say where it is.
  std::call_once(heights_once_, [this] {
    sampled_heights_ = SampleDepthMapHeights(*this);
    WarnAboutInput(SparseFile(dir_, "points3D"),
                   "the sparse model has no points; the block's height range is taken from " +
                       std::to_string(sampled_heights_.size()) + " depth-map pixels sampled over the " +
                       std::to_string(views_.size()) + " views instead");
  });
  return sampled_heights_;
}

std::string ColmapWorkspace::SceneHeightsSource() const {
  for (const auto& [id, p] : model_.points3D) {
    if (std::isfinite(p.xyz.z())) return "sparse points";
  }
  return "depth-map sample (the sparse model has no points)";
}

NormalMap ColmapWorkspace::ReadNormalMap(const View& view) const {
  return ReadDenseForView(NormalMapPath(view), view, 3, "normal map");
}

RgbImage ColmapWorkspace::ReadImage(const View& view) const {
  // COLMAP ignores EXIF orientation; so must we, or the raster would not match the camera (ReadRgbImageFile).
  return ReadRgbImageFile(ImagePath(view), "image " + Quoted(view.name), view.camera.width, view.camera.height);
}

void WriteColmapStereoConfigs(const std::string& workspace_dir, const std::vector<std::string>& image_names,
                              const std::vector<std::vector<std::string>>& sources) {
  const std::string fusion_path = JoinPath(workspace_dir, "stereo/fusion.cfg");
  if (!sources.empty() && sources.size() != image_names.size()) {
    throw Error(fusion_path + ": " + std::to_string(sources.size()) + " source lists for " +
                std::to_string(image_names.size()) + " images");
  }
  std::string fusion;
  std::string patch_match;
  for (size_t i = 0; i < image_names.size(); ++i) {
    const std::string& name = image_names[i];
    if (name.empty() || name.find_first_of("\r\n,") != std::string::npos) {
      throw Error(fusion_path + ": image name " + Quoted(name) + " cannot be written to a line-based config");
    }
    fusion += name + "\n";
    std::string line;
    for (const std::string& source : sources.empty() ? std::vector<std::string>{} : sources[i]) {
      line += (line.empty() ? "" : ", ") + source;
    }
    patch_match += name + "\n" + (line.empty() ? "__auto__, 20" : line) + "\n";
  }
  WriteFileAtomically(fusion_path, fusion);
  WriteFileAtomically(JoinPath(workspace_dir, "stereo/patch-match.cfg"), patch_match);
}

}  // namespace sacfuse
