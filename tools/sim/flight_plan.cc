#include "tools/sim/flight_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "core/error.h"

namespace sacfuse::sim {
namespace {

struct CameraSpec {
  ViewKind kind;
  Eigen::Vector2d toward;  // horizontal tilt direction (unused for nadir)
  double tilt_rad;
  PinholeCamera camera;
};

Rigid3d PoseAt(const Eigen::Vector3d& center, const Eigen::Matrix3d& world_from_cam) {
  Rigid3d world_from_camera{Eigen::Quaterniond(world_from_cam).normalized(), center};
  return world_from_camera.Inverse();
}

std::vector<Eigen::Vector2d> ClipPolygon(const std::vector<Eigen::Vector2d>& poly, int axis, double bound, bool keep_ge) {
  std::vector<Eigen::Vector2d> out;
  const size_t n = poly.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % n];
    const bool in_a = keep_ge ? a[axis] >= bound : a[axis] <= bound;
    const bool in_b = keep_ge ? b[axis] >= bound : b[axis] <= bound;
    if (in_a) out.push_back(a);
    if (in_a != in_b) {
      const double t = (bound - a[axis]) / (b[axis] - a[axis]);
      out.push_back(a + t * (b - a));
    }
  }
  return out;
}

double PolygonArea(const std::vector<Eigen::Vector2d>& poly) {
  double twice = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % poly.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice);
}

}  // namespace

const char* ViewKindName(ViewKind kind) {
  switch (kind) {
    case ViewKind::kNadir:
      return "nadir";
    case ViewKind::kObliqueForward:
      return "oblique_fwd";
    case ViewKind::kObliqueBackward:
      return "oblique_bwd";
    case ViewKind::kObliqueLeft:
      return "oblique_left";
    case ViewKind::kObliqueRight:
      return "oblique_right";
  }
  return "unknown";
}

int FlightPlan::num_nadir() const {
  return static_cast<int>(
      std::count_if(views.begin(), views.end(), [](const PlannedView& v) { return v.kind == ViewKind::kNadir; }));
}
int FlightPlan::num_oblique() const { return static_cast<int>(views.size()) - num_nadir(); }

Eigen::Matrix3d WorldFromCameraRotation(const Eigen::Vector2d& toward, double tilt_rad) {
  const Eigen::Vector3d h(toward.x(), toward.y(), 0.0);
  const Eigen::Vector3d up(0.0, 0.0, 1.0);
  const Eigen::Vector3d z = std::sin(tilt_rad) * h - std::cos(tilt_rad) * up;
  const Eigen::Vector3d y = -(std::cos(tilt_rad) * h + std::sin(tilt_rad) * up);
  const Eigen::Vector3d x = y.cross(z);
  Eigen::Matrix3d r;
  r.col(0) = x.normalized();
  r.col(1) = y.normalized();
  r.col(2) = z.normalized();
  return r;
}

bool FootprintOnPlane(const PinholeCamera& camera, const Rigid3d& cam_from_world, double plane_z,
                      std::vector<Eigen::Vector2d>* corners) {
  const Rigid3d world_from_cam = cam_from_world.Inverse();
  const Eigen::Vector3d c = world_from_cam.translation;
  const double us[] = {0.0, static_cast<double>(camera.width), static_cast<double>(camera.width), 0.0};
  const double vs[] = {0.0, 0.0, static_cast<double>(camera.height), static_cast<double>(camera.height)};
  corners->clear();
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d d = world_from_cam.rotation * camera.Unproject(us[k], vs[k], 1.0);
    if (d.z() >= -1e-9 || c.z() <= plane_z) return false;
    const double t = (plane_z - c.z()) / d.z();
    corners->push_back((c + t * d).head<2>());
  }
  return true;
}

double ClippedArea(const std::vector<Eigen::Vector2d>& polygon, const Box2d& box) {
  auto p = ClipPolygon(polygon, 0, box.min.x(), true);
  p = ClipPolygon(p, 0, box.max.x(), false);
  p = ClipPolygon(p, 1, box.min.y(), true);
  p = ClipPolygon(p, 1, box.max.y(), false);
  return p.size() < 3 ? 0.0 : PolygonArea(p);
}

