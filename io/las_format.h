#pragma once
// Byte-level LAS layout shared by the reader and the writer (private to io/): public header field offsets,
// point data record format (PDRF) sizes and fields, little-endian put/get, quantisation.
// See ../shared/reference/jobs-and-las.md part B for the tables these constants come from.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/las_types.h"

namespace sacfuse::las_format {

// Public header sizes by version.
constexpr size_t kHeaderSize12 = 227;  // LAS 1.0-1.2
constexpr size_t kHeaderSize13 = 235;  // LAS 1.3
constexpr size_t kHeaderSize14 = 375;  // LAS 1.4
constexpr size_t kVlrHeaderSize = 54;
constexpr size_t kEvlrHeaderSize = 60;

// Public header field offsets.
constexpr size_t kOffFileSourceId = 4;
constexpr size_t kOffGlobalEncoding = 6;
constexpr size_t kOffVersionMajor = 24;
constexpr size_t kOffVersionMinor = 25;
constexpr size_t kOffSystemId = 26;
constexpr size_t kOffSoftware = 58;
constexpr size_t kIdFieldSize = 32;  // System ID and Generating Software
constexpr size_t kOffCreationDay = 90;
constexpr size_t kOffCreationYear = 92;
constexpr size_t kOffHeaderSize = 94;
constexpr size_t kOffPointOffset = 96;
constexpr size_t kOffNumVlrs = 100;
constexpr size_t kOffPdrf = 104;
constexpr size_t kOffRecordLength = 105;
constexpr size_t kOffLegacyCount = 107;
constexpr size_t kOffLegacyByReturn = 111;  // u32[5]
constexpr size_t kOffScale = 131;           // f64[3]
constexpr size_t kOffOffset = 155;          // f64[3]
constexpr size_t kOffBounds = 179;          // MaxX, MinX, MaxY, MinY, MaxZ, MinZ
constexpr size_t kOffWaveformStart = 227;   // 1.3+
constexpr size_t kOffEvlrStart = 235;       // 1.4
constexpr size_t kOffEvlrCount = 243;       // 1.4
constexpr size_t kOffCount64 = 247;         // 1.4
constexpr size_t kOffByReturn64 = 255;      // 1.4, u64[15]

// VLR user ID / record ID of interest.
constexpr const char* kProjectionUserId = "LASF_Projection";
constexpr uint16_t kWktRecordId = 2112;
constexpr const char* kLaszipUserId = "laszip encoded";
constexpr uint16_t kLaszipRecordId = 22204;
constexpr const char* kCopcUserId = "copc";
constexpr uint16_t kCopcInfoRecordId = 1;          // the COPC info VLR (io/copc_format.h)
constexpr uint16_t kCopcHierarchyRecordId = 1000;  // the COPC hierarchy EVLR

// Minimum header size of LAS 1.<minor>.
size_t MinHeaderSize(int version_minor);

// Size in bytes of the standard fields of PDRF 0-10, or 0 for an unknown format.
size_t BaseRecordSize(int pdrf);
inline bool IsExtendedFormat(int pdrf) { return pdrf >= 6; }
bool HasGpsTime(int pdrf);
bool HasRgb(int pdrf);
bool HasNir(int pdrf);

// Little-endian scalar access (independent of the host byte order).
inline void PutU8(uint8_t* p, uint8_t v) { p[0] = v; }
inline void PutU16(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v);
  p[1] = static_cast<uint8_t>(v >> 8);
}
inline void PutU32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
inline void PutU64(uint8_t* p, uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
inline void PutI32(uint8_t* p, int32_t v) { PutU32(p, static_cast<uint32_t>(v)); }
inline void PutF64(uint8_t* p, double v) {
  uint64_t bits;
  std::memcpy(&bits, &v, sizeof(bits));
  PutU64(p, bits);
}
inline uint16_t GetU16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
inline uint32_t GetU32(const uint8_t* p) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
inline uint64_t GetU64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
inline int32_t GetI32(const uint8_t* p) { return static_cast<int32_t>(GetU32(p)); }
inline double GetF64(const uint8_t* p) {
  const uint64_t bits = GetU64(p);
  double v;
  std::memcpy(&v, &bits, sizeof(v));
  return v;
}

// Fixed-size, NUL-padded character field -> string up to the first NUL.
std::string GetPaddedString(const uint8_t* p, size_t size);
// String -> fixed-size NUL-padded field; the caller has checked that value.size() <= size.
void PutPaddedString(uint8_t* p, size_t size, const std::string& value);

// Coordinate <-> stored integer. Dequantise is the one formula used for points and header bounds, so that the
// bounds written from integer min/max equal the coordinates a reader computes.
inline double Dequantise(int32_t stored, double scale, double offset) {
  return static_cast<double>(stored) * scale + offset;
}
// round((value - offset) / scale) half away from zero (llround, as PDAL and LASlib); false when the result is
// not finite or does not fit int32.
bool Quantise(double value, double scale, double offset, int32_t* stored);

// True when scale is 10^k x {1, 0.5, 0.25} (within 1e-9 relative), k any integer; *canonical gets the nearest
// double to that decimal value (e.g. 0.001 exactly as the literal).
bool CanonicalLasScale(double scale, double* canonical);

// Writes the standard fields of `point` into `record` (BaseRecordSize(pdrf) bytes, zero-filled by the caller,
// extra bytes untouched) with the already quantised coordinates. Returns "" on success, otherwise a message
// naming the field the format cannot hold (nothing is clamped).
std::string EncodePointRecord(const LasPoint& point, const std::array<int32_t, 3>& stored, int pdrf,
                              uint8_t* record);
// The public header fields a writer sets (LasWriter, CopcWriter): one encoder for both.
struct HeaderFields {
  int version_minor = 4;
  int pdrf = 7;
  bool compressed = false;  // LAZ: the point format id gets bit 7, as LASzip marks compression
  size_t header_size = kHeaderSize14;
  size_t record_length = 36;
  uint32_t point_offset = 0;
  uint32_t num_vlrs = 0;
  uint16_t global_encoding = 0;
  std::string system_identifier;
  std::string generating_software;
  uint16_t creation_day = 0;
  uint16_t creation_year = 0;
  Eigen::Vector3d scale = Eigen::Vector3d::Constant(0.001);
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  uint64_t count = 0;
  std::array<uint64_t, 15> by_return = {};
  std::array<int32_t, 3> stored_min = {};  // bounds as stored integers (0 written when count is 0)
  std::array<int32_t, 3> stored_max = {};
  uint64_t evlr_start = 0;  // LAS 1.4
  uint32_t num_evlrs = 0;
};
// header_size bytes. Legacy counts are written before 1.4, and in 1.4 for PDRF < 6 with at most 2^32-1 points.
std::vector<uint8_t> EncodeHeader(const HeaderFields& fields);
// The 54-byte header of a VLR, or the 60-byte header of an EVLR (vlr.extended), for vlr.data.size() bytes.
std::vector<uint8_t> EncodeVlrHeader(const LasVlr& vlr);
// Records that describe how a file's points are stored (LASzip's "laszip encoded", COPC's info and hierarchy):
// writers make their own and never copy these from a source file's VLRs.
bool IsLayoutVlr(const LasVlr& vlr);

// Reads the standard fields of one record; waveform packet fields and extra bytes are skipped.
void DecodePointRecord(const uint8_t* record, int pdrf, const Eigen::Vector3d& scale, const Eigen::Vector3d& offset,
                       LasPoint* point);

}  // namespace sacfuse::las_format
