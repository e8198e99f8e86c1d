// An allocator whose blocks begin on a cache line and fill their last one, so that no other block
// of the heap shares a line with them: for a thread's scratch that it writes at every evaluation
// (Workspace's buffers, the pruned view) while the other threads read the program's small blocks,
// which the heap places among them. A line written by one thread and read by another moves
// between their cores at every write: with the main thread's buffers sharing lines with the
// program's children and args, Fig. 12(b)'s 2-thread process (640x480) took 175-260 ms of CPU
// by the layout its command line's strings left, against 160-165 ms in every layout with this.
#pragma once

#include <cstddef>
#include <new>

namespace softtrace {

template <class T>
struct OwnLines {
  using value_type = T;
  static constexpr size_t kLine = 64;

  OwnLines() = default;
  template <class U>
  constexpr OwnLines(const OwnLines<U>&) noexcept {}

  static size_t bytes(size_t n) { return (n * sizeof(T) + kLine - 1) / kLine * kLine; }
  T* allocate(size_t n) {
    return static_cast<T*>(::operator new(bytes(n), std::align_val_t(kLine)));
  }
  // The unsized form: clang declares the sized one only under -fsized-deallocation.
  void deallocate(T* p, size_t) noexcept { ::operator delete(p, std::align_val_t(kLine)); }
  template <class U>
  bool operator==(const OwnLines<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const OwnLines<U>&) const noexcept {
    return false;
  }
};

}  // namespace softtrace
