#include "io/las_writer.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/las_format.h"
#include "io/las_reader.h"
#include "io/laz_chunk_writer.h"

namespace sacfuse {
namespace lf = las_format;

namespace {

constexpr size_t kBufferRecords = 65536;  // records buffered before one fwrite (LAZ: LazChunkWriter's batch)
constexpr double kAutoOffsetGrid = 1000.0;  // metres; the automatic offset is a multiple of this
constexpr double kMaxScale = 1000.0;        // so that the automatic offset is a multiple of the scale

const char* kAxisNames[3] = {"X", "Y", "Z"};

std::string FormatDouble(double v) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.10g", v);
  return text;
}

LasPoint ToLasPoint(const FusedPoint& fused, const std::string& path) {
  if (fused.view_index >= 65535u) {
    throw Error(path + ": view index " + std::to_string(fused.view_index) +
                " does not fit a LAS point source ID (view index + 1 must be <= 65535)");
  }
  LasPoint point;
  point.xyz = fused.point_in_world;
  for (int c = 0; c < 3; ++c) point.rgb[c] = static_cast<uint16_t>(fused.rgb[c] * 256u);
  point.return_number = 1;
  point.number_of_returns = 1;
  point.point_source_id = static_cast<uint16_t>(fused.view_index + 1);
  return point;
}

}  // namespace

struct LasWriter::Impl {
  std::string path;
  std::string temp_path;
  LasWriterOptions options;
  int version_minor = 4;
  int pdrf = 7;
  size_t header_size = lf::kHeaderSize14;
  size_t record_length = 36;
  uint32_t point_offset = 0;
  uint16_t global_encoding = 0;
  uint32_t num_vlrs = 0;
  Eigen::Vector3d scale = Eigen::Vector3d::Constant(0.001);
  std::optional<Eigen::Vector3d> offset;
  uint16_t creation_day = 0;
  uint16_t creation_year = 0;

  FILE* file = nullptr;
  std::unique_ptr<LazChunkWriter> laz;  // set when writing LAZ
  size_t buffer_records = kBufferRecords;
  // Room for buffer_records records (LAZ: 8 chunks of 50,000, 14 MB at 36 B a record), allocated at the first
  // write and never zero-filled nor grown: its pages become memory as records land on them, so a small tile's
  // writer does not hold the whole batch, and a merge's writer touches each page once.
  std::unique_ptr<uint8_t[]> buffer;
  size_t buffered = 0;          // records in buffer
  uint64_t count = 0;
  std::array<uint64_t, 15> by_return = {};
  std::array<int32_t, 3> stored_min = {};
  std::array<int32_t, 3> stored_max = {};
  bool closed = false;
  bool failed = false;

  void ValidateOptions();
  void Open();
  std::vector<uint8_t> BuildHeader(uint64_t evlr_start, uint32_t num_evlrs) const;
  void WriteBytes(const uint8_t* data, size_t size);
  void FlushBuffer();
  void Discard();
  void Fail(const std::string& message) {
    failed = true;
    throw Error(path + ": " + message);
  }

  // Stores one point as a record; returns what the format cannot hold of it (empty when nothing).
  std::string StoreOne(const LasPoint& point, const Eigen::Vector3d& use_offset, uint8_t* record) const {
    std::array<int32_t, 3> stored;
    for (int a = 0; a < 3; ++a) {
      if (!lf::Quantise(point.xyz[a], scale[a], use_offset[a], &stored[a])) {
        return std::string(kAxisNames[a]) + " = " + FormatDouble(point.xyz[a]) + " does not fit a LAS int32 at scale " +
               FormatDouble(scale[a]) + " and offset " + FormatDouble(use_offset[a]) + " (choose an offset near the data)";
      }
    }
    std::memset(record, 0, record_length);
    return lf::EncodePointRecord(point, stored, pdrf, record);
  }
  // Checks (first pass) or stores (second pass) one point; throws naming the point on a value the format
  // cannot hold.
  void EncodeOne(const LasPoint& point, uint64_t index, const Eigen::Vector3d& use_offset, uint8_t* record) const {
    const std::string problem = StoreOne(point, use_offset, record);
    if (!problem.empty()) throw Error(path + ": point " + std::to_string(index) + ": " + problem);
  }

