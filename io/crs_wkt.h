#pragma once
// The WKT of a run's project CRS (config key `crs`, io/crs.h) for the writers of georeferenced files: one call,
// no PROJ types. LAS/LAZ/COPC point clouds take kLas14; GDAL rasters (OGRSpatialReference::importFromWkt,
// GDALDataset::SetProjection, which also write the GeoTIFF keys) take kGdal.
#include <string>

namespace sacfuse {

enum class CrsWktDialect {
  // OGC WKT1 as GDAL and PDAL write it into LAS 1.4 (LASF_Projection/2112) and COPC files, from PROJ's
  // definition: COMPD_CS[PROJCS, VERT_CS] with the vertical CRS for orthometric heights (EPSG:2154+5720), and for
  // a 2D projected CRS (its z is the ellipsoidal height) COMPD_CS[PROJCS, VERT_CS["Ellipsoid (metre)",
  // VERT_DATUM["Ellipsoid",2002],...]]; sacfuse's LOCAL_CS for ENU:lat,lon,h.
  kLas14,
  // WKT2:2019 of the CRS as `crs` names it (GDAL 3 reads it); the LOCAL_CS above for ENU:lat,lon,h.
  kGdal,
};

// "" when `crs` is "" (not georeferenced). Throws ConfigError naming the key `crs` when it is not a CRS sacfuse
// accepts (io/crs.h). Parses `crs` each call (a few milliseconds: PROJ opens its database).
std::string ProjectCrsWkt(const std::string& crs, CrsWktDialect dialect);

}  // namespace sacfuse
