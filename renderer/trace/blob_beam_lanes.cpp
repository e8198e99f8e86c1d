// Balls against a block's frustum four at a time (blob_beam_lanes.h). As blob_ray_lanes.cpp's
// kernel: compiled for AVX2 alone (not "fma", which would round a multiply-add once where the
// scalar test rounds twice), chosen at run time, each lane the scalar test's operations in its
// order. std::sqrt and division are correctly rounded in both.
#include "trace/blob_beam_lanes.h"

#include <immintrin.h>

#include <cmath>
#include <cstddef>
#include <limits>

namespace softtrace {

bool ball_in_beam(const BlobSum::Blob& ball, const BeamSides& sides, double* near, double* far) {
  const double r = std::sqrt(1 / ball.inv_r2);
  const Vec3 v = ball.centre - sides.eye;
  const double distance = length(v);
  const double slack = 1e-9 * (distance + r + sides.eye_scale);
  for (const Vec3& n : sides.normals)
    if (dot(v, n) < -r - slack) return false;
  *near = distance - r - slack;
  *far = distance + r + slack;
  return true;
}

unsigned balls_in_beam_scalar(const BlobSum::Blob* const (&balls)[4], const BeamSides& sides,
                              double (&near)[4], double (&far)[4]) {
  unsigned out = 0;
  for (int i = 0; i < 4; ++i) {
    if (!(1 / balls[i]->inv_r2 < std::numeric_limits<double>::infinity())) {
      out |= 16u << i;
      continue;
    }
    out |= static_cast<unsigned>(ball_in_beam(*balls[i], sides, &near[i], &far[i])) << i;
  }
  return out;
}

static_assert(offsetof(BlobSum::Blob, centre) == 0 && offsetof(BlobSum::Blob, inv_r2) == 24);

__attribute__((target("avx2"))) unsigned balls_in_beam_avx2(const BlobSum::Blob* const (&balls)[4],
                                                            const BeamSides& sides,
                                                            double (&near)[4], double (&far)[4]) {
  // The balls' (centre, inv_r2) rows as lanes.
  const __m256d b0 = _mm256_loadu_pd(&balls[0]->centre.x),
                b1 = _mm256_loadu_pd(&balls[1]->centre.x);
  const __m256d b2 = _mm256_loadu_pd(&balls[2]->centre.x),
                b3 = _mm256_loadu_pd(&balls[3]->centre.x);
  const __m256d lo01 = _mm256_unpacklo_pd(b0, b1), hi01 = _mm256_unpackhi_pd(b0, b1);
  const __m256d lo23 = _mm256_unpacklo_pd(b2, b3), hi23 = _mm256_unpackhi_pd(b2, b3);
  const __m256d cx = _mm256_permute2f128_pd(lo01, lo23, 0x20);
  const __m256d cy = _mm256_permute2f128_pd(hi01, hi23, 0x20);
  const __m256d cz = _mm256_permute2f128_pd(lo01, lo23, 0x31);
  const __m256d inv_r2 = _mm256_permute2f128_pd(hi01, hi23, 0x31);

  const __m256d r2 = _mm256_div_pd(_mm256_set1_pd(1.0), inv_r2);
  const __m256d finite =
      _mm256_cmp_pd(r2, _mm256_set1_pd(std::numeric_limits<double>::infinity()), _CMP_LT_OQ);
  const __m256d r = _mm256_sqrt_pd(r2);
  const __m256d vx = _mm256_sub_pd(cx, _mm256_set1_pd(sides.eye.x));
  const __m256d vy = _mm256_sub_pd(cy, _mm256_set1_pd(sides.eye.y));
  const __m256d vz = _mm256_sub_pd(cz, _mm256_set1_pd(sides.eye.z));
  const __m256d distance = _mm256_sqrt_pd(_mm256_add_pd(
      _mm256_add_pd(_mm256_mul_pd(vx, vx), _mm256_mul_pd(vy, vy)), _mm256_mul_pd(vz, vz)));
  const __m256d slack =
      _mm256_mul_pd(_mm256_set1_pd(1e-9),
                    _mm256_add_pd(_mm256_add_pd(distance, r), _mm256_set1_pd(sides.eye_scale)));
  // -r - slack: the negation is exact, as the scalar's unary minus.
  const __m256d reach = _mm256_sub_pd(_mm256_xor_pd(r, _mm256_set1_pd(-0.0)), slack);
  __m256d inside = finite;
  for (const Vec3& n : sides.normals) {
    const __m256d along = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(vx, _mm256_set1_pd(n.x)),
                                                      _mm256_mul_pd(vy, _mm256_set1_pd(n.y))),
                                        _mm256_mul_pd(vz, _mm256_set1_pd(n.z)));
    // The scalar test drops the ball where along < reach: it stays where that is false.
    inside = _mm256_andnot_pd(_mm256_cmp_pd(along, reach, _CMP_LT_OQ), inside);
  }
  _mm256_storeu_pd(near, _mm256_sub_pd(_mm256_sub_pd(distance, r), slack));
  _mm256_storeu_pd(far, _mm256_add_pd(_mm256_add_pd(distance, r), slack));
  const unsigned not_finite = static_cast<unsigned>(_mm256_movemask_pd(
      _mm256_cmp_pd(r2, _mm256_set1_pd(std::numeric_limits<double>::infinity()), _CMP_NLT_UQ)));
  return static_cast<unsigned>(_mm256_movemask_pd(inside)) | not_finite << 4;
}

BallsInBeam balls_in_beam() {
  static const BallsInBeam chosen = BlobSum::has_avx2() ? balls_in_beam_avx2 : balls_in_beam_scalar;
  return chosen;
}

}  // namespace softtrace
