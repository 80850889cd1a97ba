#include "io/copc_writer.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <set>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/copc_buckets.h"
#include "io/copc_file.h"
#include "io/copc_octree.h"
#include "io/las_format.h"
#include "io/las_reader.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace lf = las_format;
using copc::AllIndices;
using copc::BuiltNode;
using copc::RecordView;
using copc::VoxelKey;

namespace {

constexpr uint64_t kBytesPerPoint = 96;  // a record of format 7, its indices and cell slots while a node is built
constexpr uint64_t kMinBucketPoints = 4096;
constexpr size_t kMaxBucketBuffers = size_t{64} << 20;

std::vector<uint8_t> Gather(const RecordView& records, const std::vector<uint32_t>& points) {
  std::vector<uint8_t> out(points.size() * records.record_length);
  for (size_t j = 0; j < points.size(); ++j) {
    std::copy_n(records.data + static_cast<size_t>(points[j]) * records.record_length, records.record_length,
                out.begin() + static_cast<std::ptrdiff_t>(j * records.record_length));
  }
  return out;
}

// Builds every bucket in memory and the nodes above them bottom-up, writing nodes as they are finished.
class TreeBuilder {
 public:
  TreeBuilder(const copc::Cube& cube, const std::vector<copc::Bucket>& buckets, const std::string& spill_path,
              size_t record_length, size_t max_node_points, copc::CopcFile* file)
      : cube_(cube), spill_path_(spill_path), record_length_(record_length), max_node_points_(max_node_points),
        file_(file) {
    for (const copc::Bucket& b : buckets) {
      buckets_.emplace(b.key, &b);
      for (VoxelKey key = b.key; key.level > 0; key = key.Parent()) children_[key.Parent()].insert(key);
    }
  }

  void Build() {
    Candidates root = Process(VoxelKey{});
    const RecordView view{root.records.data(), record_length_};
    file_->WriteNodes(view, {BuiltNode{VoxelKey{}, AllIndices(root.records.size() / record_length_)}});
  }

 private:
  // A finished subtree's root points, not yet written: its parent may take some.
  struct Candidates {
    std::vector<uint8_t> records;
    bool has_descendants = false;
  };

  Candidates Process(const VoxelKey& key) {
    const auto bucket = buckets_.find(key);
    if (bucket != buckets_.end()) return BuildBucket(*bucket->second);
    // Bottom-up: the node keeps one point per cell of its children's own points; the rest stay in the children.
    std::vector<VoxelKey> kids(children_[key].begin(), children_[key].end());
    std::vector<Candidates> below;
    std::vector<uint8_t> all;
    std::vector<size_t> first;  // first record of each child in `all`
    for (const VoxelKey& kid : kids) {
      below.push_back(Process(kid));
      first.push_back(all.size() / record_length_);
      all.insert(all.end(), below.back().records.begin(), below.back().records.end());
      below.back().records = std::vector<uint8_t>();
    }
    first.push_back(all.size() / record_length_);
    const RecordView view{all.data(), record_length_};
    std::vector<uint32_t> own, rest;
    copc::SelectOnePerCell(cube_, key, view, AllIndices(first.back()), &own, &rest);
    std::vector<BuiltNode> finished;
    size_t r = 0;
    for (size_t k = 0; k < kids.size(); ++k) {
      BuiltNode node{kids[k], {}};
      while (r < rest.size() && rest[r] < first[k + 1]) node.points.push_back(rest[r++]);
      if (!node.points.empty() || below[k].has_descendants) finished.push_back(std::move(node));
    }
    file_->WriteNodes(view, finished);
    return {Gather(view, own), true};
  }

  Candidates BuildBucket(const copc::Bucket& bucket) {
    const std::unique_ptr<uint8_t[]> records = copc::LoadBucket(bucket, record_length_);
    if (bucket.path != spill_path_) fs::remove(bucket.path);
    const RecordView view{records.get(), record_length_};
    copc::BuiltSubtree subtree =
        copc::BuildSubtree(cube_, bucket.key, view, AllIndices(bucket.points), max_node_points_);
    file_->WriteNodes(view, subtree.descendants);
    return {Gather(view, subtree.own), !subtree.descendants.empty()};
  }

  const copc::Cube& cube_;
  const std::string spill_path_;
  const size_t record_length_;
  const size_t max_node_points_;
  copc::CopcFile* file_;
  std::map<VoxelKey, const copc::Bucket*> buckets_;
  std::map<VoxelKey, std::set<VoxelKey>> children_;  // of the nodes above the buckets
};

}  // namespace

struct CopcWriter::Impl {
  std::string path;
  LasWriterOptions las;
  CopcOptions copc;
  std::string work_dir;
  std::string spill_path;
  std::unique_ptr<LasWriter> spill;
  bool closed = false;

  void RemoveWorkDir() {
    std::error_code ec;
    if (!work_dir.empty()) fs::remove_all(work_dir, ec);
  }
  // Closes the spill, builds the octree, writes the file; logs the time since `start`.
  void Build(std::chrono::steady_clock::time_point start);
};

