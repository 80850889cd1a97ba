#include "io/raster_crs.h"


#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include "io/las_crs.h"
#include "io/wkt1.h"

namespace sacfuse {

std::string RasterCrsWkt(const ProjectCrs& crs) { return ProjectCrsWkt1(crs); }

std::string RasterCrsWktOfLas(const LasHeader& header) {
  const LasCrsInfo info = ReadLasCrs(header);
  if (!info.wkt.empty()) return info.wkt;
  if (info.epsg == 0) return "";
  OGRSpatialReference srs;
  if (srs.importFromEPSG(info.epsg) != OGRERR_NONE) return "";
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string out = wkt != nullptr ? wkt : "";
  CPLFree(wkt);
  return out;
}

}  // namespace sacfuse
