#include "io/raster_block.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>

#include "core/backproject.h"
#include "core/error.h"
#include "io/input_warnings.h"
#include "io/rgb_image_file.h"
#include "io/tiff_depth.h"
#include "io/view_checks.h"

namespace sacfuse {
namespace {

std::string Quoted(const std::string& s) { return "\"" + s + "\""; }

std::string Resolve(const std::string& base_dir, const std::string& path) {
  if (path.empty()) return path;
  const std::filesystem::path p(path);
  if (p.is_absolute() || base_dir.empty()) return p.lexically_normal().string();
  return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

// True when (w, h) is (W, H) scaled by one factor with each side rounded to within 1 px (the COLMAP rule).
bool SizeMatchesAspect(int w, int h, int image_w, int image_h) {
  if (w <= 0 || h <= 0 || w > image_w || h > image_h) return false;
  const double lo = std::max((w - 1.0) / image_w, (h - 1.0) / image_h);
  const double hi = std::min((w + 1.0) / image_w, (h + 1.0) / image_h);
  return lo <= hi;
}

// Runs `read`, appending the view to the message of an InputError from the depth raster.
template <typename F>
auto ForView(const View& view, F&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const InputError& e) {
    throw InputError(e.file(), e.message() + " (depth raster of image " + Quoted(view.name) + ")");
  }
}

}  // namespace

std::string FindCameraFile(const std::string& dir) {
  std::vector<std::string> found;
  for (const char* name : {"cameras.yaml", "cameras.yml", "cameras.csv"}) {
    const std::filesystem::path p = std::filesystem::path(dir) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(p, ec)) found.push_back(p.string());
  }
  if (found.empty()) {
    throw InputError(dir, "no camera file: set input.cameras or put cameras.yaml (or .yml, .csv) into this folder");
  }
  if (found.size() > 1) throw InputError(dir, "several camera files (cameras.yaml/.yml/.csv); set input.cameras");
  return found.front();
}

DepthKind ParseDepthKind(const std::string& text) {
  if (text == "z") return DepthKind::kZ;
  if (text == "range") return DepthKind::kRange;
  throw ConfigError("input.depth_kind = " + text + ": must be z (along the optical axis) or range (along the ray)");
}

RasterBlock::RasterBlock(const std::string& camera_file, DepthKind depth_kind, const CameraFrame& frame)
    : camera_file_(camera_file),
      base_dir_(std::filesystem::path(camera_file).parent_path().string()),
      depth_kind_(depth_kind),
      file_(ReadCameraFile(camera_file)) {
  const CameraPlacement placement(frame);
  views_.reserve(file_.views.size());
  std::vector<double> shifts;
  for (const CameraFileView& fv : file_.views) {
    View view;
    view.index = static_cast<uint32_t>(views_.size());
    view.name = fv.image;
    view.camera = fv.camera;
    view.cam_from_world = placement.CamFromWorld(fv, camera_file_);
    CheckViewIntrinsics(view.camera, camera_file_, CameraFileViewText(fv));
    CheckViewPose(view.cam_from_world, camera_file_, CameraFileViewText(fv));
    shifts.push_back(placement.HeightShiftM(fv, view.cam_from_world));
    views_.push_back(std::move(view));
  }
  // Their mean, exactly the common value when all are equal (no input.cameras_crs: input.origin_m's z).
  scene_height_shift_m_ = shifts.empty() ? frame.origin_m.z() : shifts[0];
  double deviation = 0.0;
  for (const double s : shifts) deviation += s - shifts[0];
  if (!shifts.empty()) scene_height_shift_m_ += deviation / static_cast<double>(shifts.size());
  const size_t without_image = static_cast<size_t>(std::count_if(
      file_.views.begin(), file_.views.end(), [](const CameraFileView& v) { return v.image_path.empty(); }));
  if (without_image > 0) {
    WarnAboutInput(camera_file_, std::to_string(without_image) + " of " + std::to_string(views_.size()) +
                                     " views have no image_path: their points get no colour (mid grey)");
  }
}

std::string RasterBlock::DepthMapPath(const View& view) const {
  return Resolve(base_dir_, file_.views.at(view.index).depth);
}

std::string RasterBlock::ImagePath(const View& view) const {
  return Resolve(base_dir_, file_.views.at(view.index).image_path);
}