CopcWriter::CopcWriter(const std::string& path, const LasWriterOptions& las, const CopcOptions& copc)
    : impl_(std::make_unique<Impl>()) {
  Impl& w = *impl_;
  w.path = path;
  w.las = las;
  w.copc = copc;
  w.las.compressed = false;  // the spill; the file itself is LAZ
  if (w.las.version_minor != 4) throw Error(path + ": COPC is LAS 1.4 (output.las_version 1.4)");
  const int pdrf = w.las.point_format.value_or(7);
  if (pdrf < 6 || pdrf > 8) {
    throw Error(path + ": COPC takes point formats 6, 7 and 8 only, not " + std::to_string(pdrf));
  }
  if (w.las.scale_xyz && ((*w.las.scale_xyz)[0] != (*w.las.scale_xyz)[1] ||
                          (*w.las.scale_xyz)[0] != (*w.las.scale_xyz)[2])) {
    throw Error(path + ": COPC needs the same scale on every axis (its octree is made of cubes)");
  }
  const fs::path target(path);
  const fs::path dir = copc.temp_dir.empty() ? target.parent_path() : fs::path(copc.temp_dir);
  w.work_dir = TemporaryPathFor((dir / target.filename()).string());
  std::error_code ec;
  fs::create_directories(w.work_dir, ec);
  if (ec) throw Error(path + ": cannot create the COPC work folder " + w.work_dir + ": " + ec.message());
  w.spill_path = (fs::path(w.work_dir) / "spill.las").string();
  try {
    w.spill = std::make_unique<LasWriter>(w.spill_path, w.las);
  } catch (...) {
    w.RemoveWorkDir();
    throw;
  }
}

CopcWriter::~CopcWriter() {
  impl_->spill.reset();
  impl_->RemoveWorkDir();
}

void CopcWriter::Write(const FusedPoint* points, size_t count) { impl_->spill->Write(points, count); }

void CopcWriter::WritePoints(const LasPoint* points, size_t count) { impl_->spill->WritePoints(points, count); }

void CopcWriter::Impl::Build(std::chrono::steady_clock::time_point start) {
  spill->Close();
  LasHeader h;
  {
    LasReader reader(spill_path);
    h = reader.header();
  }
  std::array<int32_t, 3> lo{}, hi{};
  if (h.point_count > 0) {
    for (int a = 0; a < 3; ++a) {
      lf::Quantise(h.min[a], h.scale[a], h.offset[a], &lo[a]);
      lf::Quantise(h.max[a], h.scale[a], h.offset[a], &hi[a]);
    }
  }
  const copc::Cube cube = copc::Cube::Around(lo, hi);
  const size_t length = h.point_record_length;
  const uint64_t max_bucket = std::max(kMinBucketPoints, copc.memory_bytes / kBytesPerPoint);
  const size_t buffers = static_cast<size_t>(std::min<uint64_t>(kMaxBucketBuffers, copc.memory_bytes / 8));
  const std::vector<copc::Bucket> buckets = copc::MakeBuckets(spill_path, h.offset_to_point_data, h.point_count,
                                                              length, cube, max_bucket, buffers, work_dir);
  if (buckets.size() > 1) {
    spdlog::info("{}: {} points sorted into {} octree buckets of at most {} points", path, h.point_count,
                 buckets.size(), max_bucket);
  }

  lf::HeaderFields f;
  f.version_minor = 4;
  f.pdrf = h.point_format;
  f.record_length = length;
  f.global_encoding = h.global_encoding;
  f.system_identifier = h.system_identifier;
  f.generating_software = h.generating_software;
  f.creation_day = h.creation_day;
  f.creation_year = h.creation_year;
  f.scale = h.scale;
  f.offset = h.offset;
  f.count = h.point_count;
  f.by_return = h.points_by_return;
  f.stored_min = lo;
  f.stored_max = hi;
  copc::CopcFile file(path, f, las.vlrs, cube.ToInfo(h.scale[0], h.offset),
                      copc::PageLayout{copc.page_levels, copc.min_page_entries});
  TreeBuilder(cube, buckets, spill_path, length, copc.max_node_points, &file).Build();
  file.Finish();
  spdlog::info("{}: COPC of {} points built in {:.1f} s: {} nodes in {} levels, {} hierarchy page{}, root spacing "
               "{:.3f} m", path, h.point_count,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), file.nodes(),
               file.levels(), file.pages(), file.pages() == 1 ? "" : "s", cube.ToInfo(h.scale[0], h.offset).spacing);
}

void CopcWriter::Close() {
  Impl& w = *impl_;
  if (w.closed) return;
  try {
    w.Build(std::chrono::steady_clock::now());
  } catch (...) {
    w.spill.reset();
    w.RemoveWorkDir();
    throw;
  }
  w.closed = true;
  w.RemoveWorkDir();
}

uint64_t CopcWriter::num_points() const { return impl_->spill->num_points(); }

const std::string& CopcWriter::path() const { return impl_->path; }

}  // namespace sacfuse
