// The scene's load's small blocks taken in order from large chunks, for the two programs. A
// 1000-component scene's load asks operator new for about 22,000 blocks (its JSON document's
// nodes, strings and arrays, then the components' nodes and their Params), which the C library
// carved one by one from its heap's top at about 175 instructions each, a fifth of the load.
// Here each is a pointer bump. A block freed is not reused: the load's temporaries stay until
// exit, next to the document and the components that do anyway (a render process ends with
// _exit, the scene never freed). So the programs replace the global operator new and delete
// (load_arena.cpp): delete leaves the chunks' blocks alone and frees every other block as before.
// Sanitizer builds keep the C library's allocator for every block, so that it still checks them.
#pragma once

#include <cstddef>

namespace softtrace {

// While one lives, operator new on the calling thread takes blocks of up to
// kLoadArenaLargestBlock bytes from the chunks; larger ones, and every other thread's, come from
// the C library as before. Scopes nest.
class LoadArena {
 public:
  LoadArena();
  ~LoadArena();
  LoadArena(const LoadArena&) = delete;
  LoadArena& operator=(const LoadArena&) = delete;

 private:
  [[maybe_unused]] bool outer_active_;  // a sanitizer build has no arena to restore
};

// Larger blocks are the load's few big vectors (a 1000-component blend's list of children), which
// the C library takes as cheaply and whose copies, grown, would waste a chunk's space.
constexpr size_t kLoadArenaLargestBlock = 1024;

// Whether `p` lies in one of the chunks (any thread's); false in a sanitizer build.
bool load_arena_holds(const void* p);

}  // namespace softtrace
