#pragma once
// LAS point and header as sacfuse sees them (ASPRS LAS 1.0-1.4, uncompressed). Coordinates are doubles in the
// file's CRS; the integer/scale/offset encoding is the reader's and writer's business.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sacfuse {

// Every standard field of point data record formats 0-10 (fields a format lacks stay at their defaults).
struct LasPoint {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // dequantised: integer * scale + offset
  uint16_t intensity = 0;
  uint8_t return_number = 1;
  uint8_t number_of_returns = 1;
  uint8_t classification = 0;      // full 8 bits for PDRF 6-10, 5 bits for PDRF 0-5
  uint8_t flags = 0;               // bit 0 synthetic, 1 key-point, 2 withheld, 3 overlap (PDRF 6+)
  uint8_t scanner_channel = 0;     // PDRF 6+
  bool scan_direction = false;
  bool edge_of_flight_line = false;
  float scan_angle_deg = 0.0f;     // PDRF 0-5: rank in whole degrees; PDRF 6+: 0.006 degree steps
  uint8_t user_data = 0;
  uint16_t point_source_id = 0;
  double gps_time = 0.0;
  std::array<uint16_t, 3> rgb = {0, 0, 0};  // 16-bit normalised colour
  uint16_t nir = 0;
};

struct LasVlr {
  std::string user_id;       // up to 16 chars
  uint16_t record_id = 0;
  std::string description;   // up to 32 chars
  std::vector<uint8_t> data;
  bool extended = false;     // true for an EVLR (LAS 1.4, stored after the points)
};

struct LasHeader {
  uint8_t version_major = 1;
  uint8_t version_minor = 4;
  uint16_t file_source_id = 0;
  uint16_t global_encoding = 0;
  std::string system_identifier;
  std::string generating_software;
  uint16_t creation_day = 0;
  uint16_t creation_year = 0;
  uint16_t header_size = 0;
  uint32_t offset_to_point_data = 0;
  uint8_t point_format = 0;          // PDRF 0-10
  uint16_t point_record_length = 0;  // bytes, including extra bytes
  uint64_t point_count = 0;          // the 64-bit count for 1.4, the legacy count before
  std::array<uint64_t, 15> points_by_return = {};
  Eigen::Vector3d scale = Eigen::Vector3d::Constant(0.001);
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  // bounds as stored in the header
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  std::vector<LasVlr> vlrs;          // VLRs and EVLRs

  // OGC WKT from a LASF_Projection/2112 record, or "" when there is none.
  std::string Wkt() const;
};

}  // namespace sacfuse
