#pragma once
// The simulated world: a 2.5D surface z(x, y) in the project CRS (metres) with a LAS class and a
// view-independent albedo. Walls are vertical (they appear where the height jumps); there are no overhangs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <Eigen/Core>

#include "core/box2d.h"

namespace sacfuse::sim {

// LAS classes used by the simulator.
constexpr uint8_t kClassGround = 2;
constexpr uint8_t kClassVegetation = 5;
constexpr uint8_t kClassBuilding = 6;

// Height interval, metres; empty (lo > hi) where the surface is undefined.
struct HeightRange {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  bool IsEmpty() const { return lo > hi; }
};

class Surface {
 public:
  virtual ~Surface() = default;

  // Height of the top surface at (x, y), metres; NaN where the surface is not defined (outside a LiDAR scene).
  virtual double Height(double x, double y) const = 0;
  // LAS class of the top surface at (x, y).
  virtual uint8_t Class(double x, double y) const = 0;
  // Albedo in [0, 1] (RGB) at surface point p whose geometric unit normal is n (pointing to the outside, i.e.
  // toward a camera that sees p). Walls have |n.z| small; they get façade textures.
  virtual Eigen::Vector3f Albedo(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const = 0;
  // A CONSERVATIVE height interval over `box` (rendering culls tiles with it); empty where undefined.
  virtual HeightRange RangeOver(const Box2d& box) const = 0;
  // Where the surface is defined (Infinite() for the procedural city whose terrain never ends).
  virtual Box2d Extent() const = 0;
  // Height interval of the whole scene around the area (footprints use it).
  virtual HeightRange GlobalRange() const = 0;
  // Short description for logs and metadata ("city: 212 buildings, 340 trees").
  virtual std::string Describe() const = 0;
};

// Lambert shading with ambient light, view-independent: rgb8 = 255 * albedo * shade(n) where
// shade(n) = (ambient + (1 - ambient) * max(0, n . sun)) / (ambient + (1 - ambient) * sun.z), i.e. flat ground is
// shown with its albedo and slopes facing away from the sun get darker.
struct Lighting {
  Eigen::Vector3d sun = Eigen::Vector3d(0.0, 0.0, 1.0);  // unit vector toward the sun
  double ambient = 0.35;

  static Lighting FromAngles(double azimuth_deg, double elevation_deg, double ambient);
  float Shade(const Eigen::Vector3f& n) const;
};

}  // namespace sacfuse::sim