PinholeCamera RasterBlock::DepthCamera(const View& view, int width, int height, const std::string& path) const {
  if (!SizeMatchesAspect(width, height, view.camera.width, view.camera.height)) {
    throw InputError(path, "size " + std::to_string(width) + "x" + std::to_string(height) + " is not the image size " +
                               std::to_string(view.camera.width) + "x" + std::to_string(view.camera.height) +
                               " or a downscale of it with the same aspect (depth raster of image " +
                               Quoted(view.name) + ")");
  }
  return view.camera.Scaled(width, height);
}

void RasterBlock::RangeToZ(const PinholeCamera& cam, int row0, int col0, DepthMap* depth) const {
  if (depth_kind_ != DepthKind::kRange) return;
  for (int r = 0; r < depth->height; ++r) {
    const double y = (row0 + r + 0.5 - cam.cy) / cam.fy;
    for (int c = 0; c < depth->width; ++c) {
      float& d = depth->at(r, c);
      if (!IsValidDepth(d)) continue;
      const double x = (col0 + c + 0.5 - cam.cx) / cam.fx;
      d = static_cast<float>(static_cast<double>(d) / std::sqrt(1.0 + x * x + y * y));
    }
  }
}

DepthRasterSize RasterBlock::DepthSize(const View& view) const {
  const std::string path = DepthMapPath(view);
  const TiffDepthInfo info = ForView(view, [&] { return ReadTiffDepthInfo(path); });
  DepthCamera(view, info.width, info.height, path);
  return {info.width, info.height};
}

DepthMap RasterBlock::ReadDepthMap(const View& view) const {
  const std::string path = DepthMapPath(view);
  TiffDepthReader reader = ForView(view, [&] { return TiffDepthReader(path); });
  const PinholeCamera cam = DepthCamera(view, reader.info().width, reader.info().height, path);
  DepthMap depth = ForView(view, [&] { return reader.ReadWindow({0, cam.height, 0, cam.width}); });
  RangeToZ(cam, 0, 0, &depth);
  return WarnIfNoValidDepth(std::move(depth), view, path);
}

DepthMap RasterBlock::ReadDepthWindow(const View& view, const PixelWindow& window) const {
  const std::string path = DepthMapPath(view);
  TiffDepthReader reader = ForView(view, [&] { return TiffDepthReader(path); });
  const PinholeCamera cam = DepthCamera(view, reader.info().width, reader.info().height, path);
  DepthMap depth = ForView(view, [&] { return reader.ReadWindow(window); });
  RangeToZ(cam, window.row_begin, window.col_begin, &depth);
  return depth;
}

RgbImage RasterBlock::ReadImage(const View& view) const {
  const std::string path = ImagePath(view);
  if (path.empty()) return {};
  return ReadRgbImageFile(path, "image " + Quoted(view.name), view.camera.width, view.camera.height);
}

std::vector<double> RasterBlock::SceneHeights() const {
  if (!file_.scene_heights_m.empty()) {
    std::vector<double> z = file_.scene_heights_m;
    for (double& h : z) h += scene_height_shift_m_;
    return z;
  }
  std::call_once(heights_once_, [this] {
    constexpr int kGrid = 8, kSegment = 32;
    std::vector<double> z;
    for (const View& view : views_) {
      const std::string path = DepthMapPath(view);
      TiffDepthReader reader = ForView(view, [&] { return TiffDepthReader(path); });
      const PinholeCamera cam = DepthCamera(view, reader.info().width, reader.info().height, path);
      const Rigid3d world_from_cam = view.cam_from_world.Inverse();
      for (int gy = 0; gy < kGrid; ++gy) {
        const int row = std::min(cam.height - 1, static_cast<int>((gy + 0.5) * cam.height / kGrid));
        for (int gx = 0; gx < kGrid; ++gx) {
          const int centre = static_cast<int>((gx + 0.5) * cam.width / kGrid);
          const int col0 = std::clamp(centre - kSegment / 2, 0, std::max(0, cam.width - kSegment));
          const PixelWindow w{row, row + 1, col0, std::min(cam.width, col0 + kSegment)};
          DepthMap d = ForView(view, [&] { return reader.ReadWindow(w); });
          RangeToZ(cam, w.row_begin, w.col_begin, &d);
          for (int c = 0; c < d.width; ++c) {
            if (IsValidDepth(d.at(0, c)))
              z.push_back(DepthPixelToWorld(cam, world_from_cam, col0 + c, row, d.at(0, c)).z());
          }
        }
      }
    }
    heights_ = std::move(z);
  });
  return heights_;
}

}  // namespace sacfuse
