#include "tools/sim/surface.h"

#include <algorithm>
#include <cmath>

namespace sacfuse::sim {

Lighting Lighting::FromAngles(double azimuth_deg, double elevation_deg, double ambient) {
  const double az = azimuth_deg * M_PI / 180.0;
  const double el = elevation_deg * M_PI / 180.0;
  Lighting l;
  // Azimuth clockwise from north: east = sin, north = cos.
  l.sun = Eigen::Vector3d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
  l.ambient = ambient;
  return l;
}


float Lighting::Shade(const Eigen::Vector3f& n) const {
  const double cosine = std::max(0.0, n.cast<double>().dot(sun));
  const double flat = ambient + (1.0 - ambient) * std::max(0.0, sun.z());
  return static_cast<float>((ambient + (1.0 - ambient) * cosine) / std::max(flat, 1e-3));
}

}  // namespace sacfuse::sim
