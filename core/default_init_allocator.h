#pragma once
// An allocator whose value-less construction default-initialises: std::vector<T, DefaultInitAllocator<T>>::resize
// leaves trivial elements (integers, floats) uninitialised instead of zero-filling them. For buffers that parallel
// code fills completely right after growing them: the zero fill would be a serial pass over fresh memory (and take
// all of its page faults on one thread) before the threads start.
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace sacfuse {

template <typename T>
class DefaultInitAllocator : public std::allocator<T> {
 public:
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  using std::allocator<T>::allocator;

  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace sacfuse
