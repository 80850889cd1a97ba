#include "io/las_validate.h"

#include "io/las_reader.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <memory>

#include "core/error.h"
#include "io/copc_validate.h"
#include "io/input_file.h"
#include "io/las_crs.h"
#include "io/las_format.h"
#include "io/wkt1.h"
#include "io/unique_file.h"

namespace sacfuse {
namespace lf = las_format;
namespace {

constexpr size_t kChunkRecords = 65536;
constexpr uint64_t kMaxCrsPayload = uint64_t{1} << 20;  // CRS records larger than this are not parsed
constexpr double kGpsWeekSeconds = 604800.0;
const char* kAxis[3] = {"X", "Y", "Z"};

std::string Num(double v) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.10g", v);
  return text;
}


class Validator {
 public:
  explicit Validator(const std::string& path) : path_(path) {}

  std::vector<std::string> Run() {
    try {
      CheckInputFile(path_, "LAS file");
    } catch (const InputError& e) {
      return {std::string("file: ") + e.what()};
    }
    file_.reset(std::fopen(path_.c_str(), "rb"));
    if (!file_) return {"file: cannot open " + path_ + ": " + std::strerror(errno)};
    if (std::fseek(file_.get(), 0, SEEK_END) != 0) return {"file: cannot seek in " + path_};
    file_size_ = static_cast<uint64_t>(std::ftell(file_.get()));
    if (!ReadHeader()) return findings_;
    CheckHeaderFields();
    ReadVlrs();
    const bool layout_ok = CheckFormatAndLength();
    CheckCounts();
    const bool size_ok = layout_ok && CheckFileSize();
    CheckScaleOffset();
    CheckCrs();
    if (size_ok) CheckPoints();
    if (compressed_) CheckCompressedPoints();
    for (const std::string& f : ValidateCopc(path_)) findings_.push_back(f);
    return findings_;
  }

 private:
  void Add(const std::string& rule, const std::string& what) { findings_.push_back(rule + ": " + what); }

  bool ReadAt(uint64_t at, void* out, size_t size) {
    if (at + size > file_size_) return false;
    if (std::fseek(file_.get(), static_cast<long>(at), SEEK_SET) != 0) return false;
    return std::fread(out, 1, size, file_.get()) == size;
  }

