#include "io/las_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/input_file.h"
#include "io/las_format.h"
#include "io/laz_point_reader.h"

namespace sacfuse {
namespace lf = las_format;

namespace {

constexpr size_t kReadBlockRecords = 65536;              // records per fread
constexpr uint64_t kMaxEvlrPayload = uint64_t{64} << 20;  // larger EVLRs (waveform data) are not loaded

std::string VlrName(const LasVlr& vlr) { return vlr.user_id + "/" + std::to_string(vlr.record_id); }

LasVlr ParseVlrHeader(const uint8_t* p, bool extended, uint64_t* payload_size) {
  LasVlr vlr;
  vlr.extended = extended;
  vlr.user_id = lf::GetPaddedString(p + 2, 16);
  vlr.record_id = lf::GetU16(p + 18);
  *payload_size = extended ? lf::GetU64(p + 20) : lf::GetU16(p + 20);
  vlr.description = lf::GetPaddedString(p + (extended ? 28 : 22), 32);
  return vlr;
}

}  // namespace

struct LasReader::Impl {
  std::string path;
  FILE* file = nullptr;
  uint64_t file_size = 0;
  LasHeader header;
  uint64_t next = 0;  // index of the next point to read
  std::vector<uint8_t> block;
  // LAZ: set when the point format has LASzip's compression bit or a "laszip encoded" VLR is present.
  bool compressed = false;
  std::vector<uint8_t> laszip_vlr;
  std::unique_ptr<LazPointReader> laz;

  [[noreturn]] void Fail(const std::string& message) const { throw InputError(path, message); }

  void ReadAt(uint64_t position, uint8_t* out, size_t size) {
    if (fseeko(file, static_cast<off_t>(position), SEEK_SET) != 0 || std::fread(out, 1, size, file) != size) {
      Fail("cannot read " + std::to_string(size) + " bytes at offset " + std::to_string(position) + ": " +
           std::strerror(errno));
    }
  }

  void Open();
  void ParseHeader();
  void ReadVlrs(uint32_t num_vlrs);
  void ReadEvlrs(uint64_t start, uint32_t num_evlrs, uint64_t point_end);
};

void LasReader::Impl::Open() {
  CheckInputFile(path, "LAS file");
  file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) ThrowInputOsError(path, "LAS file", errno);
  if (fseeko(file, 0, SEEK_END) != 0) Fail("cannot seek");
  file_size = static_cast<uint64_t>(ftello(file));
  ParseHeader();
  if (compressed) {
    if (laszip_vlr.empty()) Fail("point format has the LAZ compression bit set but there is no laszip VLR");
    laz = std::make_unique<LazPointReader>(path, file, file_size, header, laszip_vlr);
    return;
  }
  if (fseeko(file, static_cast<off_t>(header.offset_to_point_data), SEEK_SET) != 0) Fail("cannot seek");
}

