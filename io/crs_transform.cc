#include "io/crs_transform.h"

#include <cmath>
#include <cstdio>
#include <mutex>
#include <vector>

#include <proj_experimental.h>

#include "core/error.h"
#include "io/crs_impl.h"
#include "io/proj_handles.h"

namespace sacfuse {
namespace {


// The topocentric conversion of an ENU frame: (longitude deg, latitude deg, ellipsoidal h m) on WGS 84 ->
// (east, north, up) m at the origin.
PjPtr Topocentric(const ProjContext& ctx, const Eigen::Vector3d& origin) {
  char def[512];
  std::snprintf(def, sizeof(def),
                "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad +step +proj=cart +ellps=WGS84 "
                "+step +proj=topocentric +ellps=WGS84 +lat_0=%.17g +lon_0=%.17g +h_0=%.17g",
                origin.x(), origin.y(), origin.z());
  PjPtr p(proj_create(ctx.get(), def));
  if (!p) throw Error(std::string("PROJ cannot build the topocentric conversion ") + def);
  return p;
}

PjPtr CreateCrs(ProjContext& ctx, const CrsImpl& c) {
  PjPtr p(proj_create(ctx.get(), c.definition.c_str()));
  if (!p) throw Error("PROJ cannot rebuild " + CrsQuoted(c.name) + ": " + ctx.TakeMessages());
  return p;
}

// Why there is no operation: the grids the best candidate (ignoring grid availability) needs and PROJ lacks.
std::string WhyNoOperation(ProjContext& ctx, const PJ* src, const PJ* dst) {
  PJ_OPERATION_FACTORY_CONTEXT* oc = proj_create_operation_factory_context(ctx.get(), nullptr);
  proj_operation_factory_context_set_grid_availability_use(ctx.get(), oc, PROJ_GRID_AVAILABILITY_IGNORED);
  proj_operation_factory_context_set_allow_ballpark_transformations(ctx.get(), oc, 0);
  proj_operation_factory_context_set_spatial_criterion(ctx.get(), oc, PROJ_SPATIAL_CRITERION_PARTIAL_INTERSECTION);
  PJ_OBJ_LIST* ops = proj_create_operations(ctx.get(), src, dst, oc);
  std::string why;
  if (ops != nullptr && proj_list_get_count(ops) > 0) {
    PjPtr best(proj_list_get(ctx.get(), ops, 0));
    std::string grids;
    for (int g = 0; best && g < proj_coordoperation_get_grid_used_count(ctx.get(), best.get()); ++g) {
      const char *short_name = nullptr, *full_name = nullptr, *package = nullptr, *url = nullptr;
      int direct = 0, open_license = 0, available = 0;
      proj_coordoperation_get_grid_used(ctx.get(), best.get(), g, &short_name, &full_name, &package, &url, &direct,
                                        &open_license, &available);
      if (available) continue;
      grids += (grids.empty() ? "" : ", ") + std::string(short_name ? short_name : "?") +
               (url != nullptr && *url ? std::string(" (") + url + ")" : std::string());
    }
    if (!grids.empty()) {
      why = "the operation " + CrsQuoted(proj_get_name(best.get())) + " needs the grid " + grids +
            ", which PROJ does not find in its search path (" + JoinedSearchPaths(ctx) +
            "): put the file into one of these folders (or into a folder named by the environment variable "
            "PROJ_DATA); sacfuse never downloads grids";
    }
  }
  if (ops != nullptr) proj_list_destroy(ops);
  proj_operation_factory_context_destroy(oc);
  if (why.empty()) {
    why = "PROJ knows no transformation between them other than a ballpark one, which would ignore datum shifts "
          "and geoid heights";
  }
  ctx.TakeMessages();
  return why;
}

}  // namespace

struct CrsTransform::State {
  std::mutex mutex;
  ProjContext ctx;
  PjPtr op;  // axes normalised (longitude first, easting first); null: identity
  PjPtr from_enu, to_enu;
  bool from_geographic = false, to_geographic = false;
  std::string from_name, to_name, description;