FlightPlan PlanFlight(const SimOptions& o, const Box2d& area, double ground_z) {
  FlightPlan plan;
  const double pixel_mm = o.pixel_size_um / 1000.0;
  plan.nadir_focal_px = o.nadir_focal_mm / pixel_mm;
  plan.oblique_focal_px = o.oblique_focal_mm / pixel_mm;
  plan.flying_height_m = o.gsd_m * plan.nadir_focal_px;
  plan.camera_z_m = ground_z + plan.flying_height_m;
  plan.baseline_m = (1.0 - o.forward_overlap) * o.nadir_width_px * o.gsd_m;
  plan.line_spacing_m = (1.0 - o.side_overlap) * o.nadir_height_px * o.gsd_m;

  std::vector<CameraSpec> specs;
  specs.push_back({ViewKind::kNadir, Eigen::Vector2d(0, 1), 0.0,
                   PinholeCamera::Centered(o.nadir_width_px, o.nadir_height_px, plan.nadir_focal_px)});
  if (o.obliques) {
    const double t = o.oblique_tilt_deg * M_PI / 180.0;
    const PinholeCamera oc = PinholeCamera::Centered(o.nadir_height_px, o.nadir_width_px, plan.oblique_focal_px);
    specs.push_back({ViewKind::kObliqueForward, Eigen::Vector2d(1, 0), t, oc});
    specs.push_back({ViewKind::kObliqueBackward, Eigen::Vector2d(-1, 0), t, oc});
    specs.push_back({ViewKind::kObliqueLeft, Eigen::Vector2d(0, 1), t, oc});
    specs.push_back({ViewKind::kObliqueRight, Eigen::Vector2d(0, -1), t, oc});
  }
  // Footprints relative to the exposure centre (the same for every exposure).
  std::vector<std::vector<Eigen::Vector2d>> relative(specs.size());
  Box2d reach{1e300, 1e300, -1e300, -1e300};
  for (size_t s = 0; s < specs.size(); ++s) {
    const Rigid3d pose = PoseAt(Eigen::Vector3d(0, 0, plan.flying_height_m),
                                WorldFromCameraRotation(specs[s].toward, specs[s].tilt_rad));
    if (!FootprintOnPlane(specs[s].camera, pose, 0.0, &relative[s])) {
      throw ConfigError("oblique_tilt_deg = " + std::to_string(o.oblique_tilt_deg) +
                        ": an image corner looks above the horizon; lower the tilt or lengthen the focal length");
    }
    for (const auto& p : relative[s]) {
      reach.min.x() = std::min(reach.min.x(), p.x()), reach.max.x() = std::max(reach.max.x(), p.x());
      reach.min.y() = std::min(reach.min.y(), p.y()), reach.max.y() = std::max(reach.max.y(), p.y());
    }
  }
  const Eigen::Vector2d center = area.Center();
  const int k0 = static_cast<int>(std::floor((area.min.x() - reach.max.x() - center.x()) / plan.baseline_m));
  const int k1 = static_cast<int>(std::ceil((area.max.x() - reach.min.x() - center.x()) / plan.baseline_m));
  const int l0 = static_cast<int>(std::floor((area.min.y() - reach.max.y() - center.y()) / plan.line_spacing_m));
  const int l1 = static_cast<int>(std::ceil((area.max.y() - reach.min.y() - center.y()) / plan.line_spacing_m));
  if (static_cast<double>(k1 - k0 + 1) * (l1 - l0 + 1) > 2e6) {
    throw ConfigError("forward_overlap = " + std::to_string(o.forward_overlap) + ", side_overlap = " +
                      std::to_string(o.side_overlap) + ": more than 2 million exposures; lower the overlaps");
  }

  struct Candidate {
    PlannedView view;
    int k, l;
    size_t spec;
    double distance;
  };
  std::vector<Candidate> nadir, oblique;
  for (int l = l0; l <= l1; ++l) {
    for (int k = k0; k <= k1; ++k) {
      const Eigen::Vector2d p = center + Eigen::Vector2d(k * plan.baseline_m, l * plan.line_spacing_m);
      for (size_t s = 0; s < specs.size(); ++s) {
        std::vector<Eigen::Vector2d> poly = relative[s];
        Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
        for (auto& q : poly) {
          q += p;
          centroid += 0.25 * q;
        }
        const double inside = ClippedArea(poly, area);
        if (inside <= 1e-6 * area.Width() * area.Height()) continue;
        Candidate c;
        c.view.kind = specs[s].kind;
        c.view.camera = specs[s].camera;
        c.view.cam_from_world = PoseAt(Eigen::Vector3d(p.x(), p.y(), plan.camera_z_m),
                                       WorldFromCameraRotation(specs[s].toward, specs[s].tilt_rad));
        c.view.footprint_center = centroid;
        c.view.footprint_in_area_m2 = inside;
        c.view.line = l - l0;
        c.k = k;
        c.l = l;
        c.spec = s;
        c.distance = (centroid - center).norm();
        (s == 0 ? nadir : oblique).push_back(c);
      }
    }
  }
  plan.candidate_nadir = static_cast<int>(nadir.size());
  plan.candidate_oblique = static_cast<int>(oblique.size());
  auto cap = [](std::vector<Candidate>* list, int max_views) {
    if (max_views <= 0 || static_cast<int>(list->size()) <= max_views) return;
    std::stable_sort(list->begin(), list->end(),
                     [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
    list->resize(max_views);
  };
  cap(&nadir, o.max_nadir_views);
  cap(&oblique, o.max_oblique_views);

  std::vector<Candidate> all = nadir;
  all.insert(all.end(), oblique.begin(), oblique.end());
  std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.l, a.k, a.spec) < std::tie(b.l, b.k, b.spec);
  });
  int exposure = -1;
  int last_k = 0, last_l = 0;
  for (Candidate& c : all) {
    if (exposure < 0 || c.k != last_k || c.l != last_l) ++exposure;
    last_k = c.k;
    last_l = c.l;
    c.view.exposure = exposure;
    char name[64];
    std::snprintf(name, sizeof(name), "%s/%04d.jpg", ViewKindName(c.view.kind), exposure);
    c.view.name = name;
    plan.views.push_back(c.view);
  }
  plan.num_exposures = exposure + 1;
  return plan;
}

}  // namespace sacfuse::sim