void LasReader::Impl::ParseHeader() {
  std::vector<uint8_t> h(std::min<uint64_t>(file_size, lf::kHeaderSize14));
  if (!h.empty()) ReadAt(0, h.data(), h.size());
  if (h.size() < 4 || std::memcmp(h.data(), "LASF", 4) != 0) Fail("not a LAS file (the signature is not \"LASF\")");
  if (h.size() < lf::kHeaderSize12) {
    Fail("file of " + std::to_string(file_size) + " bytes is smaller than a LAS header (227 bytes)");
  }
  LasHeader& hd = header;
  hd.version_major = h[lf::kOffVersionMajor];
  hd.version_minor = h[lf::kOffVersionMinor];
  const std::string version = std::to_string(hd.version_major) + "." + std::to_string(hd.version_minor);
  if (hd.version_major != 1 || hd.version_minor > 4) Fail("LAS version " + version + " is not supported (1.0-1.4)");
  hd.header_size = lf::GetU16(&h[lf::kOffHeaderSize]);
  const size_t min_header = lf::MinHeaderSize(hd.version_minor);
  if (hd.header_size < min_header) {
    Fail("header size " + std::to_string(hd.header_size) + " is smaller than the " + std::to_string(min_header) +
         " bytes of LAS " + version);
  }
  if (file_size < hd.header_size) {
    Fail("file of " + std::to_string(file_size) + " bytes is smaller than its header (" +
         std::to_string(hd.header_size) + " bytes)");
  }
  hd.file_source_id = lf::GetU16(&h[lf::kOffFileSourceId]);
  hd.global_encoding = lf::GetU16(&h[lf::kOffGlobalEncoding]);
  hd.system_identifier = lf::GetPaddedString(&h[lf::kOffSystemId], lf::kIdFieldSize);
  hd.generating_software = lf::GetPaddedString(&h[lf::kOffSoftware], lf::kIdFieldSize);
  hd.creation_day = lf::GetU16(&h[lf::kOffCreationDay]);
  hd.creation_year = lf::GetU16(&h[lf::kOffCreationYear]);
  hd.offset_to_point_data = lf::GetU32(&h[lf::kOffPointOffset]);
  const uint32_t num_vlrs = lf::GetU32(&h[lf::kOffNumVlrs]);
  const uint8_t raw_format = h[lf::kOffPdrf];
  hd.point_record_length = lf::GetU16(&h[lf::kOffRecordLength]);
  for (int a = 0; a < 3; ++a) {
    hd.scale[a] = lf::GetF64(&h[lf::kOffScale + 8 * a]);
    hd.offset[a] = lf::GetF64(&h[lf::kOffOffset + 8 * a]);
    hd.max[a] = lf::GetF64(&h[lf::kOffBounds + 16 * a]);
    hd.min[a] = lf::GetF64(&h[lf::kOffBounds + 16 * a + 8]);
  }
  // LASzip marks compressed files by setting bit 7 (and historically bit 6) of the point format.
  compressed = (raw_format & 0xC0) != 0;
  hd.point_format = raw_format & 0x3F;

  if (hd.offset_to_point_data < hd.header_size) {
    Fail("offset to point data " + std::to_string(hd.offset_to_point_data) + " is smaller than the header size " +
         std::to_string(hd.header_size));
  }
  if (hd.offset_to_point_data > file_size) {
    Fail("offset to point data " + std::to_string(hd.offset_to_point_data) + " is beyond the end of the file (" +
         std::to_string(file_size) + " bytes)");
  }
  ReadVlrs(num_vlrs);
  compressed = compressed || !laszip_vlr.empty();

  const size_t base = lf::BaseRecordSize(hd.point_format);
  if (base == 0) Fail("unknown point data record format " + std::to_string(hd.point_format));
  if (hd.point_record_length < base) {
    Fail("point record length " + std::to_string(hd.point_record_length) + " is smaller than the " +
         std::to_string(base) + " bytes of point format " + std::to_string(hd.point_format));
  }

  // Counts. LAS 1.4 readers (PDAL, laspy) use only the 64-bit count; we fall back to the legacy count when the
  // 64-bit one is 0 (as LASlib does), since the truncation check below still guards against a bogus value.
  const uint32_t legacy_count = lf::GetU32(&h[lf::kOffLegacyCount]);
  const bool has_14_fields = hd.version_minor >= 4 && hd.header_size >= lf::kHeaderSize14;
  const uint64_t count64 = has_14_fields ? lf::GetU64(&h[lf::kOffCount64]) : 0;
  hd.points_by_return = {};
  if (count64 != 0) {
    hd.point_count = count64;
    for (int r = 0; r < 15; ++r) hd.points_by_return[r] = lf::GetU64(&h[lf::kOffByReturn64 + 8 * r]);
  } else {
    hd.point_count = legacy_count;
    for (int r = 0; r < 5; ++r) hd.points_by_return[r] = lf::GetU32(&h[lf::kOffLegacyByReturn + 4 * r]);
  }
  const uint64_t available = file_size - hd.offset_to_point_data;
  const uint64_t holds = available / hd.point_record_length;
  if (!compressed && hd.point_count > holds) {
    Fail("truncated: the header says " + std::to_string(hd.point_count) + " points of " +
         std::to_string(hd.point_record_length) + " bytes from offset " + std::to_string(hd.offset_to_point_data) +
         ", but the file (" + std::to_string(file_size) + " bytes) can hold only " + std::to_string(holds));
  }
  if (has_14_fields) {
    const uint64_t evlr_start = lf::GetU64(&h[lf::kOffEvlrStart]);
    const uint32_t num_evlrs = lf::GetU32(&h[lf::kOffEvlrCount]);
    // LAZ: the EVLRs follow the chunk table, somewhere after the (compressed) points.
    const uint64_t point_end =
        compressed ? hd.offset_to_point_data : hd.offset_to_point_data + hd.point_count * hd.point_record_length;
    if (evlr_start != 0 && num_evlrs != 0) ReadEvlrs(evlr_start, num_evlrs, point_end);
  }
}

