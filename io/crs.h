#pragma once
// Coordinate reference systems through PROJ (Debian's libproj): the project CRS of a run (config key `crs`), the
// CRS of a camera file's positions (input.cameras_crs), geodetic conversions, and what the CRS is called.
// In io/ because PROJ reads its database (proj.db) and grids from files; core/ stays free of file I/O.
//
// Accepted text (blanks around it ignored):
//   ""                 not georeferenced: local metres, no CRS written (kNone)
//   AUTH:CODE          any CRS of PROJ's database, e.g. "EPSG:25832", "EPSG:2154", "EPSG:5698", "IGNF:LAMB93"
//   AUTH:H+V           a compound CRS of a horizontal and a vertical code, e.g. "EPSG:2154+5720" (Lambert-93 +
//                      NGF-IGN69 heights); also "EPSG:2154+EPSG:5720" and urn:ogc:def:crs:... forms
//   WKT                OGC WKT1 (PROJCS[...], COMPD_CS[...]) or WKT2 (PROJCRS[...], COMPOUNDCRS[...])
//   PROJJSON           {"type": "ProjectedCRS", ...}
//   +proj=... +type=crs  a PROJ string
//   ENU:lat,lon,h      sacfuse's local east-north-up tangent frame at that origin (degrees, degrees, metres of
//                      ellipsoidal height) on the WGS 84 ellipsoid; x east, y north, z up along the origin's
//                      ellipsoid normal (PROJ's topocentric conversion)
// CRS names alone ("WGS 84 / UTM zone 32N") are refused: PROJ matches names loosely, a typo could pick another CRS.
//
// A project CRS must be metric east/north/up: a projected CRS (its z is then the ellipsoidal height) or a compound
// of a projected and a vertical CRS (z is that gravity-related height, e.g. NGF-IGN69), axes east and north in
// metres, heights in metres; or ENU. Geographic (latitude/longitude) CRSs are refused as project CRS; an input CRS
// (input.cameras_crs) may also be geographic (positions given as latitude, longitude, ellipsoidal height).
//
// Conventions:
// - Geodetic coordinates (latitude, longitude in degrees, ellipsoidal height in metres) are on the datum of the
//   CRS's own geodetic CRS (ETRS89 for EPSG:25832, RGF93 v1 for EPSG:2154, WGS 84 for ENU).
// - Heights: ellipsoidal unless the CRS has a vertical part; then PROJ converts through the geoid model EPSG
//   names for it (e.g. RAF18 for NGF-IGN69), which must be installed in PROJ's search path: nothing is downloaded.
//   A missing grid is an error naming the grid, never a silent pass-through (PROJ's "ballpark" operations, which
//   ignore the geoid, are not used).
// - Rotations: ProjectFromLocalEnuRotation turns attitudes given w.r.t. local east-north-up into the CRS's axes:
//   a rotation about the vertical by the grid (meridian) convergence for a projected CRS, the rotation between
//   the two tangent planes for ENU. The grid scale factor is not part of it (a rotation, not a Jacobian).
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sacfuse {

struct CrsImpl;  // io/crs_impl.h: the PROJ objects

class Crs {
 public:
  enum class Kind {
    kNone,        // "": not georeferenced
    kProjected,   // projected, or compound projected + vertical
    kGeographic,  // latitude/longitude(/ellipsoidal height): input CRSs only
    kLocalEnu,    // ENU:lat,lon,h
  };
  Crs();  // kNone

  Kind kind() const;
  bool georeferenced() const { return kind() != Kind::kNone; }
  const std::string& text() const;  // as given, e.g. "EPSG:2154+5720"
  const std::string& key() const;   // the config key it came from ("crs", "input.cameras_crs"), for messages
  // PROJ's name, e.g. "ETRS89 / UTM zone 32N", "RGF93 v1 / Lambert-93 + NGF-IGN69 height"; for ENU
  // "local ENU at 51.5, 7.46, 120 m"; "" for kNone.
  std::string Name() const;
  // The authority code, e.g. "EPSG:25832", "EPSG:5698", or "EPSG:2154+5720" for a compound without a code of its
  // own; "" when PROJ knows none (a custom WKT, ENU, kNone).
  std::string Code() const;
  int horizontal_epsg() const;  // EPSG code of the projected (or geographic) part; 0 when it has none
  int vertical_epsg() const;    // EPSG code of the vertical part; 0 when none
  bool orthometric() const;     // z is a gravity-related height (a vertical CRS); else ellipsoidal
  // "NGF-IGN69 height" (the vertical CRS's name), "ellipsoidal height", or for ENU "height above the tangent plane".
  std::string HeightName() const;
  // kLocalEnu: the origin (degrees, degrees, metres of ellipsoidal height).
  Eigen::Vector3d enu_origin() const;

  const CrsImpl& impl() const { return *impl_; }  // for io/crs*.cc

 private:
  friend Crs MakeCrs(std::shared_ptr<const CrsImpl> impl);
  std::shared_ptr<const CrsImpl> impl_;
};

// The project CRS: "", ENU:lat,lon,h, or a metric projected (or compound projected + vertical) CRS PROJ knows.
// Throws Error "crs \"<text>\": <why>; <what crs accepts>" for anything else (geographic CRSs, feet, axes not
// east/north, CRS names, text PROJ cannot read).
Crs ParseProjectCrs(const std::string& text);
// The CRS of an input's positions (input.cameras_crs): as the project CRS, and also geographic CRSs. Messages name
// the key input.cameras_crs.
Crs ParseInputCrs(const std::string& text);

// The geographic 3D CRS (latitude, longitude, ellipsoidal height) of a CRS's datum, e.g. ETRS89 for EPSG:25832,
// WGS 84 for ENU. Throws for kNone.
Crs GeodeticCrsOf(const Crs& crs);

// Throws Error when (lat, lon) lies more than kAreaOfUseMarginDeg outside the CRS's area of use (PROJ's database;
// e.g. 6..12 E for UTM zone 32N): a wrong zone or national grid, whose distortions sacfuse would not notice. No
// check for ENU and CRSs without an area.
constexpr double kAreaOfUseMarginDeg = 3.0;
void CheckAreaOfUse(const Crs& crs, double lat_deg, double lon_deg);

// Geodetic coordinates on the CRS's datum (latitude, longitude in degrees, ellipsoidal height in metres) -> CRS
// coordinates (east, north, height in metres). Throws Error for kNone, for points outside the area of use
// (CheckAreaOfUse) or that PROJ cannot convert (outside a grid's extent; non-finite) naming the point, and for a
// vertical CRS whose geoid grid is missing (naming the grid and where PROJ looked).
Eigen::Vector3d ProjectFromGeodetic(const Crs& crs, double lat_deg, double lon_deg, double h_m);
// The inverse (lat deg, lon deg, ellipsoidal h m). Throws as ProjectFromGeodetic.
Eigen::Vector3d GeodeticFromProject(const Crs& crs, const Eigen::Vector3d& point_in_crs);
// Latitude and longitude (degrees) of a point of the CRS, without its height conversion (needs no geoid grid).
Eigen::Vector2d LatLonFromProject(const Crs& crs, const Eigen::Vector3d& point_in_crs);
// Rotation taking vectors in the local east-north-up frame at (lat, lon) into the CRS's axes (see above; identity
// for a geographic CRS). Throws for kNone.
Eigen::Matrix3d ProjectFromLocalEnuRotation(const Crs& crs, double lat_deg, double lon_deg);
// Grid (meridian) convergence of a projected CRS at (lat, lon), degrees: the bearing of grid north clockwise from
// true north (positive east of the central meridian of a transverse Mercator projection in the north). Throws
// unless kProjected.
double GridConvergenceDeg(const Crs& crs, double lat_deg, double lon_deg);

// What a CRS definition (WKT, AUTH:CODE, ...) from a file is, for messages: PROJ's name and code; kind and checks
// are not applied. Throws Error with PROJ's message when PROJ cannot read it.
struct CrsLabel {
  std::string name;  // e.g. "RGF93 v1 / Lambert-93 + NGF-IGN69 height"
  std::string code;  // e.g. "EPSG:2154+5720", "EPSG:25832"; "" when none
};
CrsLabel LabelCrs(const std::string& definition);

// Folders searched for PROJ grids (and proj.db) before PROJ's own search path, for CRSs parsed from now on
// (process-wide; tests point it at a folder with a hand-made grid). Users install grids into PROJ's search path
// instead (`projinfo --searchpaths` lists it; PROJ_DATA adds folders).
void SetExtraProjSearchPaths(const std::vector<std::string>& dirs);

}  // namespace sacfuse
