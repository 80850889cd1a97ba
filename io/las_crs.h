#pragma once
// The CRS records of the LAS files sacfuse writes, and reading them back
// (../shared/reference/jobs-and-las.md B5):
// - LAS 1.4: one LASF_Projection/2112 VLR holding OGC WKT1 as PROJ writes it for GDAL (io/crs_wkt.h, kLas14),
//   NUL-terminated, and global encoding bit 4 (WKT) set; no GeoTIFF records (a spec error for point formats 6-10).
// - LAS 1.2: GeoTIFF keys: LASF_Projection/34735 (GeoKeyDirectoryTag) and 34737 (GeoAsciiParamsTag, the citation);
//   no WKT, bit 4 clear. A projected CRS: GTModelType = 1 (projected), ProjectedCSType = its EPSG code,
//   ProjLinearUnits = 9001 (metre), VerticalCSType = the vertical CRS's EPSG code when heights are orthometric
//   (e.g. 5720 NGF-IGN69), VerticalUnits = 9001; the citation names the CRS, its code and its heights. GeoTIFF keys
//   hold EPSG codes only: a CRS without one cannot be written to LAS 1.2 (config validation refuses it, naming
//   output.las_version). A local ENU frame: GTModelType = 32767 (user-defined), the frame in GTCitation, vertical
//   units metre.
// - Not georeferenced (crs ""): no CRS record at all.
#include <cstdint>
#include <string>
#include <vector>

#include "io/crs.h"
#include "io/las_types.h"
#include "io/las_writer.h"

namespace sacfuse {

constexpr uint16_t kLasGeoKeyDirectoryRecordId = 34735;
constexpr uint16_t kLasGeoDoubleParamsRecordId = 34736;
constexpr uint16_t kLasGeoAsciiParamsRecordId = 34737;
constexpr uint16_t kLasGlobalEncodingWktBit = 0x10;

// GeoKey ids used here (GeoTIFF 1.0 / OGC 19-008).
constexpr uint16_t kGeoKeyModelType = 1024;          // 1 projected, 2 geographic, 3 geocentric, 32767 user-defined
constexpr uint16_t kGeoKeyCitation = 1026;           // GTCitationGeoKey (ASCII)
constexpr uint16_t kGeoKeyGeographicType = 2048;     // GeographicTypeGeoKey (EPSG)
constexpr uint16_t kGeoKeyProjectedCsType = 3072;    // ProjectedCSTypeGeoKey (EPSG)
constexpr uint16_t kGeoKeyProjLinearUnits = 3076;    // ProjLinearUnitsGeoKey (EPSG unit)
constexpr uint16_t kGeoKeyVerticalCsType = 4096;     // VerticalCSTypeGeoKey
constexpr uint16_t kGeoKeyVerticalUnits = 4099;      // VerticalUnitsGeoKey (EPSG unit)

struct LasCrsRecords {
  std::vector<LasVlr> vlrs;
  uint16_t global_encoding_bits = 0;  // kLasGlobalEncodingWktBit for LAS 1.4 with a CRS
};

// The VLRs (and global-encoding bits) carrying `crs` in a LAS 1.<version_minor> file (2 or 4; others throw, as
// does a CRS LAS 1.2's GeoTIFF keys cannot name: LasCrsProblem).
LasCrsRecords LasCrsVlrs(const Crs& crs, int version_minor);
// Why a LAS 1.<version_minor> file cannot carry `crs`, or "" when it can.
std::string LasCrsProblem(const Crs& crs, int version_minor);

// THE helper every writer of a job goes through: adds LasCrsVlrs(crs, options->version_minor) to the options'
// VLRs and global-encoding bits. Throws when the options already carry a CRS record.
void AddCrsToLasOptions(const Crs& crs, LasWriterOptions* options);

// One entry of a GeoKeyDirectory, with its value resolved.
struct GeoKey {
  uint16_t id = 0;
  uint16_t location = 0;       // 0: value inline; 34736: doubles; 34737: ASCII
  uint16_t count = 0;
  uint16_t value = 0;          // inline value, or the offset into the params record
  std::vector<double> doubles;  // location 34736
  std::string ascii;            // location 34737, without the '|' terminator
};

// The GeoKeys of a header's LASF_Projection/34735 record (empty when there is none). Throws sacfuse::Error
// naming what is wrong for a malformed directory (bad header, count beyond the record, params out of range).
std::vector<GeoKey> ParseLasGeoKeys(const LasHeader& header);

// What a LAS file says about its CRS.
struct LasCrsInfo {
  std::string wkt;                 // LASF_Projection/2112 text ("" when none)
  std::vector<GeoKey> geokeys;     // LASF_Projection/34735 ("" when none)
  int wkt_records = 0;             // number of 2112 records (more than one is a spec error)
  int geokey_records = 0;          // number of 34735 records
  int epsg = 0;                    // horizontal EPSG code: from the WKT when present, else ProjectedCSType, else
                                   // GeographicType; 0 when unknown or user-defined
  std::string name;                // PROJ's name of the CRS, e.g. "RGF93 v1 / Lambert-93 + NGF-IGN69 height"; ""
                                   // when none or PROJ cannot read it
  std::string code;                // PROJ's code, e.g. "EPSG:2154+5720"; "" when none
  // e.g. "EPSG:2154+5720 \"RGF93 v1 / Lambert-93 + NGF-IGN69 height\" (WKT1 COMPD_CS)", or "none"; a WKT PROJ
  // cannot read is described by its structure with PROJ's complaint.
  std::string description;
};
// Throws sacfuse::Error for malformed WKT or GeoKeys (a WKT1 that PROJ refuses but that is well-formed is not an
// error: `name` stays empty and the description says why).
LasCrsInfo ReadLasCrs(const LasHeader& header);

}  // namespace sacfuse
