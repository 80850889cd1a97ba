#pragma once
// The project coordinate reference system (config key `crs`): what sacfuse's world coordinates are, and the
// conversions from geodetic positions (latitude, longitude, ellipsoidal height) into them.
//
// Supported:
//   ""                 not georeferenced: local metres, no CRS written to the LAS (kNone)
//   "EPSG:326zz"       WGS 84 / UTM zone zz N (zz = 01..60)
//   "EPSG:327zz"       WGS 84 / UTM zone zz S
//   "EPSG:258zz"       ETRS89 / UTM zone zz N, zz = 28..38 (the zones EPSG defines)
//   "ENU:lat,lon,h"    a local east-north-up tangent frame at that origin (degrees, degrees, metres ellipsoidal)
//
// Conventions (documented for users in docs/outputs.md):
// - ETRS89 and WGS 84 are treated as the same earth-fixed frame (no time-dependent transformation between them;
//   today they differ by ~0.5-1 m in Europe). Each uses its own ellipsoid (GRS 1980 / WGS 84), which differ by
//   0.1 mm in semi-minor axis, so the UTM numbers agree with PROJ's EPSG definitions to < 1 mm.
// - Heights are used as given: ellipsoidal in, ellipsoidal out (no geoid model). Project z = ellipsoidal height
//   for UTM; for ENU, z is the height above the origin's tangent plane.
// - UTM is the Transverse Mercator projection (Krueger series, GeographicLib), scale 0.9996, false easting
//   500 km, false northing 0 (N) or 10,000 km (S). A point is accepted within 6 degrees of longitude of the zone's
//   central meridian (the zone plus half of each neighbour, as block projects spilling over a zone border use
//   it), latitude 0..84 N for a north zone and 80 S..0 for a south zone.
#include <string>

#include <Eigen/Core>

namespace sacfuse {

struct ProjectCrs {
  enum class Kind { kNone, kUtm, kLocalEnu };
  Kind kind = Kind::kNone;
  std::string text;          // as given in the config, e.g. "EPSG:25832" or "ENU:51.5,7.46,120"
  int epsg = 0;              // EPSG code of the projected CRS (0 for kNone / kLocalEnu)
  int utm_zone = 0;          // 1..60
  bool north = true;         // hemisphere
  std::string datum;         // "WGS84" or "ETRS89"
  double origin_lat_deg = 0, origin_lon_deg = 0, origin_h_m = 0;  // kLocalEnu origin (ellipsoidal height)

  bool georeferenced() const { return kind != Kind::kNone; }
  // Human-readable name, e.g. "ETRS89 / UTM zone 32N" or "local ENU at 51.5, 7.46, 120 m"; "" for kNone.
  std::string Name() const;
};

// Parses "" (kNone), "EPSG:326zz"/"EPSG:327zz" (WGS 84 / UTM zone zz N/S), "EPSG:258zz" (ETRS89 / UTM zone zz N,
// zones 28..38 as EPSG defines them), "ENU:lat,lon,h" (local east-north-up tangent frame, degrees, metres).
// Leading/trailing blanks are ignored and "epsg"/"enu" may be lower case. Anything else throws sacfuse::Error
// naming the text and listing what is supported.
ProjectCrs ParseProjectCrs(const std::string& text);

// Geodetic (latitude, longitude in degrees; ellipsoidal height in metres) -> project coordinates (metres).
// Throws for kNone and for points outside the zone's valid band (see above), naming the point and the band.
Eigen::Vector3d ProjectFromGeodetic(const ProjectCrs& crs, double lat_deg, double lon_deg, double h_m);
// The inverse: project coordinates -> (lat deg, lon deg, h m). Throws for kNone and non-finite input.
Eigen::Vector3d GeodeticFromProject(const ProjectCrs& crs, const Eigen::Vector3d& point_in_project);

// Rotation taking vectors in the local east-north-up frame at (lat, lon) into the project frame's axes
// (meridian convergence for UTM: a rotation about z by the grid convergence; identity at the ENU origin; for a
// local ENU frame the rotation between the tangent planes). Used to turn attitudes given w.r.t. local ENU into
// project-frame rotations. For UTM the grid scale factor is not part of it (a rotation, not a Jacobian).
Eigen::Matrix3d ProjectFromLocalEnuRotation(const ProjectCrs& crs, double lat_deg, double lon_deg);

// UTM meridian convergence at (lat, lon), degrees: the bearing of grid north measured clockwise from true
// north (positive east of the central meridian in the northern hemisphere). Throws unless crs is kUtm.
double UtmConvergenceDeg(const ProjectCrs& crs, double lat_deg, double lon_deg);

}  // namespace sacfuse
