#pragma once
// What a parsed Crs (io/crs.h) holds: its description, its WKT, the definitions its transformations are built
// from, and the PROJ objects of its own context. Internal to io/crs*.cc and io/las_crs.cc.
#include <memory>
#include <mutex>
#include <string>

#include <Eigen/Core>

#include "io/crs.h"
#include "io/proj_handles.h"

namespace sacfuse {

class CrsTransform;

// Numbers ("%.10g") and quoted names in the messages of io/crs*.cc.
std::string CrsNumberText(double v, const char* format = "%.10g");
inline std::string CrsQuoted(const std::string& s) { return "\"" + s + "\""; }

struct CrsImpl {
  Crs::Kind kind = Crs::Kind::kNone;
  std::string text;  // as given
  std::string key;   // the config key it came from, for messages ("crs", "input.cameras_crs")
  std::string name, code;
  int horizontal_epsg = 0, vertical_epsg = 0;
  bool orthometric = false;
  std::string height_name;
  Eigen::Vector3d enu_origin = Eigen::Vector3d::Zero();  // kLocalEnu: lat deg, lon deg, h m

  // Exact definitions (PROJJSON) PROJ rebuilds the CRS from in another context: the CRS with its heights (a 2D
  // projected or geographic CRS promoted to 3D: ellipsoidal heights; a compound as it is), and the geographic 3D
  // CRS of its datum (the frame of geodetic coordinates). For ENU: WGS 84 (EPSG:4979) for both.
  std::string definition;
  std::string geodetic_definition;
  std::string geodetic_name;  // e.g. "ETRS89", "RGF93 v1"

  std::string wkt1_las;  // the project CRS as LAS 1.4 writes it ("" for kNone and input CRSs)
  std::string wkt2;      // WKT2:2019 of the CRS as given (ENU: wkt1_las)
  std::string las12_problem;  // why LAS 1.2 GeoTIFF keys cannot name it; "" when they can
  // PROJ's area of use of the horizontal part (degrees; west > east across the antimeridian); none for custom CRSs.
  bool has_area = false;
  double area_west = 0, area_south = 0, area_east = 0, area_north = 0;

  // PROJ objects of this CRS, used under `mutex`: the projected part in 2D (grid convergence) and, made on first
  // use, the transformations of ProjectFromGeodetic (geodetic 3D -> this) and LatLonFromProject (2D inverse).
  mutable std::mutex mutex;
  std::unique_ptr<ProjContext> ctx;
  PjPtr horizontal;
  mutable std::shared_ptr<const CrsTransform> from_geodetic;
  mutable PjPtr latlon_from_horizontal;
};

}  // namespace sacfuse
