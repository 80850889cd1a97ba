#include "tools/sim/depth_normals.h"

#include "core/backproject.h"
#include "core/plane_fit.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>


namespace sacfuse::sim {

NormalMap NormalsFromDepth(const DepthMap& depth, const PinholeCamera& cam) {
  const int w = depth.width, h = depth.height;
  NormalMap normals(w, h, 3, 0.0f);
  const double focal = std::min(cam.fx, cam.fy);
  tbb::parallel_for(0, h, [&](int row) {
    for (int col = 0; col < w; ++col) {
      const float d0 = depth.at(row, col);
      if (!IsValidDepth(d0)) continue;
      const Eigen::Vector3d p0 = DepthPixelInCamera(cam, col, row, d0);
      const double max_step = std::max(0.3, 4.0 * d0 / focal);
      PlaneFit plane;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int r = row + dr, c = col + dc;
          if (!depth.Contains(r, c)) continue;
          const float d = depth.at(r, c);
          if (!IsValidDepth(d) || std::abs(d - d0) > max_step) continue;
          plane.Add(DepthPixelInCamera(cam, c, r, d) - p0);  // relative to the centre for conditioning
        }
      }
      Eigen::Vector3d normal = -p0.normalized();
      if (plane.count() >= 3) {
        Eigen::Vector3d ev;  // ascending, mean squared distances
        const Eigen::Vector3d fitted = plane.Normal(&ev);
        // A line-like neighbourhood (two tiny eigenvalues; 1e-12 m^2 summed over the points) has no plane.
        if (ev[1] * plane.count() > 1e-12 && ev[0] < 0.5 * ev[1]) normal = fitted.normalized();
      }
      if (normal.dot(p0) > 0.0) normal = -normal;
      // Edge-on planes (walls seen at grazing angles) are tilted to >= ~3 degrees toward the camera, so every
      // normal strictly faces it as MVS normals do.
      const Eigen::Vector3d to_camera = -p0.normalized();
      const double facing = normal.dot(to_camera);
      if (facing < 0.05) normal = (normal + (0.05 - facing) * to_camera).normalized();
      for (int k = 0; k < 3; ++k) normals.at(row, col, k) = static_cast<float>(normal[k]);
    }
  });
  return normals;
}

}  // namespace sacfuse::sim
