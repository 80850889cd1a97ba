#pragma once
// Output points and the streaming sink they are written to (a LAS writer, a tile buffer, a counter...).
#include <array>
#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

namespace sacfuse {

struct FusedPoint {
  Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();  // metres, project CRS
  std::array<uint8_t, 3> rgb = {0, 0, 0};
  uint32_t view_index = 0;  // the depth map the point was taken from (LAS point source ID = view_index + 1)
};

// Receives points in chunks; implementations must not keep the pointer after Write returns.
class PointSink {
 public:
  virtual ~PointSink() = default;
  virtual void Write(const FusedPoint* points, size_t count) = 0;
};

}  // namespace sacfuse
