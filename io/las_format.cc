#include "io/las_format.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sacfuse::las_format {
namespace {

// 10^n as an exact double (n <= 22).
double ExactPow10(int n) {
  double p = 1.0;
  for (int i = 0; i < n; ++i) p *= 10.0;
  return p;
}

std::string NonZeroFieldError(const char* field, int pdrf) {
  return std::string(field) + " is set but point format " + std::to_string(pdrf) + " has no such field";
}

}  // namespace

size_t MinHeaderSize(int version_minor) {
  if (version_minor >= 4) return kHeaderSize14;
  if (version_minor == 3) return kHeaderSize13;
  return kHeaderSize12;
}

size_t BaseRecordSize(int pdrf) {
  static constexpr std::array<size_t, 11> kSizes = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  if (pdrf < 0 || pdrf > 10) return 0;
  return kSizes[static_cast<size_t>(pdrf)];
}

bool HasGpsTime(int pdrf) { return pdrf != 0 && pdrf != 2 && pdrf >= 0 && pdrf <= 10; }
bool HasRgb(int pdrf) { return pdrf == 2 || pdrf == 3 || pdrf == 5 || pdrf == 7 || pdrf == 8 || pdrf == 10; }
bool HasNir(int pdrf) { return pdrf == 8 || pdrf == 10; }

std::string GetPaddedString(const uint8_t* p, size_t size) {
  size_t n = 0;
  while (n < size && p[n] != 0) ++n;
  return std::string(reinterpret_cast<const char*>(p), n);
}

void PutPaddedString(uint8_t* p, size_t size, const std::string& value) {
  std::memset(p, 0, size);
  std::memcpy(p, value.data(), std::min(size, value.size()));
}

bool Quantise(double value, double scale, double offset, int32_t* stored) {
  const double v = (value - offset) / scale;
  if (!std::isfinite(v) || !(v > -2147483648.5) || !(v < 2147483647.5)) return false;
  *stored = static_cast<int32_t>(std::llround(v));
  return true;
}

bool CanonicalLasScale(double scale, double* canonical) {
  if (!std::isfinite(scale) || !(scale > 0.0)) return false;
  const int k0 = static_cast<int>(std::floor(std::log10(scale)));
  for (int k = k0 - 1; k <= k0 + 1; ++k) {
    if (k < -22 || k > 22) continue;
    for (double mantissa : {1.0, 2.5, 5.0}) {  // 10^k x {1, 0.5, 0.25} = 10^(k') x {1, 5, 2.5}
      const double candidate = k >= 0 ? mantissa * ExactPow10(k) : mantissa / ExactPow10(-k);
      if (std::abs(scale - candidate) <= 1e-9 * candidate) {
        *canonical = candidate;
        return true;
      }
    }
  }
  return false;
}

