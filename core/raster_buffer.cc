#include "core/raster_buffer.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace sacfuse {
namespace {

constexpr size_t kPageBytes = 4096;

size_t RoundUp(size_t bytes, size_t unit) { return (bytes + unit - 1) / unit * unit; }

}  // namespace

void* AllocateRasterBuffer(size_t bytes) {
  if (bytes < kHugePageBytes) return ::operator new(bytes);
#if defined(__linux__)
  // Fresh zero pages from the kernel, never touched (so the first touch maps huge pages): one huge page more than
  // needed, trimmed to a run that starts on a huge page. Its length is rounded to small pages only, so the last
  // partial huge page stays in small pages and is not held whole.
  const size_t rounded = RoundUp(bytes, kPageBytes);
  void* raw = mmap(nullptr, rounded + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t begin = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (begin + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (aligned > begin) munmap(raw, aligned - begin);
  const uintptr_t end = begin + rounded + kHugePageBytes;
  if (end > aligned + rounded) munmap(reinterpret_cast<void*>(aligned + rounded), end - (aligned + rounded));
  void* p = reinterpret_cast<void*>(aligned);
#if defined(MADV_HUGEPAGE)
  madvise(p, rounded, MADV_HUGEPAGE);  // advice only: where it is refused the buffer keeps ordinary pages
#endif
  return p;
#else
  const size_t rounded = RoundUp(bytes, kHugePageBytes);
  void* p = std::aligned_alloc(kHugePageBytes, rounded);
  if (p == nullptr) throw std::bad_alloc();
  std::memset(p, 0, rounded);  // the contract: a large buffer starts zero (RasterBufferIsZeroed)
  return p;
#endif
}

void FreeRasterBuffer(void* p, size_t bytes) noexcept {
  if (p == nullptr) return;
  if (bytes < kHugePageBytes) {
    ::operator delete(p);
    return;
  }
#if defined(__linux__)
  munmap(p, RoundUp(bytes, kPageBytes));
#else
  std::free(p);
#endif
}

}  // namespace sacfuse