// VLRs fill [header size, offset to point data). A VLR whose payload runs past the point offset is an error
// (PDAL: "flows into point data"). An overstated VLR count is tolerated when the VLRs read so far end exactly at
// the point data (or at the 2-byte LAS 1.0 point data start signature 0xDD 0xCC): the point layout is then
// unambiguous (LASlib does the same; laspy reads such a file too).
void LasReader::Impl::ReadVlrs(uint32_t num_vlrs) {
  const uint64_t begin = header.header_size;
  const uint64_t end = header.offset_to_point_data;
  std::vector<uint8_t> region(end - begin);
  if (!region.empty()) ReadAt(begin, region.data(), region.size());
  size_t pos = 0;
  for (uint32_t i = 0; i < num_vlrs; ++i) {
    const size_t remaining = region.size() - pos;
    if (remaining < lf::kVlrHeaderSize) {
      const bool dd_cc = remaining == 2 && region[pos] == 0xDD && region[pos + 1] == 0xCC;
      if (remaining == 0 || dd_cc) break;
      Fail("VLR " + std::to_string(i + 1) + " of " + std::to_string(num_vlrs) +
           ": its 54-byte header flows into point data (only " + std::to_string(remaining) +
           " bytes left before offset " + std::to_string(end) + ")");
    }
    uint64_t size = 0;
    LasVlr vlr = ParseVlrHeader(&region[pos], false, &size);
    if (lf::kVlrHeaderSize + size > remaining) {
      Fail("VLR " + std::to_string(i + 1) + " of " + std::to_string(num_vlrs) + " (" + VlrName(vlr) + ", " +
           std::to_string(size) + " bytes) flows into point data at offset " + std::to_string(end));
    }
    const uint8_t* payload = &region[pos + lf::kVlrHeaderSize];
    pos += lf::kVlrHeaderSize + size;
    if (vlr.user_id == lf::kLaszipUserId && vlr.record_id == lf::kLaszipRecordId) {
      // How the points are compressed: kept by the reader, not listed among the header's VLRs.
      laszip_vlr.assign(payload, payload + size);
      continue;
    }
    vlr.data.assign(payload, payload + size);
    header.vlrs.push_back(std::move(vlr));
  }
}

void LasReader::Impl::ReadEvlrs(uint64_t start, uint32_t num_evlrs, uint64_t point_end) {
  if (start < point_end) {
    Fail("EVLRs start at offset " + std::to_string(start) + ", inside the point data (which ends at " +
         std::to_string(point_end) + ")");
  }
  uint64_t pos = start;
  for (uint32_t i = 0; i < num_evlrs; ++i) {
    if (pos > file_size || file_size - pos < lf::kEvlrHeaderSize) {
      Fail("EVLR " + std::to_string(i + 1) + " of " + std::to_string(num_evlrs) + " at offset " +
           std::to_string(pos) + " runs past the end of the file");
    }
    uint8_t head[lf::kEvlrHeaderSize];
    ReadAt(pos, head, sizeof(head));
    uint64_t size = 0;
    LasVlr vlr = ParseVlrHeader(head, true, &size);
    pos += lf::kEvlrHeaderSize;
    if (size > file_size - pos) {
      Fail("EVLR " + std::to_string(i + 1) + " (" + VlrName(vlr) + ", " + std::to_string(size) +
           " bytes) runs past the end of the file");
    }
    if (size <= kMaxEvlrPayload) {
      vlr.data.resize(size);
      if (size > 0) ReadAt(pos, vlr.data.data(), size);
    }
    header.vlrs.push_back(std::move(vlr));
    pos += size;
  }
}

