#include "cli/heap_pages.h"

#include <cstdlib>

#include "film/plane_memory.h"

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#include <malloc.h>
#include <sys/mman.h>
#if defined(MADV_HUGEPAGE)
#define SOFTTRACE_HEAP_HUGE_PAGES 1
#endif
#endif

namespace softtrace {

#ifdef SOFTTRACE_HEAP_HUGE_PAGES

namespace {

// Blocks below this come from the heap's top, not from mappings of their own (glibc's default
// threshold starts at 128 KiB), and a top this large stays the process's when blocks are freed.
constexpr int kFromHeapBelow = 16 << 20;
constexpr int kTrimAbove = 32 << 20;
// glibc's block header: a block handed out at p begins 16 bytes before p, and one of n bytes
// asked for takes n + 8 rounded up to 16 (the next block's first word is this one's last).
constexpr size_t kHeader = 16;
constexpr size_t kMinBlock = 32;

// Set once heap_in_huge_pages has set the thresholds, which hold for every thread's arena.
bool g_thresholds_set = false;

// The calling thread's heap's top grown by `bytes` (whole huge pages) past its next 2 MiB
// boundary, the front up to the boundary kept in `front` for the process's life, the rest advised.
HeapPages advise_top(size_t bytes, void*& front) {
  // A block this large comes from the top, which grows to hold it; freed, it is the top again.
  char* const block = static_cast<char*>(std::malloc(bytes + kHugePage));
  if (!block) return {};
  const uintptr_t start = reinterpret_cast<uintptr_t>(block);
  const uintptr_t aligned = huge_page_ceil(start);
  std::free(block);
  // The front, from the top's start to the boundary, as one block kept for the process's life:
  // the next block then begins at the boundary.
  if (aligned - start >= kMinBlock) {
    front = std::malloc(aligned - start - kHeader / 2);
    if (!front) return {};
  }
  if (::madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE) != 0) return {};
  return {aligned, aligned + bytes};
}

}  // namespace

HeapPages heap_in_huge_pages(size_t bytes) {
  bytes = huge_page_ceil(bytes);
  if (bytes == 0 || bytes > size_t(kFromHeapBelow) - kHugePage) return {};
  if (!mallopt(M_MMAP_THRESHOLD, kFromHeapBelow) || !mallopt(M_TRIM_THRESHOLD, kTrimAbove))
    return {};
  g_thresholds_set = true;
  static void* front = nullptr;
  return advise_top(bytes, front);
}

HeapPages thread_heap_in_huge_pages(size_t bytes) {
  bytes = huge_page_ceil(bytes);
  // Without the process's thresholds a freed top of the arena would be trimmed, its advice lost.
  if (!g_thresholds_set || bytes == 0 || bytes > size_t(kFromHeapBelow) - kHugePage) return {};
  thread_local void* front = nullptr;
  const HeapPages range = advise_top(bytes, front);
#if defined(MADV_POPULATE_WRITE)
  // Advice only, as the huge pages are: a kernel without it faults the page at first touch.
  if (range.end > range.begin)
    ::madvise(reinterpret_cast<void*>(range.begin), kHugePage, MADV_POPULATE_WRITE);
#endif
  return range;
}

#else

HeapPages heap_in_huge_pages(size_t) {
  return {};
}

HeapPages thread_heap_in_huge_pages(size_t) {
  return {};
}

#endif

}  // namespace softtrace
