#include "io/openmvs_block.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/backproject.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/rgb_image_file.h"
#include "io/view_checks.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

std::string DmapFileName(uint32_t number) {
  char name[32];
  std::snprintf(name, sizeof(name), "depth%04u.dmap", number);
  return name;
}

// The number of a "depth<digits>.dmap" name, or -1 for other names. Throws InputError for names that look like
// OpenMVS depth maps but are not how OpenMVS spells them (so no view is silently skipped).
long long DmapNumber(const fs::path& file) {
  const std::string name = file.filename().string();
  constexpr size_t kPrefix = 5, kSuffix = 5;  // "depth", ".dmap"
  if (name.size() <= kPrefix + kSuffix || name.compare(0, kPrefix, "depth") != 0 ||
      name.compare(name.size() - kSuffix, kSuffix, ".dmap") != 0) {
    return -1;
  }
  const std::string digits = name.substr(kPrefix, name.size() - kPrefix - kSuffix);
  const bool numeric = !digits.empty() && digits.size() <= 10 &&
                       std::all_of(digits.begin(), digits.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
  const unsigned long long number = numeric ? std::strtoull(digits.c_str(), nullptr, 10) : 0;
  if (!numeric || number > std::numeric_limits<uint32_t>::max() ||
      DmapFileName(static_cast<uint32_t>(number)) != name) {
    throw InputError(file.string(), "looks like an OpenMVS depth map but is not named depth%04u.dmap (e.g. "
                                    "depth0007.dmap, depth12345.dmap); rename it or move it out of the folder");
  }
  return static_cast<long long>(number);
}

std::string ForView(uint32_t index, const std::string& dmap_name) {
  return " (view " + std::to_string(index) + ", " + dmap_name + ")";
}

// Whether an image of image_w x image_h is the camera's size or a scale of it with the same aspect, allowing one
// pixel of rounding at the coarser of the two resolutions: |h_i W - w_i H| <= max(W, w_i).
bool SameAspect(int image_w, int image_h, int camera_w, int camera_h) {
  const double cross = std::abs(static_cast<double>(image_h) * camera_w - static_cast<double>(image_w) * camera_h);
  return image_w > 0 && image_h > 0 && cross <= std::max(camera_w, image_w);
}

// A view name usable as a relative path below images/ (no absolute path, no "..", no empty parts).
bool IsPlainRelativePath(const std::string& name) {
  if (name.empty() || name.front() == '/' || name.find('\\') != std::string::npos) return false;
  for (const auto& part : fs::path(name)) {
    const std::string p = part.string();
    if (p.empty() || p == "." || p == "..") return false;
  }
  return true;
}

}  // namespace

PinholeCamera PinholeFromDmap(const DmapHeader& header, const std::string& path, const std::string& who) {
  const auto& K = header.camera.K;
  for (const double k : K) {
    if (!std::isfinite(k)) throw InputError(path, "camera matrix K has a non-finite entry" + who);
  }
  constexpr double kZeroTol = 1e-12;
  if (std::abs(K[3]) > kZeroTol || std::abs(K[6]) > kZeroTol || std::abs(K[7]) > kZeroTol ||
      std::abs(K[8] - 1.0) > kZeroTol) {
    throw InputError(path, "camera matrix K is not upper triangular with K[2][2] = 1 (rows " + std::to_string(K[3]) +
                               " " + std::to_string(K[6]) + " " + std::to_string(K[7]) + " " +
                               std::to_string(K[8]) + ")" + who);
  }
  if (!(K[0] > 0.0) || !(K[4] > 0.0)) {
    throw InputError(path, "camera focal lengths must be positive (fx " + std::to_string(K[0]) + ", fy " +
                               std::to_string(K[4]) + ")" + who);
  }
  if (std::abs(K[1]) > 1e-6 * K[0]) {
    throw InputError(path, "camera matrix K has skew " + std::to_string(K[1]) +
                               "; sacfuse cameras have none (undistort/resample the images first)" + who);
  }
  PinholeCamera camera;
  camera.width = static_cast<int>(header.image_width);  // <= INT_MAX, checked by ReadDmapHeader
  camera.height = static_cast<int>(header.image_height);
  camera.fx = K[0];
  camera.fy = K[4];
  camera.cx = K[2] + 0.5;  // OpenMVS pixel centres at integers -> sacfuse corner convention
  camera.cy = K[5] + 0.5;
  return camera;
}

Rigid3d CamFromWorldFromDmap(const DmapCamera& camera, const std::string& path, const std::string& who) {
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R(r, c) = camera.R[3 * r + c];
  }
  const Eigen::Vector3d C(camera.C[0], camera.C[1], camera.C[2]);
  if (!R.allFinite() || !C.allFinite()) throw InputError(path, "camera rotation or centre is not finite" + who);
  const double orthonormality = (R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthonormality > 1e-6 || R.determinant() <= 0.0) {
    throw InputError(path, "camera R is not a rotation (max |R R^T - I| = " + std::to_string(orthonormality) +
                               ", det " + std::to_string(R.determinant()) + ")" + who);
  }
  Rigid3d cam_from_world;
  cam_from_world.rotation = Eigen::Quaterniond(R).normalized();
  cam_from_world.translation = -(cam_from_world.rotation * C);
  return cam_from_world;
}

