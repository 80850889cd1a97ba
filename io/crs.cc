#include "io/crs.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>

#include <Eigen/Geometry>
#include <proj_experimental.h>

#include "core/error.h"
#include "io/crs_impl.h"
#include "io/crs_transform.h"
#include "io/trimmed.h"

namespace sacfuse {

std::string CrsNumberText(double v, const char* format) {
  char text[64];
  std::snprintf(text, sizeof(text), format, v);
  return text;
}

Crs MakeCrs(std::shared_ptr<const CrsImpl> impl) {
  Crs crs;
  crs.impl_ = std::move(impl);
  return crs;
}

namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr int kMaxGeoKeyCode = 32766;  // GeoTIFF keys: EPSG codes 1..32766; 32767 = user-defined

const char* kProjectAccepts =
    "crs takes \"\" (not georeferenced), the code of a projected CRS in metres (e.g. \"EPSG:25832\" ETRS89 / UTM "
    "32N, \"EPSG:2154\" Lambert-93), a compound code for orthometric heights (e.g. \"EPSG:2154+5720\" Lambert-93 + "
    "NGF-IGN69), WKT1 or WKT2, PROJJSON, a PROJ string with +type=crs, or \"ENU:lat,lon,h\" (local east-north-up "
    "frame at that origin: degrees, degrees, metres of ellipsoidal height)";
const char* kInputAccepts =
    "input.cameras_crs takes \"\" (the positions are in crs), or the code, WKT, PROJJSON or PROJ string of a "
    "projected CRS in metres (e.g. \"EPSG:32631\"), of a compound one (e.g. \"EPSG:2154+5720\"), or of a "
    "geographic one (e.g. \"EPSG:4979\" WGS 84 latitude/longitude/ellipsoidal height), or \"ENU:lat,lon,h\"";

bool StartsWithNoCase(const std::string& s, const std::string& prefix) {
  if (s.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i) {
    if (std::toupper(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  }
  return true;
}

bool ParseDouble(const std::string& s, double* v) {
  const std::string t = Trimmed(s);
  if (t.empty()) return false;
  char* end = nullptr;
  *v = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && std::isfinite(*v);
}

// Which key the text came from and what that key accepts: the parts of every message.
struct Parsing {
  std::string key;
  std::string text;
  bool allow_geographic = false;
  const char* accepts = kProjectAccepts;

  [[noreturn]] void Fail(const std::string& why) const {
    throw Error(key + " " + CrsQuoted(text) + ": " + why + "; " + accepts);
  }
};

// The forms PROJ parses exactly: AUTH:CODE (and urn:ogc:def:...), WKT, PROJJSON, PROJ strings. Plain names are
// not among them (PROJ would look them up loosely).
bool IsDefinitionForm(const std::string& t) {
  if (t.empty()) return false;
  if (t[0] == '{' || t[0] == '+') return true;
  size_t i = 0;
  while (i < t.size() && (std::isalnum(static_cast<unsigned char>(t[i])) || t[i] == '_')) ++i;
  if (i > 0 && i < t.size()) {
    size_t j = i;
    while (j < t.size() && std::isspace(static_cast<unsigned char>(t[j]))) ++j;
    if (j < t.size() && (t[j] == '[' || t[j] == '(')) return true;  // WKT keyword
    if (t[i] == ':' && std::isalpha(static_cast<unsigned char>(t[0]))) {
      for (char c : t) {
        if (std::isspace(static_cast<unsigned char>(c))) return false;
      }
      return true;  // AUTH:CODE, AUTH:H+V, urn:ogc:def:crs:...
    }
  }
  return false;
}

std::string TypeName(PJ_TYPE type) {
  switch (type) {
    case PJ_TYPE_GEOGRAPHIC_2D_CRS: return "a geographic 2D CRS (latitude/longitude)";
    case PJ_TYPE_GEOGRAPHIC_3D_CRS: return "a geographic 3D CRS (latitude/longitude/ellipsoidal height)";
    case PJ_TYPE_GEOCENTRIC_CRS: return "a geocentric CRS (earth-centred X/Y/Z)";
    case PJ_TYPE_VERTICAL_CRS: return "a vertical CRS (heights only)";
    case PJ_TYPE_ENGINEERING_CRS: return "an engineering CRS";
    case PJ_TYPE_TEMPORAL_CRS: return "a temporal CRS";
    case PJ_TYPE_CONVERSION:
    case PJ_TYPE_TRANSFORMATION:
    case PJ_TYPE_CONCATENATED_OPERATION:
    case PJ_TYPE_OTHER_COORDINATE_OPERATION:
      return "a coordinate operation, not a CRS (a PROJ string needs +type=crs to define a CRS)";
    default: return "not a CRS sacfuse can use (PROJ type " + std::to_string(static_cast<int>(type)) + ")";
  }
}

bool IsGeographic(PJ_TYPE type) { return type == PJ_TYPE_GEOGRAPHIC_2D_CRS || type == PJ_TYPE_GEOGRAPHIC_3D_CRS; }

// The CRS under a BoundCRS (a CRS with a transformation to WGS 84 attached, e.g. WKT1 TOWGS84); else itself.
PjPtr Unbound(const ProjContext& ctx, const PJ* crs) {
  if (proj_get_type(crs) == PJ_TYPE_BOUND_CRS) return PjPtr(proj_get_source_crs(ctx.get(), crs));
  return PjPtr(proj_clone(ctx.get(), crs));
}

struct AxisInfo {
  std::string name, direction, unit;
  double unit_factor = 0.0;
};

std::vector<AxisInfo> Axes(const ProjContext& ctx, const PJ* crs) {
  std::vector<AxisInfo> out;
  PjPtr cs(proj_crs_get_coordinate_system(ctx.get(), crs));
  if (!cs) return out;
  const int n = proj_cs_get_axis_count(ctx.get(), cs.get());
  for (int i = 0; i < n; ++i) {
    const char *name = nullptr, *abbrev = nullptr, *direction = nullptr, *unit_name = nullptr, *auth = nullptr,
               *code = nullptr;
    AxisInfo a;
    proj_cs_get_axis_info(ctx.get(), cs.get(), i, &name, &abbrev, &direction, &a.unit_factor, &unit_name, &auth, &code);
    a.name = name ? name : "";
    a.direction = direction ? direction : "";
    a.unit = unit_name ? unit_name : "";
    out.push_back(a);
  }
  return out;
}

std::string IdOf(const PJ* obj) {
  const char* auth = proj_get_id_auth_name(obj, 0);
  const char* code = proj_get_id_code(obj, 0);
  return auth != nullptr && code != nullptr ? std::string(auth) + ":" + code : std::string();
}

int EpsgOf(const PJ* obj) {
  const char* auth = proj_get_id_auth_name(obj, 0);
  const char* code = proj_get_id_code(obj, 0);
  if (auth == nullptr || code == nullptr || std::string(auth) != "EPSG") return 0;
  char* end = nullptr;
  const long v = std::strtol(code, &end, 10);
  return end != code && *end == '\0' && v > 0 && v < 10000000 ? static_cast<int>(v) : 0;
}

// "AUTH:CODE" of a CRS, or for a compound without a code of its own "AUTH:H+V" ("AUTH:H+AUTH2:V").
std::string CodeOf(const ProjContext& ctx, const PJ* crs) {
  std::string id = IdOf(crs);
  if (!id.empty() || proj_get_type(crs) != PJ_TYPE_COMPOUND_CRS) return id;
  PjPtr h(proj_crs_get_sub_crs(ctx.get(), crs, 0));
  PjPtr v(proj_crs_get_sub_crs(ctx.get(), crs, 1));
  const std::string hid = h ? IdOf(h.get()) : "", vid = v ? IdOf(v.get()) : "";
  if (hid.empty() || vid.empty()) return "";
  const size_t hc = hid.find(':'), vc = vid.find(':');
  if (hid.substr(0, hc) == vid.substr(0, vc)) return hid + "+" + vid.substr(vc + 1);
  return hid + "+" + vid;
}

std::string Projjson(ProjContext& ctx, const PJ* crs, const Parsing& p) {
  const char* json = proj_as_projjson(ctx.get(), crs, nullptr);
  if (json == nullptr) p.Fail("PROJ cannot write it as PROJJSON: " + ctx.TakeMessages());
  return json;
}

std::string Wkt(ProjContext& ctx, const PJ* crs, PJ_WKT_TYPE type) {
  const char* const options[] = {"MULTILINE=NO", "ALLOW_ELLIPSOIDAL_HEIGHT_AS_VERTICAL_CRS=YES", nullptr};
  const char* wkt = proj_as_wkt(ctx.get(), crs, type, options);
  return wkt != nullptr ? wkt : "";
}

std::string EnuWkt1(const Eigen::Vector3d& o) {
  // WKT1 has no topocentric frame: the origin is in the name; two axes because PROJ 9.1 refuses a LOCAL_CS with
  // three (z shares the metre unit).
  return "LOCAL_CS[\"sacfuse local ENU: origin lat " + CrsNumberText(o.x(), "%.15g") + ", lon " +
         CrsNumberText(o.y(), "%.15g") + ", h " + CrsNumberText(o.z(), "%.15g") +
         " m (WGS 84 ellipsoid); z = up, metres\",LOCAL_DATUM[\"east-north-up tangent plane\",32767],"
         "UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],AXIS[\"Northing\",NORTH]]";
}

std::shared_ptr<CrsImpl> ParseEnu(const Parsing& p, const std::string& t) {
  const std::string rest = t.substr(4);
  double v[3] = {0, 0, 0};
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = rest.find(',', start);
    const bool last = i == 2;
    if (last != (comma == std::string::npos)) p.Fail("ENU needs exactly three numbers lat,lon,h");
    const std::string item = rest.substr(start, last ? std::string::npos : comma - start);
    if (!ParseDouble(item, &v[i])) p.Fail(CrsQuoted(Trimmed(item)) + " is not a finite number");
    start = comma + 1;
  }
  if (std::abs(v[0]) > 90.0) p.Fail("ENU origin latitude must be in [-90, 90] degrees");
  if (std::abs(v[1]) > 180.0) p.Fail("ENU origin longitude must be in [-180, 180] degrees");
  auto c = std::make_shared<CrsImpl>();
  c->kind = Crs::Kind::kLocalEnu;
  c->enu_origin = Eigen::Vector3d(v[0], v[1], v[2]);
  c->name = "local ENU at " + CrsNumberText(v[0]) + ", " + CrsNumberText(v[1]) + ", " + CrsNumberText(v[2]) + " m";
  c->height_name = "height above the tangent plane";
  c->definition = c->geodetic_definition = "EPSG:4979";
  c->geodetic_name = "WGS 84";
  c->wkt1_las = c->wkt2 = EnuWkt1(c->enu_origin);
  c->las12_problem = "";  // written as user-defined GeoTIFF keys (io/las_crs.h)
  c->ctx = std::make_unique<ProjContext>();
  return c;
}

void CheckMetricAxes(const ProjContext& ctx, const PJ* horizontal, const PJ* vertical, const Parsing& p) {
  PjPtr normalised(proj_normalize_for_visualization(ctx.get(), horizontal));
  const std::vector<AxisInfo> axes = Axes(ctx, normalised ? normalised.get() : horizontal);
  if (axes.size() < 2 || axes[0].direction != "east" || axes[1].direction != "north") {
    std::string have;
    for (const AxisInfo& a : axes) have += (have.empty() ? "" : ", ") + a.name + " (" + a.direction + ")";
    p.Fail("its axes are " + have + ": sacfuse's coordinates are easting and northing");
  }
  for (const AxisInfo& a : axes) {
    if (std::abs(a.unit_factor - 1.0) > 1e-12) {
      p.Fail("its axis " + CrsQuoted(a.name) + " is in " + a.unit + ": coordinates must be metres (depth maps are)");
    }
  }
  if (vertical != nullptr) {
    for (const AxisInfo& a : Axes(ctx, vertical)) {
      if (std::abs(a.unit_factor - 1.0) > 1e-12) p.Fail("its heights are in " + a.unit + ": they must be metres");
    }
  }
}

std::shared_ptr<CrsImpl> ParseWithProj(const Parsing& p, const std::string& t) {
  if (!IsDefinitionForm(t)) {
    p.Fail("not a CRS definition (a CRS name is not accepted: PROJ matches names loosely; `projinfo --list-crs "
           "| grep NAME` finds the code)");
  }
  auto c = std::make_shared<CrsImpl>();
  c->ctx = std::make_unique<ProjContext>();
  ProjContext& ctx = *c->ctx;
  PjPtr given(proj_create(ctx.get(), t.c_str()));
  if (!given) {
    const std::string msg = ctx.TakeMessages();
    p.Fail("PROJ cannot read it" + (msg.empty() ? std::string() : " (" + msg + ")"));
  }
  if (!proj_is_crs(given.get())) p.Fail(TypeName(proj_get_type(given.get())));
  PjPtr crs = Unbound(ctx, given.get());
  const PJ_TYPE type = proj_get_type(crs.get());
  PjPtr horizontal, vertical;
  if (type == PJ_TYPE_COMPOUND_CRS) {
    PjPtr h(proj_crs_get_sub_crs(ctx.get(), crs.get(), 0));
    PjPtr v(proj_crs_get_sub_crs(ctx.get(), crs.get(), 1));
    if (!h || !v) p.Fail("PROJ cannot split the compound CRS: " + ctx.TakeMessages());
    horizontal = Unbound(ctx, h.get());
    vertical = Unbound(ctx, v.get());
    const PJ_TYPE ht = proj_get_type(horizontal.get());
    if (ht != PJ_TYPE_PROJECTED_CRS && !(p.allow_geographic && IsGeographic(ht))) {
      p.Fail("its horizontal part " + CrsQuoted(proj_get_name(horizontal.get())) + " is " +
             (IsGeographic(ht) ? std::string("geographic (latitude/longitude): the horizontal part must be a "
                                             "projected CRS in metres")
                               : TypeName(ht)));
    }
    if (proj_get_type(vertical.get()) != PJ_TYPE_VERTICAL_CRS) {
      p.Fail("its second part " + CrsQuoted(proj_get_name(vertical.get())) + " is not a vertical CRS");
    }
  } else if (type == PJ_TYPE_PROJECTED_CRS || (p.allow_geographic && IsGeographic(type))) {
    horizontal = PjPtr(proj_clone(ctx.get(), crs.get()));
  } else if (IsGeographic(type)) {
    p.Fail(CrsQuoted(proj_get_name(crs.get())) + " is " + TypeName(type) +
           ": the project CRS must be projected, in metres (e.g. the UTM zone of the area, EPSG:326zz or "
           "EPSG:258zz, or the national grid); latitude/longitude camera positions are converted into it");
  } else if (type == PJ_TYPE_VERTICAL_CRS) {
    p.Fail(CrsQuoted(proj_get_name(crs.get())) + " is " + TypeName(type) +
           ": combine it with a projected CRS, e.g. EPSG:2154+5720");
  } else {
    p.Fail(CrsQuoted(proj_get_name(crs.get())) + " is " + TypeName(type));
  }
  const bool geographic = IsGeographic(proj_get_type(horizontal.get()));
  if (!geographic) CheckMetricAxes(ctx, horizontal.get(), vertical.get(), p);
  c->kind = geographic ? Crs::Kind::kGeographic : Crs::Kind::kProjected;
  c->name = proj_get_name(given.get());
  c->code = CodeOf(ctx, given.get());
  if (c->code.empty()) c->code = CodeOf(ctx, crs.get());
  c->horizontal_epsg = EpsgOf(horizontal.get());
  c->orthometric = vertical != nullptr;
  c->vertical_epsg = vertical ? EpsgOf(vertical.get()) : 0;
  c->height_name = vertical ? proj_get_name(vertical.get()) : "ellipsoidal height";

  // With heights: 2D CRSs (projected or geographic) promoted to 3D, whose third axis is the ellipsoidal height.
  const bool three_d = type == PJ_TYPE_COMPOUND_CRS || Axes(ctx, crs.get()).size() >= 3;
  PjPtr with_heights(three_d ? proj_clone(ctx.get(), given.get())
                             : proj_crs_promote_to_3D(ctx.get(), nullptr, given.get()));
  if (!with_heights) p.Fail("PROJ cannot give it a height axis: " + ctx.TakeMessages());
  c->definition = Projjson(ctx, with_heights.get(), p);
  PjPtr geodetic(proj_crs_get_geodetic_crs(ctx.get(), crs.get()));
  if (!geodetic) p.Fail("PROJ finds no geodetic CRS under it: " + ctx.TakeMessages());
  c->geodetic_name = proj_get_name(geodetic.get());
  PjPtr geodetic3d(proj_get_type(geodetic.get()) == PJ_TYPE_GEOGRAPHIC_3D_CRS
                       ? proj_clone(ctx.get(), geodetic.get())
                       : proj_crs_promote_to_3D(ctx.get(), nullptr, geodetic.get()));
  if (!geodetic3d) p.Fail("PROJ cannot give its geodetic CRS a height axis: " + ctx.TakeMessages());
  c->geodetic_definition = Projjson(ctx, geodetic3d.get(), p);

  c->wkt2 = Wkt(ctx, given.get(), PJ_WKT2_2019);
  if (!geographic) {
    c->wkt1_las = Wkt(ctx, with_heights.get(), PJ_WKT1_GDAL);
    if (c->wkt1_las.empty()) {
      p.Fail("PROJ cannot write it as OGC WKT1, which LAS 1.4 files carry (" + ctx.TakeMessages() + ")");
    }
    if (c->horizontal_epsg <= 0 || c->horizontal_epsg > kMaxGeoKeyCode) {
      c->las12_problem = "LAS 1.2 stores the CRS as GeoTIFF keys, which name an EPSG code (1..32766); " +
                         CrsQuoted(proj_get_name(horizontal.get())) + " has none";
    } else if (vertical && (c->vertical_epsg <= 0 || c->vertical_epsg > kMaxGeoKeyCode)) {
      c->las12_problem = "LAS 1.2 stores the CRS as GeoTIFF keys, which name an EPSG code (1..32766); the vertical "
                         "CRS " + CrsQuoted(c->height_name) + " has none";
    }
  }
  double west = 0, south = 0, east = 0, north = 0;
  const char* area_name = nullptr;
  if (proj_get_area_of_use(ctx.get(), horizontal.get(), &west, &south, &east, &north, &area_name) &&
      west > -1000 && south > -1000) {
    c->has_area = true;
    c->area_west = west, c->area_south = south, c->area_east = east, c->area_north = north;
  }
  c->horizontal = std::move(horizontal);
  ctx.TakeMessages();
  return c;
}

Crs Parse(const Parsing& p) {
  const std::string t = Trimmed(p.text);
  if (t.empty()) {
    auto c = std::make_shared<CrsImpl>();
    c->text = p.text;
    c->key = p.key;
    return MakeCrs(std::move(c));
  }
  std::shared_ptr<CrsImpl> c = StartsWithNoCase(t, "ENU:") ? ParseEnu(p, t) : ParseWithProj(p, t);
  c->text = p.text;
  c->key = p.key;
  return MakeCrs(std::move(c));
}

void RequireGeoreferenced(const Crs& crs, const char* what) {
  if (!crs.georeferenced()) {
    throw Error(std::string(what) + ": no CRS (config key `crs` is empty), so geodetic coordinates cannot be "
                "converted; set crs, e.g. \"EPSG:25832\" or \"ENU:51.5,7.46,120\"");
  }
}

void CheckLatLon(const Crs& crs, double lat_deg, double lon_deg, double h_m) {
  if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg) || !std::isfinite(h_m)) {
    throw Error(crs.key() + " " + CrsQuoted(crs.text()) + ": point (lat " + CrsNumberText(lat_deg) + ", lon " +
                CrsNumberText(lon_deg) + ", h " + CrsNumberText(h_m) + " m): not finite");
  }
  if (std::abs(lat_deg) > 90.0 || std::abs(lon_deg) > 540.0) {
    throw Error(crs.key() + " " + CrsQuoted(crs.text()) + ": point (lat " + CrsNumberText(lat_deg) + ", lon " +
                CrsNumberText(lon_deg) + "): latitude must be in [-90, 90] and longitude in [-180, 180] degrees");
  }
}