std::string EncodePointRecord(const LasPoint& point, const std::array<int32_t, 3>& stored, int pdrf,
                              uint8_t* record) {
  PutI32(record + 0, stored[0]);
  PutI32(record + 4, stored[1]);
  PutI32(record + 8, stored[2]);
  PutU16(record + 12, point.intensity);
  const uint8_t direction = point.scan_direction ? 1 : 0;
  const uint8_t edge = point.edge_of_flight_line ? 1 : 0;
  if (!std::isfinite(point.scan_angle_deg)) return "scan angle is not finite";
  if (!IsExtendedFormat(pdrf)) {
    if (point.return_number > 7) return "return number " + std::to_string(point.return_number) + " > 7";
    if (point.number_of_returns > 7) return "number of returns " + std::to_string(point.number_of_returns) + " > 7";
    if (point.classification > 31) {
      return "classification " + std::to_string(point.classification) + " > 31 (PDRF 0-5 hold 5 bits)";
    }
    if (point.flags > 7) return "flags " + std::to_string(point.flags) + " need PDRF 6+ (overlap bit)";
    if (point.scanner_channel != 0) return NonZeroFieldError("scanner channel", pdrf);
    const long long rank = std::llround(point.scan_angle_deg);
    if (rank < -128 || rank > 127) return "scan angle rank " + std::to_string(rank) + " does not fit int8";
    PutU8(record + 14, static_cast<uint8_t>(point.return_number | (point.number_of_returns << 3) |
                                            (direction << 6) | (edge << 7)));
    PutU8(record + 15, static_cast<uint8_t>(point.classification | (point.flags << 5)));
    PutU8(record + 16, static_cast<uint8_t>(static_cast<int8_t>(rank)));
    PutU8(record + 17, point.user_data);
    PutU16(record + 18, point.point_source_id);
    if (HasGpsTime(pdrf)) PutF64(record + 20, point.gps_time);
    if (HasRgb(pdrf)) {
      uint8_t* rgb = record + (pdrf == 2 ? 20 : 28);
      for (int c = 0; c < 3; ++c) PutU16(rgb + 2 * c, point.rgb[c]);
    }
  } else {
    if (point.return_number > 15) return "return number " + std::to_string(point.return_number) + " > 15";
    if (point.number_of_returns > 15) {
      return "number of returns " + std::to_string(point.number_of_returns) + " > 15";
    }
    if (point.flags > 15) return "flags " + std::to_string(point.flags) + " > 15";
    if (point.scanner_channel > 3) return "scanner channel " + std::to_string(point.scanner_channel) + " > 3";
    const long long angle = std::llround(static_cast<double>(point.scan_angle_deg) / 0.006);
    if (angle < -32768 || angle > 32767) return "scan angle " + std::to_string(point.scan_angle_deg) + " too large";
    PutU8(record + 14, static_cast<uint8_t>(point.return_number | (point.number_of_returns << 4)));
    PutU8(record + 15, static_cast<uint8_t>(point.flags | (point.scanner_channel << 4) | (direction << 6) |
                                            (edge << 7)));
    PutU8(record + 16, point.classification);
    PutU8(record + 17, point.user_data);
    PutU16(record + 18, static_cast<uint16_t>(static_cast<int16_t>(angle)));
    PutU16(record + 20, point.point_source_id);
    PutF64(record + 22, point.gps_time);
    if (HasRgb(pdrf)) {
      for (int c = 0; c < 3; ++c) PutU16(record + 30 + 2 * c, point.rgb[c]);
    }
    if (HasNir(pdrf)) PutU16(record + 36, point.nir);
  }
  if (!HasGpsTime(pdrf) && point.gps_time != 0.0) return NonZeroFieldError("GPS time", pdrf);
  if (!HasRgb(pdrf) && (point.rgb[0] != 0 || point.rgb[1] != 0 || point.rgb[2] != 0)) {
    return NonZeroFieldError("RGB", pdrf);
  }
  if (!HasNir(pdrf) && point.nir != 0) return NonZeroFieldError("NIR", pdrf);
  // Waveform packet fields (PDRF 4, 5, 9, 10) stay zero: the caller zero-filled the record.
  return "";
}

std::vector<uint8_t> EncodeHeader(const HeaderFields& f) {
  std::vector<uint8_t> h(f.header_size, 0);
  std::memcpy(h.data(), "LASF", 4);
  PutU16(&h[kOffFileSourceId], 0);  // aggregated sources: the point source IDs name the views
  PutU16(&h[kOffGlobalEncoding], f.global_encoding);
  h[kOffVersionMajor] = 1;
  h[kOffVersionMinor] = static_cast<uint8_t>(f.version_minor);
  PutPaddedString(&h[kOffSystemId], kIdFieldSize, f.system_identifier);
  PutPaddedString(&h[kOffSoftware], kIdFieldSize, f.generating_software);
  PutU16(&h[kOffCreationDay], f.creation_day);
  PutU16(&h[kOffCreationYear], f.creation_year);
  PutU16(&h[kOffHeaderSize], static_cast<uint16_t>(f.header_size));
  PutU32(&h[kOffPointOffset], f.point_offset);
  PutU32(&h[kOffNumVlrs], f.num_vlrs);
  h[kOffPdrf] = static_cast<uint8_t>(f.pdrf | (f.compressed ? 0x80 : 0));
  PutU16(&h[kOffRecordLength], static_cast<uint16_t>(f.record_length));
  // Legacy counts: the only counts before 1.4; in 1.4 zero for PDRF >= 6 or counts beyond 32 bits.
  const bool legacy = f.version_minor < 4 || (f.pdrf < 6 && f.count <= std::numeric_limits<uint32_t>::max());
  if (legacy) {
    PutU32(&h[kOffLegacyCount], static_cast<uint32_t>(f.count));
    for (int r = 0; r < 5; ++r) PutU32(&h[kOffLegacyByReturn + 4 * r], static_cast<uint32_t>(f.by_return[r]));
  }
  for (int a = 0; a < 3; ++a) {
    PutF64(&h[kOffScale + 8 * a], f.scale[a]);
    PutF64(&h[kOffOffset + 8 * a], f.offset[a]);
    const double max = f.count == 0 ? 0.0 : Dequantise(f.stored_max[a], f.scale[a], f.offset[a]);
    const double min = f.count == 0 ? 0.0 : Dequantise(f.stored_min[a], f.scale[a], f.offset[a]);
    PutF64(&h[kOffBounds + 16 * a], max);  // max before min
    PutF64(&h[kOffBounds + 16 * a + 8], min);
  }
  if (f.version_minor >= 4) {
    PutU64(&h[kOffWaveformStart], 0);
    PutU64(&h[kOffEvlrStart], f.evlr_start);
    PutU32(&h[kOffEvlrCount], f.num_evlrs);
    PutU64(&h[kOffCount64], f.count);
    for (int r = 0; r < 15; ++r) PutU64(&h[kOffByReturn64 + 8 * r], f.by_return[r]);
  }
  return h;
}