  Eigen::Vector3d OffsetFor(const LasPoint& first, uint64_t index) const {
    if (offset) return *offset;
    Eigen::Vector3d snapped;
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(first.xyz[a])) {
        throw Error(path + ": point " + std::to_string(index) + ": " + kAxisNames[a] + " is not finite");
      }
      snapped[a] = std::floor(first.xyz[a] / kAutoOffsetGrid) * kAutoOffsetGrid;
    }
    return snapped;
  }

  void CheckWritable(uint64_t n) const {
    if (closed) throw Error(path + ": write after Close()");
    if (failed) throw Error(path + ": write after an earlier I/O error");
    if (version_minor < 4 && count + n > std::numeric_limits<uint32_t>::max()) {
      throw Error(path + ": LAS 1." + std::to_string(version_minor) + " holds at most 4294967295 points");
    }
  }

  // Takes points already stored elsewhere into the header's count, bounds (stored integers) and returns.
  void CountStored(uint64_t n, const std::array<int32_t, 3>& lo, const std::array<int32_t, 3>& hi,
                   const std::array<uint64_t, 15>& returns) {
    for (int a = 0; a < 3; ++a) {
      stored_min[a] = count == 0 ? lo[a] : std::min(stored_min[a], lo[a]);
      stored_max[a] = count == 0 ? hi[a] : std::max(stored_max[a], hi[a]);
    }
    for (size_t r = 0; r < returns.size(); ++r) by_return[r] += returns[r];
    count += n;
  }

  std::optional<LazAppendPart> PrepareLazAppend(LasReader& reader) const;
  void AppendLaz(LasReader& reader, const LazAppendPart& part);

  // The stored integers' bounds and the returns of a run of records.
  struct RecordStats {
    std::array<int32_t, 3> lo = {std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::max(),
                                 std::numeric_limits<int32_t>::max()};
    std::array<int32_t, 3> hi = {std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::min(),
                                 std::numeric_limits<int32_t>::min()};
    std::array<uint64_t, 15> returns = {};
    void Add(const RecordStats& o) {
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], o.lo[a]), hi[a] = std::max(hi[a], o.hi[a]);
      for (size_t r = 0; r < returns.size(); ++r) returns[r] += o.returns[r];
    }
  };

  // Points are converted and encoded in parallel, kEncodeGrain at a time: records are independent, and a serial
  // loop here was the serial share of an untiled run's fusion stage. Bounds and counts are exact (min, max, sums),
  // so the file is the same for any thread count.
  static constexpr size_t kEncodeGrain = 4096;

  // Stores points 0..n-1 (`get(i)`, each checked already) as records at `records`, in parallel; their stats.
  // `index` is the first one's index in the file, for EncodeOne's messages.
  template <typename GetPoint>
  RecordStats EncodeRecords(size_t n, GetPoint get, uint64_t index, const Eigen::Vector3d& use_offset,
                            uint8_t* records) const {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, kEncodeGrain), RecordStats{},
        [&](const tbb::blocked_range<size_t>& r, RecordStats acc) {
          for (size_t i = r.begin(); i < r.end(); ++i) {
            const LasPoint& point = get(i);
            uint8_t* record = records + i * record_length;
            EncodeOne(point, index + i, use_offset, record);
            for (int a = 0; a < 3; ++a) {
              const int32_t v = lf::GetI32(record + 4 * a);
              acc.lo[a] = std::min(acc.lo[a], v);
              acc.hi[a] = std::max(acc.hi[a], v);
            }
            if (point.return_number >= 1 && point.return_number <= 15) ++acc.returns[point.return_number - 1];
          }
          return acc;
        },
        [](RecordStats a, const RecordStats& b) {
          a.Add(b);
          return a;
        });
  }

  // Puts `n` records into the buffer in runs that end where it fills and is flushed: `store(first, take, at)`
  // writes records first..first+take-1 at `at`. The caller counts them (CountStored).
  template <typename Store>
  void BufferRecords(size_t n, Store store) {
    if (!buffer) buffer.reset(new uint8_t[buffer_records * record_length]);  // not zero-filled: see `buffer`
    for (size_t first = 0; first < n;) {
      const size_t take = std::min(n - first, buffer_records - buffered);
      store(first, take, buffer.get() + buffered * record_length);
      buffered += take;
      first += take;
      if (buffered == buffer_records) FlushBuffer();
    }
  }

  template <typename GetPoint>
  void WriteChunk(size_t n, GetPoint get) {
    CheckWritable(n);
    if (n == 0) return;
    // Pass 1: validate the whole chunk, so that a rejected chunk leaves the file unchanged. When a point fails, a
    // serial pass finds the first one and throws its error.
    const Eigen::Vector3d use_offset = OffsetFor(get(0), count);
    std::atomic<bool> rejected{false};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kEncodeGrain), [&](const tbb::blocked_range<size_t>& r) {
      std::vector<uint8_t> scratch(record_length);
      try {
        for (size_t i = r.begin(); i < r.end(); ++i) EncodeOne(get(i), count + i, use_offset, scratch.data());
      } catch (const Error&) {
        rejected = true;
      }
    });
    if (rejected) {
      std::vector<uint8_t> scratch(record_length);
      for (size_t i = 0; i < n; ++i) EncodeOne(get(i), count + i, use_offset, scratch.data());
    }
    // Pass 2: store.
    if (!offset) offset = use_offset;  // (not rewritten once set: PrepareLazAppend may read it meanwhile)
    RecordStats stats;
    BufferRecords(n, [&](size_t first, size_t take, uint8_t* records) {
      stats.Add(EncodeRecords(
          take, [&](size_t i) -> decltype(auto) { return get(first + i); }, count + first, use_offset, records));
    });
    CountStored(n, stats.lo, stats.hi, stats.returns);
  }
};