const CrsTransform& FromGeodetic(const Crs& crs) {
  const CrsImpl& c = crs.impl();
  std::lock_guard<std::mutex> lock(c.mutex);
  if (!c.from_geodetic) {
    try {
      c.from_geodetic = std::make_shared<CrsTransform>(GeodeticCrsOf(crs), crs);
    } catch (const Error& e) {
      throw Error(c.key + " " + CrsQuoted(c.text) + ": geodetic coordinates (latitude, longitude, ellipsoidal height) "
                  "cannot be converted: " + e.what());
    }
  }
  return *c.from_geodetic;
}

// Rows: east, north and up unit vectors at (lat, lon) in earth-centred earth-fixed axes (geodetic latitude: up is
// the ellipsoid normal), i.e. the rotation taking ECEF vectors into ENU there.
Eigen::Matrix3d EnuFromEcef(double lat_deg, double lon_deg) {
  const double sp = std::sin(lat_deg * kDegToRad), cp = std::cos(lat_deg * kDegToRad);
  const double sl = std::sin(lon_deg * kDegToRad), cl = std::cos(lon_deg * kDegToRad);
  Eigen::Matrix3d m;
  m << -sl, cl, 0.0,           //
      -sp * cl, -sp * sl, cp,  //
      cp * cl, cp * sl, sp;
  return m;
}

}  // namespace

