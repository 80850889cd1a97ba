#include "core/crs.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <Eigen/Geometry>
#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/TransverseMercator.hpp>

#include "core/error.h"

namespace sacfuse {
namespace {

constexpr double kUtmScale = 0.9996;
constexpr double kUtmFalseEastingM = 500000.0;
constexpr double kUtmFalseNorthingSouthM = 10000000.0;
constexpr double kMaxLonFromCentralDeg = 6.0;  // the zone (3 degrees) plus half of each neighbouring zone
constexpr double kUtmMaxLatNorthDeg = 84.0;
constexpr double kUtmMinLatSouthDeg = -80.0;
constexpr double kGrs80InverseFlattening = 298.257222101;
constexpr double kDegToRad = M_PI / 180.0;

const char* kSupported =
    "supported: \"\" (not georeferenced), \"EPSG:326zz\" / \"EPSG:327zz\" (WGS 84 / UTM zone zz N / S, zz = 1..60), "
    "\"EPSG:258zz\" (ETRS89 / UTM zone zz N, zz = 28..38), \"ENU:lat,lon,h\" (local east-north-up frame at that "
    "origin: degrees, degrees, metres of ellipsoidal height)";

std::string Fmt(double v, const char* format = "%.10g") {
  char text[64];
  std::snprintf(text, sizeof(text), format, v);
  return text;
}

[[noreturn]] void Unsupported(const std::string& text, const std::string& why) {
  throw Error("crs \"" + text + "\": " + why + "; " + kSupported);
}

std::string Trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

bool StartsWithNoCase(const std::string& s, const std::string& prefix) {
  if (s.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i) {
    if (std::toupper(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  }
  return true;
}

// A whole string as a finite double (blanks around it allowed).
bool ParseDouble(const std::string& s, double* v) {
  const std::string t = Trim(s);
  if (t.empty()) return false;
  char* end = nullptr;
  *v = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && std::isfinite(*v);
}

const GeographicLib::TransverseMercator& UtmProjection(const std::string& datum) {
  static const GeographicLib::TransverseMercator wgs84(GeographicLib::Constants::WGS84_a(),
                                                       GeographicLib::Constants::WGS84_f(), kUtmScale);
  static const GeographicLib::TransverseMercator grs80(GeographicLib::Constants::WGS84_a(),
                                                       1.0 / kGrs80InverseFlattening, kUtmScale);
  return datum == "ETRS89" ? grs80 : wgs84;
}

double CentralMeridianDeg(int zone) { return 6.0 * zone - 183.0; }

// Longitude difference wrapped to [-180, 180).
double LonDiffDeg(double lon, double lon0) {
  double d = std::fmod(lon - lon0 + 180.0, 360.0);
  if (d < 0) d += 360.0;
  return d - 180.0;
}

void CheckGeodetic(const ProjectCrs& crs, double lat_deg, double lon_deg, double h_m) {
  const std::string where = "crs " + crs.text + ": point (lat " + Fmt(lat_deg) + ", lon " + Fmt(lon_deg) +
                            ", h " + Fmt(h_m) + " m)";
  if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg) || !std::isfinite(h_m)) {
    throw Error(where + ": not finite");
  }
  if (std::abs(lat_deg) > 90.0 || std::abs(lon_deg) > 540.0) {
    throw Error(where + ": latitude must be in [-90, 90] and longitude in [-180, 180] degrees");
  }
  if (crs.kind != ProjectCrs::Kind::kUtm) return;
  const double lon0 = CentralMeridianDeg(crs.utm_zone);
  const bool lat_ok = crs.north ? (lat_deg >= 0.0 && lat_deg <= kUtmMaxLatNorthDeg)
                                : (lat_deg <= 0.0 && lat_deg >= kUtmMinLatSouthDeg);
  if (!lat_ok || std::abs(LonDiffDeg(lon_deg, lon0)) > kMaxLonFromCentralDeg) {
    throw Error(where + " is outside the valid band of " + crs.Name() + ": latitude " +
                (crs.north ? "0..84 N" : "80 S..0") + ", longitude within " + Fmt(kMaxLonFromCentralDeg) +
                " degrees of the central meridian " + Fmt(lon0) + " (i.e. " + Fmt(lon0 - kMaxLonFromCentralDeg) +
                ".." + Fmt(lon0 + kMaxLonFromCentralDeg) + "); choose the UTM zone of the project area");
  }
}

void RequireGeoreferenced(const ProjectCrs& crs, const char* what) {
  if (crs.kind == ProjectCrs::Kind::kNone) {
    throw Error(std::string(what) + ": no project CRS (config key `crs` is empty), so geodetic coordinates cannot "
                "be converted; set crs, e.g. \"EPSG:25832\" or \"ENU:51.5,7.46,120\"");
  }
}

// The local tangent frame of a kLocalEnu CRS (WGS 84 ellipsoid).
GeographicLib::LocalCartesian EnuFrame(const ProjectCrs& crs) {
  return GeographicLib::LocalCartesian(crs.origin_lat_deg, crs.origin_lon_deg, crs.origin_h_m,
                                       GeographicLib::Geocentric::WGS84());
}

// Rows: the east, north and up unit vectors at (lat, lon) in earth-centred earth-fixed axes, i.e. the rotation
// taking ECEF vectors into ENU at that place (geodetic latitude: up is the ellipsoid normal).
Eigen::Matrix3d EnuFromEcef(double lat_deg, double lon_deg) {
  const double sp = std::sin(lat_deg * kDegToRad), cp = std::cos(lat_deg * kDegToRad);
  const double sl = std::sin(lon_deg * kDegToRad), cl = std::cos(lon_deg * kDegToRad);
  Eigen::Matrix3d m;
  m << -sl, cl, 0.0,                //
      -sp * cl, -sp * sl, cp,       //
      cp * cl, cp * sl, sp;
  return m;
}

}  // namespace

std::string ProjectCrs::Name() const {
  switch (kind) {
    case Kind::kNone: return "";
    case Kind::kUtm:
      return std::string(datum == "ETRS89" ? "ETRS89" : "WGS 84") + " / UTM zone " + std::to_string(utm_zone) +
             (north ? "N" : "S");
    case Kind::kLocalEnu:
      return "local ENU at " + Fmt(origin_lat_deg) + ", " + Fmt(origin_lon_deg) + ", " + Fmt(origin_h_m) + " m";
  }
  return "";
}

ProjectCrs ParseProjectCrs(const std::string& text) {
  ProjectCrs crs;
  crs.text = text;
  const std::string t = Trim(text);
  if (t.empty()) return crs;
  if (StartsWithNoCase(t, "EPSG:")) {
    const std::string digits = Trim(t.substr(5));
    if (digits.empty() || digits.size() > 6 ||
        digits.find_first_not_of("0123456789") != std::string::npos) {
      Unsupported(text, "expected EPSG:<code> with a numeric code");
    }
    const int code = std::atoi(digits.c_str());
    crs.kind = ProjectCrs::Kind::kUtm;
    crs.epsg = code;
    if (code >= 32601 && code <= 32660) {
      crs.datum = "WGS84", crs.north = true, crs.utm_zone = code - 32600;
    } else if (code >= 32701 && code <= 32760) {
      crs.datum = "WGS84", crs.north = false, crs.utm_zone = code - 32700;
    } else if (code >= 25828 && code <= 25838) {
      crs.datum = "ETRS89", crs.north = true, crs.utm_zone = code - 25800;
    } else {
      Unsupported(text, "EPSG code " + std::to_string(code) + " is not one of the supported projected CRSs");
    }
    return crs;
  }
  if (StartsWithNoCase(t, "ENU:")) {
    const std::string rest = t.substr(4);
    double v[3] = {0, 0, 0};
    size_t start = 0;
    for (int i = 0; i < 3; ++i) {
      const size_t comma = rest.find(',', start);
      const bool last = i == 2;
      if (last != (comma == std::string::npos)) Unsupported(text, "ENU needs exactly three numbers lat,lon,h");
      const std::string item = rest.substr(start, last ? std::string::npos : comma - start);
      if (!ParseDouble(item, &v[i])) Unsupported(text, "\"" + Trim(item) + "\" is not a finite number");
      start = comma + 1;
    }
    if (std::abs(v[0]) > 90.0) Unsupported(text, "ENU origin latitude must be in [-90, 90] degrees");
    if (std::abs(v[1]) > 180.0) Unsupported(text, "ENU origin longitude must be in [-180, 180] degrees");
    crs.kind = ProjectCrs::Kind::kLocalEnu;
    crs.datum = "WGS84";
    crs.origin_lat_deg = v[0];
    crs.origin_lon_deg = v[1];
    crs.origin_h_m = v[2];
    return crs;
  }
  Unsupported(text, "unknown CRS");
}

Eigen::Vector3d ProjectFromGeodetic(const ProjectCrs& crs, double lat_deg, double lon_deg, double h_m) {
  RequireGeoreferenced(crs, "ProjectFromGeodetic");
  CheckGeodetic(crs, lat_deg, lon_deg, h_m);
  if (crs.kind == ProjectCrs::Kind::kLocalEnu) {
    Eigen::Vector3d p;
    EnuFrame(crs).Forward(lat_deg, lon_deg, h_m, p.x(), p.y(), p.z());
    return p;
  }
  double x = 0, y = 0, gamma = 0, k = 0;
  UtmProjection(crs.datum).Forward(CentralMeridianDeg(crs.utm_zone), lat_deg, lon_deg, x, y, gamma, k);
  return {x + kUtmFalseEastingM, y + (crs.north ? 0.0 : kUtmFalseNorthingSouthM), h_m};
}

Eigen::Vector3d GeodeticFromProject(const ProjectCrs& crs, const Eigen::Vector3d& point_in_project) {
  RequireGeoreferenced(crs, "GeodeticFromProject");
  if (!point_in_project.allFinite()) {
    throw Error("crs " + crs.text + ": project point (" + Fmt(point_in_project.x()) + ", " +
                Fmt(point_in_project.y()) + ", " + Fmt(point_in_project.z()) + ") is not finite");
  }
  Eigen::Vector3d g;
  if (crs.kind == ProjectCrs::Kind::kLocalEnu) {
    EnuFrame(crs).Reverse(point_in_project.x(), point_in_project.y(), point_in_project.z(), g[0], g[1], g[2]);
    return g;
  }
  double gamma = 0, k = 0;
  UtmProjection(crs.datum).Reverse(CentralMeridianDeg(crs.utm_zone), point_in_project.x() - kUtmFalseEastingM,
                                   point_in_project.y() - (crs.north ? 0.0 : kUtmFalseNorthingSouthM), g[0], g[1],
                                   gamma, k);
  g[2] = point_in_project.z();
  return g;
}

double UtmConvergenceDeg(const ProjectCrs& crs, double lat_deg, double lon_deg) {
  if (crs.kind != ProjectCrs::Kind::kUtm) throw Error("crs \"" + crs.text + "\": not a UTM CRS (no grid convergence)");
  CheckGeodetic(crs, lat_deg, lon_deg, 0.0);
  double x = 0, y = 0, gamma = 0, k = 0;
  UtmProjection(crs.datum).Forward(CentralMeridianDeg(crs.utm_zone), lat_deg, lon_deg, x, y, gamma, k);
  return gamma;
}

Eigen::Matrix3d ProjectFromLocalEnuRotation(const ProjectCrs& crs, double lat_deg, double lon_deg) {
  RequireGeoreferenced(crs, "ProjectFromLocalEnuRotation");
  if (crs.kind == ProjectCrs::Kind::kLocalEnu) {
    CheckGeodetic(crs, lat_deg, lon_deg, 0.0);
    // ENU at the place -> ECEF -> ENU at the origin.
    return EnuFromEcef(crs.origin_lat_deg, crs.origin_lon_deg) * EnuFromEcef(lat_deg, lon_deg).transpose();
  }
  // Grid north lies gamma clockwise from true north, so true north (ENU y) appears gamma counter-clockwise from
  // grid north: a right-handed rotation about the up axis by +gamma.
  const double gamma_rad = UtmConvergenceDeg(crs, lat_deg, lon_deg) * kDegToRad;
  return Eigen::AngleAxisd(gamma_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace sacfuse