std::vector<uint8_t> EncodeVlrHeader(const LasVlr& vlr) {
  std::vector<uint8_t> head(vlr.extended ? kEvlrHeaderSize : kVlrHeaderSize, 0);
  PutPaddedString(&head[2], 16, vlr.user_id);
  PutU16(&head[18], vlr.record_id);
  if (vlr.extended) {
    PutU64(&head[20], vlr.data.size());
    PutPaddedString(&head[28], 32, vlr.description);
  } else {
    PutU16(&head[20], static_cast<uint16_t>(vlr.data.size()));
    PutPaddedString(&head[22], 32, vlr.description);
  }
  return head;
}

bool IsLayoutVlr(const LasVlr& vlr) {
  const bool copc = vlr.user_id == kCopcUserId &&
                    (vlr.record_id == kCopcInfoRecordId || vlr.record_id == kCopcHierarchyRecordId);
  return copc || (vlr.user_id == kLaszipUserId && vlr.record_id == kLaszipRecordId);
}

void DecodePointRecord(const uint8_t* record, int pdrf, const Eigen::Vector3d& scale, const Eigen::Vector3d& offset,
                       LasPoint* point) {
  for (int a = 0; a < 3; ++a) point->xyz[a] = Dequantise(GetI32(record + 4 * a), scale[a], offset[a]);
  point->intensity = GetU16(record + 12);
  const uint8_t b14 = record[14];
  const uint8_t b15 = record[15];
  if (!IsExtendedFormat(pdrf)) {
    point->return_number = b14 & 0x07;
    point->number_of_returns = (b14 >> 3) & 0x07;
    point->scan_direction = (b14 >> 6) & 1;
    point->edge_of_flight_line = (b14 >> 7) & 1;
    point->classification = b15 & 0x1f;
    point->flags = b15 >> 5;
    point->scanner_channel = 0;
    point->scan_angle_deg = static_cast<float>(static_cast<int8_t>(record[16]));
    point->user_data = record[17];
    point->point_source_id = GetU16(record + 18);
    point->gps_time = HasGpsTime(pdrf) ? GetF64(record + 20) : 0.0;
    if (HasRgb(pdrf)) {
      const uint8_t* rgb = record + (pdrf == 2 ? 20 : 28);
      for (int c = 0; c < 3; ++c) point->rgb[c] = GetU16(rgb + 2 * c);
    } else {
      point->rgb = {0, 0, 0};
    }
    point->nir = 0;
  } else {
    point->return_number = b14 & 0x0f;
    point->number_of_returns = b14 >> 4;
    point->flags = b15 & 0x0f;
    point->scanner_channel = (b15 >> 4) & 0x03;
    point->scan_direction = (b15 >> 6) & 1;
    point->edge_of_flight_line = (b15 >> 7) & 1;
    point->classification = record[16];
    point->user_data = record[17];
    point->scan_angle_deg = static_cast<float>(static_cast<int16_t>(GetU16(record + 18)) * 0.006);
    point->point_source_id = GetU16(record + 20);
    point->gps_time = GetF64(record + 22);
    if (HasRgb(pdrf)) {
      for (int c = 0; c < 3; ++c) point->rgb[c] = GetU16(record + 30 + 2 * c);
    } else {
      point->rgb = {0, 0, 0};
    }
    point->nir = HasNir(pdrf) ? GetU16(record + 36) : 0;
  }
}

}  // namespace sacfuse::las_format
