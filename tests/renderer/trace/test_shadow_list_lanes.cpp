// A shadow ray's entries on its line (renderer/trace/shadow_list_lanes.h), two at a time with
// SSE2 and four with AVX2 (where the CPU has it): the entries the scalar test keeps, in the
// list's order, for lists of every length (the last one to three entries after the pairs or
// fours), entries exactly at their reach, and spheres of no known size.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "trace/shadow_list_lanes.h"

namespace softtrace::test {

namespace {
// first_hit_blobs' filter one entry at a time, as it was before the pairs.
std::vector<BlobBeam::Entry> on_line_one_at_a_time(const BlobBeam& list,
                                                   const double (&across)[2]) {
  std::vector<BlobBeam::Entry> out;
  for (size_t i = 0; i < list.entries.size(); ++i) {
    const BlobBeam::Across& a = list.across[i];
    const double dx = a.x - across[0], dy = a.y - across[1];
    if (dx * dx + dy * dy <= a.reach * a.reach) out.push_back(list.entries[i]);
  }
  return out;
}

using OnLine = int (*)(const BlobBeam&, const double (&)[2], BlobBeam::Entry*);

void keeps_the_scalar_tests_entries_in_order(OnLine on_line) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::mt19937_64 rng(38);
  std::uniform_real_distribution<double> unit(-1, 1), pos(0, 1);
  long kept = 0, dropped = 0, at_reach = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    BlobBeam list;
    list.parallel = true;
    const int n = static_cast<int>(pos(rng) * 40);
    const double across[2] = {5 * unit(rng), 5 * unit(rng)};
    for (int i = 0; i < n; ++i) {
      const double kind = pos(rng);
      BlobBeam::Across a;
      if (kind < 0.05) {  // no sphere known: on every ray's list (shadow_beam)
        a = {0, 0, kInf};
      } else if (kind < 0.25) {
        // On the reach's boundary: a 3-4-5 triangle, exact in doubles, and the reach one ulp
        // either side of it.
        const double k = 1 + static_cast<int>(pos(rng) * 8), side = pos(rng) < 0.5 ? -1 : 1;
        const double r = 5 * k;
        const double ulp = pos(rng);
        a = {across[0] + side * 3 * k, across[1] - side * 4 * k,
             ulp < 1.0 / 3   ? r
             : ulp < 2.0 / 3 ? std::nextafter(r, 0)
                             : std::nextafter(r, kInf)};
      } else {
        a = {across[0] + 3 * unit(rng), across[1] + 3 * unit(rng), 2 * pos(rng)};
      }
      list.across.push_back(a);
      list.entries.push_back({-unit(rng), 1 + pos(rng), i});
    }
    std::vector<BlobBeam::Entry> out(list.entries.size());
    const int found = on_line(list, across, out.data());
    const std::vector<BlobBeam::Entry> want = on_line_one_at_a_time(list, across);
    ASSERT_EQ(found, static_cast<int>(want.size())) << "trial " << trial;
    for (int i = 0; i < found; ++i) {
      ASSERT_EQ(out[i].id, want[i].id) << "trial " << trial << " entry " << i;
      ASSERT_EQ(out[i].near, want[i].near);
      ASSERT_EQ(out[i].far, want[i].far);
    }
    kept += found;
    dropped += n - found;
    for (const BlobBeam::Across& a : list.across) {
      const double dx = a.x - across[0], dy = a.y - across[1];
      at_reach += dx * dx + dy * dy == a.reach * a.reach;
    }
  }
  // The lists had entries of both answers, and some exactly at their reach.
  EXPECT_GT(kept, 10000);
  EXPECT_GT(dropped, 10000);
  EXPECT_GT(at_reach, 1000);
}
}  // namespace

TEST(ShadowListLanes, APairsTestKeepsTheEntriesTheScalarTestKeepsInOrder) {
  keeps_the_scalar_tests_entries_in_order(entries_on_line_pairs);
}

TEST(ShadowListLanes, AFoursTestKeepsTheEntriesTheScalarTestKeepsInOrder) {
#ifdef __SSE2__
  if (!BlobSum::has_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  keeps_the_scalar_tests_entries_in_order(entries_on_line_four);
#else
  GTEST_SKIP() << "no AVX2 form off x86-64";
#endif
}

// The form this CPU's rays take.
TEST(ShadowListLanes, TheChosenFormKeepsTheEntriesTheScalarTestKeepsInOrder) {
  keeps_the_scalar_tests_entries_in_order(entries_on_line);
}

}  // namespace softtrace::test
