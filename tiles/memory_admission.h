#pragma once
// Admission of tiles into memory: tiles running at once reserve their estimated bytes from a pool (the memory
// budget minus what the process keeps for itself), so parallel tiles never add up past resources.memory_gb.
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace sacfuse {

class MemoryAdmission {
 public:
  explicit MemoryAdmission(uint64_t pool_bytes) : pool_(pool_bytes) {}

  // Blocks until `bytes` fit next to the current reservations. A request larger than the whole pool is admitted
  // only when nothing else is reserved (callers refuse such tiles before asking: CheckTileFitsBudget,
  // tiles/tile_worker.h).
  void Acquire(uint64_t bytes);
  void Release(uint64_t bytes);

  uint64_t pool() const { return pool_; }
  uint64_t peak_reserved() const;

 private:
  const uint64_t pool_;
  mutable std::mutex mutex_;
  std::condition_variable freed_;
  uint64_t reserved_ = 0, peak_ = 0;
};

// Holds a reservation for one scope.
class MemoryReservation {
 public:
  MemoryReservation(MemoryAdmission& admission, uint64_t bytes) : admission_(admission), bytes_(bytes) {
    admission_.Acquire(bytes_);
  }
  ~MemoryReservation() { admission_.Release(bytes_); }
  MemoryReservation(const MemoryReservation&) = delete;
  MemoryReservation& operator=(const MemoryReservation&) = delete;

 private:
  MemoryAdmission& admission_;
  uint64_t bytes_;
};

}  // namespace sacfuse
