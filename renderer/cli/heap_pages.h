// The process's heap in transparent huge pages. A fresh 4 KiB page costs the process a fault and
// its zeroing at first touch; on the KVM guest of docs/performance.md that is 11 µs a page, while
// an aligned 2 MiB huge page costs about 150 µs (0.3 µs a 4 KiB of it). A 1000-component scene's
// load grows the heap to 2.3 MB: 590 faults, 6.5 ms of a 30 ms run. The heap's memory is the C
// library's, so this asks it (glibc's mallopt) to serve blocks below 16 MiB from the heap's top
// and keep what is freed there, grows the top by `bytes` past its next 2 MiB boundary, keeps the
// front up to that boundary out of use (virtual memory only: nothing touches it but one header),
// and advises the kernel to back the rest with huge pages (MADV_HUGEPAGE; its default "madvise"
// mode grants them only so). The heap then carves its blocks from the boundary on. Advice only:
// where the kernel has no huge pages, or the C library is another, the pages are ordinary ones.
// The film's planes have their own mappings (film/plane_memory.h).
#pragma once

#include <cstddef>
#include <cstdint>

namespace softtrace {

// The heap's range advised for huge pages, [begin, end); empty where nothing was advised.
struct HeapPages {
  uintptr_t begin = 0, end = 0;
};

// Once, at the program's start, before the work that fills the heap; `bytes` rounds up to 2 MiB.
HeapPages heap_in_huge_pages(size_t bytes);

// The same for the calling thread's own heap, on a worker thread at its start, after the
// process's heap_in_huge_pages: glibc gives each thread that allocates a malloc arena of its own
// (one arena shared by all made fig12b's frames contend for its lock, session 34), and each fresh
// 4 KiB page of it cost a fault: meets1's worker touched 150 (its frame's scratch, its PNG bands'
// deflate state), 1.6-2.0 ms of CPU on this guest, where a huge page is one fault of 0.15-0.3 ms.
// The first huge page is also filled now (MADV_POPULATE_WRITE), while the caller loads the
// scene, not at the frame's first tile.
HeapPages thread_heap_in_huge_pages(size_t bytes);

}  // namespace softtrace
