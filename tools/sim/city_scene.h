#pragma once
// The procedural city as a Surface: z(x, y) = max(terrain, roofs, canopies), evaluated through a uniform grid
// index over buildings and trees (no raster, so a 1 km^2 scene costs a few MB).
#include <memory>
#include <string>
#include <vector>

#include "tools/sim/city_layout.h"
#include "tools/sim/surface.h"

namespace sacfuse::sim {

class CityScene : public Surface {
 public:
  explicit CityScene(CityLayout layout);

  double Height(double x, double y) const override;
  uint8_t Class(double x, double y) const override;
  Eigen::Vector3f Albedo(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const override;
  HeightRange RangeOver(const Box2d& box) const override;
  Box2d Extent() const override { return Box2d::Infinite(); }
  HeightRange GlobalRange() const override { return global_; }
  std::string Describe() const override;

  const CityLayout& layout() const { return layout_; }

  // What is on top at (x, y).
  enum class Kind : uint8_t { kTerrain, kBuilding, kTree };
  struct Hit {
    double z = 0.0;
    Kind kind = Kind::kTerrain;
    uint32_t index = 0;  // into layout().buildings or layout().trees
  };
  Hit Query(double x, double y) const;

 private:
  Hit QueryCity(double u, double v, double terrain_z) const;
  int CellIndex(double u, double v) const;  // -1 outside the index

  CityLayout layout_;
  uint64_t texture_seed_ = 0;
  double cell_ = 16.0;
  double origin_ = 0.0;  // index covers [origin_, origin_ + n_ * cell_) in u and v
  int n_ = 0;
  std::vector<std::vector<uint32_t>> cells_;  // object ids: buildings first, then trees (id - num buildings)
  std::vector<double> cell_top_;              // highest object top per cell, -inf when empty
  HeightRange global_;
};

}  // namespace sacfuse::sim
