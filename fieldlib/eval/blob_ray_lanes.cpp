// BlobSum::ball_terms4's kernels: four balls' terms of one stretch (BlobSum::ball_term) at once.
// The build has no -march (the same bits on every CI machine), so the AVX2 kernel is compiled for
// that target alone and chosen at run time where the CPU has it. It gives ball_term's bits in
// every lane: the same IEEE operations (+, -, *, /, sqrt, compares) in the same order, each
// correctly rounded in a vector register as in a scalar one, under the same MXCSR (flush-to-zero
// in a frame). Not "fma": a fused multiply-add rounds once where ball_term rounds twice. The
// scalar path is built with -std=c++17, whose -ffp-contract=off fuses nothing either (and the
// x86-64 baseline has no FMA). std::max(a, b) is a < b ? b : a, which is maxpd(b, a) (maxpd(x, y)
// is x > y ? x : y), std::min(a, b) is minpd(b, a): equal for NaNs and signed zeros too.
#include <immintrin.h>

#include <cstddef>

#include "eval/blob_ray.h"
#include "math/cpu_avx2.h"

namespace softtrace {

// The loads and stores below read a Blob's (centre, inv_r2) and (c2, c3), and write a Term's
// (enter, exit, mid, alpha) and (h2, c2, c3, peak), each as one run of doubles.
static_assert(offsetof(BlobSum::Blob, centre) == 0 && offsetof(BlobSum::Blob, inv_r2) == 24 &&
              offsetof(BlobSum::Blob, c2) == 32 && offsetof(BlobSum::Blob, c3) == 40);
static_assert(offsetof(BlobSum::Term, enter) == 0 && offsetof(BlobSum::Term, exit) == 8 &&
              offsetof(BlobSum::Term, mid) == 16 && offsetof(BlobSum::Term, alpha) == 24 &&
              offsetof(BlobSum::Term, h2) == 32 && offsetof(BlobSum::Term, c2) == 40 &&
              offsetof(BlobSum::Term, c3) == 48 && offsetof(BlobSum::Term, peak) == 56 &&
              sizeof(BlobSum::Term) == 64);

unsigned BlobSum::ball_lanes_scalar(const Blob* const (&balls)[4], const Vec3& o, const Vec3& d,
                                    double dd, double len, Term (&out)[4]) {
  unsigned found = 0;
  for (int i = 0; i < 4; ++i)
    found |= static_cast<unsigned>(ball_term(*balls[i], o, d, dd, len, &out[i])) << i;
  return found;
}

bool BlobSum::has_avx2() {
  return cpu_has_avx2();
}

namespace {
// The rows a, b, c, e (four lanes each) as four columns: out[i] = (a[i], b[i], c[i], e[i]).
__attribute__((target("avx2"))) void transpose(__m256d a, __m256d b, __m256d c, __m256d e,
                                               __m256d (&out)[4]) {
  const __m256d ab_lo = _mm256_unpacklo_pd(a, b), ab_hi = _mm256_unpackhi_pd(a, b);
  const __m256d ce_lo = _mm256_unpacklo_pd(c, e), ce_hi = _mm256_unpackhi_pd(c, e);
  out[0] = _mm256_permute2f128_pd(ab_lo, ce_lo, 0x20);
  out[1] = _mm256_permute2f128_pd(ab_hi, ce_hi, 0x20);
  out[2] = _mm256_permute2f128_pd(ab_lo, ce_lo, 0x31);
  out[3] = _mm256_permute2f128_pd(ab_hi, ce_hi, 0x31);
}
}  // namespace

__attribute__((target("avx2"))) unsigned BlobSum::ball_lanes_avx2(const Blob* const (&balls)[4],
                                                                  const Vec3& o, const Vec3& d,
                                                                  double dd, double len,
                                                                  Term (&out)[4]) {
  // Each ball's (centre.x, centre.y, centre.z, inv_r2) as lanes: cx, cy, cz, inv_r2.
  __m256d ball[4];
  transpose(_mm256_loadu_pd(&balls[0]->centre.x), _mm256_loadu_pd(&balls[1]->centre.x),
            _mm256_loadu_pd(&balls[2]->centre.x), _mm256_loadu_pd(&balls[3]->centre.x), ball);
  // (c2, c3) of balls 0 and 2, and of 1 and 3: interleaved, lanes in order.
  const __m256d c02 = _mm256_set_m128d(_mm_loadu_pd(&balls[2]->c2), _mm_loadu_pd(&balls[0]->c2));
  const __m256d c13 = _mm256_set_m128d(_mm_loadu_pd(&balls[3]->c2), _mm_loadu_pd(&balls[1]->c2));
  const __m256d c2 = _mm256_unpacklo_pd(c02, c13), c3 = _mm256_unpackhi_pd(c02, c13);
  const __m256d inv_r2 = ball[3];
  const __m256d zero = _mm256_setzero_pd();
  const __m256d dx = _mm256_set1_pd(d.x), dy = _mm256_set1_pd(d.y), dz = _mm256_set1_pd(d.z);
  const __m256d vdd = _mm256_set1_pd(dd);

  // ball_term, lane by lane.
  const __m256d ocx = _mm256_sub_pd(_mm256_set1_pd(o.x), ball[0]);
  const __m256d ocy = _mm256_sub_pd(_mm256_set1_pd(o.y), ball[1]);
  const __m256d ocz = _mm256_sub_pd(_mm256_set1_pd(o.z), ball[2]);
  const __m256d oc_d = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(ocx, dx), _mm256_mul_pd(ocy, dy)),
                                     _mm256_mul_pd(ocz, dz));
  const __m256d mid = _mm256_div_pd(_mm256_xor_pd(oc_d, _mm256_set1_pd(-0.0)), vdd);
  const __m256d nx = _mm256_add_pd(ocx, _mm256_mul_pd(dx, mid));
  const __m256d ny = _mm256_add_pd(ocy, _mm256_mul_pd(dy, mid));
  const __m256d nz = _mm256_add_pd(ocz, _mm256_mul_pd(dz, mid));
  const __m256d n2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(nx, nx), _mm256_mul_pd(ny, ny)),
                                   _mm256_mul_pd(nz, nz));
  const __m256d h2 = _mm256_sub_pd(_mm256_set1_pd(1.0), _mm256_mul_pd(n2, inv_r2));
  const __m256d alpha = _mm256_mul_pd(vdd, inv_r2);
  const __m256d inside = _mm256_cmp_pd(h2, zero, _CMP_GT_OQ);  // h2 > 0
  // No lane's line meets its ball (most of a shadow ray's four in a cloud): no term, as
  // ball_term's h2 test gives none, without the division and square root below, whose latency
  // was most of this kernel's time (perf, blob1000 at 640x480).
  if (_mm256_movemask_pd(inside) == 0) return 0;
  const __m256d half = _mm256_sqrt_pd(_mm256_div_pd(h2, alpha));
  const __m256d enter = _mm256_max_pd(zero, _mm256_sub_pd(mid, half));
  const __m256d exit = _mm256_min_pd(_mm256_set1_pd(len), _mm256_add_pd(mid, half));
  const __m256d open = _mm256_cmp_pd(enter, exit, _CMP_LT_OQ);  // enter < exit
  // gap = mid < enter ? enter - mid : mid > exit ? mid - exit : 0
  const __m256d before = _mm256_cmp_pd(mid, enter, _CMP_LT_OQ);
  const __m256d after = _mm256_cmp_pd(mid, exit, _CMP_GT_OQ);
  const __m256d gap = _mm256_blendv_pd(_mm256_blendv_pd(zero, _mm256_sub_pd(mid, exit), after),
                                       _mm256_sub_pd(enter, mid), before);
  const __m256d r =
      _mm256_max_pd(zero, _mm256_sub_pd(h2, _mm256_mul_pd(_mm256_mul_pd(alpha, gap), gap)));
  // polynomial_potential: r * r * (c2 + c3 * r); then std::max(0.0, p) = maxpd(p, 0).
  const __m256d p = _mm256_mul_pd(_mm256_mul_pd(r, r), _mm256_add_pd(c2, _mm256_mul_pd(c3, r)));
  const __m256d peak = _mm256_max_pd(p, zero);

  __m256d head[4], tail[4];
  transpose(enter, exit, mid, alpha, head);
  transpose(h2, c2, c3, peak, tail);
  for (int i = 0; i < 4; ++i) {
    _mm256_storeu_pd(&out[i].enter, head[i]);
    _mm256_storeu_pd(&out[i].h2, tail[i]);
  }
  return static_cast<unsigned>(_mm256_movemask_pd(_mm256_and_pd(inside, open)));
}

}  // namespace softtrace
