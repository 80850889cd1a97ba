#include "tiles/memory_admission.h"

#include <algorithm>

namespace sacfuse {

void MemoryAdmission::Acquire(uint64_t bytes) {
  std::unique_lock<std::mutex> lock(mutex_);
  freed_.wait(lock, [&] { return reserved_ == 0 || reserved_ + bytes <= pool_; });
  reserved_ += bytes;
  peak_ = std::max(peak_, reserved_);
}

void MemoryAdmission::Release(uint64_t bytes) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    reserved_ -= std::min(reserved_, bytes);
  }
  freed_.notify_all();
}

uint64_t MemoryAdmission::peak_reserved() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return peak_;
}

}  // namespace sacfuse