DmapCamera DmapCameraFromView(const View& view) {
  DmapCamera out;
  const PinholeCamera& cam = view.camera;
  out.K = {cam.fx, 0.0, cam.cx - 0.5, 0.0, cam.fy, cam.cy - 0.5, 0.0, 0.0, 1.0};
  const Eigen::Matrix3d R = view.cam_from_world.rotation.normalized().toRotationMatrix();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.R[3 * r + c] = R(r, c);
  }
  const Eigen::Vector3d C = view.CenterInWorld();
  out.C = {C.x(), C.y(), C.z()};
  return out;
}

OpenMvsBlock::OpenMvsBlock(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir, "OpenMVS input folder does not exist or is not a folder");
  std::map<uint32_t, fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    // Every depth%04u.dmap is a view, whatever it is: ReadDmapHeader refuses one that is not a regular file.
    const long long number = DmapNumber(entry.path());
    if (number >= 0) files.emplace(static_cast<uint32_t>(number), entry.path());
  }
  if (ec) throw InputError(dir, "cannot list the folder: " + ec.message());
  if (files.empty()) {
    throw InputError(dir, "no OpenMVS depth maps (depth%04u.dmap files) in this folder");
  }
  for (const auto& [number, file] : files) {
    const std::string path = file.string();
    const DmapHeader header = ReadDmapHeader(path);
    View view;
    view.index = static_cast<uint32_t>(views_.size());
    view.name = file.filename().string();
    const std::string who = ForView(view.index, view.name);
    view.camera = PinholeFromDmap(header, path, who);
    view.cam_from_world = CamFromWorldFromDmap(header.camera, path, who);
    const std::string view_text = "view " + std::to_string(view.index) + " (" + view.name + ")";
    CheckViewIntrinsics(view.camera, path, view_text);
    CheckViewPose(view.cam_from_world, path, view_text);
    std::string image = header.image_path;
    std::replace(image.begin(), image.end(), '\\', '/');  // written on Windows
    if (image.empty()) throw InputError(path, "the depth map names no image" + who);
    views_.push_back(std::move(view));
    dmap_paths_.push_back(path);
    image_paths_.push_back(image);
  }
}

std::string OpenMvsBlock::DepthMapPath(const View& view) const { return dmap_paths_.at(view.index); }

std::string OpenMvsBlock::ImagePath(const View& view) const {
  const fs::path image(image_paths_.at(view.index));
  return image.is_absolute() ? image.string() : (fs::path(dir_) / image).lexically_normal().string();
}

DepthRasterSize OpenMvsBlock::DepthSize(const View& view) const {
  const DmapHeader h = ReadDmapHeader(DepthMapPath(view));
  return {static_cast<int>(h.depth_width), static_cast<int>(h.depth_height)};
}

DepthMap OpenMvsBlock::ReadDepthMap(const View& view) const {
  return WarnIfNoValidDepth(ReadDmapDepth(DepthMapPath(view)), view, DepthMapPath(view));
}

DepthMap OpenMvsBlock::ReadDepthWindow(const View& view, const PixelWindow& window) const {
  return ReadDmapDepthWindow(DepthMapPath(view), window);
}

RgbImage OpenMvsBlock::ReadImage(const View& view) const {
  const std::string path = ImagePath(view);
  const std::string who = "image of " + view.name + ", view " + std::to_string(view.index);
  RgbImage rgb = ReadRgbImageFile(path, who);
  if (!SameAspect(rgb.width, rgb.height, view.camera.width, view.camera.height)) {
    throw InputError(path, "image is " + std::to_string(rgb.width) + "x" + std::to_string(rgb.height) +
                               " but the depth map's camera is " + std::to_string(view.camera.width) + "x" +
                               std::to_string(view.camera.height) + " (neither that size nor a scale of it) (" + who +
                               ")");
  }
  return rgb;
}

std::vector<double> OpenMvsBlock::SceneHeights() const { return SampleDepthMapHeights(*this); }

void WriteOpenMvsBlock(const DepthBlock& input, const std::string& out_dir) {
  fs::create_directories(out_dir);
  for (const auto& entry : fs::directory_iterator(out_dir)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 5 && name.compare(name.size() - 5, 5, ".dmap") == 0) {
      throw Error(out_dir + ": already holds OpenMVS depth maps (" + name +
                  "); convert into an empty folder so no stale view is picked up");
    }
  }
  const auto& views = input.views();
  for (const View& view : views) {
    RgbImage image = input.ReadImage(view);
    if (image.empty()) {
      throw Error(input.source() + ": view " + std::to_string(view.index) + " (" + view.name +
                  ") has no image; an OpenMVS depth map must name one");
    }
    char fallback[32];
    std::snprintf(fallback, sizeof(fallback), "%04u.png", view.index);
    const std::string image_name =
        "images/" + (IsPlainRelativePath(view.name) ? view.name + ".png" : std::string(fallback));
    WriteRgbImagePng((fs::path(out_dir) / image_name).string(), image);
    image = RgbImage();

    DmapContents dmap;
    dmap.depth = input.ReadDepthMap(view);
    float lo = std::numeric_limits<float>::max(), hi = 0.0f;
    for (float& d : dmap.depth.data) {
      if (!IsValidDepth(d)) {
        d = 0.0f;  // OpenMVS: 0 = invalid
        continue;
      }
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    dmap.depth_min = hi > 0.0f ? lo : 0.0f;
    dmap.depth_max = hi;
    dmap.image_width = static_cast<uint32_t>(view.camera.width);
    dmap.image_height = static_cast<uint32_t>(view.camera.height);
    dmap.image_path = image_name;
    dmap.view_ids = {view.index};
    dmap.camera = DmapCameraFromView(view);
    WriteDmap((fs::path(out_dir) / DmapFileName(view.index)).string(), dmap);
  }
}

}  // namespace sacfuse