void LasWriter::Impl::ValidateOptions() {
  version_minor = options.version_minor;
  if (version_minor != 4 && version_minor != 2) {
    throw Error(path + ": LAS version 1." + std::to_string(version_minor) + " is not written (use 1.4 or 1.2)");
  }
  pdrf = options.point_format.value_or(version_minor == 4 ? 7 : 3);
  const bool pdrf_ok = version_minor == 2 ? (pdrf >= 0 && pdrf <= 3)
                                          : ((pdrf >= 0 && pdrf <= 3) || (pdrf >= 6 && pdrf <= 8));
  if (!pdrf_ok) {
    throw Error(path + ": point format " + std::to_string(pdrf) + " is not written for LAS 1." +
                std::to_string(version_minor) + " (1.2: 0-3, 1.4: 0-3 or 6-8)");
  }
  header_size = version_minor == 4 ? lf::kHeaderSize14 : lf::kHeaderSize12;
  record_length = lf::BaseRecordSize(pdrf);

  const Eigen::Vector3d requested = options.scale_xyz.value_or(Eigen::Vector3d::Constant(options.scale_m));
  for (int a = 0; a < 3; ++a) {
    double canonical = 0.0;
    if (!lf::CanonicalLasScale(requested[a], &canonical) || canonical > kMaxScale) {
      throw Error(path + ": LAS scale " + FormatDouble(requested[a]) +
                  " must be 10^k x {1, 0.5, 0.25} and at most 1000 (e.g. 0.001, 0.0025, 0.005, 0.01)");
    }
    scale[a] = canonical;
  }
  if (options.offset) {
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite((*options.offset)[a])) throw Error(path + ": LAS offset is not finite");
    }
    offset = options.offset;
  }

  const uint16_t allowed_bits = version_minor == 2 ? 0x1 : (0x1 | 0x8 | 0x10);
  if ((options.global_encoding_extra_bits & ~allowed_bits) != 0) {
    throw Error(path + ": global encoding bits 0x" + [&] {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "%x", options.global_encoding_extra_bits & ~allowed_bits);
      return std::string(hex);
    }() + " are not allowed for LAS 1." + std::to_string(version_minor));
  }
  global_encoding = options.global_encoding_extra_bits;

  if (options.system_identifier.size() > lf::kIdFieldSize || options.generating_software.size() > lf::kIdFieldSize) {
    throw Error(path + ": system identifier and generating software are limited to 32 characters");
  }
  uint64_t vlr_bytes = 0;
  // Layout records (laszip, COPC) describe a source file's storage: never copied (LAZ gets our own below).
  options.vlrs.erase(std::remove_if(options.vlrs.begin(), options.vlrs.end(), lf::IsLayoutVlr), options.vlrs.end());
  if (options.compressed) {
    laz = std::make_unique<LazChunkWriter>(pdrf, record_length);
    buffer_records = LazChunkWriter::kBatchChunks * LazChunkWriter::kChunkPoints;
    options.vlrs.push_back(laz->Vlr());
  }
  for (const LasVlr& vlr : options.vlrs) {
    const std::string what = "VLR " + vlr.user_id + "/" + std::to_string(vlr.record_id);
    if (vlr.user_id.size() > 16 || vlr.description.size() > 32) {
      throw Error(path + ": " + what + ": user ID is limited to 16 characters, description to 32");
    }
    if (vlr.extended) {
      if (version_minor < 4) throw Error(path + ": " + what + ": extended VLRs need LAS 1.4");
      continue;
    }
    if (vlr.data.size() > 65535) {
      throw Error(path + ": " + what + ": payload of " + std::to_string(vlr.data.size()) +
                  " bytes does not fit a VLR (65535 at most; use an extended VLR in LAS 1.4)");
    }
    vlr_bytes += lf::kVlrHeaderSize + vlr.data.size();
    ++num_vlrs;
  }
  if (header_size + vlr_bytes > std::numeric_limits<uint32_t>::max()) throw Error(path + ": VLRs too large");
  point_offset = static_cast<uint32_t>(header_size + vlr_bytes);

  std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  creation_day = static_cast<uint16_t>(utc.tm_yday + 1);
  creation_year = static_cast<uint16_t>(utc.tm_year + 1900);
}