LasReader::LasReader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  try {
    impl_->Open();
  } catch (...) {
    if (impl_->file != nullptr) std::fclose(impl_->file);
    impl_->file = nullptr;
    throw;
  }
}

LasReader::~LasReader() {
  impl_->laz.reset();  // first: its read-ahead may still be reading the file
  if (impl_->file != nullptr) std::fclose(impl_->file);
}

const LasHeader& LasReader::header() const { return impl_->header; }

size_t LasReader::Read(std::vector<LasPoint>* out, size_t max_count) {
  Impl& r = *impl_;
  const LasHeader& h = r.header;
  const size_t n = static_cast<size_t>(std::min<uint64_t>(max_count, h.point_count - r.next));
  out->resize(n);
  const size_t length = h.point_record_length;
  size_t done = 0;
  while (done < n) {
    size_t k = 0;
    const uint8_t* records = nullptr;
    if (r.laz) {
      records = r.laz->Next(n - done, &k);  // decoded on the pool, read in place
    } else {
      k = std::min(kReadBlockRecords, n - done);
      r.block.resize(k * length);
      if (std::fread(r.block.data(), length, k, r.file) != k) {
        r.Fail("cannot read points " + std::to_string(r.next) + ".." + std::to_string(r.next + k) +
               " (file changed while reading?)");
      }
      records = r.block.data();
    }
    // Records are independent: decoded in parallel (a serial share of every reading of a large cloud otherwise).
    tbb::parallel_for(tbb::blocked_range<size_t>(0, k, 4096), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t i = range.begin(); i < range.end(); ++i) {
        lf::DecodePointRecord(records + i * length, h.point_format, h.scale, h.offset, &(*out)[done + i]);
      }
    });
    done += k;
    r.next += k;
  }
  return n;
}

void LasReader::Rewind() {
  Impl& r = *impl_;
  r.next = 0;
  if (r.laz) {
    r.laz->Rewind();
    return;
  }
  if (fseeko(r.file, static_cast<off_t>(r.header.offset_to_point_data), SEEK_SET) != 0) r.Fail("cannot seek");
}

const std::vector<uint8_t>& LasReader::laszip_vlr() const { return impl_->laszip_vlr; }

bool LasReader::ReadStoredChunk(std::vector<uint8_t>* bytes, uint64_t* points) {
  Impl& r = *impl_;
  if (!r.laz || !r.laz->ReadStoredChunk(bytes, points)) return false;
  r.next += *points;
  return true;
}

bool LasReader::SkipStoredChunks(uint64_t chunks) {
  Impl& r = *impl_;
  uint64_t points = 0;
  if (!r.laz || !r.laz->SkipStoredChunks(chunks, &points)) return false;
  r.next += points;
  return true;
}

const std::string& LasReader::path() const { return impl_->path; }

uint64_t LasReader::laz_chunk_table_end() const { return impl_->laz ? impl_->laz->chunk_table_end() : 0; }

std::vector<LasPoint> ReadAllLasPoints(const std::string& path, LasHeader* header) {
  LasReader reader(path);
  if (header != nullptr) *header = reader.header();
  std::vector<LasPoint> points;
  points.reserve(static_cast<size_t>(reader.header().point_count));
  std::vector<LasPoint> chunk;
  while (reader.Read(&chunk, kReadBlockRecords) > 0) points.insert(points.end(), chunk.begin(), chunk.end());
  return points;
}

}  // namespace sacfuse
