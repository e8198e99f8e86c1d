// The mesh's arrays: std::vector with an allocator whose resize(n) leaves the new elements
// unwritten. The mesher sizes its arrays (a 1024^3 mesh's are ~1.5 GB) and then writes every
// element on its threads; a std::vector would first zero-fill them on one thread, and fresh
// pages cost about 1 s a gigabyte at first write on this machine (docs/performance.md
// "Meshing"), so the first write is left to the threads. Elements made with values (push_back,
// resize(n, value), assign) are constructed as usual.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace softtrace {

template <class T>
struct UninitializedAllocator {
  using value_type = T;

  UninitializedAllocator() = default;
  template <class U>
  constexpr UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}

  T* allocate(size_t n) { return std::allocator<T>().allocate(n); }
  void deallocate(T* p, size_t n) noexcept { std::allocator<T>().deallocate(p, n); }

  // Made without a value: left as the storage was (only for types whose bytes are their value,
  // e.g. Vec3, whose default constructor would write zeros).
  template <class U>
  void construct(U*) noexcept {
    static_assert(std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>,
                  "only plain values may be left unwritten");
  }
  template <class U, class A, class... Rest>
  void construct(U* p, A&& a, Rest&&... rest) {
    ::new (static_cast<void*>(p)) U(std::forward<A>(a), std::forward<Rest>(rest)...);
  }
};

template <class T, class U>
constexpr bool operator==(const UninitializedAllocator<T>&, const UninitializedAllocator<U>&) {
  return true;
}
template <class T, class U>
constexpr bool operator!=(const UninitializedAllocator<T>&, const UninitializedAllocator<U>&) {
  return false;
}

// resize(n) leaves the new elements unwritten; everything else is std::vector's.
template <class T>
using MeshArray = std::vector<T, UninitializedAllocator<T>>;

}  // namespace softtrace
