#include "film/plane_memory.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <new>

#if defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
#include <sys/mman.h>
#if defined(MADV_HUGEPAGE)
#define SOFTTRACE_PLANE_HUGE_PAGES 1
#endif
#endif

namespace softtrace {

namespace {

// The heap's memory is not zero when it is reused: zeroed here, as the plane's own (std::vector's
// value-initialisation, which PlaneAllocator::construct leaves out) was.
void* heap_zeroed(size_t bytes) {
  void* const p = ::operator new(bytes);
  std::memset(p, 0, bytes);
  return p;
}

}  // namespace

#ifdef SOFTTRACE_PLANE_HUGE_PAGES

namespace {

constexpr size_t kMapped = size_t(1) << 20;  // a plane this large or larger is mapped on its own
std::atomic<size_t> g_mapped_from{kMapped};  // planes_from_heap_below's

}  // namespace

bool plane_mapped(size_t bytes) {
  return bytes >= g_mapped_from.load(std::memory_order_relaxed);
}

void planes_from_heap_below(size_t bytes) {
  g_mapped_from.store(std::max(bytes, kMapped), std::memory_order_relaxed);
}

void* plane_allocate(size_t bytes) {
  if (!plane_mapped(bytes)) return heap_zeroed(bytes);
  if (bytes > SIZE_MAX - 2 * kHugePage) throw std::bad_alloc();
  // Mapped with a huge page's worth to spare, then the unaligned ends given back: a huge page
  // covers only an aligned 2 MiB of the mapping.
  const size_t length = huge_page_ceil(bytes);
  void* const m = ::mmap(nullptr, length + kHugePage, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t start = reinterpret_cast<uintptr_t>(m);
  const uintptr_t aligned = huge_page_ceil(start);
  if (aligned > start) ::munmap(m, aligned - start);
  ::munmap(reinterpret_cast<void*>(aligned + length), start + kHugePage - aligned);
  void* const p = reinterpret_cast<void*>(aligned);
  ::madvise(p, length, MADV_HUGEPAGE);  // advice only: ordinary pages where it is refused
#if defined(MADV_POPULATE_WRITE)
  // The plane's pages faulted in now, zeroed by the kernel, on the thread that makes it (the
  // render's worker beside the tracers' build), as its value-initialisation did, not by the
  // frame's first writes. Advice only: a kernel without it (before Linux 5.14) faults them then,
  // zero all the same.
  ::madvise(p, bytes, MADV_POPULATE_WRITE);
#endif
  return p;
}

void plane_free(void* p, size_t bytes) noexcept {
  if (!p) return;
  if (plane_mapped(bytes))
    ::munmap(p, huge_page_ceil(bytes));
  else
    ::operator delete(p);
}

#else

bool plane_mapped(size_t) {
  return false;
}

void planes_from_heap_below(size_t) {}

void* plane_allocate(size_t bytes) {
  return heap_zeroed(bytes);
}

void plane_free(void* p, size_t) noexcept {
  ::operator delete(p);
}

#endif

}  // namespace softtrace