Crs::Crs() : impl_(std::make_shared<CrsImpl>()) {}

Crs::Kind Crs::kind() const { return impl_->kind; }
const std::string& Crs::text() const { return impl_->text; }
const std::string& Crs::key() const { return impl_->key; }
std::string Crs::Name() const { return impl_->name; }
std::string Crs::Code() const { return impl_->code; }
int Crs::horizontal_epsg() const { return impl_->horizontal_epsg; }
int Crs::vertical_epsg() const { return impl_->vertical_epsg; }
bool Crs::orthometric() const { return impl_->orthometric; }
std::string Crs::HeightName() const { return impl_->height_name; }
Eigen::Vector3d Crs::enu_origin() const { return impl_->enu_origin; }

Crs GeodeticCrsOf(const Crs& crs) {
  RequireGeoreferenced(crs, "GeodeticCrsOf");
  auto g = std::make_shared<CrsImpl>();
  g->kind = Crs::Kind::kGeographic;
  g->text = crs.text();
  g->key = crs.impl().key;
  g->name = crs.impl().geodetic_name;
  g->definition = g->geodetic_definition = crs.impl().geodetic_definition;
  g->height_name = "ellipsoidal height";
  return MakeCrs(std::move(g));
}

Crs ParseProjectCrs(const std::string& text) { return Parse(Parsing{"crs", text, false, kProjectAccepts}); }

