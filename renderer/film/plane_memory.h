// The memory of the film's planes. A fresh plane costs the process a page fault per 4 KiB it
// touches (the kernel zeroes each page); a 320x240 frame's RGBA plane was 300 faults, 37 % of the
// whole process's, and 640x480's 1,200 (about 1.2 ms). A plane of 1 MiB or more is mapped on its
// own, 2 MiB-aligned and in whole 2 MiB, and asked for transparent huge pages (MADV_HUGEPAGE;
// the kernel's default "madvise" mode grants them only so): one fault per 2 MiB, and the same
// 1.2 MB zeroed in 69 instead of 283 µs here. Where the kernel has none to give, the pages are
// ordinary ones, as before. Smaller planes, builds under AddressSanitizer (which watches only its
// own heap) and systems without huge pages take the ordinary heap. A process whose heaps are in
// huge pages already (the command line's, cli/heap_pages.h) raises the bound for its planes
// (planes_from_heap_below).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>

namespace softtrace {

// x86-64's transparent huge page, and `x` (a length or an address) rounded up to a whole number
// of them: a huge page backs only an aligned 2 MiB of advised memory (the planes here, and the
// heap's advised range, cli/heap_pages.h).
constexpr size_t kHugePage = size_t(1) << 21;
constexpr uintptr_t huge_page_ceil(uintptr_t x) {
  return (x + kHugePage - 1) / kHugePage * kHugePage;
}

// `bytes` of memory for a plane, aligned for any scalar and zero; throws std::bad_alloc.
void* plane_allocate(size_t bytes);
// Frees what plane_allocate(bytes) gave, with the same `bytes`.
void plane_free(void* p, size_t bytes) noexcept;
// Whether plane_allocate(bytes) maps the plane on its own (asking for huge pages).
bool plane_mapped(size_t bytes);
// Planes below `bytes` (1 MiB at least, the default) come from the heap from now on: for a process
// whose heaps are in huge pages, where a 320x240 frame's RGBA plane (1.2 MB) then lies in its
// thread's huge page, made already (the heap's first, or the worker's, filled at its start),
// instead of a 2 MiB page zeroed for it alone and four system calls. Once, before any plane is
// made: plane_free tells how a plane was made from its size, by the rule in force.
void planes_from_heap_below(size_t bytes);

template <class T>
struct PlaneAllocator {
  using value_type = T;
  PlaneAllocator() = default;
  template <class U>
  PlaneAllocator(const PlaneAllocator<U>&) noexcept {}
  T* allocate(size_t n) { return static_cast<T*>(plane_allocate(n * sizeof(T))); }
  void deallocate(T* p, size_t n) noexcept { plane_free(p, n * sizeof(T)); }
  // An element made without a value is left as allocate() gave it, zero: a plane's value-
  // initialisation wrote every byte again (meets1 640x480: 4.9 M instructions, the RGBA plane's
  // 4.9 MB, though a fresh mapping is zero already).
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const PlaneAllocator<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const PlaneAllocator<U>&) const noexcept {
    return false;
  }
};

// A plane of the film: samples in row order, zero as made (its memory is: PlaneAllocator). Its
// size is set once, as it is made: grown again within its capacity (resize() after a shrink) it
// would keep the old values.
using FilmPlane = std::vector<float, PlaneAllocator<float>>;

}  // namespace softtrace
