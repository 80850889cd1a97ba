// Multi-ray intersection: exact rays meet at a known point; parallel rays need the depth terms.
#include "core/ray_triangulation.h"

#include <gtest/gtest.h>

namespace sacfuse {
namespace {

TriangulationRay RayThrough(const Eigen::Vector3d& origin, const Eigen::Vector3d& target, double fraction,
                            double lateral = 0.1, double along = 0.0) {
  TriangulationRay r;
  r.origin = origin;
  r.direction = (target - origin).normalized();
  r.measured = origin + fraction * (target - origin);  // a point on the ray, not necessarily the target
  r.lateral_sigma_m = lateral;
  r.along_sigma_m = along;
  return r;
}

TEST(RayTriangulationTest, ExactRaysMeetAtTheKnownPointWhereverTheirMeasuredPointsLie) {
  const Eigen::Vector3d target(390012.25, 5705033.5, 101.75);  // UTM-sized
  const std::vector<TriangulationRay> rays = {
      RayThrough({390000, 5705000, 600}, target, 1.0), RayThrough({390200, 5705000, 610}, target, 0.97, 0.2),
      RayThrough({390000, 5705300, 590}, target, 1.04, 0.05)};
  const auto x = TriangulateRays(rays);
  ASSERT_TRUE(x.has_value());
  EXPECT_LT((*x - target).norm(), 1e-6);
}

TEST(RayTriangulationTest, TheDepthTermsPullAlongTheRaysOnly) {
  const Eigen::Vector3d target(10, 20, 30);
  // Two rays crossing at 90 degrees, measured points 1 m short and long of the target along each ray: with
  // depth terms the crossing is still where the precise lateral terms put it (lateral 1 cm vs along 1 m).
  std::vector<TriangulationRay> rays = {RayThrough({0, 20, 30}, target, 0.9, 0.01, 1.0),
                                        RayThrough({10, 0, 30}, target, 1.05, 0.01, 1.0)};
  auto x = TriangulateRays(rays);
  ASSERT_TRUE(x.has_value());
  EXPECT_LT((*x - target).norm(), 2e-3);
  // Parallel rays: no intersection without depth terms...
  rays = {RayThrough({0, 0, 100}, {0, 0, 0}, 1.0), RayThrough({1, 0, 100}, {1, 0, 0}, 1.0)};
  EXPECT_FALSE(TriangulateRays(rays).has_value());
  // ...with them, the point between the two measured points (equal weights): (0.5, 0, 1).
  rays = {RayThrough({0, 0, 100}, {0, 0, 0}, 0.99, 1.0, 1.0), RayThrough({1, 0, 100}, {1, 0, 0}, 0.99, 1.0, 1.0)};
  x = TriangulateRays(rays);
  ASSERT_TRUE(x.has_value());
  EXPECT_LT((*x - Eigen::Vector3d(0.5, 0, 1)).norm(), 1e-9);
  EXPECT_FALSE(TriangulateRays({}).has_value());
}

}  // namespace
}  // namespace sacfuse
