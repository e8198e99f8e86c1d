// scaled() and divided() (math/interval.h) give the bits of the general product and quotient they
// stand for in the bounds pass: over signed zeros, infinities, NaN, subnormals and random ends.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "math/interval.h"

namespace softtrace {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
}

::testing::AssertionResult same(Interval got, Interval want) {
  if (same_bits(got.lo, want.lo) && same_bits(got.hi, want.hi))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "[" << got.lo << ", " << got.hi << "] against [" << want.lo << ", " << want.hi << "]";
}

// Interval ends (lo <= hi) and scalars that reach every branch: signs, zeros, infinities, NaN,
// the smallest and largest doubles.
std::vector<double> special_values() {
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double big = std::numeric_limits<double>::max();
  return {-kInf, -big, -2.5, -1, -1e-300, -tiny, -0.0, 0.0, tiny, 1e-300, 0.3, 1, 2.5, big, kInf};
}

std::vector<Interval> intervals(std::mt19937_64& rng) {
  std::vector<Interval> out;
  const std::vector<double> v = special_values();
  for (double a : v)
    for (double b : v)
      if (a <= b) out.push_back({a, b});
  out.push_back({NAN, 1});
  out.push_back({-1, NAN});
  std::uniform_real_distribution<double> u(-4, 4), e(-30, 30);
  for (int i = 0; i < 2000; ++i) {
    double a = u(rng) * std::pow(10, e(rng)), b = u(rng) * std::pow(10, e(rng));
    if (a > b) std::swap(a, b);
    out.push_back({a, b});
  }
  return out;
}

TEST(IntervalConstants, ScaledIsTheGeneralProduct) {
  std::mt19937_64 rng(36);
  const std::vector<Interval> xs = intervals(rng);
  std::vector<double> ss = special_values();
  ss.push_back(NAN);
  std::uniform_real_distribution<double> u(-4, 4);
  for (int i = 0; i < 200; ++i) ss.push_back(u(rng));
  for (double s : ss)
    for (const Interval& a : xs) EXPECT_TRUE(same(scaled(s, a), Interval(s) * a)) << "s = " << s;
}

TEST(IntervalConstants, DividedIsTheGeneralQuotient) {
  std::mt19937_64 rng(37);
  const std::vector<Interval> xs = intervals(rng);
  std::vector<double> bs = special_values();
  bs.push_back(NAN);
  std::uniform_real_distribution<double> u(0, 8);
  for (int i = 0; i < 200; ++i) bs.push_back(u(rng));
  for (double b : bs)
    for (const Interval& a : xs) EXPECT_TRUE(same(divided(a, b), a / Interval(b))) << "b = " << b;
}

}  // namespace
}  // namespace softtrace
