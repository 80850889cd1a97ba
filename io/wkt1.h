#pragma once
// OGC WKT1 (CT 1.0, the dialect of LAS 1.4's LASF_Projection/2112 record): what sacfuse writes for its project
// CRS, and a small parser so readers and tests can look inside any WKT1 string.
#include <optional>
#include <string>
#include <vector>

#include "core/crs.h"

namespace sacfuse {

// One WKT1 node: KEYWORD["quoted", 1.5, CHILD[...], ENUM].
struct WktNode {
  std::string keyword;                 // e.g. "PROJCS"
  std::vector<std::string> values;     // quoted strings (unquoted), numbers and bare words, in order
  std::vector<WktNode> children;

  const WktNode* Child(const std::string& keyword) const;  // first child with that keyword, or nullptr
  // EPSG code of this node's AUTHORITY["EPSG","code"] child, or 0.
  int EpsgAuthority() const;
};

// Parses one WKT1 node (keyword, brackets [] or (), quoted strings with "" escapes). Throws sacfuse::Error with
// the character position on malformed text or trailing garbage.
WktNode ParseWkt1(const std::string& text);

// The WKT1 string of a project CRS:
// - UTM: COMPD_CS[<name> + ellipsoidal height, PROJCS[... as EPSG and PROJ write it, AUTHORITY["EPSG",code]],
//   VERT_CS["ellipsoidal height", VERT_DATUM["Ellipsoid",2002], UNIT["metre",1], AXIS["Up",UP]]]: horizontal
//   EPSG:326zz/327zz/258zz, vertical: ellipsoidal heights in metres (datum type 2002 = ellipsoidal, which PROJ and
//   GDAL read as a 3D projected CRS).
// - ENU: LOCAL_CS["sacfuse local ENU: origin lat ..., lon ..., h ... m (WGS 84 ellipsoid); z = up, metres",
//   LOCAL_DATUM["east-north-up tangent plane", 32767], UNIT["metre",1], AXIS["Easting",EAST],
//   AXIS["Northing",NORTH]]. WKT1 has no topocentric frame, so the origin is in the name; two axes because PROJ
//   (9.1) refuses a LOCAL_CS with three, z shares the metre unit.
// "" for kNone.
std::string ProjectCrsWkt1(const ProjectCrs& crs);

// Horizontal EPSG code of a WKT1 CRS: the AUTHORITY of PROJCS or GEOGCS (also inside COMPD_CS), or 0.
int WktHorizontalEpsg(const WktNode& root);

}  // namespace sacfuse