  bool ReadHeader() {
    if (file_size_ < lf::kHeaderSize12) {
      std::array<char, 4> sig{};
      if (file_size_ < 4 || !ReadAt(0, sig.data(), 4) || std::string(sig.data(), 4) != "LASF") {
        Add("file", "not a LAS file (no LASF signature)");
      } else {
        Add("file", std::to_string(file_size_) + " bytes, shorter than the smallest LAS header (227)");
      }
      return false;
    }
    h_.assign(lf::kHeaderSize14, 0);
    ReadAt(0, h_.data(), static_cast<size_t>(std::min<uint64_t>(file_size_, lf::kHeaderSize14)));
    if (std::string(reinterpret_cast<const char*>(h_.data()), 4) != "LASF") {
      Add("file", "not a LAS file (no LASF signature)");
      return false;
    }
    major_ = h_[lf::kOffVersionMajor];
    minor_ = h_[lf::kOffVersionMinor];
    if (major_ != 1 || minor_ > 4) {
      Add("file", "LAS version " + std::to_string(major_) + "." + std::to_string(minor_) + " (1.0-1.4 are checked)");
      return false;
    }
    header_size_ = lf::GetU16(&h_[lf::kOffHeaderSize]);
    point_offset_ = lf::GetU32(&h_[lf::kOffPointOffset]);
    num_vlrs_ = lf::GetU32(&h_[lf::kOffNumVlrs]);
    pdrf_ = h_[lf::kOffPdrf] & 0x3f;  // bits 6-7 flag LAZ compression
    compressed_ = (h_[lf::kOffPdrf] & 0xc0) != 0;
    record_length_ = lf::GetU16(&h_[lf::kOffRecordLength]);
    global_encoding_ = lf::GetU16(&h_[lf::kOffGlobalEncoding]);
    legacy_count_ = lf::GetU32(&h_[lf::kOffLegacyCount]);
    for (int r = 0; r < 5; ++r) legacy_by_return_[r] = lf::GetU32(&h_[lf::kOffLegacyByReturn + 4 * r]);
    for (int a = 0; a < 3; ++a) {
      scale_[a] = lf::GetF64(&h_[lf::kOffScale + 8 * a]);
      offset_[a] = lf::GetF64(&h_[lf::kOffOffset + 8 * a]);
      max_[a] = lf::GetF64(&h_[lf::kOffBounds + 16 * a]);
      min_[a] = lf::GetF64(&h_[lf::kOffBounds + 16 * a + 8]);
    }
    if (minor_ >= 3) waveform_start_ = lf::GetU64(&h_[lf::kOffWaveformStart]);
    if (minor_ >= 4) {
      evlr_start_ = lf::GetU64(&h_[lf::kOffEvlrStart]);
      num_evlrs_ = lf::GetU32(&h_[lf::kOffEvlrCount]);
      count64_ = lf::GetU64(&h_[lf::kOffCount64]);
      for (int r = 0; r < 15; ++r) by_return64_[r] = lf::GetU64(&h_[lf::kOffByReturn64 + 8 * r]);
    }
    // The count the points are checked against: the 64-bit one in 1.4 (a 0 there with a legacy count set is
    // reported under "legacy counts" and the legacy one used, as readers do).
    count_ = minor_ >= 4 ? (count64_ == 0 && legacy_count_ != 0 ? legacy_count_ : count64_) : legacy_count_;
    return true;
  }

  void CheckPaddedString(size_t offset, const char* rule) {
    size_t n = 0;
    while (n < lf::kIdFieldSize && h_[offset + n] != 0) ++n;
    if (n == lf::kIdFieldSize) {
      Add(rule, "not NUL-terminated (32 characters without a NUL)");
      return;
    }
    for (size_t i = n; i < lf::kIdFieldSize; ++i) {
      if (h_[offset + i] != 0) {
        Add(rule, "characters after the terminating NUL (byte " + std::to_string(i) + " of 32); must be NUL-padded");
        return;
      }
    }
  }

  void CheckHeaderFields() {
    const size_t min_header = lf::MinHeaderSize(minor_);
    if (header_size_ < min_header) {
      Add("header size", std::to_string(header_size_) + ", LAS 1." + std::to_string(minor_) + " needs at least " +
                             std::to_string(min_header));
    }
    CheckPaddedString(lf::kOffSystemId, "system identifier");
    CheckPaddedString(lf::kOffSoftware, "generating software");
    const uint16_t day = lf::GetU16(&h_[lf::kOffCreationDay]);
    const uint16_t year = lf::GetU16(&h_[lf::kOffCreationYear]);
    std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    const int this_year = utc.tm_year + 1900;
    if (year == 0) {  // as lasvalidate: a year without a day is not flagged
      Add("creation date", "not set (day " + std::to_string(day) + " of year " + std::to_string(year) + ")");
    } else if (day > 366) {
      Add("creation date", "day of year " + std::to_string(day) + " > 366");
    } else if (year > this_year || (year == this_year && day > utc.tm_yday + 1)) {
      Add("creation date", "day " + std::to_string(day) + " of " + std::to_string(year) + " is in the future");
    }
    // Global encoding bits defined per version: 1.0-1.1 none, 1.2 bit 0, 1.3 bits 0-3, 1.4 bits 0-4.
    const uint16_t allowed = minor_ <= 1 ? 0x0 : minor_ == 2 ? 0x1 : minor_ == 3 ? 0xf : 0x1f;
    if ((global_encoding_ & ~allowed) != 0) {
      char hex[16];
      std::snprintf(hex, sizeof(hex), "0x%x", global_encoding_ & ~allowed);
      Add("global encoding", std::string("bits ") + hex + " are not defined for LAS 1." + std::to_string(minor_));
    }
    const bool waveform_format = pdrf_ == 4 || pdrf_ == 5 || pdrf_ == 9 || pdrf_ == 10;
    if ((global_encoding_ & 0x6) != 0 && minor_ >= 3 && !waveform_format) {
      Add("global encoding", "waveform bits (1, 2) set for point format " + std::to_string(pdrf_));
    }
    if ((global_encoding_ & 0x1) != 0 && (pdrf_ == 0 || pdrf_ == 2)) {
      Add("global encoding",
          "GPS time bit (0) set for point format " + std::to_string(pdrf_) + ", which has no GPS time");
    }
    if (minor_ >= 3 && (global_encoding_ & 0x2) == 0 && waveform_start_ != 0) {
      Add("global encoding", "start of waveform data " + std::to_string(waveform_start_) +
                                 " but the internal-waveform bit (1) is clear");
    }
  }

