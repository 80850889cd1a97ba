#pragma once
// Any point cloud a user hands to `sacfuse dsm` or `sacfuse eval`: LAS/LAZ (io/las_reader.h) or binary PLY
// (io/ply_reader.h: COLMAP's fused.ply, Open3D's clouds), read in chunks of coordinates (plus the LAS
// classification), with an optional shift added to every point (PLY clouds written in a local frame).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/box2d.h"

namespace sacfuse {

// A good number of points to Read at once (~1.6 MiB of coordinates).
constexpr size_t kCloudReadChunkPoints = size_t{1} << 16;

struct CloudChunk {
  std::vector<Eigen::Vector3d> xyz;     // metres, in the file's CRS (plus the shift)
  std::vector<uint8_t> classification;  // LAS classification; 0 (never classified) for PLY
  std::vector<uint16_t> source_id;      // LAS point source ID (sacfuse: view index + 1); 0 for PLY
  std::vector<std::array<uint8_t, 3>> rgb;  // 8-bit colour (LAS: the 16-bit colour's high byte); 0 when none
};

class PointCloudFile {
 public:
  // Opens by content: a LAS/LAZ signature ("LASF") or "ply". Throws InputError naming the file otherwise.
  explicit PointCloudFile(const std::string& path, const Eigen::Vector3d& shift = Eigen::Vector3d::Zero());
  ~PointCloudFile();
  PointCloudFile(const PointCloudFile&) = delete;
  PointCloudFile& operator=(const PointCloudFile&) = delete;

  const std::string& path() const;
  bool is_las() const;
  uint64_t point_count() const;
  // The LAS header's XY bounds (plus the shift); for PLY the bounds of the points, found by one pass on first use.
  Box2d bounds_xy();
  // LAS: the distance the file's quantum allows a coordinate to move (its scale), 0 for PLY.
  double quantum_m() const;
  // The CRS of a LAS file as WKT GDAL reads (io/raster_crs.h); "" for PLY or a LAS file without one.
  std::string crs_wkt() const;

  // Up to max_points further points into *chunk (resized); returns how many (0 at the end).
  size_t Read(CloudChunk* chunk, size_t max_points);
  void Rewind();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sacfuse
