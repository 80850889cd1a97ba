#include "io/copc_validate.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <map>
#include <memory>
#include <set>

#include "io/copc_format.h"
#include "io/copc_hierarchy.h"
#include "io/las_format.h"
#include "io/laz_arithmetic.h"
#include "io/laz_chunk_codec.h"
#include "io/laz_chunk_table.h"
#include "io/laz_vlr.h"
#include "io/unique_file.h"

namespace sacfuse {
namespace lf = las_format;
using copc::Entry;
using copc::VoxelKey;

namespace {

constexpr size_t kListed = 5;  // findings of one kind listed; the rest are counted
constexpr size_t kGpsTimeByte = 22;

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}


class CopcCheck {
 public:
  explicit CopcCheck(const std::string& path) : path_(path) {}

  // Reads the header and the (E)VLR directory; false when the file is not COPC (findings say why when it is
  // named as COPC).
  bool Open() {
    const bool named = EndsWith(path_, ".copc.laz");
    file_.reset(std::fopen(path_.c_str(), "rb"));
    if (!file_) return false;  // the LAS rules report the file
    fseeko(file_.get(), 0, SEEK_END);
    size_ = static_cast<uint64_t>(ftello(file_.get()));
    std::vector<uint8_t> h;
    if (!Read(0, lf::kHeaderSize14, &h) || std::string(h.begin(), h.begin() + 4) != "LASF" ||
        h[lf::kOffVersionMinor] != 4) {
      if (named) Add("format", "named *.copc.laz but not a LAS 1.4 file (COPC is LAS 1.4)");
      return false;
    }
    header_size_ = lf::GetU16(&h[lf::kOffHeaderSize]);
    point_offset_ = lf::GetU32(&h[lf::kOffPointOffset]);
    const uint32_t num_vlrs = lf::GetU32(&h[lf::kOffNumVlrs]);
    pdrf_byte_ = h[lf::kOffPdrf];
    record_length_ = lf::GetU16(&h[lf::kOffRecordLength]);
    count_ = lf::GetU64(&h[lf::kOffCount64]);
    for (int a = 0; a < 3; ++a) {
      scale_[a] = lf::GetF64(&h[lf::kOffScale + 8 * a]);
      offset_[a] = lf::GetF64(&h[lf::kOffOffset + 8 * a]);
      max_[a] = lf::GetF64(&h[lf::kOffBounds + 16 * a]);
      min_[a] = lf::GetF64(&h[lf::kOffBounds + 16 * a + 8]);
    }
    evlr_start_ = lf::GetU64(&h[lf::kOffEvlrStart]);
    const uint32_t num_evlrs = lf::GetU32(&h[lf::kOffEvlrCount]);
    uint64_t at = header_size_;
    std::vector<uint8_t> head;
    for (uint32_t i = 0; i < num_vlrs && at + lf::kVlrHeaderSize <= point_offset_; ++i) {
      if (!Read(at, lf::kVlrHeaderSize, &head)) break;
      Record r{lf::GetPaddedString(&head[2], 16), lf::GetU16(&head[18]), at + lf::kVlrHeaderSize,
               lf::GetU16(&head[20])};
      vlrs_.push_back(r);
      at = r.payload + r.length;
    }
    at = evlr_start_;
    for (uint32_t i = 0; i < num_evlrs && at > 0 && Read(at, lf::kEvlrHeaderSize, &head); ++i) {
      Record r{lf::GetPaddedString(&head[2], 16), lf::GetU16(&head[18]), at + lf::kEvlrHeaderSize,
               lf::GetU64(&head[20])};
      evlrs_.push_back(r);
      at = r.payload + r.length;
    }
    const bool info_first = !vlrs_.empty() && vlrs_[0].user_id == lf::kCopcUserId &&
                            vlrs_[0].record_id == lf::kCopcInfoRecordId && vlrs_[0].payload == 375 + lf::kVlrHeaderSize;
    if (!info_first) {
      if (named) Add("format", "named *.copc.laz but its first VLR is not the COPC info VLR (copc/1 at offset 375)");
      return false;
    }
    return true;
  }