std::vector<uint8_t> LasWriter::Impl::BuildHeader(uint64_t evlr_start, uint32_t num_evlrs) const {
  lf::HeaderFields f;
  f.version_minor = version_minor;
  f.pdrf = pdrf;
  f.compressed = laz != nullptr;
  f.header_size = header_size;
  f.record_length = record_length;
  f.point_offset = point_offset;
  f.num_vlrs = num_vlrs;
  f.global_encoding = global_encoding;
  f.system_identifier = options.system_identifier;
  f.generating_software = options.generating_software;
  f.creation_day = creation_day;
  f.creation_year = creation_year;
  f.scale = scale;
  f.offset = offset.value_or(Eigen::Vector3d::Zero());
  f.count = count;
  f.by_return = by_return;
  f.stored_min = stored_min;
  f.stored_max = stored_max;
  f.evlr_start = evlr_start;
  f.num_evlrs = num_evlrs;
  return lf::EncodeHeader(f);
}

void LasWriter::Impl::WriteBytes(const uint8_t* data, size_t size) {
  if (size == 0) return;
  if (std::fwrite(data, 1, size, file) != size) {
    Fail(std::string("write to ") + temp_path + " failed (disk full?): " + std::strerror(errno));
  }
}

void LasWriter::Impl::FlushBuffer() {
  if (laz) {
    if (buffered > 0) {
      for (const std::vector<uint8_t>& chunk : laz->Chunks(buffer.get(), buffered)) {
        WriteBytes(chunk.data(), chunk.size());
      }
    }
  } else {
    WriteBytes(buffer.get(), buffered * record_length);
  }
  buffered = 0;
}

void LasWriter::Impl::Open() {
  temp_path = TemporaryPathFor(path);
  file = std::fopen(temp_path.c_str(), "wb");
  if (file == nullptr) {
    throw Error(path + ": cannot create temporary file " + temp_path + ": " + std::strerror(errno));
  }
  try {
    const std::vector<uint8_t> header = BuildHeader(0, 0);
    WriteBytes(header.data(), header.size());
    for (const LasVlr& vlr : options.vlrs) {
      if (vlr.extended) continue;
      const std::vector<uint8_t> head = lf::EncodeVlrHeader(vlr);
      WriteBytes(head.data(), head.size());
      WriteBytes(vlr.data.data(), vlr.data.size());
    }
    if (laz) {
      const uint8_t table_offset[8] = {};  // patched at Close()
      WriteBytes(table_offset, sizeof(table_offset));
    }
  } catch (...) {
    Discard();
    throw;
  }
}

