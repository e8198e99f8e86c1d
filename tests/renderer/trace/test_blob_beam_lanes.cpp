// blob_beam's ball test four at a time (renderer/trace/blob_beam_lanes.h): the AVX2 kernel keeps
// the balls the scalar test keeps, with the same ranges to the bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "trace/blob_beam_lanes.h"

namespace softtrace::test {

TEST(BallsInBeam, Avx2GivesTheScalarTestsBitsInEveryLane) {
  if (!BlobSum::has_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> unit(-1, 1), pos(0, 1);
  const auto direction = [&] {
    Vec3 v{unit(rng), unit(rng), unit(rng)};
    while (!(length(v) > 0.1)) v = {unit(rng), unit(rng), unit(rng)};
    return v / length(v);
  };
  int kept = 0, dropped = 0, not_finite = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    BeamSides sides;
    sides.eye = {30 * unit(rng), 30 * unit(rng), 30 * unit(rng)};
    sides.eye_scale = max_abs(sides.eye);
    // A narrow frustum about `forward` (its side planes' normals lean towards it), now and then
    // with a zero normal (two corners that coincide).
    const Vec3 forward = direction();
    for (Vec3& n : sides.normals) {
      n = pos(rng) < 0.05 ? Vec3{0, 0, 0} : normalize(forward * (0.3 * pos(rng)) + direction());
    }
    BlobSum::Blob balls[4];
    for (BlobSum::Blob& b : balls) {
      const double radius = 0.05 + 2 * pos(rng);
      // Some with the eye on their sphere, where near = distance - r - slack is about -slack
      // (its rounding shows there), the others anywhere about the frustum.
      b.centre = pos(rng) < 0.2
                     ? sides.eye + direction() * (radius * (1 + 1e-15 * unit(rng)))
                     : sides.eye + forward * (40 * pos(rng)) + direction() * (8 * pos(rng));
      // Now and then a ball whose radius overflows (1 / inv_r2 = inf): the caller's other way.
      b.inv_r2 = pos(rng) < 0.01 ? 1e-320 : 1 / (radius * radius);
      b.c2 = 1;
      b.c3 = 0;
    }
    const BlobSum::Blob* const lanes[4] = {&balls[0], &balls[1], &balls[2], &balls[3]};
    double near_s[4], far_s[4], near_v[4], far_v[4];
    const unsigned s = balls_in_beam_scalar(lanes, sides, near_s, far_s);
    const unsigned v = balls_in_beam_avx2(lanes, sides, near_v, far_v);
    ASSERT_EQ(s >> 4, v >> 4) << "trial " << trial;
    for (int i = 0; i < 4; ++i) {
      if (s >> (4 + i) & 1) {
        ++not_finite;
        continue;
      }
      ASSERT_EQ(s >> i & 1, v >> i & 1) << "trial " << trial << " lane " << i;
      if (!(s >> i & 1)) {
        ++dropped;
        continue;
      }
      ++kept;
      ASSERT_EQ(std::memcmp(&near_s[i], &near_v[i], sizeof(double)), 0)
          << near_s[i] << " / " << near_v[i];
      ASSERT_EQ(std::memcmp(&far_s[i], &far_v[i], sizeof(double)), 0)
          << far_s[i] << " / " << far_v[i];
    }
  }
  // Both outcomes, and the overflowing radius, were compared many times.
  EXPECT_GT(kept, 50000);
  EXPECT_GT(dropped, 50000);
  EXPECT_GT(not_finite, 1000);
}

TEST(BallsInBeam, Avx2DropsTheScalarTestsBallsAtTheirPlanesToTheUlp) {
  // A ball moved across one side plane (the others cut nothing) by bisection to the two adjacent
  // offsets where the scalar test turns; there the plane's dot product and the reach decide to
  // the last bit, and the kernel must turn at the same offset.
  if (!BlobSum::has_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> unit(-1, 1), pos(0, 1);
  int turns = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    BeamSides sides;
    sides.eye = {20 * unit(rng), 20 * unit(rng), 20 * unit(rng)};
    sides.eye_scale = max_abs(sides.eye);
    const Vec3 n = normalize(Vec3{unit(rng), unit(rng), unit(rng)});
    sides.normals[0] = n;
    for (int i = 1; i < 4; ++i) sides.normals[i] = {0, 0, 0};
    const double radius = 0.1 + 3 * pos(rng);
    const Vec3 base = sides.eye + normalize(cross(n, Vec3{0.2, 1, 0.3})) * (30 * pos(rng));
    BlobSum::Blob ball;
    ball.inv_r2 = 1 / (radius * radius);
    ball.c2 = 1;
    ball.c3 = 0;
    const auto in = [&](double s) {
      ball.centre = base + n * s;
      double near, far;
      return ball_in_beam(ball, sides, &near, &far);
    };
    double out = -2 * radius, inside = 0;  // out of the beam at `out`, in it at `inside`
    if (in(out) || !in(inside)) continue;
    while (std::nextafter(out, inside) != inside) {
      const double mid = 0.5 * (out + inside);
      if (mid == out || mid == inside) break;
      (in(mid) ? inside : out) = mid;
    }
    for (double s = out, k = 0; k < 8; s = std::nextafter(s, inside), ++k) {
      const bool scalar = in(s);
      const BlobSum::Blob* const lanes[4] = {&ball, &ball, &ball, &ball};
      double near[4], far[4];
      const unsigned v = balls_in_beam_avx2(lanes, sides, near, far);
      ASSERT_EQ(scalar, (v & 1) != 0) << "trial " << trial << " offset " << s;
      ASSERT_EQ(v & 15, scalar ? 15u : 0u);
      turns += scalar && s != out;
    }
  }
  EXPECT_GT(turns, 1000);
}

}  // namespace softtrace::test
