#include "tools/bench/ply_to_las.h"

#include <cmath>
#include <vector>

#include "io/ply_reader.h"

namespace sacfuse {

uint64_t ConvertPlyToLas(const std::string& ply_path, const std::string& las_path, const Eigen::Vector3d& offset,
                         LasWriterOptions options) {
  PlyVertexReader ply(ply_path);
  if (!options.offset) {
    Eigen::Vector3d snapped;
    for (int k = 0; k < 3; ++k) snapped[k] = std::floor(offset[k] / 1000.0) * 1000.0;
    options.offset = snapped;
  }
  LasWriter las(las_path, options);
  constexpr size_t kChunk = 1 << 16;
  std::vector<PlyVertex> vertices;
  std::vector<LasPoint> points;
  while (ply.Read(&vertices, kChunk) > 0) {
    points.resize(vertices.size());
    for (size_t i = 0; i < vertices.size(); ++i) {
      LasPoint& p = points[i];
      p = LasPoint();
      p.xyz = vertices[i].xyz + offset;
      for (int k = 0; k < 3; ++k) p.rgb[k] = static_cast<uint16_t>(vertices[i].rgb[k] * 256);
      p.point_source_id = 0;
    }
    las.WritePoints(points.data(), points.size());
  }
  las.Close();
  return las.num_points();
}

}  // namespace sacfuse