Crs ParseInputCrs(const std::string& text) {
  return Parse(Parsing{"input.cameras_crs", text, true, kInputAccepts});
}

void CheckAreaOfUse(const Crs& crs, double lat_deg, double lon_deg) {
  const CrsImpl& c = crs.impl();
  if (!c.has_area) return;
  const double m = kAreaOfUseMarginDeg;
  // Longitude east of the area's west edge, in [0, 360); the area spans (east - west) mod 360 degrees.
  const auto east_of = [](double lon, double west) { return std::fmod(std::fmod(lon - west, 360.0) + 360.0, 360.0); };
  const double span = c.area_east >= c.area_west ? c.area_east - c.area_west : c.area_east - c.area_west + 360.0;
  const double d = east_of(lon_deg, c.area_west - m);
  const bool lon_ok = span + 2 * m >= 360.0 || d <= span + 2 * m;
  const bool lat_ok = lat_deg >= c.area_south - m && lat_deg <= c.area_north + m;
  if (!lon_ok || !lat_ok) {
    throw Error(c.key + " " + CrsQuoted(c.text) + ": point (lat " + CrsNumberText(lat_deg) + ", lon " +
                CrsNumberText(lon_deg) + ") is outside the area of use of " + CrsQuoted(c.name) + " (longitude " +
                CrsNumberText(c.area_west) + ".." + CrsNumberText(c.area_east) + ", latitude " +
                CrsNumberText(c.area_south) + ".." + CrsNumberText(c.area_north) + ", plus " + CrsNumberText(m) +
                " degrees): choose the CRS of the project area (e.g. its UTM zone)");
  }
}

