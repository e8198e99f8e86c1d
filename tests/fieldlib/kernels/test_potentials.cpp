// Potential properties of docs/math.md §3 ([PB-1]..[PB-6]) for several s, and Wyvill/quartic facts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "model/potential.h"

namespace softtrace {
namespace {

double P(const Potential& p, double d) {
  return p.eval(d, nullptr);
}
double dP(const Potential& p, double d) {
  double g;
  p.eval(d, &g);
  return g;
}

class Blanc : public testing::TestWithParam<double> {};

TEST_P(Blanc, StatedValues) {  // [PB-1], [PB-6] at the level
  const auto p = make_blanc(GetParam());
  EXPECT_DOUBLE_EQ(P(*p, 0), 1);
  EXPECT_NEAR(P(*p, 0.5), 0.5, 1e-15);
  EXPECT_NEAR(P(*p, std::nextafter(0.5, 1.0)), 0.5, 1e-12);  // both branches meet
  EXPECT_EQ(P(*p, 1), 0);
  EXPECT_EQ(P(*p, 1.7), 0);
  EXPECT_EQ(P(*p, -0.3), 1) << "d is clamped at 0 (docs/math.md §3.1)";
}

TEST_P(Blanc, FlatAtBothEnds) {  // [PB-2]
  const auto p = make_blanc(GetParam());
  EXPECT_EQ(dP(*p, 0), 0);
  EXPECT_NEAR(dP(*p, 1e-9), 0, 1e-7);
  EXPECT_NEAR(dP(*p, 1 - 1e-9), 0, 1e-7);
  EXPECT_EQ(dP(*p, 1), 0);
}

TEST_P(Blanc, C1AtTheJoint) {  // [PB-3]
  const double s = GetParam();
  const auto p = make_blanc(s);
  const double expect = -2 - 16.0 / 9.0 * s;
  EXPECT_NEAR(dP(*p, 0.5), expect, 1e-12);
  EXPECT_NEAR(dP(*p, std::nextafter(0.5, 1.0)), expect, 1e-9);
}

TEST_P(Blanc, MonotoneAndLipschitz) {  // [PB-4], [PB-5], and P = 0.5 only at d = 0.5 ([PB-6])
  const auto p = make_blanc(GetParam());
  double prev = P(*p, 0), max_slope = 0;
  for (int i = 1; i <= 20000; ++i) {
    const double d = i / 20000.0, v = P(*p, d);
    ASSERT_LE(v, prev + 1e-15) << "at d = " << d;
    if (std::abs(d - 0.5) > 1e-3) {
      ASSERT_NE(v, 0.5) << "at d = " << d;
    }
    max_slope = std::max(max_slope, std::abs(dP(*p, d)));
    // analytic derivative agrees with the values
    if (d > 1e-3 && d < 1 - 1e-3 && std::abs(d - 0.5) > 1e-3) {
      const double h = 1e-7, fd = (P(*p, d + h) - P(*p, d - h)) / (2 * h);
      ASSERT_NEAR(dP(*p, d), fd, 1e-6 * std::max(1.0, std::abs(fd))) << "at d = " << d;
    }
    prev = v;
  }
  EXPECT_LE(max_slope, p->lipschitz());
  EXPECT_NEAR(max_slope, p->lipschitz(), 1e-3) << "the bound is attained at d = 0.5";
}

// The batch evaluator's form gives the kernel's bits: across both pieces, at the joint, the ends,
// outside, below 0 and at NaN.
TEST_P(Blanc, LanesGiveTheKernelsBits) {
  const double s = GetParam();
  std::vector<double> d;
  for (int i = -20; i <= 260; ++i) d.push_back(i / 200.0);
  for (const double e : {0.5, std::nextafter(0.5, 0.0), std::nextafter(0.5, 1.0), 1.0,
                         std::nextafter(1.0, 0.0), 1e-300, -0.0, double(NAN), double(INFINITY)})
    d.push_back(e);
  for (size_t at = 0; at < d.size(); at += 16) {
    const int n = static_cast<int>(std::min<size_t>(16, d.size() - at));
    double P[16];
    blanc_lanes(d.data() + at, s, n, P);
    for (int l = 0; l < n; ++l) {
      const double want = blanc(d[at + l], s, nullptr);
      if (std::isnan(want))
        EXPECT_TRUE(std::isnan(P[l])) << "d = " << d[at + l];
      else
        EXPECT_EQ(P[l], want) << "d = " << d[at + l] << ", s = " << s;
    }
  }
}

// The bounds' one call per end: the values and the slope range of the four calls apart, bit for
// bit, for ends below 0, past 1, at -0, NaN, and an empty interval.
TEST_P(Blanc, EndsGiveTheSeparateCallsBits) {
  const double s = GetParam();
  std::vector<double> d;
  for (int i = -30; i <= 260; i += 7) d.push_back(i / 200.0);
  for (const double e :
       {0.5, std::nextafter(0.5, 0.0), std::nextafter(0.5, 1.0), 1.0, std::nextafter(1.0, 0.0),
        1e-300, -0.0, 0.0, double(NAN), double(INFINITY), -double(INFINITY)})
    d.push_back(e);
  const auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  for (const double lo : d)
    for (const double hi : d) {
      const Interval I{lo, hi};
      double least, most;
      Interval slope;
      blanc_ends(s, I, &least, &most, &slope);
      const Interval want = blanc_slope_range(s, I);
      ASSERT_TRUE(same(least, blanc(hi, s, nullptr))) << lo << " " << hi;
      ASSERT_TRUE(same(most, blanc(std::max(0.0, lo), s, nullptr))) << lo << " " << hi;
      ASSERT_TRUE(same(slope.lo, want.lo) && same(slope.hi, want.hi)) << lo << " " << hi;
      double least_only, most_only;
      blanc_ends(s, I, &least_only, &most_only, nullptr);
      ASSERT_TRUE(same(least_only, least) && same(most_only, most)) << lo << " " << hi;
    }
}

INSTANTIATE_TEST_SUITE_P(Softness, Blanc, testing::Values(0.0, 0.25, 0.5, 1.0, 3.0, 20.0));

TEST(Wyvill, RequirementsAndBound) {
  const auto p =
      create_wyvill(Params(nlohmann::json::object(), "", std::make_shared<std::string>("t")));
  EXPECT_EQ(P(*p, 0), 1);
  EXPECT_NEAR(P(*p, 0.5), 0.5, 1e-15);
  EXPECT_NEAR(P(*p, 1), 0, 1e-15);
  EXPECT_NEAR(dP(*p, 1), 0, 1e-14);
  double max_slope = 0;
  for (int i = 0; i <= 20000; ++i) max_slope = std::max(max_slope, std::abs(dP(*p, i / 20000.0)));
  EXPECT_LE(max_slope, p->lipschitz());
  EXPECT_NEAR(max_slope, p->lipschitz(), 1e-6);
}

TEST(Murakami, QuarticFacts) {
  const auto p =
      create_murakami(Params(nlohmann::json::object(), "", std::make_shared<std::string>("t")));
  EXPECT_NEAR(P(*p, 0.5), 9.0 / 16.0, 1e-15);
  EXPECT_NEAR(P(*p, std::sqrt(1 - std::sqrt(0.5))), 0.5, 1e-15);  // its 0.5 level, d = 0.5412
  double max_slope = 0;
  for (int i = 0; i <= 20000; ++i) max_slope = std::max(max_slope, std::abs(dP(*p, i / 20000.0)));
  EXPECT_LE(max_slope, p->lipschitz());
  EXPECT_NEAR(max_slope, p->lipschitz(), 1e-6);
}

// The range of |P'| over an interval of d (the tracer's slope along a segment) holds every
// sampled |P'| in it, and is the ends' values and the peak: tight, not just [0, max].
void check_slope_ranges(const Potential& p, Interval (*range)(const Potential&, Interval),
                        double peak_at) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 1.2);
  int narrowed = 0;
  for (int i = 0; i < 2000; ++i) {
    double lo = u(rng), hi = u(rng);
    if (lo > hi) std::swap(lo, hi);
    if (i % 4 == 0) hi = lo + (hi - lo) * 1e-3;  // short ones, as along a short segment
    const Interval r = range(p, {lo, hi});
    for (int j = 0; j <= 50; ++j) {
      const double d = lo + (hi - lo) * j / 50, s = std::abs(dP(p, d));
      ASSERT_LE(r.lo, s) << "[" << lo << ", " << hi << "] at " << d;
      ASSERT_GE(r.hi, s) << "[" << lo << ", " << hi << "] at " << d;
    }
    const double a = std::abs(dP(p, std::clamp(lo, 0.0, 1.0)));
    const double b = std::abs(dP(p, std::clamp(hi, 0.0, 1.0)));
    EXPECT_NEAR(r.lo, std::min(a, b), 1e-9);
    const bool peak = lo <= peak_at && peak_at <= hi;
    EXPECT_NEAR(r.hi, peak ? p.lipschitz() : std::max(a, b), 1e-9);
    narrowed += r.lo > 0;
  }
  EXPECT_GT(narrowed, 500);
}

