// The process's heap in huge pages (cli/heap_pages.h): the range advised starts at a 2 MiB
// boundary, the heap's next block from its top starts exactly there, and the kernel counts the
// range as eligible for huge pages where it grants them on advice; a worker thread's own heap
// likewise, its first huge page already there.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdint>
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

TEST(HeapPages, NothingIsAdvisedForNothingOrForMoreThanTheHeapServes) {
  EXPECT_EQ(heap_in_huge_pages(0).begin, heap_in_huge_pages(0).end);
  const HeapPages too_big = heap_in_huge_pages(size_t(64) << 20);
  EXPECT_EQ(too_big.begin, too_big.end);
}

long thread_faults() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return usage.ru_minflt;
}

// A thread's first 600 KB of blocks (meets1's worker's frame and PNG bands) take no fault: its
// first huge page was filled by the call (without the filling, one fault; without the advice, one
// per 4 KiB page, 150). In a process of its own (a death-test child), where the thread is the
// first besides the main one and so gets a fresh malloc arena.
TEST(HeapPages, AWorkersHeapIsInHugePagesItsFirstAlreadyThere) {
  if (!test::huge_pages_on_advice()) {
    GTEST_SKIP() << "this kernel grants no huge pages on advice";
  }
  if (heap_in_huge_pages(kTwoMiB).begin == 0) {
    GTEST_SKIP() << "this build's C library takes no such advice";
  }
  EXPECT_EXIT(
      {
        bool ok = false;
        std::thread([&] {
          std::vector<std::unique_ptr<char[]>> blocks;  // before: its first block makes the arena
          blocks.reserve(50);
          const HeapPages range = thread_heap_in_huge_pages(2 * kTwoMiB);
          const long before = thread_faults();
          for (int i = 0; i < 50; ++i) {
            blocks.emplace_back(new char[12 << 10]);
            std::fill_n(blocks.back().get(), 12 << 10, char(i));
          }
          const long faults = thread_faults() - before;
          const uintptr_t first = reinterpret_cast<uintptr_t>(blocks.front().get());
          ok = range.begin % kTwoMiB == 0 && range.end - range.begin == 2 * kTwoMiB &&
               range.begin <= first && first < range.begin + kTwoMiB && faults == 0;
          if (!ok)
            std::fprintf(stderr, "range %lx-%lx, first block %p, %ld faults\n",
                         static_cast<unsigned long>(range.begin),
                         static_cast<unsigned long>(range.end),
                         static_cast<void*>(blocks.front().get()), faults);
        }).join();
        std::exit(ok ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace softtrace