Eigen::Vector3d ProjectFromGeodetic(const Crs& crs, double lat_deg, double lon_deg, double h_m) {
  RequireGeoreferenced(crs, "ProjectFromGeodetic");
  CheckLatLon(crs, lat_deg, lon_deg, h_m);
  CheckAreaOfUse(crs, lat_deg, lon_deg);
  if (crs.kind() == Crs::Kind::kGeographic) return {lat_deg, lon_deg, h_m};
  return FromGeodetic(crs).Apply(Eigen::Vector3d(lat_deg, lon_deg, h_m));
}

Eigen::Vector3d GeodeticFromProject(const Crs& crs, const Eigen::Vector3d& point_in_crs) {
  RequireGeoreferenced(crs, "GeodeticFromProject");
  if (crs.kind() == Crs::Kind::kGeographic) return point_in_crs;
  return FromGeodetic(crs).ApplyInverse(point_in_crs);
}

namespace {

// The 2D projection of a projected CRS, normalised: (longitude, latitude) degrees <-> (easting, northing) metres;
// PJ_INV projects, PJ_FWD inverts. Made on first use; call with c.mutex held.
PJ* HorizontalProjection(const CrsImpl& c) {
  if (!c.latlon_from_horizontal) {
    ProjContext& ctx = *c.ctx;
    PjPtr geographic(proj_crs_get_geodetic_crs(ctx.get(), c.horizontal.get()));
    PjPtr op(geographic ? proj_create_crs_to_crs_from_pj(ctx.get(), c.horizontal.get(), geographic.get(), nullptr,
                                                         nullptr)
                        : nullptr);
    if (op) c.latlon_from_horizontal.reset(proj_normalize_for_visualization(ctx.get(), op.get()));
    if (!c.latlon_from_horizontal) {
      throw Error(c.key + " " + CrsQuoted(c.text) + ": PROJ cannot invert the projection: " + ctx.TakeMessages());
    }
  }
  return c.latlon_from_horizontal.get();
}

// One step through HorizontalProjection; throws naming the point.
Eigen::Vector2d ProjectionStep(const CrsImpl& c, PJ_DIRECTION dir, double x, double y) {
  PJ* op = HorizontalProjection(c);
  proj_errno_reset(op);
  const PJ_COORD r = proj_trans(op, dir, proj_coord(x, y, 0, 0));
  if (proj_errno(op) != 0 || !std::isfinite(r.xy.x) || !std::isfinite(r.xy.y)) {
    proj_errno_reset(op);
    throw Error(c.key + " " + CrsQuoted(c.text) + ": point (" + CrsNumberText(x) + ", " + CrsNumberText(y) +
                ") is outside the projection's domain: " + c.ctx->TakeMessages());
  }
  return {r.xy.x, r.xy.y};
}

}  // namespace