TEST_P(Blanc, SlopeRangeIsUnimodal) {  // |P'| rises to d = 0.5 and falls after (docs/math.md §3.2)
  check_slope_ranges(
      *make_blanc(GetParam()),
      [](const Potential& p, Interval d) { return blanc_slope_range(p.parameter(), d); }, 0.5);
}

TEST(Wyvill, SlopeRangeIsUnimodal) {
  const auto p =
      create_wyvill(Params(nlohmann::json::object(), "", std::make_shared<std::string>("t")));
  check_slope_ranges(
      *p, [](const Potential&, Interval d) { return wyvill_slope_range(d); }, wyvill_peak());
}

TEST(Murakami, SlopeRangeIsUnimodal) {
  const auto p =
      create_murakami(Params(nlohmann::json::object(), "", std::make_shared<std::string>("t")));
  check_slope_ranges(
      *p, [](const Potential&, Interval d) { return murakami_slope_range(d); }, 1 / std::sqrt(3.0));
}

TEST(Potential, IntervalIsTheMonotoneImage) {
  const auto p = make_blanc(0.3);
  const Interval I = p->interval({0.2, 0.7});
  EXPECT_LE(I.lo, P(*p, 0.7));
  EXPECT_GE(I.hi, P(*p, 0.2));
  EXPECT_NEAR(I.lo, P(*p, 0.7), 1e-15);
  EXPECT_EQ(p->lipschitz(Interval{1.0, 3.0}), 0) << "flat beyond the influential radius";
}

}  // namespace
}  // namespace softtrace
