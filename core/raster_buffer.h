#pragma once
// Where the rasters (core/raster.h) keep their values. Buffers of at least kHugePageBytes are fresh pages from the
// kernel, aligned to a huge page and, on Linux, advised for transparent huge pages (madvise(MADV_HUGEPAGE)) before
// their first use; smaller ones come from the ordinary heap. Why (issue 48):
// - A 50 Mpx view's depth map, image and colours are freshly allocated for every view a run reads. With 4 KiB
//   pages each such buffer costs one page fault per 4 KiB at its first touch (on a virtual machine each fault is
//   dear), and zero-filling it first touches it twice. On the full Dortmund block the superpixel stage spent about
//   40 % of its CPU time in memset and page faults. With 2 MiB pages a 200 MB map faults 100 times, not 50,000.
// - SAC reads the depth maps, labels and verdicts of ~40 views at every pixel's projections; huge pages cover them
//   with far fewer TLB entries.
// A large buffer is zero when it is handed out (the kernel's fresh pages), so a raster filled with zeros needs no
// pass of its own (RasterBufferIsZeroed). RasterAllocator default-initialises (a `resize` without a value leaves
// trivial values as the buffer has them): core/raster.h only grows its buffer at construction, where it writes the
// fill unless the buffer is already zero, or in Raster::Uninitialized, whose caller writes every value.
// The values, and so every result, are the same as with std::allocator; only where the bytes lie differs. Where the
// kernel has transparent huge pages off (/sys/kernel/mm/transparent_hugepage/enabled = never) the advice is ignored.
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace sacfuse {

inline constexpr size_t kHugePageBytes = size_t{2} << 20;

// Allocates `bytes` (> 0). From kHugePageBytes up: aligned to kHugePageBytes, with the huge-page advice, and zero
// (RasterBufferIsZeroed); below: operator new. Throws std::bad_alloc. Free with FreeRasterBuffer(p, bytes).
void* AllocateRasterBuffer(size_t bytes);
void FreeRasterBuffer(void* p, size_t bytes) noexcept;

// Whether a buffer of `bytes` from AllocateRasterBuffer holds only zero bytes when it is handed out.
inline bool RasterBufferIsZeroed(size_t bytes) { return bytes >= kHugePageBytes; }

template <typename T>
struct RasterAllocator {
  using value_type = T;
  RasterAllocator() noexcept = default;
  template <typename U>
  RasterAllocator(const RasterAllocator<U>&) noexcept {}  // NOLINT: converting, as std::allocator
  T* allocate(size_t n) { return static_cast<T*>(AllocateRasterBuffer(n * sizeof(T))); }
  void deallocate(T* p, size_t n) noexcept { FreeRasterBuffer(p, n * sizeof(T)); }
  // Default-initialisation: no value is written where none is given.
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const RasterAllocator<U>&) const noexcept {
    return true;
  }
  template <typename U>
  bool operator!=(const RasterAllocator<U>&) const noexcept {
    return false;
  }
};

}  // namespace sacfuse
