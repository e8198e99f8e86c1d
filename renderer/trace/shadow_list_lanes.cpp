// Two entries of a shadow prism's list at once (shadow_list_lanes.h). SSE2 is x86-64's baseline:
// no choice at run time. Each lane computes the scalar test's expression with the same operations
// (dx * dx + dy * dy against reach * reach; addition is commutative in IEEE arithmetic, and a
// comparison with a NaN is false in both), so a lane keeps an entry exactly where the scalar test
// does.
#include "trace/shadow_list_lanes.h"

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace softtrace {

int entries_on_line(const BlobBeam& list, const double (&across)[2], BlobBeam::Entry* out) {
  const BlobBeam::Entry* const entries = list.entries.data();
  const BlobBeam::Across* const a = list.across.data();
  const int n = static_cast<int>(list.entries.size());
  int kept = 0, i = 0;
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

}  // namespace softtrace