  // A VLR or EVLR; payloads are kept only for the records the checks look into.
  struct Record {
    std::string user_id;
    uint16_t record_id = 0;
    std::vector<uint8_t> data;
    bool extended = false;
  };

  bool Interesting(const std::string& user_id) const {
    return user_id == lf::kProjectionUserId || user_id == "LASF_Spec";
  }

  void ReadVlrs() {
    uint64_t at = header_size_;
    for (uint32_t i = 0; i < num_vlrs_; ++i) {
      if (at == point_offset_) {
        Add("offset to point data", "the header counts " + std::to_string(num_vlrs_) + " VLRs, only " +
                                        std::to_string(i) + " lie before the point data");
        return;
      }
      uint8_t head[lf::kVlrHeaderSize];
      if (!ReadAt(at, head, sizeof(head))) {
        Add("offset to point data", "VLR " + std::to_string(i) + " header beyond the end of the file");
        return;
      }
      Record r;
      r.user_id = lf::GetPaddedString(head + 2, 16);
      r.record_id = lf::GetU16(head + 18);
      const uint16_t length = lf::GetU16(head + 20);
      if (Interesting(r.user_id)) {
        r.data.resize(length);
        if (!ReadAt(at + lf::kVlrHeaderSize, r.data.data(), length)) r.data.clear();
      }
      records_.push_back(std::move(r));
      at += lf::kVlrHeaderSize + length;
    }
    if (at > point_offset_) {
      Add("offset to point data", std::to_string(point_offset_) + ", but the header and VLRs end at " +
                                      std::to_string(at) + " (a VLR flows into the point data)");
    }
  }

  // Point format vs version and record length. False when the records cannot be walked.
  bool CheckFormatAndLength() {
    if (compressed_) return false;  // the records are checked decoded (CheckCompressedPoints)
    const int max_pdrf = minor_ <= 1 ? 1 : minor_ == 2 ? 3 : minor_ == 3 ? 5 : 10;
    if (pdrf_ > max_pdrf) {
      Add("point format", std::to_string(pdrf_) + " is not allowed in LAS 1." + std::to_string(minor_) + " (0-" +
                              std::to_string(max_pdrf) + ")");
    }
    const size_t base = lf::BaseRecordSize(pdrf_);
    if (base == 0) return false;
    if (record_length_ < base) {
      Add("record length", std::to_string(record_length_) + " bytes, point format " + std::to_string(pdrf_) +
                               " needs at least " + std::to_string(base));
      return false;
    }
    if (record_length_ > base) {
      const std::string extra = std::to_string(record_length_ - base) + " extra bytes per record";
      if (minor_ < 4) {
        Add("record length", extra + ": LAS 1." + std::to_string(minor_) + " allows no extra bytes");
      } else if (std::none_of(records_.begin(), records_.end(), [](const Record& r) {
                   return r.user_id == "LASF_Spec" && r.record_id == 4;
                 })) {
        Add("record length", extra + " without an Extra Bytes (LASF_Spec/4) record");
      }
    }
    if (point_offset_ > file_size_) {
      Add("offset to point data", std::to_string(point_offset_) + " beyond the end of the file (" +
                                      std::to_string(file_size_) + " bytes)");
      return false;
    }
    return true;
  }

