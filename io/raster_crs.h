#pragma once
// The CRS written into raster products (GeoTIFF keys through GDAL): one place, so that the CRS definitions of a
// later PROJ-based project CRS replace only the bodies here.
#include <string>

#include "core/crs.h"
#include "io/las_types.h"

namespace sacfuse {

// WKT of the project CRS for a raster ("" when not georeferenced): today the WKT1 our LAS files carry
// (io/wkt1.h ProjectCrsWkt1: the UTM zone with ellipsoidal heights, or the local ENU frame). A CRS with an
// ellipsoidal height axis is written as its horizontal CRS (GeoTIFF has no keys for ellipsoidal heights; the
// raster's heights are those of the LAS files, docs/dsm-and-ortho.md); compound CRSs keep their vertical part.
std::string RasterCrsWkt(const ProjectCrs& crs);

// The CRS of a LAS file as WKT GDAL reads (a 3D one as its horizontal CRS, as above): its WKT record (LAS 1.4),
// else the EPSG code of its GeoKeys (LAS 1.2: ProjectedCSType / GeographicType) expanded by GDAL; "" when it has
// none or GDAL does not know the code.
std::string RasterCrsWktOfLas(const LasHeader& header);

}  // namespace sacfuse