void LasWriter::Impl::Discard() {
  if (file != nullptr) {
    std::fclose(file);
    file = nullptr;
  }
  if (!temp_path.empty()) std::remove(temp_path.c_str());
}

std::optional<LazAppendPart> LasWriter::Impl::PrepareLazAppend(LasReader& reader) const {
  // Reads only the layout and the offset, fixed once set (by the options or the first points written).
  const LasHeader& h = reader.header();
  if (!laz || !offset || reader.laszip_vlr() != laz->Vlr().data || h.version_minor != version_minor ||
      h.point_format != pdrf || h.point_record_length != record_length || h.scale != scale ||
      h.offset != *offset) {
    return std::nullopt;
  }
  LazAppendPart part;
  for (int a = 0; a < 3; ++a) {
    if (!lf::Quantise(h.min[a], scale[a], (*offset)[a], &part.stored_min[a]) ||
        !lf::Quantise(h.max[a], scale[a], (*offset)[a], &part.stored_max[a])) {
      return std::nullopt;
    }
  }
  part.full_chunks = h.point_count / LazChunkWriter::kChunkPoints;
  part.copied_returns = h.points_by_return;
  if (h.point_count == 0) return part;
  // The last, shorter chunk is decoded here; the header's returns less its returns are the copied ones (LAS 1.2
  // headers count returns 1-5 only, and so does this writer's header then).
  reader.Rewind();
  if (!reader.SkipStoredChunks(part.full_chunks)) {
    throw InputError(reader.path(), "its LAZ chunks could not be skipped to its last chunk");
  }
  std::vector<LasPoint> tail;
  reader.Read(&tail, static_cast<size_t>(h.point_count - part.full_chunks * LazChunkWriter::kChunkPoints));
  const int counted_returns = version_minor >= 4 ? 15 : 5;
  for (const LasPoint& p : tail) {
    if (p.return_number < 1 || p.return_number > counted_returns) continue;
    if (part.copied_returns[p.return_number - 1] == 0) {
      throw InputError(reader.path(), "its header does not count its returns");
    }
    --part.copied_returns[p.return_number - 1];
  }
  // Stored here, on the caller's thread, as WritePoints would (in one pass: the records are the part's own until
  // appended); when a point fails, a serial pass names the first one.
  part.tail_points = tail.size();
  part.tail_records.resize(tail.size() * record_length);
  RecordStats stats;
  try {
    stats = EncodeRecords(
        tail.size(), [&](size_t i) -> const LasPoint& { return tail[i]; }, 0, *offset, part.tail_records.data());
  } catch (const Error&) {
    const uint64_t first_tail_point = part.full_chunks * LazChunkWriter::kChunkPoints;
    for (size_t i = 0; i < tail.size(); ++i) {
      const std::string problem = StoreOne(tail[i], *offset, part.tail_records.data());
      if (!problem.empty()) {
        throw InputError(reader.path(), "point " + std::to_string(first_tail_point + i) +
                                            " cannot be written to " + path + ": " + problem);
      }
    }
    throw;
  }
  part.tail_min = stats.lo;
  part.tail_max = stats.hi;
  part.tail_returns = stats.returns;
  return part;
}

void LasWriter::Impl::AppendLaz(LasReader& reader, const LazAppendPart& part) {
  const uint64_t copied_points = part.full_chunks * LazChunkWriter::kChunkPoints;
  CheckWritable(copied_points + part.tail_points);
  if (copied_points + part.tail_points == 0) return;
  reader.Rewind();
  try {
    std::vector<uint8_t> bytes;
    uint64_t points = 0;
    for (uint64_t c = 0; c < part.full_chunks; ++c) {
      if (!reader.ReadStoredChunk(&bytes, &points) || points != LazChunkWriter::kChunkPoints) {
        Fail("LAZ chunk " + std::to_string(c) + " of the file appended could not be copied");
      }
      WriteBytes(bytes.data(), bytes.size());
      laz->AddStoredChunk(bytes.size());
    }
    if (part.tail_points > 0) {
      BufferRecords(part.tail_points, [&](size_t first, size_t take, uint8_t* records) {
        std::memcpy(records, part.tail_records.data() + first * record_length, take * record_length);
      });
      CountStored(part.tail_points, part.tail_min, part.tail_max, part.tail_returns);
    }
    CountStored(copied_points, part.stored_min, part.stored_max, part.copied_returns);
  } catch (...) {
    failed = true;  // chunks may be written: the file cannot be completed
    throw;
  }
}

