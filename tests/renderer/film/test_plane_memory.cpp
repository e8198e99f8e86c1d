// The film's planes: one of 1 MiB or more is mapped on its own at a 2 MiB boundary, zeroed, and
// the kernel may back it with huge pages (smaps' THPeligible); a small one comes from the heap,
// and so does one below the bound a process whose heaps are in huge pages sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "film/film.h"
#include "film/plane_memory.h"
#include "huge_pages.h"

namespace softtrace {
namespace {

using test::huge_pages_on_advice;
using test::thp_eligible;

TEST(PlaneMemory, AFramesPlaneOfAMebibyteOrMoreIsMappedAtAHugePageAndZeroed) {
  const Film film(640, 480, AovSelection{});  // the RGBA plane alone
  const size_t bytes = film.rgba.size() * sizeof(float);
  ASSERT_EQ(film.rgba.size(), size_t(640) * 480 * 4);
  EXPECT_TRUE(std::all_of(film.rgba.begin(), film.rgba.end(), [](float v) { return v == 0; }));
  EXPECT_TRUE(film.depth.empty());
  if (!plane_mapped(bytes)) {
    GTEST_SKIP() << "no huge pages in this build";
  }
  EXPECT_EQ(reinterpret_cast<uintptr_t>(film.rgba.data()) % (size_t(1) << 21), 0u);
  if (huge_pages_on_advice()) {
    const int eligible = thp_eligible(film.rgba.data());
    if (eligible >= 0) {
      EXPECT_EQ(eligible, 1);
    }
  }
}

TEST(PlaneMemory, APlaneIsWritableToItsEndAndCopiesAndGrows) {
  FilmPlane plane(size_t(3) << 18, 0.0f);  // 3 MiB: two huge pages' worth
  for (size_t i = 0; i < plane.size(); ++i) plane[i] = float(i % 1000);
  FilmPlane copy = plane;
  EXPECT_EQ(copy, plane);
  copy.resize(copy.size() + 7, 2.5f);
  EXPECT_EQ(copy.back(), 2.5f);
  EXPECT_EQ(copy[plane.size() - 1], plane.back());
  FilmPlane small(100, 1.0f);  // the heap's
  EXPECT_FALSE(plane_mapped(small.size() * sizeof(float)));
  small.clear();
  small.shrink_to_fit();
  EXPECT_TRUE(small.empty());
}

// A plane's elements are left as its memory came (PlaneAllocator::construct): a small plane's
// heap block, which last held other values, must be zeroed by plane_allocate.
TEST(PlaneMemory, ASmallPlaneIsZeroWhereTheHeapHeldOtherValues) {
  for (int round = 0; round < 3; ++round) {
    {
      const std::vector<float> used(100, 7.0f);  // freed: the heap's next block of its size
      ASSERT_EQ(used.back(), 7.0f);
    }
    const FilmPlane small(100);
    EXPECT_FALSE(plane_mapped(small.size() * sizeof(float)));
    EXPECT_TRUE(std::all_of(small.begin(), small.end(), [](float v) { return v == 0; }));
  }
}

// Below the bound the command line sets (planes_from_heap_below), a 320x240 frame's RGBA plane
// (1.2 MB) comes from the heap, zeroed where the heap's freed block of its size held other values;
// a plane at the bound is still mapped on its own. In a process of its own (a death-test child):
// the bound holds for the process's life.
TEST(PlaneMemory, BelowTheProcessesBoundAFramesPlaneComesFromTheHeapZeroed) {
  const size_t rgba_bytes = size_t(320) * 240 * 4 * sizeof(float), bound = size_t(3) << 19;
  if (!plane_mapped(rgba_bytes)) {
    GTEST_SKIP() << "no huge pages in this build";
  }
  EXPECT_EXIT(
      {
        planes_from_heap_below(bound);
        bool ok = !plane_mapped(rgba_bytes) && plane_mapped(bound);
        {
          const std::vector<float> used(rgba_bytes / sizeof(float), 7.0f);
          ok = ok && used.back() == 7.0f;
        }
        const Film film(320, 240, AovSelection{});
        ok = ok && std::all_of(film.rgba.begin(), film.rgba.end(), [](float v) { return v == 0; });
        // A heap block begins after its header, never at a 2 MiB boundary, where a mapped plane
        // always does.
        ok = ok && reinterpret_cast<uintptr_t>(film.rgba.data()) % (size_t(1) << 21) != 0;
        std::exit(ok ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace softtrace
