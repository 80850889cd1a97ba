#pragma once
// A Surface from airborne LiDAR (`scene: las`): a DSM raster with the maximum z per cell of first/only returns
// (noise classes 7 and 18 and withheld points skipped), holes filled from their neighbours (lower median, repeated
// until none is left), bilinear between cell centres. Class per cell from the highest classified point (overlap
// class 12 and unclassified 0/1 do not count when anything else is there); albedo from the LAS RGB when the point
// format has it, else procedural by class (roof colours, green canopies, asphalt/grass mix, façades with windows).
// The world frame is the file's; the area is the file's XY bounds or a centred crop of area_width x area_height
// when that is smaller.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tools/sim/surface.h"

namespace sacfuse::sim {

struct LasSceneOptions {
  std::string path;
  double area_width_m = 0.0;   // crop (centred) when smaller than the file's extent; 0 = the whole file
  double area_height_m = 0.0;
  double cell_m = 0.0;         // DSM cell, metres (0 = sqrt(3 / density of first returns), 0.1..2 m)
  double margin_m = 60.0;      // the DSM extends this far beyond the area (within the file)
  uint64_t seed = 1;           // procedural textures
};

class LasScene : public Surface {
 public:
  // Throws InputError (file named) for unreadable files and files without usable points in the area.
  explicit LasScene(const LasSceneOptions& options);

  double Height(double x, double y) const override;
  uint8_t Class(double x, double y) const override;
  Eigen::Vector3f Albedo(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const override;
  HeightRange RangeOver(const Box2d& box) const override;
  Box2d Extent() const override { return extent_; }
  HeightRange GlobalRange() const override { return global_; }
  std::string Describe() const override;

  const Box2d& area() const { return area_; }
  double ground_z() const { return ground_z_; }  // 5th percentile of the DSM inside the area
  double cell_m() const { return cell_; }
  bool has_rgb() const { return has_rgb_; }
  const std::string& path() const { return path_; }
  std::string crs_wkt() const { return wkt_; }

 private:
  size_t Index(int row, int col) const { return static_cast<size_t>(row) * width_ + col; }
  // Nearest cell of (x, y), clamped; false outside the extent.
  bool Cell(double x, double y, int* row, int* col) const;
  void FillHoles();
  void BuildBlockRanges();

  std::string path_;
  std::string wkt_;
  uint64_t seed_;
  Box2d area_, extent_;
  double cell_ = 0.25;
  int width_ = 0, height_ = 0;       // cells; row 0 at extent_.min.y() (south)
  std::vector<float> z_;             // relative to z_base_
  double z_base_ = 0.0;
  std::vector<uint8_t> class_;
  std::vector<std::array<uint8_t, 3>> rgb_;
  bool has_rgb_ = false;
  double ground_z_ = 0.0;
  HeightRange global_;
  static constexpr int kBlock = 16;  // cells per side of a RangeOver block
  int blocks_x_ = 0, blocks_y_ = 0;
  std::vector<float> block_lo_, block_hi_;
  size_t points_used_ = 0;
};

}  // namespace sacfuse::sim