  void CheckCounts() {
    if (minor_ < 4) {
      if (legacy_count_ == 0) Add("zero points", "LAS 1." + std::to_string(minor_) + " files need at least one point");
      return;
    }
    const bool legacy_must_be_zero = pdrf_ >= 6 || count64_ > std::numeric_limits<uint32_t>::max();
    if (legacy_must_be_zero) {
      bool by_return_set = false;
      for (uint32_t v : legacy_by_return_) by_return_set = by_return_set || v != 0;
      if (legacy_count_ != 0 || by_return_set) {
        Add("legacy counts", "legacy point count " + std::to_string(legacy_count_) +
                                 (by_return_set ? " and legacy points by return" : "") +
                                 " must be 0 for point format " + std::to_string(pdrf_) +
                                 (pdrf_ >= 6 ? "" : " with more than 2^32-1 points"));
      }
      return;
    }
    bool by_return_differ = false;
    for (int r = 0; r < 5; ++r) by_return_differ = by_return_differ || legacy_by_return_[r] != by_return64_[r];
    if (legacy_count_ != count64_ || by_return_differ) {
      Add("legacy counts", "legacy count " + std::to_string(legacy_count_) + " / points by return must equal the " +
                               "64-bit ones (" + std::to_string(count64_) + ") for point format " +
                               std::to_string(pdrf_));
    }
  }

  // File size vs offset + count x record length, EVLRs and waveform data. False when points are missing.
  bool CheckFileSize() {
    const uint64_t points_end = point_offset_ + count_ * record_length_;
    if (points_end > file_size_) {
      const uint64_t fit = (file_size_ - point_offset_) / record_length_;
      Add("file size", std::to_string(file_size_) + " bytes: truncated; " + std::to_string(count_) + " points of " +
                           std::to_string(record_length_) + " bytes need " + std::to_string(points_end) +
                           " (only " + std::to_string(fit) + " fit; points not checked)");
      return false;
    }
    uint64_t end = points_end;
    if (minor_ >= 4 && num_evlrs_ > 0) {
      if (evlr_start_ < points_end) {
        Add("file size", "first EVLR at " + std::to_string(evlr_start_) + " lies inside the point data (ends at " +
                             std::to_string(points_end) + ")");
        return true;
      }
      uint64_t at = evlr_start_;
      for (uint32_t i = 0; i < num_evlrs_; ++i) {
        uint8_t head[lf::kEvlrHeaderSize];
        if (!ReadAt(at, head, sizeof(head))) {
          Add("file size", "EVLR " + std::to_string(i) + " of " + std::to_string(num_evlrs_) +
                               " beyond the end of the file");
          return true;
        }
        Record r;
        r.user_id = lf::GetPaddedString(head + 2, 16);
        r.record_id = lf::GetU16(head + 18);
        r.extended = true;
        const uint64_t length = lf::GetU64(head + 20);
        if (at + lf::kEvlrHeaderSize + length > file_size_) {
          Add("file size", "EVLR " + std::to_string(i) + " (" + r.user_id + "/" + std::to_string(r.record_id) +
                               ") runs past the end of the file");
          return true;
        }
        if (Interesting(r.user_id) && length <= kMaxCrsPayload) {
          r.data.resize(static_cast<size_t>(length));
          ReadAt(at + lf::kEvlrHeaderSize, r.data.data(), r.data.size());
        }
        records_.push_back(std::move(r));
        at += lf::kEvlrHeaderSize + length;
      }
      end = std::max(end, at);
    }
    const bool internal_waveform = minor_ >= 3 && (global_encoding_ & 0x2) != 0 && waveform_start_ >= points_end;
    if (internal_waveform) end = file_size_;  // waveform packets run to the end of the file
    if (end < file_size_) {
      Add("file size", std::to_string(file_size_ - end) + " bytes after the points" +
                           (num_evlrs_ > 0 ? std::string(" and EVLRs") : std::string()) +
                           " not accounted for (offset to point data + count x record length = " +
                           std::to_string(points_end) + ")");
    }
    return true;
  }

