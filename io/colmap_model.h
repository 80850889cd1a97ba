#pragma once
// COLMAP sparse model (cameras, images, points3D) in the text and binary forms COLMAP 3.8 writes.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sacfuse {

struct ColmapCamera {
  uint32_t camera_id = 0;
  std::string model;            // "PINHOLE", "SIMPLE_PINHOLE", "SIMPLE_RADIAL", "OPENCV", ...
  uint64_t width = 0;
  uint64_t height = 0;
  std::vector<double> params;   // in COLMAP's order for the model
};

struct ColmapPoint2D {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  uint64_t point3D_id = UINT64_MAX;  // UINT64_MAX (-1 in text) = not triangulated
};

struct ColmapImage {
  uint32_t image_id = 0;
  Eigen::Quaterniond cam_from_world_rotation = Eigen::Quaterniond::Identity();  // QW QX QY QZ
  Eigen::Vector3d cam_from_world_translation = Eigen::Vector3d::Zero();          // TX TY TZ
  uint32_t camera_id = 0;
  std::string name;
  std::vector<ColmapPoint2D> points2D;
};

struct ColmapTrackElement {
  uint32_t image_id = 0;
  uint32_t point2D_idx = 0;
};

struct ColmapPoint3D {
  uint64_t point3D_id = 0;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  std::array<uint8_t, 3> rgb = {0, 0, 0};
  double error = 0.0;
  std::vector<ColmapTrackElement> track;
};

struct ColmapModel {
  std::map<uint32_t, ColmapCamera> cameras;
  std::vector<ColmapImage> images;  // in file order (COLMAP's registered-image order)
  std::map<uint64_t, ColmapPoint3D> points3D;
};

// COLMAP camera model table (ids 0-10 as in COLMAP 3.8, plus 11 RAD_TAN_THIN_PRISM_FISHEYE of 3.9+).
// Return -1 for an unknown model; name "" for an unknown id.
int ColmapCameraModelId(const std::string& model_name);
std::string ColmapCameraModelName(int model_id);
int ColmapCameraModelNumParams(const std::string& model_name);

// Reads DIR/{cameras,images,points3D}.bin, or the .txt files when the .bin are absent.
// Throws InputError naming the file on any malformed or truncated content.
ColmapModel ReadColmapModel(const std::string& dir);
void WriteColmapModelBinary(const ColmapModel& model, const std::string& dir);
void WriteColmapModelText(const ColmapModel& model, const std::string& dir);

}  // namespace sacfuse
