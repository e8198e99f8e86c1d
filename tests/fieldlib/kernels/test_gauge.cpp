// power_sum, its batched form (fieldlib/gauge.h) and its form with partials (convex_slope.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "kernels/convex_slope.h"
#include "kernels/gauge.h"
#include "math/int_power.h"

namespace softtrace::test {

namespace {
// (Σ u_i^n)^(1/n) in long double (64-bit mantissa): a reference 2^11 times finer than a double.
long double reference(const double* u, int k, double n) {
  long double m = 0, s = 0;
  for (int i = 0; i < k; ++i) m = std::max<long double>(m, u[i]);
  for (int i = 0; i < k; ++i) s += std::pow(u[i] / m, static_cast<long double>(n));
  return m * std::pow(s, 1 / static_cast<long double>(n));
}
}  // namespace

// power_sum against long double, over the exponents the scenes use and a spread of others: within
// 2 ulps for n >= 1 and 4 for n < 1, which the interval forms' 1e-13 widening covers many times.
TEST(PowerSum, IsWithinAFewUlps) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (const double n : {0.5, 0.8, 1.5, 2.5, 3.0, 4.0, 7.0, 8.0, 16.0, 20.0, 50.0, 200.0}) {
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
      const double v[3] = {u(rng), u(rng), i % 3 ? u(rng) : 0.0};
      const double f = power_sum(v, 3, n, nullptr);
      const long double ref = reference(v, 3, n);
      worst = std::max(worst, static_cast<double>(std::abs(f - ref) / ref) / 0x1p-52);
    }
    EXPECT_LE(worst, n >= 1 ? 2 : 4) << "n = " << n << ": " << worst << " ulps";
  }
}

// The root of a power sum relative to its largest term (s in [1, k]) by square roots for n = 4, 8
// and 16: within an ulp of the long double root, as std::pow is.
TEST(PowerRoot, SquareRootsAreWithinAnUlp) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(1, 3);
  for (const double n : {4.0, 8.0, 16.0}) {
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
      const double s = u(rng);
      const long double ref =
          std::pow(static_cast<long double>(s), 1 / static_cast<long double>(n));
      worst =
          std::max(worst, static_cast<double>(std::abs(power_root(s, n) - ref) / ref) / 0x1p-53);
    }
    EXPECT_LE(worst, 2) << "n = " << n << ": " << worst << " half-ulps";
  }
  EXPECT_EQ(power_root(0, 8), 0);
  EXPECT_EQ(power_root(1, 16), 1);
}

// The cubes' and bars' root (n = 20) by root_20 over [1, 4), the sums of up to four terms: within
// an ulp of the long double root (a faithful rounding) across the range and at its joins, and
// std::pow's bits outside it.
TEST(PowerRoot, TwentiethIsWithinAnUlp) {
  std::mt19937_64 rng(36);
  std::uniform_real_distribution<double> u(1, 4);
  std::vector<double> s_values = {1, std::nextafter(1.0, 2), std::nextafter(2.0, 1), 2, 1.5,
                                  3, std::nextafter(4.0, 1)};
  for (int i = 0; i < 200000; ++i) s_values.push_back(u(rng));
  double worst = 0;
  for (const double s : s_values) {
    const long double ref = std::pow(static_cast<long double>(s), 1 / 20.0L);
    const double r = power_root(s, 20);
    EXPECT_EQ(r, root_20(s));
    worst = std::max(worst, static_cast<double>(std::abs(r - ref) / ref) / 0x1p-53);
  }
  EXPECT_LE(worst, 2) << worst << " half-ulps";
  EXPECT_EQ(power_root(1, 20), 1);
  for (const double s : {0.0, 0.5, 4.0, 1e300, HUGE_VAL})
    EXPECT_EQ(root_20(s), std::pow(s, 0.05)) << "s = " << s;
  EXPECT_TRUE(std::isnan(root_20(NAN)));
}

// The batch gives power_sum's bits lane by lane, zeros, infinities and NaN included.
TEST(PowerSum, LanesGiveTheSingleCallsBits) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0, 3);
  for (const double n : {0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 8.0, 16.0, 20.0, -3.0}) {
    for (const int k : {1, 2, 3}) {
      double terms[3][16];
      for (int i = 0; i < k; ++i)
        for (int l = 0; l < 16; ++l) terms[i][l] = u(rng);
      for (int i = 0; i < k; ++i) terms[i][3] = 0;  // a lane at the centre
      terms[0][5] = INFINITY;
      terms[k - 1][7] = NAN;
      terms[0][9] = 1e-300;  // terms that underflow relative to the largest
      const double* rows[3] = {terms[0], terms[1], terms[2]};
      double f[16];
      power_sum_lanes(rows, k, n, 13, f);
      for (int l = 0; l < 13; ++l) {
        double v[3];
        for (int i = 0; i < k; ++i) v[i] = terms[i][l];
        const double want = power_sum(v, k, n, nullptr);
        if (std::isnan(want))
          EXPECT_TRUE(std::isnan(f[l])) << "n = " << n << ", k = " << k << ", lane " << l;
        else
          EXPECT_EQ(f[l], want) << "n = " << n << ", k = " << k << ", lane " << l;
      }
    }
  }
}

// power_sum_partials at n = 20, its powers and root inline with the exponent fixed, gives the
// bits of the run-time forms (pow_by_squaring(b, 19), power_root(s, 20)) for f and every partial.
TEST(PowerSum, PartialsAtTwentyGiveTheRunTimeFormsBits) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 3);
  for (int trial = 0; trial < 2000; ++trial) {
    const int k = 1 + trial % 3;
    double v[3];
    for (int i = 0; i < k; ++i) v[i] = u(rng);
    if (trial % 7 == 0) v[0] = 0;
    if (trial % 11 == 0) v[k - 1] = 1e-300;
    if (trial == 13) std::fill(v, v + k, 0.0);
    double got[3], want[3];
    const double f = power_sum_partials(v, k, 20, got);
    const double g = power_sum_partials_with(
        v, k, want, [](double b) { return pow_by_squaring(b, 19); },
        [](double s) { return power_root(s, 20); });
    ASSERT_EQ(f, g) << "trial " << trial;
    for (int i = 0; i < k; ++i) ASSERT_EQ(got[i], want[i]) << "trial " << trial << ", term " << i;
  }
}

}  // namespace softtrace::test
