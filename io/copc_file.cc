#include "io/copc_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <unistd.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/laz_chunk_codec.h"
#include "io/laz_chunk_table.h"
#include "io/laz_vlr.h"

namespace sacfuse::copc {
namespace lf = las_format;
namespace {

constexpr size_t kBatchPoints = size_t{1} << 21;  // points compressed per parallel batch (bounds the chunk bytes held)
constexpr size_t kGpsTimeByte = 22;              // of a PDRF 6-8 record

}  // namespace

struct CopcFile::Encoders {
  laz::LazVlr vlr;
  size_t record_length = 0;
  tbb::enumerable_thread_specific<std::unique_ptr<laz::ChunkEncoder>> per_thread;
  laz::ChunkEncoder& Get() {
    std::unique_ptr<laz::ChunkEncoder>& e = per_thread.local();
    if (!e) e = std::make_unique<laz::ChunkEncoder>(vlr, record_length);
    return *e;
  }
};

CopcFile::CopcFile(const std::string& path, const lf::HeaderFields& header, const std::vector<LasVlr>& vlrs,
                   const Info& info, const PageLayout& layout)
    : path_(path), header_(header), info_(info), layout_(layout), encoders_(std::make_unique<Encoders>()) {
  if (header_.version_minor != 4 || header_.pdrf < 6 || header_.pdrf > 8) {
    throw Error(path + ": COPC needs LAS 1.4 with point format 6, 7 or 8 (got LAS 1." +
                std::to_string(header_.version_minor) + ", point format " + std::to_string(header_.pdrf) + ")");
  }
  const size_t base = lf::BaseRecordSize(header_.pdrf);
  encoders_->vlr = laz::LazVlr::ForFormat(header_.pdrf, static_cast<uint16_t>(header_.record_length - base));
  encoders_->vlr.chunk_size = laz::kVariableChunkSize;
  encoders_->record_length = header_.record_length;
  const std::string unsupported = encoders_->vlr.Unsupported(header_.pdrf, header_.record_length);
  if (!unsupported.empty()) throw Error(path + ": COPC cannot be written: " + unsupported);

  // VLRs: the info record first (COPC 1.0 wants it at offset 375), the carried ones, the laszip record last.
  std::vector<LasVlr> head;
  LasVlr info_vlr;
  info_vlr.user_id = lf::kCopcUserId;
  info_vlr.record_id = lf::kCopcInfoRecordId;
  info_vlr.description = "COPC info";
  info_vlr.data = EncodeInfo(info_);
  head.push_back(info_vlr);
  for (const LasVlr& v : vlrs) {
    if (lf::IsLayoutVlr(v)) continue;
    (v.extended ? evlrs_ : head).push_back(v);
  }
  LasVlr laszip;
  laszip.user_id = lf::kLaszipUserId;
  laszip.record_id = lf::kLaszipRecordId;
  laszip.description = "sacfuse LAZ (LASzip format)";
  laszip.data = encoders_->vlr.Serialize();
  head.push_back(laszip);

  header_.compressed = true;
  header_.header_size = lf::kHeaderSize14;
  header_.num_vlrs = static_cast<uint32_t>(head.size());
  uint64_t at = header_.header_size;
  std::vector<uint8_t> vlr_bytes;
  for (const LasVlr& v : head) {
    if (v.data.size() > std::numeric_limits<uint16_t>::max()) {
      throw Error(path + ": VLR " + v.user_id + "/" + std::to_string(v.record_id) + " too large for a VLR");
    }
    const std::vector<uint8_t> h = lf::EncodeVlrHeader(v);
    vlr_bytes.insert(vlr_bytes.end(), h.begin(), h.end());
    vlr_bytes.insert(vlr_bytes.end(), v.data.begin(), v.data.end());
  }
  info_payload_offset_ = static_cast<uint32_t>(at + lf::kVlrHeaderSize);
  header_.point_offset = static_cast<uint32_t>(at + vlr_bytes.size());

  temp_path_ = TemporaryPathFor(path);
  file_ = std::fopen(temp_path_.c_str(), "wb");
  if (file_ == nullptr) throw Error(path + ": cannot create " + temp_path_ + ": " + std::strerror(errno));
  const std::vector<uint8_t> h = lf::EncodeHeader(header_);  // patched by Finish
  Write(h.data(), h.size());
  Write(vlr_bytes.data(), vlr_bytes.size());
  const uint8_t table_offset[8] = {};  // patched by Finish
  Write(table_offset, sizeof(table_offset));
}

CopcFile::~CopcFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!finished_ && !temp_path_.empty()) std::remove(temp_path_.c_str());
}

void CopcFile::Write(const uint8_t* data, size_t size) {
  if (size > 0 && std::fwrite(data, 1, size, file_) != size) {
    throw Error(path_ + ": write to " + temp_path_ + " failed (disk full?): " + std::strerror(errno));
  }
  position_ += size;
}

void CopcFile::WriteAt(uint64_t offset, const std::vector<uint8_t>& bytes) {
  if (fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0 ||
      std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
    throw Error(path_ + ": cannot patch " + temp_path_ + " at " + std::to_string(offset) + ": " +
                std::strerror(errno));
  }
}