Eigen::Vector2d LatLonFromProject(const Crs& crs, const Eigen::Vector3d& point_in_crs) {
  RequireGeoreferenced(crs, "LatLonFromProject");
  const CrsImpl& c = crs.impl();
  if (c.kind == Crs::Kind::kGeographic) return point_in_crs.head<2>();
  if (c.kind == Crs::Kind::kLocalEnu) return GeodeticFromProject(crs, point_in_crs).head<2>();
  std::lock_guard<std::mutex> lock(c.mutex);
  const Eigen::Vector2d lon_lat = ProjectionStep(c, PJ_FWD, point_in_crs.x(), point_in_crs.y());
  return {lon_lat.y(), lon_lat.x()};
}

double GridConvergenceDeg(const Crs& crs, double lat_deg, double lon_deg) {
  const CrsImpl& c = crs.impl();
  if (c.kind != Crs::Kind::kProjected) {
    throw Error(c.key + " " + CrsQuoted(c.text) + ": not a projected CRS (no grid convergence)");
  }
  CheckLatLon(crs, lat_deg, lon_deg, 0.0);
  // The direction of the meridian on the grid, by central differences over +-11 m (PROJ's projections are exact
  // to nanometres, so the angle is good to ~1e-10 rad): true north points atan2(dE, dN) clockwise from grid north.
  constexpr double kStepDeg = 1e-4;
  std::lock_guard<std::mutex> lock(c.mutex);
  const Eigen::Vector2d a = ProjectionStep(c, PJ_INV, lon_deg, lat_deg - kStepDeg);
  const Eigen::Vector2d b = ProjectionStep(c, PJ_INV, lon_deg, lat_deg + kStepDeg);
  const Eigen::Vector2d d = b - a;
  return std::atan2(-d.x(), d.y()) / kDegToRad;
}

