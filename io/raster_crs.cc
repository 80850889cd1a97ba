#include "io/raster_crs.h"

#include <cstdlib>
#include <string>

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include "io/las_crs.h"

namespace sacfuse {

std::string RasterCrsWktOf(const std::string& wkt) {
  if (wkt.empty()) return wkt;
  OGRSpatialReference srs;
  if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return wkt;
  if (srs.IsCompound() || srs.GetAxesCount() != 3 || !(srs.IsProjected() || srs.IsGeographic())) return wkt;
  if (srs.DemoteTo2D(nullptr) != OGRERR_NONE) return wkt;
  // The horizontal CRS by its EPSG code when PROJ's database knows it (e.g. EPSG:25832), so that the GeoTIFF keys
  // name the code and GIS tools show it.
  int matches = 0;
  int* confidence = nullptr;
  OGRSpatialReferenceH* found = srs.FindMatches(nullptr, &matches, &confidence);
  if (matches > 0 && confidence[0] >= 90) {
    const OGRSpatialReference* best = OGRSpatialReference::FromHandle(found[0]);
    const char* name = best->GetAuthorityName(nullptr);
    const char* code = best->GetAuthorityCode(nullptr);
    OGRSpatialReference by_code;
    if (name != nullptr && code != nullptr && std::string(name) == "EPSG" &&
        by_code.importFromEPSG(std::atoi(code)) == OGRERR_NONE) {
      srs = by_code;
    }
  }
  OSRFreeSRSArray(found);
  CPLFree(confidence);
  char* out = nullptr;
  const char* options[] = {"FORMAT=WKT1_GDAL", nullptr};
  if (srs.exportToWkt(&out, options) != OGRERR_NONE || out == nullptr) {
    CPLFree(out);
    return wkt;
  }
  std::string horizontal = out;
  CPLFree(out);
  return horizontal;
}

std::string RasterCrsWktOfLas(const LasHeader& header) {
  const LasCrsInfo info = ReadLasCrs(header);
  if (!info.wkt.empty()) return RasterCrsWktOf(info.wkt);
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