  // The header, info and laszip VLRs, the cube and the hierarchy; false when the hierarchy cannot be walked.
  bool CheckStructure() {
    const int pdrf = pdrf_byte_ & 0x3f;
    if (pdrf < 6 || pdrf > 8) Add("format", "point format " + std::to_string(pdrf) + " (COPC takes 6, 7 or 8)");
    if ((pdrf_byte_ & 0x80) == 0) Add("format", "the point format's compression bit (7) is clear: COPC is LAZ");
    if (header_size_ != lf::kHeaderSize14) Add("format", "header size " + std::to_string(header_size_) + " (375)");
    std::vector<uint8_t> payload;
    if (!Read(vlrs_[0].payload, static_cast<size_t>(vlrs_[0].length), &payload)) {
      Add("info", "info VLR beyond the end of the file");
      return false;
    }
    const std::string bad_info = copc::DecodeInfo(payload, &info_);
    if (!bad_info.empty()) {
      Add("info", bad_info);
      return false;
    }
    CheckLaszip(pdrf);
    CheckCube();
    return WalkHierarchy();
  }

  void CheckAll() {
    if (!CheckStructure()) return;
    CheckNodes();
    CheckChunks();
    if (decoder_vlr_) DecodeNodes(pdrf_byte_ & 0x3f);
  }

  std::vector<std::string> Findings() const {
    std::vector<std::string> out;
    for (const auto& [kind, list] : findings_) {
      for (size_t i = 0; i < list.size() && i < kListed; ++i) out.push_back("COPC: " + kind + ": " + list[i]);
      if (list.size() > kListed) {
        out.push_back("COPC: " + kind + ": ... and " + std::to_string(list.size() - kListed) + " more");
      }
    }
    return out;
  }

  const copc::HierarchyWalk& walk() const { return walk_; }

 private:
  struct Record {
    std::string user_id;
    uint16_t record_id = 0;
    uint64_t payload = 0;  // offset of the payload
    uint64_t length = 0;
  };

  void Add(const std::string& kind, const std::string& what) { findings_[kind].push_back(what); }

  bool Read(uint64_t at, size_t n, std::vector<uint8_t>* out) {
    out->resize(n);
    if (at > size_ || n > size_ - at) return false;
    return fseeko(file_.get(), static_cast<off_t>(at), SEEK_SET) == 0 &&
           std::fread(out->data(), 1, n, file_.get()) == n;
  }

  void CheckLaszip(int pdrf) {
    const auto it = std::find_if(vlrs_.begin(), vlrs_.end(), [](const Record& r) {
      return r.user_id == lf::kLaszipUserId && r.record_id == lf::kLaszipRecordId;
    });
    std::vector<uint8_t> payload;
    if (it == vlrs_.end() || !Read(it->payload, static_cast<size_t>(it->length), &payload)) {
      Add("LAZ", "no \"laszip encoded\" VLR");
      return;
    }
    try {
      const laz::LazVlr vlr = laz::LazVlr::Parse(payload);
      if (vlr.chunk_size != laz::kVariableChunkSize) {
        Add("LAZ", "fixed chunk size " + std::to_string(vlr.chunk_size) + " (COPC chunks are variable: one a node)");
      }
      const std::string unsupported = vlr.Unsupported(pdrf, record_length_);
      if (unsupported.empty()) {
        decoder_vlr_ = std::make_unique<laz::LazVlr>(vlr);
      } else {
        Add("LAZ", "the nodes' points are not checked: " + unsupported);
      }
    } catch (const laz::DataError& e) {
      Add("LAZ", std::string("\"laszip encoded\" VLR: ") + e.what());
    }
  }

