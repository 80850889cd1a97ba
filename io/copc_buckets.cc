#include "io/copc_buckets.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>

#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/las_format.h"
#include "io/unique_file.h"

namespace sacfuse::copc {
namespace lf = las_format;
namespace {

constexpr size_t kReadRecords = size_t{1} << 16;
constexpr size_t kLoadPartBytes = size_t{8} << 20;  // a bucket is loaded in parts of this size, in parallel

using File = UniqueFile;

File Open(const std::string& path, const char* mode) {
  File f(std::fopen(path.c_str(), mode));
  if (!f) throw Error(path + ": cannot open (" + std::string(std::strerror(errno)) + ")");
  return f;
}

void ReadAt(FILE* f, uint64_t offset, uint8_t* out, size_t bytes, const std::string& path) {
  if (fseeko(f, static_cast<off_t>(offset), SEEK_SET) != 0 || std::fread(out, 1, bytes, f) != bytes) {
    throw Error(path + ": cannot read " + std::to_string(bytes) + " bytes at " + std::to_string(offset));
  }
}

// Levels to descend so that a node of `points` points splits into nodes of about max_points / 3 (2.5D: 4 per
// level): ceil(log4(3 points / max_points)), at least 1.
int LevelsFor(uint64_t points, uint64_t max_points) {
  int levels = 1;
  while (levels < 10 && (uint64_t{1} << (2 * levels)) * max_points < 3 * points) ++levels;
  return levels;
}

// Appends records to the bucket file of their node at one level.
class Distributor {
 public:
  Distributor(const Cube& cube, int level, size_t record_length, size_t buffer_bytes, const std::string& dir)
      : cube_(cube), level_(level), record_length_(record_length), buffer_bytes_(buffer_bytes), dir_(dir) {}

  // The node of a record at the level (any thread).
  VoxelKey KeyOf(const uint8_t* record) const {
    const int32_t stored[3] = {lf::GetI32(record), lf::GetI32(record + 4), lf::GetI32(record + 8)};
    return cube_.KeyOf(stored, level_);
  }

  // Appends a record to the bucket of `key` (= KeyOf(record)).
  void Add(const uint8_t* record, const VoxelKey& key) {
    if (last_ == nullptr || !(key == last_key_)) {  // consecutive records mostly share their node
      last_ = &buffers_[key];
      last_key_ = key;
    }
    std::vector<uint8_t>& buffer = *last_;
    buffer.insert(buffer.end(), record, record + record_length_);
    buffered_ += record_length_;
    if (buffered_ >= buffer_bytes_) Flush();
  }

  std::vector<Bucket> Finish() {
    Flush();
    std::vector<Bucket> buckets;
    for (const auto& [key, points] : points_) buckets.push_back({key, PathOf(key), 0, points});
    return buckets;
  }

 private:
  std::string PathOf(const VoxelKey& key) const {
    return (std::filesystem::path(dir_) / (key.ToString() + ".pts")).string();
  }

  void Flush() {
    for (auto& [key, buffer] : buffers_) {
      if (buffer.empty()) continue;
      const std::string path = PathOf(key);
      File f = Open(path, "ab");
      if (std::fwrite(buffer.data(), 1, buffer.size(), f.get()) != buffer.size() || std::fflush(f.get()) != 0) {
        throw Error(path + ": write failed (disk full?): " + std::strerror(errno));
      }
      points_[key] += buffer.size() / record_length_;
      std::vector<uint8_t>().swap(buffer);  // give the memory back: the next flush may come from other nodes
    }
    buffered_ = 0;
  }

  const Cube& cube_;
  const int level_;
  const size_t record_length_;
  const size_t buffer_bytes_;
  const std::string dir_;
  std::map<VoxelKey, std::vector<uint8_t>> buffers_;
  std::map<VoxelKey, uint64_t> points_;
  size_t buffered_ = 0;
  VoxelKey last_key_;
  std::vector<uint8_t>* last_ = nullptr;  // buffers_[last_key_] (map entries stay where they are)
};

// Distributes the records of `source` to the nodes of `level`.
std::vector<Bucket> Distribute(const Bucket& source, size_t record_length, const Cube& cube, int level,
                               size_t buffer_bytes, const std::string& dir) {
  Distributor out(cube, level, record_length, buffer_bytes, dir);
  File in = Open(source.path, "rb");
  std::vector<uint8_t> block;
  std::vector<VoxelKey> keys;
  for (uint64_t done = 0; done < source.points;) {
    const size_t n = static_cast<size_t>(std::min<uint64_t>(kReadRecords, source.points - done));
    block.resize(n * record_length);
    ReadAt(in.get(), source.offset + done * record_length, block.data(), block.size(), source.path);
    keys.resize(n);  // the records' nodes in parallel, then appended in order
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) keys[i] = out.KeyOf(&block[i * record_length]);
    });
    for (size_t i = 0; i < n; ++i) out.Add(&block[i * record_length], keys[i]);
    done += n;
  }
  return out.Finish();
}

}  // namespace

std::vector<Bucket> MakeBuckets(const std::string& las_path, uint64_t point_offset, uint64_t count,
                                size_t record_length, const Cube& cube, uint64_t max_points, size_t buffer_bytes,
                                const std::string& dir) {
  const Bucket all{VoxelKey{}, las_path, point_offset, count};
  if (count <= max_points || cube.max_node_level() < 1) return {all};
  std::vector<Bucket> todo =
      Distribute(all, record_length, cube, std::min(LevelsFor(count, max_points), cube.max_node_level()),
                 buffer_bytes, dir);
  std::vector<Bucket> done;
  while (!todo.empty()) {
    const Bucket b = todo.back();
    todo.pop_back();
    if (b.points <= max_points || b.key.level >= cube.max_node_level()) {
      done.push_back(b);
      continue;
    }
    const int level = std::min(b.key.level + LevelsFor(b.points, max_points), cube.max_node_level());
    for (const Bucket& child : Distribute(b, record_length, cube, level, buffer_bytes, dir)) todo.push_back(child);
    std::filesystem::remove(b.path);
  }
  return done;
}

std::unique_ptr<uint8_t[]> LoadBucket(const Bucket& bucket, size_t record_length) {
  const size_t bytes = static_cast<size_t>(bucket.points) * record_length;
  // Not zeroed first: every byte is read. Parts read in parallel (the pages are mapped as they are read into).
  std::unique_ptr<uint8_t[]> records(new uint8_t[std::max<size_t>(bytes, 1)]);
  File in = Open(bucket.path, "rb");
  const int fd = ::fileno(in.get());
  const size_t parts = (bytes + kLoadPartBytes - 1) / kLoadPartBytes;
  tbb::parallel_for(size_t{0}, parts, [&](size_t part) {
    const size_t first = part * kLoadPartBytes, last = std::min(bytes, first + kLoadPartBytes);
    for (size_t at = first; at < last;) {
      const ssize_t got = ::pread(fd, records.get() + at, last - at, static_cast<off_t>(bucket.offset + at));
      if (got <= 0) {
        throw Error(bucket.path + ": cannot read " + std::to_string(last - at) + " bytes at " +
                    std::to_string(bucket.offset + at) + (got < 0 ? " (" + std::string(std::strerror(errno)) + ")"
                                                                  : std::string(" (the file ends before)")));
      }
      at += static_cast<size_t>(got);
    }
  });
  return records;
}

}  // namespace sacfuse::copc
