// The worker threads' loops (render/threads.h): parallel_ranges runs each range in the caller's
// floating-point mode, as parallel_each runs each task (tests/renderer/io/test_png_bands.cpp).
#include <gtest/gtest.h>

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

#include <chrono>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "render/threads.h"

namespace softtrace::test {
namespace {

// Here rounding towards zero, which the worker threads do not have: the arena is started first,
// in the usual mode (as a Python session's first render or batch starts it).
TEST(ParallelRanges, EachRangeTakesTheCallersFloatingPointMode) {
#if defined(__x86_64__) || defined(__i386__)
  // MXCSR's control bits; the low six are the exceptions' sticky flags, which any sum may set.
  const auto control = [] { return _mm_getcsr() & ~0x3Fu; };
  parallel_ranges(
      64, 1, [](size_t, size_t) { std::this_thread::sleep_for(std::chrono::microseconds(100)); });
  const unsigned before = _mm_getcsr();
  const unsigned mode = (before & ~0x3Fu) | 0x6000u;  // RC = 11: towards zero
  _mm_setcsr(mode);
  std::mutex m;
  std::vector<unsigned> seen;
  std::set<std::thread::id> threads;
  size_t covered = 0;
  parallel_ranges(64, 1, [&](size_t begin, size_t end) {
    std::this_thread::sleep_for(std::chrono::microseconds(200 * (end - begin)));
    const std::lock_guard<std::mutex> lock(m);
    seen.push_back(control());
    threads.insert(std::this_thread::get_id());
    covered += end - begin;
  });
  const unsigned after = control();
  _mm_setcsr(before);
  EXPECT_EQ(after, mode);
  EXPECT_EQ(covered, 64u);
  ASSERT_FALSE(seen.empty());
  for (const unsigned s : seen) EXPECT_EQ(s, mode);
  if (threads.size() < 2)
    GTEST_SKIP() << "every range ran on the calling thread (a loaded machine)";
#else
  GTEST_SKIP() << "x86 only";
#endif
}

}  // namespace
}  // namespace softtrace::test