  // The header's bounds inside the root cube, within half a scale step (the cube's faces are computed in floating
  // point, and other writers put them on the points' extremes).
  void CheckCube() {
    static const char* kAxis[3] = {"X", "Y", "Z"};
    for (int a = 0; a < 3; ++a) {
      const double lo = info_.center[a] - info_.halfsize, hi = info_.center[a] + info_.halfsize;
      const double slack = scale_[a] / 2;
      if (count_ > 0 && (min_[a] < lo - slack || max_[a] > hi + slack)) {
        Add("cube", std::string("header ") + kAxis[a] + " bounds [" + std::to_string(min_[a]) + ", " +
                        std::to_string(max_[a]) + "] outside the cube [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
      }
    }
  }

  bool WalkHierarchy() {
    std::vector<const Record*> hierarchy;
    for (const Record& r : evlrs_) {
      if (r.user_id == lf::kCopcUserId && r.record_id == lf::kCopcHierarchyRecordId) hierarchy.push_back(&r);
    }
    if (hierarchy.size() != 1) {
      Add("hierarchy", std::to_string(hierarchy.size()) + " hierarchy EVLRs (copc/1000); COPC has exactly one");
      if (hierarchy.empty()) return false;
    }
    const Record& h = *hierarchy[0];
    walk_ = copc::WalkHierarchy(
        [this](uint64_t at, size_t n, std::vector<uint8_t>* out) { return Read(at, n, out); },
        info_.root_hier_offset, info_.root_hier_size, h.payload, h.payload + h.length);
    for (const std::string& p : walk_.problems) Add("hierarchy", p);
    return true;
  }

  void CheckNodes() {
    std::set<VoxelKey> keys;
    for (const Entry& e : walk_.nodes) keys.insert(e.key);
    if (keys.count(VoxelKey{}) == 0) Add("hierarchy", "no root node 0-0-0-0");
    uint64_t sum = 0;
    for (const Entry& e : walk_.nodes) {
      if (e.key.level > 0 && keys.count(e.key.Parent()) == 0) {
        Add("unreachable nodes", e.key.ToString() + ": its parent " + e.key.Parent().ToString() + " is not listed");
      }
      if (e.point_count > 0) sum += static_cast<uint64_t>(e.point_count);
      if (e.point_count == 0 && (e.offset != 0 || e.byte_size != 0)) {
        Add("nodes", e.key.ToString() + ": no points but offset " + std::to_string(e.offset) + ", " +
                         std::to_string(e.byte_size) + " bytes");
      }
    }
    if (sum != count_) {
      Add("counts", "the nodes hold " + std::to_string(sum) + " points, the header counts " + std::to_string(count_));
    }
  }

  void CheckChunks() {
    std::vector<uint8_t> bytes;
    if (!Read(point_offset_, 8, &bytes)) {
      Add("chunk table", "no chunk table offset after the VLRs");
      return;
    }
    const uint64_t table = lf::GetU64(bytes.data());
    const uint64_t data_begin = point_offset_ + 8;
    const uint64_t table_end = evlr_start_ > table ? evlr_start_ : size_;
    if (table < data_begin || table + laz::kChunkTableHeaderSize > table_end ||
        !Read(table, static_cast<size_t>(table_end - table), &bytes)) {
      Add("chunk table", "offset " + std::to_string(table) + " outside the file's point data");
      return;
    }
    const uint32_t n = lf::GetU32(&bytes[4]);
    std::vector<laz::ChunkEntry> chunks;
    try {
      chunks = laz::DecodeChunkTable(bytes.data() + laz::kChunkTableHeaderSize,
                                     bytes.size() - laz::kChunkTableHeaderSize, n, /*variable_size=*/true);
    } catch (const laz::DataError& e) {
      Add("chunk table", std::string("does not decode: ") + e.what());
      return;
    }
    std::map<uint64_t, std::pair<const laz::ChunkEntry*, bool>> by_offset;  // chunk start -> entry, addressed
    uint64_t at = data_begin;
    for (const laz::ChunkEntry& c : chunks) {
      by_offset[at] = {&c, false};
      at += c.bytes;
    }
    if (at != table) {
      Add("chunk table", "its chunks end at " + std::to_string(at) + ", the table starts at " + std::to_string(table));
    }
    for (const Entry& e : walk_.nodes) {
      if (e.point_count <= 0) continue;
      const std::string name = e.key.ToString();
      if (e.offset < data_begin || e.byte_size <= 0 || e.offset + static_cast<uint64_t>(e.byte_size) > table) {
        Add("nodes", name + ": chunk at " + std::to_string(e.offset) + " (" + std::to_string(e.byte_size) +
                         " bytes) outside the point data [" + std::to_string(data_begin) + ", " +
                         std::to_string(table) + ")");
        continue;
      }
      const auto c = by_offset.find(e.offset);
      if (c == by_offset.end()) {
        Add("nodes", name + ": no chunk of the chunk table starts at " + std::to_string(e.offset));
        continue;
      }
      if (c->second.second) Add("nodes", name + ": chunk at " + std::to_string(e.offset) + " addressed twice");
      c->second.second = true;
      if (c->second.first->bytes != static_cast<uint32_t>(e.byte_size) ||
          c->second.first->points != static_cast<uint32_t>(e.point_count)) {
        Add("nodes", name + ": " + std::to_string(e.point_count) + " points in " + std::to_string(e.byte_size) +
                         " bytes, the chunk table says " + std::to_string(c->second.first->points) + " in " +
                         std::to_string(c->second.first->bytes));
      }
      nodes_to_decode_.push_back(e);
    }
    for (const auto& [start, chunk] : by_offset) {
      if (!chunk.second) Add("unreachable point data", "chunk at " + std::to_string(start) + ": no node addresses it");
    }
  }

  void DecodeNodes(int pdrf) {
    laz::ChunkDecoder decoder(*decoder_vlr_, record_length_);
    std::vector<uint8_t> bytes, record(record_length_);
    for (const Entry& e : nodes_to_decode_) {
      const std::string name = e.key.ToString();
      if (!Read(e.offset, static_cast<size_t>(e.byte_size), &bytes)) continue;
      const std::array<double, 6> b = copc::NodeBounds(info_, e.key);
      uint64_t outside = 0, off_time = 0;
      try {
        decoder.Start(bytes.data(), bytes.size(), static_cast<uint64_t>(e.point_count));
        for (int32_t i = 0; i < e.point_count; ++i) {
          decoder.Next(record.data());
          bool in = true;  // within half a scale step of the closed bounds: a point on a face may round out
          for (int a = 0; a < 3; ++a) {
            const double v = lf::Dequantise(lf::GetI32(&record[4 * a]), scale_[a], offset_[a]);
            in = in && v >= b[a] - scale_[a] / 2 && v <= b[a + 3] + scale_[a] / 2;
          }
          outside += in ? 0 : 1;
          if (pdrf >= 6) {
            const double t = lf::GetF64(&record[kGpsTimeByte]);
            off_time += (t < info_.gpstime_minimum || t > info_.gpstime_maximum) ? 1 : 0;
          }
        }
      } catch (const laz::DataError& ex) {
        Add("point data", name + ": its chunk does not decode: " + ex.what());
        continue;
      }
      if (outside > 0) {
        Add("points out of bounds", name + ": " + std::to_string(outside) + " of " + std::to_string(e.point_count) +
                                        " points outside the node's cube");
      }
      if (off_time > 0) {
        Add("GPS time", name + ": " + std::to_string(off_time) + " points outside the info VLR's GPS time range");
      }
    }
  }

  std::string path_;
  UniqueFile file_;
  uint64_t size_ = 0;
  uint16_t header_size_ = 0;
  uint32_t point_offset_ = 0;
  uint8_t pdrf_byte_ = 0;
  uint16_t record_length_ = 0;
  uint64_t count_ = 0;
  uint64_t evlr_start_ = 0;
  Eigen::Vector3d scale_ = Eigen::Vector3d::Ones(), offset_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d min_ = Eigen::Vector3d::Zero(), max_ = Eigen::Vector3d::Zero();
  std::vector<Record> vlrs_, evlrs_;
  copc::Info info_;
  std::unique_ptr<laz::LazVlr> decoder_vlr_;
  copc::HierarchyWalk walk_;
  std::vector<Entry> nodes_to_decode_;
  std::map<std::string, std::vector<std::string>> findings_;
};

}  // namespace

std::vector<std::string> ValidateCopc(const std::string& path) {
  CopcCheck check(path);
  if (check.Open()) check.CheckAll();
  return check.Findings();
}

std::string DescribeCopc(const std::string& path) {
  CopcCheck check(path);
  if (!check.Open() || !check.CheckStructure()) return "";
  const copc::HierarchyWalk& walk = check.walk();
  if (walk.nodes.empty()) return "";
  int depth = 0;
  for (const Entry& e : walk.nodes) depth = std::max(depth, e.key.level + 1);
  return "COPC 1.0, " + std::to_string(walk.nodes.size()) + " nodes in " + std::to_string(depth) + " levels, " +
         std::to_string(walk.pages) + " hierarchy page" + (walk.pages == 1 ? "" : "s");
}

}  // namespace sacfuse