  Eigen::Vector3d Run(const Eigen::Vector3d& p, bool inverse) {
    std::lock_guard<std::mutex> lock(mutex);
    const bool in_geo = inverse ? to_geographic : from_geographic;
    const bool out_geo = inverse ? from_geographic : to_geographic;
    PJ* first = inverse ? to_enu.get() : from_enu.get();
    PJ* last = inverse ? from_enu.get() : to_enu.get();
    PJ_COORD c = in_geo ? proj_coord(p.y(), p.x(), p.z(), 0) : proj_coord(p.x(), p.y(), p.z(), 0);
    bool ok = p.allFinite();
    auto step = [&](PJ* pj, PJ_DIRECTION dir) {
      if (!ok || pj == nullptr) return;
      proj_errno_reset(pj);
      c = proj_trans(pj, dir, c);
      ok = proj_errno(pj) == 0 && std::isfinite(c.xyz.x) && std::isfinite(c.xyz.y) && std::isfinite(c.xyz.z);
      proj_errno_reset(pj);
    };
    step(first, PJ_INV);
    step(op.get(), inverse ? PJ_INV : PJ_FWD);
    step(last, PJ_FWD);
    if (!ok) {
      const std::string msg = ctx.TakeMessages();
      throw Error("point (" + CrsNumberText(p.x()) + ", " + CrsNumberText(p.y()) + ", " + CrsNumberText(p.z()) +
                  ") of " + CrsQuoted(inverse ? to_name : from_name) + " cannot be transformed to " +
                  CrsQuoted(inverse ? from_name : to_name) +
                  (msg.empty() ? std::string(" (outside the area PROJ's operation covers)") : ": " + msg));
    }
    return out_geo ? Eigen::Vector3d(c.xyz.y, c.xyz.x, c.xyz.z) : Eigen::Vector3d(c.xyz.x, c.xyz.y, c.xyz.z);
  }
};

CrsTransform::CrsTransform(const Crs& from, const Crs& to) : s_(std::make_unique<State>()) {
  const CrsImpl& f = from.impl();
  const CrsImpl& t = to.impl();
  if (!from.georeferenced() || !to.georeferenced()) {
    throw Error("a transformation needs two CRSs (" + CrsQuoted(f.text) + " -> " + CrsQuoted(t.text) + ")");
  }
  State& s = *s_;
  s.from_name = from.Name();
  s.to_name = to.Name();
  s.from_geographic = f.kind == Crs::Kind::kGeographic;
  s.to_geographic = t.kind == Crs::Kind::kGeographic;
  if (f.kind == Crs::Kind::kLocalEnu) s.from_enu = Topocentric(s.ctx, f.enu_origin);
  if (t.kind == Crs::Kind::kLocalEnu) s.to_enu = Topocentric(s.ctx, t.enu_origin);
  PjPtr src = CreateCrs(s.ctx, f);
  PjPtr dst = CreateCrs(s.ctx, t);
  if (proj_is_equivalent_to_with_ctx(s.ctx.get(), src.get(), dst.get(), PJ_COMP_EQUIVALENT)) {
    s.description = "identity";
  } else {
    const char* const options[] = {"ALLOW_BALLPARK=NO", nullptr};
    PjPtr op(proj_create_crs_to_crs_from_pj(s.ctx.get(), src.get(), dst.get(), nullptr, options));
    if (!op) {
      s.ctx.TakeMessages();
      throw Error("no transformation from " + CrsQuoted(s.from_name) + " to " + CrsQuoted(s.to_name) + ": " +
                  WhyNoOperation(s.ctx, src.get(), dst.get()));
    }
    s.op.reset(proj_normalize_for_visualization(s.ctx.get(), op.get()));
    if (!s.op) throw Error("PROJ cannot normalise the axes of " + CrsQuoted(proj_get_name(op.get())));
    const char* name = proj_get_name(s.op.get());
    s.description = name != nullptr && *name ? name : "one of several operations, by area";
    const double accuracy = proj_coordoperation_get_accuracy(s.ctx.get(), s.op.get());
    if (accuracy >= 0) s.description += " (accuracy " + CrsNumberText(accuracy) + " m)";
  }
  s.ctx.TakeMessages();
}

CrsTransform::~CrsTransform() = default;

Eigen::Vector3d CrsTransform::Apply(const Eigen::Vector3d& p) const { return s_->Run(p, false); }
Eigen::Vector3d CrsTransform::ApplyInverse(const Eigen::Vector3d& p) const { return s_->Run(p, true); }
const std::string& CrsTransform::description() const { return s_->description; }

}  // namespace sacfuse
