#pragma once
// Superpixel cluster tables shared by the tiles of one process: every tile that sees a view needs that view's
// whole cluster table (20 bytes per cluster, ~4 MB for a 50 Mpx view), so neighbouring tiles (and tiles running
// in parallel) reuse a loaded table instead of reading and validating it again. Least recently used tables are
// dropped once the byte budget is exceeded (a table in use by a tile stays alive through its shared_ptr).
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/superpixels.h"

namespace sacfuse {

class ClusterTableCache {
 public:
  using Table = std::vector<SuperpixelCluster>;
  explicit ClusterTableCache(uint64_t budget_bytes) : budget_bytes_(budget_bytes) {}

  // The cluster table of a superpixel cache file, loaded on a miss (io/superpixel_io.h; throws InputError for a
  // bad file). Thread-safe.
  std::shared_ptr<const Table> Get(const std::string& path);

  uint64_t bytes() const;   // held by the cache now
  uint64_t hits() const;
  uint64_t misses() const;

 private:
  struct Entry {
    std::shared_ptr<const Table> table;
    std::list<std::string>::iterator lru;  // position in lru_ (front = most recent)
    uint64_t bytes = 0;
  };
  void EvictOverBudget();  // with mutex_ held

  const uint64_t budget_bytes_;
  mutable std::mutex mutex_;
  std::list<std::string> lru_;
  std::unordered_map<std::string, Entry> entries_;
  uint64_t bytes_ = 0, hits_ = 0, misses_ = 0;
};

}  // namespace sacfuse