LasWriter::LasWriter(const std::string& path, const LasWriterOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->options = options;
  impl_->ValidateOptions();
  impl_->Open();
}

LasWriter::~LasWriter() {
  if (!impl_->closed) impl_->Discard();
}

void LasWriter::Write(const FusedPoint* points, size_t count) {
  const std::string& path = impl_->path;
  impl_->WriteChunk(count, [&](size_t i) { return ToLasPoint(points[i], path); });
}

void LasWriter::WritePoints(const LasPoint* points, size_t count) {
  impl_->WriteChunk(count, [&](size_t i) -> const LasPoint& { return points[i]; });
}

bool LasWriter::AppendLaz(LasReader& reader) {
  const std::optional<LazAppendPart> part = impl_->PrepareLazAppend(reader);
  if (!part) return false;
  impl_->AppendLaz(reader, *part);
  return true;
}

std::optional<LazAppendPart> LasWriter::PrepareLazAppend(LasReader& reader) const {
  return impl_->PrepareLazAppend(reader);
}

void LasWriter::AppendLaz(LasReader& reader, const LazAppendPart& part) { impl_->AppendLaz(reader, part); }

void LasWriter::Close() {
  Impl& w = *impl_;
  if (w.closed) return;
  if (w.failed) {
    w.Discard();
    throw Error(w.path + ": not written: an earlier write failed");
  }
  try {
    w.FlushBuffer();
    uint64_t points_end = w.point_offset + w.count * w.record_length;
    uint64_t chunk_table = 0;
    if (w.laz) {  // LAZ: the chunk table closes the point data
      chunk_table = w.point_offset + 8 + w.laz->chunk_bytes();
      const std::vector<uint8_t> table = w.laz->Table();
      w.WriteBytes(table.data(), table.size());
      points_end = chunk_table + table.size();
    }
    // EVLRs follow the points (LAS 1.4 only; ValidateOptions rejected them otherwise).
    const uint64_t evlr_start = points_end;
    uint32_t num_evlrs = 0;
    for (const LasVlr& vlr : w.options.vlrs) {
      if (!vlr.extended) continue;
      const std::vector<uint8_t> head = lf::EncodeVlrHeader(vlr);
      w.WriteBytes(head.data(), head.size());
      w.WriteBytes(vlr.data.data(), vlr.data.size());
      ++num_evlrs;
    }
    const std::vector<uint8_t> header = w.BuildHeader(num_evlrs > 0 ? evlr_start : 0, num_evlrs);
    if (std::fseek(w.file, 0, SEEK_SET) != 0) w.Fail(std::string("seek failed: ") + std::strerror(errno));
    w.WriteBytes(header.data(), header.size());
    if (w.laz) {
      uint8_t offset[8];
      lf::PutU64(offset, chunk_table);
      if (fseeko(w.file, static_cast<off_t>(w.point_offset), SEEK_SET) != 0) {
        w.Fail(std::string("seek failed: ") + std::strerror(errno));
      }
      w.WriteBytes(offset, sizeof(offset));
    }
    if (std::fflush(w.file) != 0) w.Fail(std::string("flush failed (disk full?): ") + std::strerror(errno));
    if (::fsync(::fileno(w.file)) != 0) w.Fail(std::string("fsync failed: ") + std::strerror(errno));
    FILE* file = w.file;
    w.file = nullptr;
    if (std::fclose(file) != 0) w.Fail(std::string("close failed: ") + std::strerror(errno));
    CommitTemporaryFile(w.temp_path, w.path);
  } catch (...) {
    w.failed = true;
    w.Discard();
    throw;
  }
  w.closed = true;
  w.buffer.reset();
}

uint64_t LasWriter::num_points() const { return impl_->count; }

const std::string& LasWriter::path() const { return impl_->path; }

}  // namespace sacfuse
