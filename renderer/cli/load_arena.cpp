#include "cli/load_arena.h"

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <new>

#if defined(__SANITIZE_ADDRESS__)
#define SOFTTRACE_LOAD_ARENA 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SOFTTRACE_LOAD_ARENA 0
#endif
#endif
#ifndef SOFTTRACE_LOAD_ARENA
#define SOFTTRACE_LOAD_ARENA 1
#endif

#if SOFTTRACE_LOAD_ARENA

namespace softtrace {

namespace {

// A chunk is taken from the C library, so from the heap's top in huge pages (heap_pages.h); 1 MiB
// holds a 1000-component scene's load in about three. The table's length bounds the chunks'
// total (64 MiB, a 40,000-component load); past it the blocks come from the C library again.
constexpr size_t kChunkBytes = size_t(1) << 20;
constexpr int kMaxChunks = 64;
// operator new's blocks are aligned for any type of at most this alignment (the C library's).
constexpr size_t kAlignment = __STDCPP_DEFAULT_NEW_ALIGNMENT__;

struct Chunk {
  uintptr_t begin = 0, end = 0;
};
// Written under g_grow, each entry before the count that shows it (release); read by any thread's
// delete without a lock (acquire). A thread's own blocks are in chunks it has seen counted.
Chunk g_chunks[kMaxChunks];
std::atomic<int> g_chunk_count{0};
std::mutex g_grow;
// The chunks' hull [g_lowest, g_highest), which only widens: each bound written under g_grow
// before the count (release), so a delete that sees a chunk counted sees a hull holding it. A
// block outside it (the library's taken before the first chunk or after the last, another
// thread's) is told by two comparisons, without the table's loop; one inside still asks the table
// (the library's large blocks of the load lie between chunks).
std::atomic<uintptr_t> g_lowest{UINTPTR_MAX}, g_highest{0};

thread_local bool t_active = false;
thread_local char* t_next = nullptr;
thread_local char* t_end = nullptr;
// The blocks deleted with their size inside a scope, by size class (their size over
// kAlignment), each linked through its first word: the class's next block is the last one freed.
// Without them the load's temporaries (the Params and strings of 3000 distinct components) took
// 3.3 MB more than the document and pushed the heap past its huge pages: 200 more page faults.
constexpr size_t kClasses = kLoadArenaLargestBlock / kAlignment + 1;
thread_local void* t_freed[kClasses] = {};

bool held(const void* p) {
  const uintptr_t a = reinterpret_cast<uintptr_t>(p);
  const int n = g_chunk_count.load(std::memory_order_acquire);
  if (a < g_lowest.load(std::memory_order_relaxed) ||
      a >= g_highest.load(std::memory_order_relaxed))
    return false;
  for (int i = 0; i < n; ++i)
    if (a - g_chunks[i].begin < g_chunks[i].end - g_chunks[i].begin) return true;
  return false;
}

// A new chunk for the calling thread, or false when the table is full or the C library has none.
bool grow() {
  const std::lock_guard<std::mutex> lock(g_grow);
  const int n = g_chunk_count.load(std::memory_order_relaxed);
  if (n == kMaxChunks) return false;
  char* const chunk = static_cast<char*>(std::malloc(kChunkBytes));
  if (!chunk) return false;
  g_chunks[n] = {reinterpret_cast<uintptr_t>(chunk),
                 reinterpret_cast<uintptr_t>(chunk) + kChunkBytes};
  if (g_chunks[n].begin < g_lowest.load(std::memory_order_relaxed))
    g_lowest.store(g_chunks[n].begin, std::memory_order_relaxed);
  if (g_chunks[n].end > g_highest.load(std::memory_order_relaxed))
    g_highest.store(g_chunks[n].end, std::memory_order_relaxed);
  g_chunk_count.store(n + 1, std::memory_order_release);
  t_next = chunk;
  t_end = chunk + kChunkBytes;
  return true;
}

// Zero bytes still take a block of their own: each new-expression's pointer is distinct.
size_t block_size(size_t bytes) {
  return bytes == 0 ? kAlignment : (bytes + kAlignment - 1) & ~(kAlignment - 1);
}

// operator new's other ways, apart so that its common one saves no registers: a block from a new
// chunk, else the library's operator new (malloc, the new-handler while it has none, bad_alloc
// without one).
[[gnu::noinline]] void* new_block(size_t bytes) {
  if (t_active && bytes <= kLoadArenaLargestBlock && grow()) {
    void* const p = t_next;
    t_next += block_size(bytes);
    return p;
  }
  for (;;) {
    if (void* p = std::malloc(bytes ? bytes : 1)) return p;
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

}  // namespace

LoadArena::LoadArena() : outer_active_(t_active) {
  t_active = true;
}

LoadArena::~LoadArena() {
  t_active = outer_active_;
}

bool load_arena_holds(const void* p) {
  return held(p);
}

}  // namespace softtrace

// The C++ runtime's other forms (arrays, nothrow) call these three; the aligned forms keep their
// own allocation and free, which never see a chunk's block. A block deleted without its size, or
// outside a scope, stays where it is until exit.
void* operator new(std::size_t bytes) {
  if (softtrace::t_active && bytes <= softtrace::kLoadArenaLargestBlock) {
    const size_t size = softtrace::block_size(bytes);
    void*& freed = softtrace::t_freed[size / softtrace::kAlignment];
    if (void* const q = freed) {
      freed = *static_cast<void**>(q);
      return q;
    }
    char* const p = softtrace::t_next;
    if (size_t(softtrace::t_end - p) >= size) {
      softtrace::t_next = p + size;
      return p;
    }
  }
  return softtrace::new_block(bytes);
}

void operator delete(void* p) noexcept {
  if (!softtrace::held(p)) std::free(p);
}

void operator delete(void* p, std::size_t bytes) noexcept {
  if (!softtrace::held(p)) {
    std::free(p);
  } else if (softtrace::t_active) {
    void*& freed = softtrace::t_freed[softtrace::block_size(bytes) / softtrace::kAlignment];
    *static_cast<void**>(p) = freed;
    freed = p;
  }
}

#else

namespace softtrace {

LoadArena::LoadArena() : outer_active_(false) {}

LoadArena::~LoadArena() = default;

bool load_arena_holds(const void*) {
  return false;
}

}  // namespace softtrace

#endif
