#pragma once
// Positions from one CRS into another through PROJ (io/crs.h): datum shifts and geoid models as PROJ's database
// has them, never a "ballpark" operation (which would silently ignore a geoid or a datum shift). Coordinates are
// (east, north, height) for projected CRSs and ENU, (latitude deg, longitude deg, ellipsoidal height m) for
// geographic ones, whatever axis order the CRS declares.
#include <memory>
#include <string>

#include <Eigen/Core>

#include "io/crs.h"

namespace sacfuse {

class CrsTransform {
 public:
  // Both must be georeferenced. Throws Error naming both CRSs when PROJ has no operation between them: with the
  // grids that operation needs and PROJ cannot find (name, where it looked, where to get it).
  CrsTransform(const Crs& from, const Crs& to);
  ~CrsTransform();
  CrsTransform(const CrsTransform&) = delete;
  CrsTransform& operator=(const CrsTransform&) = delete;

  // Throws Error naming the point when PROJ cannot transform it (outside a grid or the projection's domain).
  Eigen::Vector3d Apply(const Eigen::Vector3d& point_in_from) const;
  Eigen::Vector3d ApplyInverse(const Eigen::Vector3d& point_in_to) const;
  // The operation, e.g. "RGF93 v1 to NGF-IGN69 height (1) + Lambert-93 (accuracy 0.5 m)"; "identity".
  const std::string& description() const;

  struct State;

 private:
  std::unique_ptr<State> s_;
};

}  // namespace sacfuse