  void CheckScaleOffset() {
    for (int a = 0; a < 3; ++a) {
      double canonical = 0.0;
      if (!(scale_[a] > 0.0) || !std::isfinite(scale_[a])) {
        Add("scale", std::string(kAxis[a]) + " scale " + Num(scale_[a]) + " must be > 0");
        continue;
      }
      if (!std::isfinite(offset_[a])) {
        Add("offset", std::string(kAxis[a]) + " offset is not finite");
        continue;
      }
      if (!lf::CanonicalLasScale(scale_[a], &canonical)) {
        Add("scale", std::string(kAxis[a]) + " scale " + Num(scale_[a]) + " is not 10^k x {1, 0.5, 0.25}");
        continue;  // an offset cannot be on the grid of an off-grid scale: only the scale is reported
      }
      const double steps = offset_[a] / scale_[a];
      if (std::abs(steps - std::round(steps)) > 1e-6) {
        Add("offset", std::string(kAxis[a]) + " offset " + Num(offset_[a]) + " is not a multiple of the scale " +
                          Num(scale_[a]) + " (translation fluff)");
      }
    }
  }

  void CheckCrs() {
    LasHeader crs_header;
    int wkt = 0, geotiff = 0;
    std::string wkt_text;
    for (const Record& r : records_) {
      if (r.user_id != lf::kProjectionUserId) continue;
      LasVlr vlr;
      vlr.user_id = r.user_id;
      vlr.record_id = r.record_id;
      vlr.data = r.data;
      vlr.extended = r.extended;
      crs_header.vlrs.push_back(vlr);
      if (r.record_id == lf::kWktRecordId) {
        ++wkt;
        if (wkt_text.empty()) {
          const auto nul = std::find(r.data.begin(), r.data.end(), uint8_t{0});
          wkt_text.assign(r.data.begin(), nul);
        }
      }
      if (r.record_id == kLasGeoKeyDirectoryRecordId) ++geotiff;
    }
    const bool wkt_bit = (global_encoding_ & kLasGlobalEncodingWktBit) != 0;
    if (minor_ >= 4 && wkt_bit && wkt == 0) {
      Add("global encoding", "WKT bit (4) set but there is no WKT (LASF_Projection/2112) record");
    }
    if (minor_ >= 4 && !wkt_bit && wkt > 0) {
      Add("global encoding", "WKT (LASF_Projection/2112) record present but the WKT bit (4) is clear");
    }
    if (minor_ >= 4 && pdrf_ >= 6 && geotiff > 0) {
      Add("CRS", "GeoTIFF (LASF_Projection/34735) records in a point format " + std::to_string(pdrf_) +
                     " file (LAS 1.4 formats 6-10 use WKT only)");
    }
    if (wkt > 0 && geotiff > 0) Add("CRS", "both GeoTIFF and WKT records");
    if (wkt > 1) Add("CRS", std::to_string(wkt) + " WKT records (at most one)");
    if (wkt > 0) {
      try {
        ParseWkt1(wkt_text);
      } catch (const Error& e) {
        Add("CRS", std::string("WKT record: ") + e.what());
      }
    }
    if (geotiff > 0) {
      try {
        ParseLasGeoKeys(crs_header);
      } catch (const Error& e) {
        Add("CRS", e.what());
      }
    }
  }

