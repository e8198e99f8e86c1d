// The scene's load's blocks from the programs' arena (cli/load_arena.h): inside a scope, the
// calling thread's small blocks come from the chunks, distinct, aligned and writable, those
// deleted with their size taken again; outside it, on other threads and for large blocks, the C
// library's as before. The replaced operator new is global to the executable, hence an executable
// of its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli/heap_pages.h"
#include "cli/load_arena.h"
#include "describe/params.h"
#include "scene/scene.h"

namespace softtrace {
namespace {

bool aligned(const void* p) {
  return reinterpret_cast<uintptr_t>(p) % __STDCPP_DEFAULT_NEW_ALIGNMENT__ == 0;
}

TEST(LoadArena, TheScopesSmallBlocksComeFromTheChunks) {
  std::vector<char*> blocks;
  {
    const LoadArena arena;
    // 3 MB in blocks of 0 to 1024 bytes: more than one chunk.
    for (size_t i = 0; i < 6000; ++i) blocks.push_back(new char[i % (kLoadArenaLargestBlock + 1)]);
  }
  std::set<const char*> distinct;
  for (size_t i = 0; i < blocks.size(); ++i) {
    EXPECT_TRUE(load_arena_holds(blocks[i])) << i;
    EXPECT_TRUE(aligned(blocks[i])) << i;
    distinct.insert(blocks[i]);
    std::memset(blocks[i], int(i & 0xff), i % (kLoadArenaLargestBlock + 1));
  }
  EXPECT_EQ(distinct.size(), blocks.size());
  // No block overlaps another: each still holds what was written to it.
  for (size_t i = 0; i < blocks.size(); ++i)
    for (size_t k = 0; k < i % (kLoadArenaLargestBlock + 1); ++k)
      ASSERT_EQ(blocks[i][k], char(i & 0xff)) << i << " " << k;
  for (char* b : blocks) delete[] b;  // after the scope: left alone, as inside it
}

TEST(LoadArena, OtherBlocksAreTheLibrarys) {
  const std::unique_ptr<int> before(new int(1));
  EXPECT_FALSE(load_arena_holds(before.get()));
  std::unique_ptr<int> in_scope, other_thread;
  std::unique_ptr<char[]> large;
  {
    const LoadArena arena;
    in_scope.reset(new int(2));
    large.reset(new char[kLoadArenaLargestBlock + 1]);
    std::thread([&] { other_thread.reset(new int(3)); }).join();
  }
  const std::unique_ptr<int> after(new int(4));
  EXPECT_TRUE(load_arena_holds(in_scope.get()));
  EXPECT_FALSE(load_arena_holds(large.get()));
  EXPECT_FALSE(load_arena_holds(other_thread.get()));
  EXPECT_FALSE(load_arena_holds(after.get()));
}

// Large blocks taken inside the scope between chunks lie within the chunks' hull, which holds
// every chunk's blocks, and are still the library's: the hull alone decides only for the blocks
// outside it.
TEST(LoadArena, LargeBlocksBetweenChunksAreTheLibrarys) {
  // The programs' heap (cli/heap_pages.h): the chunks and the large blocks from its top, in the
  // order they are taken.
  heap_in_huge_pages(size_t(12) << 20);
  const auto address = [](const void* p) { return reinterpret_cast<uintptr_t>(p); };
  std::vector<char*> small;
  std::vector<std::unique_ptr<char[]>> large;
  {
    const LoadArena arena;
    // Two chunks' worth of small blocks, a large one after every hundred.
    for (int i = 0; i < 4200; ++i) {
      small.push_back(new char[kLoadArenaLargestBlock / 2]);
      if (i % 100 == 0) large.emplace_back(new char[kLoadArenaLargestBlock + 1 + size_t(i)]);
    }
  }
  uintptr_t lowest = UINTPTR_MAX, highest = 0;
  for (const char* b : small) {
    ASSERT_TRUE(load_arena_holds(b));
    lowest = std::min(lowest, address(b));
    highest = std::max(highest, address(b));
  }
  int between = 0;
  for (const std::unique_ptr<char[]>& b : large) {
    EXPECT_FALSE(load_arena_holds(b.get()));
    between += lowest < address(b.get()) && address(b.get()) < highest;
  }
  EXPECT_GT(between, 0);  // where the hull's test alone would say held
}

// A block deleted with its size inside the scope is the next one of its size class (the load's
// temporaries would otherwise grow the heap past its huge pages); one deleted after the scope is
// left alone.
TEST(LoadArena, ABlockFreedInTheScopeIsTakenAgain) {
  // Addresses as numbers: a freed block's pointer is not to be used, only compared.
  const auto address = [](const void* p) { return reinterpret_cast<uintptr_t>(p); };
  uintptr_t after = 0;
  {
    const LoadArena arena;
    void* const first = ::operator new(40);
    const uintptr_t freed = address(first);
    ::operator delete(first, 40);
    EXPECT_EQ(address(::operator new(48)), freed) << "the same size class (48 bytes)";
    void* const kept = ::operator new(24);
    after = address(kept);
    EXPECT_NE(address(::operator new(24)), after);
    ::operator delete(kept, 24);
    EXPECT_EQ(address(::operator new(24)), after);
    after = address(::operator new(24));
  }
  // Deleted out of the scope: left alone, not taken by the next scope.
  ::operator delete(reinterpret_cast<void*>(after), 24);
  const LoadArena arena;
  EXPECT_NE(address(::operator new(24)), after);
}

TEST(LoadArena, ScopesNest) {
  std::unique_ptr<int> inner, outer_after;
  {
    const LoadArena outer;
    {
      const LoadArena nested;
      inner.reset(new int(1));
    }
    outer_after.reset(new int(2));
  }
  EXPECT_TRUE(load_arena_holds(inner.get()));
  EXPECT_TRUE(load_arena_holds(outer_after.get()));
}

// A scene loaded in a scope is the one loaded without: its document value for value, and its
// error the same words; the document, destroyed after the scope, leaves the chunks be.
TEST(LoadArena, AScenesLoadInItIsTheSame) {
  // 300 alike children; in `bad` the last one's "n" is refused, at its own JSON pointer.
  const auto scene_text = [](const char* last_n) {
    std::string children;
    for (int i = 0; i < 300; ++i)
      children += std::string(i ? "," : "") +
                  R"({"type": "soft_object", "potential": {"type": "murakami"}, "distance": )"
                  R"({"type": "lp_metric", "radii": [0.7, 0.7, 0.7], "n": )" +
                  (i == 299 ? last_n : "2") + R"(}, "translate": [)" + std::to_string(i) +
                  ", 0.5, -1]}";
    return R"({"camera": {"eye": [0, -40, 5], "target": [0, 0, 0]}, "objects": [)"
           R"({"field": {"type": "soft_blend", "children": [)" +
           children + "]}}]}";
  };
  const std::string text = scene_text("2");
  const Scene plain = parse_scene(text, "cloud.json");
  std::unique_ptr<Scene> in_arena;
  {
    const LoadArena arena;
    in_arena = std::make_unique<Scene>(parse_scene(text, "cloud.json"));
  }
  ASSERT_TRUE(plain.document && in_arena->document);
  EXPECT_TRUE(load_arena_holds(in_arena->document.get()));
  using json = nlohmann::json;
  EXPECT_EQ(*static_cast<const json*>(plain.document.get()),
            *static_cast<const json*>(in_arena->document.get()));
  ASSERT_EQ(plain.objects.size(), in_arena->objects.size());
  in_arena.reset();

  const std::string bad = scene_text("-2");
  std::string plain_error, arena_error;
  try {
    parse_scene(bad, "bad.json");
  } catch (const SceneError& e) {
    plain_error = e.what();
  }
  try {
    const LoadArena arena;
    parse_scene(bad, "bad.json");
  } catch (const SceneError& e) {
    arena_error = e.what();
  }
  EXPECT_NE(plain_error.find("/children/299/distance"), std::string::npos) << plain_error;
  EXPECT_EQ(plain_error, arena_error);
}

}  // namespace
}  // namespace softtrace