Eigen::Matrix3d ProjectFromLocalEnuRotation(const Crs& crs, double lat_deg, double lon_deg) {
  RequireGeoreferenced(crs, "ProjectFromLocalEnuRotation");
  switch (crs.kind()) {
    case Crs::Kind::kGeographic: return Eigen::Matrix3d::Identity();
    case Crs::Kind::kLocalEnu: {
      CheckLatLon(crs, lat_deg, lon_deg, 0.0);
      const Eigen::Vector3d o = crs.enu_origin();
      // ENU at the place -> ECEF -> ENU at the origin.
      return EnuFromEcef(o.x(), o.y()) * EnuFromEcef(lat_deg, lon_deg).transpose();
    }
    default: break;
  }
  // Grid north lies gamma clockwise from true north, so true north (ENU y) appears gamma counter-clockwise from
  // grid north: a right-handed rotation about the up axis by +gamma.
  const double gamma_rad = GridConvergenceDeg(crs, lat_deg, lon_deg) * kDegToRad;
  return Eigen::AngleAxisd(gamma_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

CrsLabel LabelCrs(const std::string& definition) {
  // PROJ reads its database to name a CRS (~10 ms of one core each time): a merge labels every tile's record, all
  // alike, and so do the report and the tile index. Memoised per definition and PROJ search path (where proj.db is
  // found), for the process's life; a definition PROJ cannot read is not kept (its error comes again).
  static std::mutex memo_mutex;
  static std::map<std::string, CrsLabel> memo;
  ProjContext ctx;
  const std::string key = JoinedSearchPaths(ctx) + '\n' + definition;
  {
    std::lock_guard<std::mutex> lock(memo_mutex);
    const auto found = memo.find(key);
    if (found != memo.end()) return found->second;
  }
  PjPtr crs(proj_create(ctx.get(), definition.c_str()));
  if (!crs) throw Error("PROJ cannot read the CRS: " + ctx.TakeMessages());
  CrsLabel label;
  const char* name = proj_get_name(crs.get());
  label.name = name != nullptr ? name : "";
  label.code = CodeOf(ctx, crs.get());
  if (label.code.empty() && proj_get_type(crs.get()) == PJ_TYPE_BOUND_CRS) {
    label.code = CodeOf(ctx, Unbound(ctx, crs.get()).get());
  }
  std::lock_guard<std::mutex> lock(memo_mutex);
  memo.emplace(key, label);
  return label;
}

}  // namespace sacfuse
