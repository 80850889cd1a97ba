#pragma once
// A virtual point cloud (.vpc): the index of a set of point cloud files that QGIS (3.32+) opens as one layer and
// PDAL wrench's tools read as one input, in the format `pdal_wrench build_vpc` writes: a GeoJSON FeatureCollection
// of STAC 1.0.0 Items (pointcloud and projection extensions), one per file, each with
//   geometry, bbox          the file's box in WGS 84 (longitude, latitude; the heights as stored), when the CRS
//                           converts to latitude/longitude; in the file's own coordinates otherwise
//   properties.pc:count     the header's point count
//   properties.proj:bbox    the header's bounds [min x, min y, min z, max x, max y, max z] in the file's CRS
//   properties.proj:geometry  that box as a polygon in the file's CRS
//   properties.proj:wkt2    the file's CRS record as stored in it (our LAS 1.4 files: OGC WKT1, which QGIS and
//                           PDAL read as well; "" when none); proj:epsg: the horizontal EPSG code, or the code
//                           of the whole CRS, but none for a compound named by two codes (EPSG:2154+5720), whose
//                           heights only proj:wkt2 states
//   properties.pc:schemas   the dimensions of the point format, named as PDAL names them
//   properties.datetime     the header's creation date
//   assets.data.href        the file, relative to the .vpc ("./tiles/3_4.copc.laz")
// QGIS streams the points of COPC members (*.copc.laz); of plain LAS/LAZ members it draws the boxes only (QGIS
// issue 53765), while PDAL wrench and QGIS's processing tools read both.
#include <string>
#include <vector>

#include "io/crs.h"

namespace sacfuse {

// Writes `vpc_path` (atomically) indexing `files` (LAS/LAZ/COPC, each readable by LasReader, in the order given),
// whose coordinates are in `crs` (the run's project CRS: used for the WGS 84 geometry; the CRS text comes from
// each file's own records). Throws InputError naming a file that cannot be read.
void WriteVirtualPointCloud(const std::string& vpc_path, const std::vector<std::string>& files, const Crs& crs);

}  // namespace sacfuse
