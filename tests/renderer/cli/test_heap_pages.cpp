// The process's heap in huge pages (cli/heap_pages.h): the range advised starts at a 2 MiB
// boundary, the heap's next block from its top starts exactly there, and the kernel counts the
// range as eligible for huge pages where it grants them on advice; a thread started after it
// takes its blocks from that heap, not from an arena of its own.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

#include "cli/heap_pages.h"
#include "huge_pages.h"

namespace softtrace {
namespace {

constexpr size_t kTwoMiB = size_t(1) << 21;  // a huge page, told independently of the code

TEST(HeapPages, TheHeapCarvesItsBlocksFromTheAdvisedBoundaryOn) {
  const HeapPages range = heap_in_huge_pages(3 * (size_t(1) << 20));  // rounds up to 4 MiB
  if (range.begin == range.end) {
    GTEST_SKIP() << "this build's C library takes no such advice";
  }
  EXPECT_EQ(range.begin % kTwoMiB, 0u);
  EXPECT_EQ(range.end - range.begin, 2 * kTwoMiB);
  // Blocks of 100 KiB, 5 MB in all: the heap's free lists serve what they hold first, then the
  // top, whose first block must begin at the boundary (the front before it kept out of use).
  std::vector<std::unique_ptr<char[]>> blocks;
  for (int i = 0; i < 50; ++i) blocks.emplace_back(new char[100 << 10]);
  const bool at_boundary = std::any_of(blocks.begin(), blocks.end(), [&](const auto& b) {
    return reinterpret_cast<uintptr_t>(b.get()) == range.begin;
  });
  EXPECT_TRUE(at_boundary);
  if (test::huge_pages_on_advice()) {
    const int eligible = test::thp_eligible(reinterpret_cast<const void*>(range.begin));
    if (eligible >= 0) {
      EXPECT_EQ(eligible, 1);
    }
  }
}

// In a process of its own (gtest re-runs the program for this test alone): a thread's arena is
// chosen at its first block, and this process's earlier threads may have left arenas to reuse.
TEST(HeapPages, AThreadStartedAfterTakesItsBlocksFromTheSameHeap) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        const HeapPages range = heap_in_huge_pages(kTwoMiB);
        if (range.begin == range.end) std::_Exit(0);  // no such C library: nothing to check
        bool in_heap = false;
        std::thread([&] {
          // Below the heap's end (the program break): a block of another arena lies in a mapping
          // of its own, far above it.
          void* block = std::malloc(100 << 10);
          in_heap =
              block && reinterpret_cast<uintptr_t>(block) < reinterpret_cast<uintptr_t>(sbrk(0));
          std::free(block);
        }).join();
        std::_Exit(in_heap ? 0 : 1);
      },
      testing::ExitedWithCode(0), "");
}

TEST(HeapPages, NothingIsAdvisedForNothingOrForMoreThanTheHeapServes) {
  EXPECT_EQ(heap_in_huge_pages(0).begin, heap_in_huge_pages(0).end);
  const HeapPages too_big = heap_in_huge_pages(size_t(64) << 20);
  EXPECT_EQ(too_big.begin, too_big.end);
}

}  // namespace
}  // namespace softtrace
