#include "tools/sim/simple_scenes.h"

#include <cmath>

#include "tools/sim/noise.h"

namespace sacfuse::sim {

BoxScene::BoxScene(double ground_z, const Box2d& box, double height_m)
    : ground_z_(ground_z), box_(box), height_(height_m) {}

double BoxScene::Height(double x, double y) const { return InBox(x, y) ? ground_z_ + height_ : ground_z_; }

uint8_t BoxScene::Class(double x, double y) const { return InBox(x, y) ? kClassBuilding : kClassGround; }

Eigen::Vector3f BoxScene::Albedo(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const {
  if (std::abs(n.z()) < 0.6f) return Eigen::Vector3f(0.8f, 0.75f, 0.6f);
  // 1 m checkerboard plus noise: strong edges and texture everywhere.
  const double x = std::fmod(p.x(), 1000.0), y = std::fmod(p.y(), 1000.0);
  const bool odd = (static_cast<int64_t>(std::floor(x)) + static_cast<int64_t>(std::floor(y))) & 1;
  const float g = static_cast<float>((odd ? 0.35 : 0.6) + 0.1 * Fbm(7, x, y, 2.0, 3));
  return InBox(p.x() - 0.01 * n.x(), p.y() - 0.01 * n.y()) ? Eigen::Vector3f(g, 0.5f * g, 0.4f * g)
                                                            : Eigen::Vector3f(g, g, g);
}

HeightRange BoxScene::RangeOver(const Box2d& b) const {
  return {ground_z_, (height_ > 0.0 && b.Intersects(box_)) ? ground_z_ + height_ : ground_z_};
}

}  // namespace sacfuse::sim