  // What the point-level rules need, gathered point by point (from raw records or from decoded LAZ points).
  struct PointTally {
    std::array<int32_t, 3> lo{}, hi{};
    std::array<uint64_t, 15> counted{};
    uint64_t bad_returns = 0, first_bad = 0, seen = 0;
    double gps_min = 0, gps_max = 0;
  };

  void Tally(const LasPoint& p, const std::array<int32_t, 3>& stored, PointTally* t) const {
    const uint64_t index = t->seen++;
    for (int a = 0; a < 3; ++a) {
      t->lo[a] = index == 0 ? stored[a] : std::min(t->lo[a], stored[a]);
      t->hi[a] = index == 0 ? stored[a] : std::max(t->hi[a], stored[a]);
    }
    const int max_returns = pdrf_ >= 6 ? 15 : 5;
    const int r = p.return_number, nr = p.number_of_returns;
    if (r == 0 || nr == 0 || r > nr || nr > max_returns) {
      if (t->bad_returns++ == 0) t->first_bad = index;
    }
    if (r >= 1 && r <= 15) ++t->counted[r - 1];
    if (lf::HasGpsTime(pdrf_)) {
      t->gps_min = index == 0 ? p.gps_time : std::min(t->gps_min, p.gps_time);
      t->gps_max = index == 0 ? p.gps_time : std::max(t->gps_max, p.gps_time);
    }
  }

  void CheckPoints() {
    PointTally t;
    std::vector<uint8_t> buffer;
    uint64_t done = 0;
    LasPoint p;
    while (done < count_) {
      const size_t n = static_cast<size_t>(std::min<uint64_t>(kChunkRecords, count_ - done));
      buffer.resize(n * record_length_);
      if (!ReadAt(point_offset_ + done * record_length_, buffer.data(), buffer.size())) {
        Add("file", "read error at point " + std::to_string(done));
        return;
      }
      for (size_t i = 0; i < n; ++i) {
        const uint8_t* rec = &buffer[i * record_length_];
        lf::DecodePointRecord(rec, pdrf_, scale_, offset_, &p);
        Tally(p, {lf::GetI32(rec), lf::GetI32(rec + 4), lf::GetI32(rec + 8)}, &t);
      }
      done += n;
    }
    CheckTally(t);
  }

  // LAZ: the points decoded by our LAZ reader (io/laz_point_reader.h), which refuses corrupt chunks.
  void CheckCompressedPoints() {
    PointTally t;
    try {
      LasReader reader(path_);
      // The table ends the point data (EVLRs of LAS 1.4 follow it): a file that ends inside it was truncated, even
      // though its missing last bytes (the coder's final zeros) decode as the zeros a reader supplies.
      const uint64_t table_end = reader.laz_chunk_table_end();
      const uint64_t limit = minor_ >= 4 && num_evlrs_ > 0 && evlr_start_ >= table_end ? evlr_start_ : file_size_;
      if (table_end > limit) {
        Add("LAZ", "the chunk table's coded entries end at byte " + std::to_string(table_end) + ", but the " +
                       (limit == file_size_ ? "file ends at " : "first EVLR starts at ") + std::to_string(limit) +
                       ": its last " + std::to_string(table_end - limit) + " bytes are missing (truncated)");
      }
      std::vector<LasPoint> chunk;
      while (reader.Read(&chunk, kChunkRecords) > 0) {
        for (const LasPoint& p : chunk) {
          std::array<int32_t, 3> stored{};
          for (int a = 0; a < 3; ++a) lf::Quantise(p.xyz[a], scale_[a], offset_[a], &stored[a]);
          Tally(p, stored, &t);
        }
      }
    } catch (const std::exception& e) {
      Add("LAZ", e.what());
      return;
    }
    if (t.seen != count_) {
      Add("LAZ", std::to_string(t.seen) + " points decoded, the header says " + std::to_string(count_));
    }
    CheckTally(t);
  }