void CopcFile::WriteNodes(const RecordView& records, const std::vector<BuiltNode>& nodes) {
  const size_t length = header_.record_length;
  for (size_t first = 0; first < nodes.size();) {
    size_t last = first, batch_points = 0;
    while (last < nodes.size() && (last == first || batch_points + nodes[last].points.size() <= kBatchPoints)) {
      batch_points += nodes[last].points.size();
      ++last;
    }
    std::vector<std::vector<uint8_t>> chunks(last - first);
    std::vector<std::pair<double, double>> gps(last - first);
    tbb::parallel_for(first, last, [&](size_t i) {
      const std::vector<uint32_t>& points = nodes[i].points;
      if (points.empty()) return;
      std::vector<uint8_t> gathered(points.size() * length);
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (size_t j = 0; j < points.size(); ++j) {
        const uint8_t* r = records.data + static_cast<size_t>(points[j]) * length;
        std::memcpy(&gathered[j * length], r, length);
        const double t = lf::GetF64(r + kGpsTimeByte);
        lo = std::min(lo, t);
        hi = std::max(hi, t);
      }
      gps[i - first] = {lo, hi};
      encoders_->Get().Encode(gathered.data(), points.size(), &chunks[i - first]);
    });
    for (size_t i = first; i < last; ++i) {
      const BuiltNode& node = nodes[i];
      const std::vector<uint8_t>& chunk = chunks[i - first];
      if (node.points.empty()) {
        entries_.push_back({node.key, 0, 0, 0});
        continue;
      }
      if (chunk.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max()) ||
          node.points.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
        throw Error(path_ + ": COPC node " + node.key.ToString() + " too large for a hierarchy entry");
      }
      entries_.push_back({node.key, position_, static_cast<int32_t>(chunk.size()),
                          static_cast<int32_t>(node.points.size())});
      chunks_.push_back({static_cast<uint32_t>(node.points.size()), static_cast<uint32_t>(chunk.size())});
      Write(chunk.data(), chunk.size());
      points_ += node.points.size();
      const auto [lo, hi] = gps[i - first];
      gps_min_ = gps_seen_ ? std::min(gps_min_, lo) : lo;
      gps_max_ = gps_seen_ ? std::max(gps_max_, hi) : hi;
      gps_seen_ = true;
    }
    first = last;
  }
}

int CopcFile::levels() const {
  int levels = 0;
  for (const Entry& e : entries_) levels = std::max(levels, e.key.level + 1);
  return levels;
}

void CopcFile::Finish() {
  if (points_ != header_.count) {
    throw Error(path_ + ": COPC build wrote " + std::to_string(points_) + " points, the header counts " +
                std::to_string(header_.count));
  }
  const bool has_root = std::any_of(entries_.begin(), entries_.end(), [](const Entry& e) { return e.key.level == 0; });
  if (!has_root) entries_.push_back({VoxelKey{}, 0, 0, 0});  // an empty cloud: the root, without points

  const uint64_t table_offset = position_;
  std::vector<laz::ChunkEntry> table;
  for (const auto& [points, bytes] : chunks_) table.push_back({points, bytes});
  const std::vector<uint8_t> table_bytes = laz::EncodeChunkTable(table, /*variable_size=*/true);
  Write(table_bytes.data(), table_bytes.size());

  // EVLRs: the hierarchy first, then the carried ones.
  const uint64_t evlr_start = position_;
  uint64_t root_page_bytes = 0;
  LasVlr hierarchy;
  hierarchy.user_id = lf::kCopcUserId;
  hierarchy.record_id = lf::kCopcHierarchyRecordId;
  hierarchy.description = "COPC hierarchy";
  hierarchy.extended = true;
  hierarchy.data = EncodeHierarchy(entries_, evlr_start + lf::kEvlrHeaderSize, layout_, &root_page_bytes, &pages_);
  std::vector<LasVlr> evlrs = {hierarchy};
  evlrs.insert(evlrs.end(), evlrs_.begin(), evlrs_.end());
  for (const LasVlr& v : evlrs) {
    const std::vector<uint8_t> h = lf::EncodeVlrHeader(v);
    Write(h.data(), h.size());
    Write(v.data.data(), v.data.size());
  }

  header_.evlr_start = evlr_start;
  header_.num_evlrs = static_cast<uint32_t>(evlrs.size());
  info_.root_hier_offset = evlr_start + lf::kEvlrHeaderSize;
  info_.root_hier_size = root_page_bytes;
  info_.gpstime_minimum = gps_seen_ ? gps_min_ : 0.0;
  info_.gpstime_maximum = gps_seen_ ? gps_max_ : 0.0;
  WriteAt(0, lf::EncodeHeader(header_));
  WriteAt(info_payload_offset_, EncodeInfo(info_));
  std::vector<uint8_t> offset(8);
  lf::PutU64(offset.data(), table_offset);
  WriteAt(header_.point_offset, offset);
  if (std::fflush(file_) != 0) throw Error(path_ + ": flush failed (disk full?): " + std::strerror(errno));
  if (::fsync(::fileno(file_)) != 0) throw Error(path_ + ": fsync failed: " + std::strerror(errno));
  FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) throw Error(path_ + ": close failed: " + std::strerror(errno));
  CommitTemporaryFile(temp_path_, path_);
  finished_ = true;
}

}  // namespace sacfuse::copc
