#include "jobs/cluster_table_cache.h"

#include "io/superpixel_io.h"

namespace sacfuse {

std::shared_ptr<const ClusterTableCache::Table> ClusterTableCache::Get(const std::string& path) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = entries_.find(path);
    if (it != entries_.end()) {
      lru_.splice(lru_.begin(), lru_, it->second.lru);
      ++hits_;
      return it->second.table;
    }
    ++misses_;
  }
  // Loaded without the lock (two tiles missing the same table at once both read it; the second insert wins).
  auto table = std::make_shared<const Table>(ReadSuperpixelClusters(path));
  const uint64_t bytes = table->size() * sizeof(SuperpixelCluster);
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = entries_.find(path);
  if (it != entries_.end()) return it->second.table;
  lru_.push_front(path);
  entries_[path] = Entry{table, lru_.begin(), bytes};
  bytes_ += bytes;
  EvictOverBudget();
  return table;
}

void ClusterTableCache::EvictOverBudget() {
  // The most recent entry always stays, even when it alone exceeds the budget.
  while (bytes_ > budget_bytes_ && lru_.size() > 1) {
    const std::string victim = lru_.back();
    lru_.pop_back();
    auto it = entries_.find(victim);
    bytes_ -= it->second.bytes;
    entries_.erase(it);
  }
}

uint64_t ClusterTableCache::bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}
uint64_t ClusterTableCache::hits() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}
uint64_t ClusterTableCache::misses() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return misses_;
}

}  // namespace sacfuse