  void CheckTally(const PointTally& t) {
    if (t.bad_returns > 0) {
      Add("return numbers", std::to_string(t.bad_returns) + " points with return number 0, number of returns 0, " +
                                "return > number of returns or number of returns > " +
                                std::to_string(pdrf_ >= 6 ? 15 : 5) + " (first: point " + std::to_string(t.first_bad) +
                                ")");
    }
    CheckByReturn(t.counted);
    if (t.seen > 0) CheckBounds(t.lo, t.hi);
    if (t.seen > 0 && lf::HasGpsTime(pdrf_) && (global_encoding_ & 0x1) == 0 &&
        (t.gps_min < 0.0 || t.gps_max > kGpsWeekSeconds)) {
      Add("global encoding", "GPS time bit (0) clear (GPS week time) but times range " + Num(t.gps_min) + " to " +
                                 Num(t.gps_max) + " s, outside [0, 604800]");
    }
  }

  void CheckByReturn(const std::array<uint64_t, 15>& counted) {
    const int slots = minor_ >= 4 ? 15 : 5;
    std::string header_list, counted_list;
    bool differ = false;
    uint64_t sum = 0;
    for (int r = 0; r < slots; ++r) {
      const uint64_t in_header = minor_ >= 4 ? by_return64_[r] : legacy_by_return_[r];
      sum += in_header;
      differ = differ || in_header != counted[r];
      header_list += (r ? "," : "") + std::to_string(in_header);
      counted_list += (r ? "," : "") + std::to_string(counted[r]);
    }
    if (differ) {
      Add("points by return", "header [" + header_list + "] (sum " + std::to_string(sum) + ", count " +
                                  std::to_string(count_) + ") but the points have [" + counted_list + "]");
    }
  }

  void CheckBounds(const std::array<int32_t, 3>& lo, const std::array<int32_t, 3>& hi) {
    for (int a = 0; a < 3; ++a) {
      const double data_min = lf::Dequantise(lo[a], scale_[a], offset_[a]);
      const double data_max = lf::Dequantise(hi[a], scale_[a], offset_[a]);
      const double half = 0.5 * scale_[a];
      if (min_[a] > data_min + half) {
        Add("bounds", std::string("header min ") + kAxis[a] + " " + Num(min_[a]) + " > the points' min " +
                          Num(data_min) + " (beyond half a scale step)");
      }
      if (max_[a] < data_max - half) {
        Add("bounds", std::string("header max ") + kAxis[a] + " " + Num(max_[a]) + " < the points' max " +
                          Num(data_max) + " (beyond half a scale step)");
      }
    }
  }

  std::string path_;
  UniqueFile file_;
  uint64_t file_size_ = 0;
  std::vector<std::string> findings_;
  std::vector<uint8_t> h_;
  int major_ = 1, minor_ = 0;
  uint16_t header_size_ = 0;
  uint32_t point_offset_ = 0;
  uint32_t num_vlrs_ = 0;
  int pdrf_ = 0;
  bool compressed_ = false;
  uint16_t record_length_ = 0;
  uint16_t global_encoding_ = 0;
  uint32_t legacy_count_ = 0;
  std::array<uint32_t, 5> legacy_by_return_{};
  uint64_t count64_ = 0;
  std::array<uint64_t, 15> by_return64_{};
  uint64_t count_ = 0;
  uint64_t waveform_start_ = 0;
  uint64_t evlr_start_ = 0;
  uint32_t num_evlrs_ = 0;
  Eigen::Vector3d scale_ = Eigen::Vector3d::Zero(), offset_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d min_ = Eigen::Vector3d::Zero(), max_ = Eigen::Vector3d::Zero();
  std::vector<Record> records_;
};

}  // namespace

std::vector<std::string> ValidateLasFile(const std::string& path) { return Validator(path).Run(); }

}  // namespace sacfuse
