#pragma once
// Minimal analytic scenes for tests and debugging: a textured horizontal plane, optionally with one box building.
#include <string>

#include "tools/sim/surface.h"

namespace sacfuse::sim {

class BoxScene : public Surface {
 public:
  // Plane z = ground_z everywhere; with height_m > 0 a flat-roofed box of that height over `box`.
  explicit BoxScene(double ground_z, const Box2d& box = Box2d{0, 0, 0, 0}, double height_m = 0.0);

  double Height(double x, double y) const override;
  uint8_t Class(double x, double y) const override;
  Eigen::Vector3f Albedo(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const override;
  HeightRange RangeOver(const Box2d& box) const override;
  Box2d Extent() const override { return Box2d::Infinite(); }
  HeightRange GlobalRange() const override { return {ground_z_, ground_z_ + height_}; }
  std::string Describe() const override { return height_ > 0.0 ? "plane with one box building" : "plane"; }

 private:
  bool InBox(double x, double y) const { return height_ > 0.0 && box_.Contains(x, y); }
  double ground_z_;
  Box2d box_;
  double height_;
};

}  // namespace sacfuse::sim
