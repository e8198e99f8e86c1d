// pow_by_squaring (math/int_power.h): the unrolled forms the papers' exponents take give the bits
// of the loop's order, which the power sums' point values and bounds share, and x^k within a few
// ulps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "math/int_power.h"

namespace softtrace {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
}

// The order the header states, written out independently.
double loop_power(double x, int k) {
  double r = 1;
  while (k) {
    if (k & 1) r *= x;
    x *= x;
    k >>= 1;
  }
  return r;
}

template <int K>
void expect_loop_bits(double x) {
  EXPECT_TRUE(same_bits(pow_by_squaring<K>(x), loop_power(x, K))) << "x = " << x << ", k = " << K;
}

TEST(IntPower, EveryFormHasTheLoopsBits) {
  std::mt19937_64 rng(35);
  std::uniform_real_distribution<double> unit(0, 1), wide(-3, 3);
  for (int trial = 0; trial < 2000; ++trial) {
    const double x = trial % 2 ? unit(rng) : wide(rng);
    for (int k = 0; k <= 64; ++k)
      EXPECT_TRUE(same_bits(pow_by_squaring(x, k), loop_power(x, k)))
          << "x = " << x << ", k = " << k;
    expect_loop_bits<4>(x);
    expect_loop_bits<19>(x);
    expect_loop_bits<20>(x);
    expect_loop_bits<33>(x);
  }
}

TEST(IntPower, NearStdPow) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(0.01, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    const double x = unit(rng);
    for (int k : {2, 3, 4, 7, 8, 19, 20, 23}) {
      const double want = std::pow(x, k);
      EXPECT_NEAR(pow_by_squaring(x, k), want, 1e-14 * want) << "x = " << x << ", k = " << k;
    }
  }
  EXPECT_TRUE(same_bits(pow_by_squaring(0.0, 0), 1.0));
  EXPECT_TRUE(std::isinf(pow_by_squaring<20>(1e300)));
  EXPECT_EQ(pow_by_squaring<19>(-1.0), -1.0);
}

}  // namespace
}  // namespace softtrace
