#pragma once
// The CRS a raster product (io/gdal_raster.h) gets from a point cloud file's CRS record (`sacfuse dsm` of a LAS
// file). A run's rasters take the project CRS from io/crs_wkt.h (ProjectCrsWkt, CrsWktDialect::kGdal) instead.
#include <string>

#include "io/las_types.h"

namespace sacfuse {

// A CRS definition (WKT) as a raster carries it: a projected or geographic CRS with an ellipsoidal height axis (the
// WKT1 of our LAS 1.4 files for a CRS without a vertical part, COMPD_CS[PROJCS, VERT_CS["Ellipsoid"]], which GDAL
// reads as a 3D CRS) becomes its horizontal CRS, by its EPSG code when PROJ's database knows it: GeoTIFF has no keys
// for ellipsoidal heights, and GDAL would write such a CRS as an ESRI PE string whose text varies with the state of
// PROJ's database queries in the process. Any other CRS (compound with a vertical CRS, local) is returned as it is.
std::string RasterCrsWktOf(const std::string& wkt);

// The CRS of a LAS file as WKT GDAL reads, through RasterCrsWktOf: its WKT record (LAS 1.4), else the EPSG code of
// its GeoKeys (LAS 1.2: ProjectedCSType / GeographicType) expanded by GDAL; "" when it has none or GDAL does not
// know the code.
std::string RasterCrsWktOfLas(const LasHeader& header);

}  // namespace sacfuse
