// A shadow prism's list's entries on a ray's line, two at a time (shadow_list_lanes.h) or four.
// SSE2 is x86-64's baseline: the pairs need no choice at run time; the fours are compiled for
// AVX2 alone (not "fma", which would let the compiler fuse a product into a sum and round it
// otherwise) and taken where the CPU has it. Each lane computes the scalar test's expression with
// the same operations (dx * dx + dy * dy against reach * reach; addition is commutative in IEEE
// arithmetic, and a comparison with a NaN is false in all of them), so a lane keeps an entry
// exactly where the scalar test does.
#include "trace/shadow_list_lanes.h"

#include <cstddef>

#include "math/cpu_avx2.h"

#ifdef __SSE2__
#include <immintrin.h>
#endif

namespace softtrace {

namespace {
// The entries from i on, into out[kept...): pairs, then the last one alone. The count kept.
inline int on_line_from(const BlobBeam& list, const double (&across)[2], BlobBeam::Entry* out,
                        int i, int kept) {
  const BlobBeam::Entry* const entries = list.entries.data();
  const BlobBeam::Across* const a = list.across.data();
  const int n = static_cast<int>(list.entries.size());
#ifdef __SSE2__
  // Most entries lie off the line (meets10 at 640x480: 84 %): a pair's one branch, on both lanes'
  // answers, skips most pairs. One entry at a time, the test was 15 instructions an entry.
  const __m128d from = _mm_loadu_pd(across);
  for (; i + 2 <= n; i += 2) {
    const __m128d d0 = _mm_sub_pd(_mm_loadu_pd(&a[i].x), from);  // dx, dy of entry i
    const __m128d d1 = _mm_sub_pd(_mm_loadu_pd(&a[i + 1].x), from);
    const __m128d s0 = _mm_mul_pd(d0, d0), s1 = _mm_mul_pd(d1, d1);
    const __m128d d2 = _mm_add_pd(_mm_unpacklo_pd(s0, s1), _mm_unpackhi_pd(s0, s1));
    const __m128d reach = _mm_loadh_pd(_mm_load_sd(&a[i].reach), &a[i + 1].reach);
    const int on = _mm_movemask_pd(_mm_cmple_pd(d2, _mm_mul_pd(reach, reach)));
    if (on == 0) continue;
    if (on & 1) out[kept++] = entries[i];
    if (on & 2) out[kept++] = entries[i + 1];
  }
#endif
  for (; i < n; ++i) {
    const double dx = a[i].x - across[0], dy = a[i].y - across[1];
    if (dx * dx + dy * dy <= a[i].reach * a[i].reach) out[kept++] = entries[i];
  }
  return kept;
}
}  // namespace

int entries_on_line_pairs(const BlobBeam& list, const double (&across)[2], BlobBeam::Entry* out) {
  return on_line_from(list, across, out, 0, 0);
}

#ifdef __SSE2__
// An entry's Across is four doubles, x, y, reach and depth: one AVX register, four of which
// transpose into the four entries' x, y and reach.
static_assert(sizeof(BlobBeam::Across) == 4 * sizeof(double) &&
              offsetof(BlobBeam::Across, y) == sizeof(double) &&
              offsetof(BlobBeam::Across, reach) == 2 * sizeof(double));

namespace {
// Which of entries at..at + 3 the line passes: bit k for entry at + k.
__attribute__((target("avx2"), always_inline)) inline unsigned four_on_line(
    const BlobBeam::Across* a, int at, __m256d fx, __m256d fy) {
  const __m256d e0 = _mm256_loadu_pd(&a[at].x), e1 = _mm256_loadu_pd(&a[at + 1].x);
  const __m256d e2 = _mm256_loadu_pd(&a[at + 2].x), e3 = _mm256_loadu_pd(&a[at + 3].x);
  const __m256d xr01 = _mm256_unpacklo_pd(e0, e1), xr23 = _mm256_unpacklo_pd(e2, e3);
  const __m256d yd01 = _mm256_unpackhi_pd(e0, e1), yd23 = _mm256_unpackhi_pd(e2, e3);
  const __m256d x = _mm256_permute2f128_pd(xr01, xr23, 0x20);
  const __m256d reach = _mm256_permute2f128_pd(xr01, xr23, 0x31);
  const __m256d y = _mm256_permute2f128_pd(yd01, yd23, 0x20);
  const __m256d dx = _mm256_sub_pd(x, fx), dy = _mm256_sub_pd(y, fy);
  const __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
  return _mm256_movemask_pd(_mm256_cmp_pd(d2, _mm256_mul_pd(reach, reach), _CMP_LE_OQ));
}
}  // namespace

__attribute__((target("avx2"))) int entries_on_line_four(const BlobBeam& list,
                                                         const double (&across)[2],
                                                         BlobBeam::Entry* out) {
  const BlobBeam::Entry* const entries = list.entries.data();
  const BlobBeam::Across* const a = list.across.data();
  const int n = static_cast<int>(list.entries.size());
  if (n < 4) return on_line_from(list, across, out, 0, 0);
  const __m256d fx = _mm256_set1_pd(across[0]), fy = _mm256_set1_pd(across[1]);
  int kept = 0, i = 0;
  // A long list's entries lie mostly off the line: its block's points are spread across a
  // prism many blob radii wide (meets10 at 640x480: the 26 % of rays whose prism is over twice
  // their blobs' reach wide read 79 % of the entries, 39 or 143 a ray, and keep 5). One branch
  // for four of them, where a pair's took one for two.
  for (; i + 4 <= n; i += 4) {
    const unsigned on = four_on_line(a, i, fx, fy);
    if (on == 0) continue;
    if (on & 1) out[kept++] = entries[i];
    if (on & 2) out[kept++] = entries[i + 1];
    if (on & 4) out[kept++] = entries[i + 2];
    if (on & 8) out[kept++] = entries[i + 3];
  }
  // The last one to three: the list's last four, less the lanes before i, taken above. The list
  // is read within its bounds, and no pair's or single entry's code follows.
  if (i < n) {
    const int at = n - 4;
    for (unsigned on = four_on_line(a, at, fx, fy) & (~0u << (i - at)); on != 0; on &= on - 1)
      out[kept++] = entries[at + __builtin_ctz(on)];
  }
  return kept;
}

namespace {
// Asked once, as the program starts: a function's static cost every call its guard's test and
// the registers saved for its first call's path (22 instructions a shadow ray).
const bool four_lanes = cpu_has_avx2();
}  // namespace
#endif

int entries_on_line(const BlobBeam& list, const double (&across)[2], BlobBeam::Entry* out) {
#ifdef __SSE2__
  if (four_lanes) return entries_on_line_four(list, across, out);
#endif
  return entries_on_line_pairs(list, across, out);
}

}  // namespace softtrace
