// Properties of the scalar BT_k operators (docs/math.md §6.1, §6.2, §7): [BH-1], [BH-2],
// [BT-1]..[BT-5], [BT2-1]..[BT2-4], [BTK-1], [BTK-2], [BD-1], [GR-1]..[GR-3], and "the level set BT
// = h is the base surface translated by h·m". Random inputs use fixed seeds; parameter ranges
// follow docs/math.md's verification scripts (verify/v4_bt.py), including hyperbolic conics and a <
// 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/bt_base.h"

namespace softtrace {
namespace {

using Rng = std::mt19937_64;

double uni(Rng& g, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(g);
}

struct Conic {
  double r1, r2, p, m[2];
  double operator()(double x1, double x2, double* dx = nullptr) const {
    const double x[2] = {x1, x2};
    return bt2_conic(x, r1, r2, p, m, dx);
  }
  bool in_ii(double x1, double x2) const {
    const double x[2] = {x1, x2};
    return conic_region_ii(x, r1, r2, m);
  }
};

Conic random_conic(Rng& g) {
  Conic c;
  c.r1 = uni(g, 0.05, 3);
  c.r2 = uni(g, 0.05, 3);
  c.p = uni(g, -4 * c.r1 * c.r2, 0.999 * c.r1 * c.r2);
  c.m[0] = uni(g, 0.1, 3);
  c.m[1] = uni(g, 0.1, 3);
  return c;
}

struct Hyper {
  int k;
  double r[6], p[6], m[6];
  double operator()(const double* x, double* dx = nullptr, int* it = nullptr) const {
    return bt_hyper(x, k, r, p, m, dx, it);
  }
};

Hyper random_hyper(Rng& g, int k) {
  Hyper h;
  h.k = k;
  for (int i = 0; i < k; ++i) {
    h.r[i] = uni(g, 0.1, 3);
    h.p[i] = uni(g, 1.1, 6);
    h.m[i] = uni(g, 0.2, 3);
  }
  return h;
}

double min_ratio(const double* x, const double* m, int k) {
  return bt_upper(x, k, m);
}

TEST(Hoffmann, IdentityAndTangencies) {  // [BH-1]
  Rng g(11);
  for (int n = 0; n < 20000; ++n) {
    const double r1 = uni(g, 0.05, 3), r2 = uni(g, 0.05, 3), p = uni(g, -5, r1 * r2);
    const double x1 = uni(g, -3, 5), x2 = uni(g, -3, 5);
    const double expanded = r2 * r2 * x1 * x1 + r1 * r1 * x2 * x2 + r2 * r2 * r1 * r1 -
                            2 * r2 * r2 * r1 * x1 - 2 * r1 * r1 * r2 * x2 + 2 * p * x1 * x2;
    const double scale = 1 + std::abs(expanded) + 100 * r1 * r1 * r2 * r2;
    ASSERT_NEAR(hoffmann_conic(x1, x2, r1, r2, p), expanded, 1e-12 * scale);
    ASSERT_NEAR(hoffmann_conic(x1, 0, r1, r2, p), r2 * r2 * (x1 - r1) * (x1 - r1), 1e-12 * scale);
    ASSERT_NEAR(hoffmann_conic(0, x2, r1, r2, p), r1 * r1 * (x2 - r2) * (x2 - r2), 1e-12 * scale);
  }
}

TEST(Hoffmann, PositiveInTheFilletNegativeOnTheChord) {  // [BH-2]
  Rng g(12);
  for (int n = 0; n < 20000; ++n) {
    const double r1 = uni(g, 0.05, 3), r2 = uni(g, 0.05, 3), p = uni(g, -5, 0.999 * r1 * r2);
    const double e = 1e-3 * std::min(r1, r2), t = uni(g, 1e-6, 1 - 1e-6);
    ASSERT_GT(hoffmann_conic(e, e, r1, r2, p), 0);
    ASSERT_LT(hoffmann_conic(t * r1, (1 - t) * r2, r1, r2, p), 0);
  }
}

TEST(BT, ZeroSetIndependentOfM) {  // [BT-1]
  Rng g(13);
  int decided = 0;
  for (int n = 0; n < 50000; ++n) {
    Conic c = random_conic(g);
    const double x1 = uni(g, -1, 4), x2 = uni(g, -1, 4);
    Conic unit = c;
    unit.m[0] = unit.m[1] = 1;
    const double v1 = unit(x1, x2), v = c(x1, x2);
    if (std::abs(v1) > 1e-9) {
      ++decided;
      ASSERT_EQ(v > 0, v1 > 0) << x1 << " " << x2;
    }
    Hyper h = random_hyper(g, 3), hu = h;
    std::fill(hu.m, hu.m + 3, 1.0);
    const double x[3] = {uni(g, -1, 4), uni(g, -1, 4), uni(g, -1, 4)};
    const double w1 = hu(x), w = h(x);
    if (std::abs(w1) > 1e-9) {
      ASSERT_EQ(w > 0, w1 > 0);
    }
  }
  EXPECT_GT(decided, 40000);
}

TEST(BT, Translation) {  // [BT-2]
  Rng g(14);
  for (int n = 0; n < 50000; ++n) {
    const Conic c = random_conic(g);
    const double x1 = uni(g, -2, 6), x2 = uni(g, -2, 6), t = uni(g, -3, 3);
    const double v = c(x1, x2);
    ASSERT_NEAR(c(x1 + t * c.m[0], x2 + t * c.m[1]), v + t, 1e-8 * (1 + std::abs(v) + std::abs(t)));
    const int k = 2 + n % 4;
    const Hyper h = random_hyper(g, k);
    double x[6], y[6];
    for (int i = 0; i < k; ++i) {
      x[i] = uni(g, -2, 5);
      y[i] = x[i] + t * h.m[i];
    }
    const double w = h(x);
    ASSERT_NEAR(h(y), w + t, 1e-8 * (1 + std::abs(w) + std::abs(t)));
  }
}

TEST(BT, MinOutsideTheBlendingRegionAndBelowItEverywhere) {  // [BT-3]
  Rng g(15);
  int outside = 0, nonblend = 0, blend = 0;
  for (int n = 0; n < 50000; ++n) {
    const Conic c = random_conic(g);
    const double x1 = uni(g, -2, 6), x2 = uni(g, -2, 6);
    const double hmin = std::min(x1 / c.m[0], x2 / c.m[1]), v = c(x1, x2);
    ASSERT_LE(v, hmin);
    if (!c.in_ii(x1, x2)) {
      ++outside;
      ASSERT_EQ(v, hmin);
    }
    const int k = 2 + n % 4;
    const Hyper h = random_hyper(g, k);
    double x[6];
    for (int i = 0; i < k; ++i) x[i] = uni(g, -2, 5);
    const double hh = min_ratio(x, h.m, k), w = h(x);
    ASSERT_LE(w, hh);
    int j = 0;
    for (int i = 1; i < k; ++i)
      if (x[i] / h.m[i] < x[j] / h.m[j]) j = i;
    bool only_j = true;  // the non-blending region of §7.3
    for (int i = 0; i < k; ++i)
      if (i != j && x[i] - h.m[i] * hh < h.r[i]) only_j = false;
    if (only_j) {
      ++nonblend;
      ASSERT_NEAR(w, hh, 1e-12 * (1 + std::abs(hh)));
    } else if (hyper_T(x, k, h.r, h.p, h.m, hh) > 1e-9) {
      ++blend;
      ASSERT_LT(w, hh);
    }
  }
  EXPECT_GT(outside, 10000);
  EXPECT_GT(nonblend, 5000);
  EXPECT_GT(blend, 5000);
}

// BT_2(BT_2(f1, f2), f3): where the inner blend is non-blending with value f_2/m_2, the outer
// band 0 <= inner <= r becomes 0 <= f_2 <= r·m_2. On f3 = 0 the outer blend moves the surface
// (value < 0) exactly while f_2 < r·m_2.
TEST(BT, SubsequentRangesScaleWithM) {  // [BT-4]
  const double r = 0.4;
  const Conic outer{r, 0.3, 0, {1, 1}};
  for (double m2 : {0.3, 0.5, 1.0, 2.0}) {
    const Hyper inner{2, {0.2, 0.2}, {2, 2}, {1, m2}};
    auto blend = [&](double f2) {
      const double x[2] = {10, f2};  // f1 far away: the inner blend is min = f2/m2
      const double v = inner(x);
      EXPECT_DOUBLE_EQ(v, f2 / m2);
      return outer(v, 0);
    };
    EXPECT_LT(blend(r * m2 * (1 - 1e-6)), 0) << "m2 = " << m2;
    EXPECT_LT(blend(r * m2 * 0.5), 0) << "m2 = " << m2;
    EXPECT_EQ(blend(r * m2 * (1 + 1e-6)), 0) << "m2 = " << m2;
    EXPECT_EQ(blend(r * m2 * 1.5), 0) << "m2 = " << m2;
  }
}

TEST(BT, MonotoneInEveryArgument) {  // [BT-5]
  Rng g(16);
  for (int n = 0; n < 30000; ++n) {
    const Conic c = random_conic(g);
    const double x1 = uni(g, -2, 6), x2 = uni(g, -2, 6), d = uni(g, 0, 0.5);
    double dx[2];
    const double v = c(x1, x2, dx);
    ASSERT_GE(dx[0], 0);
    ASSERT_GE(dx[1], 0);
    ASSERT_GE(c(x1 + d, x2), v - 1e-12 * (1 + std::abs(v)));
    ASSERT_GE(c(x1, x2 + d), v - 1e-12 * (1 + std::abs(v)));
    const Hyper h = random_hyper(g, 3);
    double x[3] = {uni(g, -2, 5), uni(g, -2, 5), uni(g, -2, 5)}, dh[3];
    const double w = h(x, dh);
    for (int i = 0; i < 3; ++i) ASSERT_GE(dh[i], 0);
    x[n % 3] += d;
    ASSERT_GE(h(x), w - 1e-12 * (1 + std::abs(w)));
  }
}

TEST(BT2, RootLiesOnTheArcBetweenChordAndCorner) {  // [BT2-1]
  Rng g(17);
  int in_ii = 0, negative_a = 0;
  for (int n = 0; n < 100000; ++n) {
    const Conic c = random_conic(g);
    const double x1 = uni(g, -2, 6), x2 = uni(g, -2, 6);
    if (!c.in_ii(x1, x2)) continue;
    ++in_ii;
    const double m1 = c.m[0], m2 = c.m[1];
    if (c.r2 * c.r2 * m1 * m1 + c.r1 * c.r1 * m2 * m2 + 2 * c.p * m1 * m2 < 0) ++negative_a;
    const double v = c(x1, x2);
    const double h1 = std::min(x1 / m1, x2 / m2);
    const double h2 = (c.r1 * x2 + c.r2 * x1 - c.r1 * c.r2) / (c.r1 * m2 + c.r2 * m1);
    ASSERT_GE(v, h2 - 1e-9);
    ASSERT_LE(v, h1);
    const double u1 = x1 - m1 * v, u2 = x2 - m2 * v;
    ASSERT_LT(std::abs(hoffmann_conic(u1, u2, c.r1, c.r2, c.p)),
              1e-7 * std::pow(std::max(1.0, c.r1 * c.r2), 2));
    ASSERT_TRUE(u1 >= -1e-9 && u1 <= c.r1 + 1e-9 && u2 >= -1e-9 && u2 <= c.r2 + 1e-9);
  }
  EXPECT_GT(in_ii, 20000);
  EXPECT_GT(negative_a, 1000) << "the sample must include a < 0";
}

TEST(BT2, C0AndC1AcrossBothBoundaryLines) {  // [BT2-2]
  Rng g(18);
  for (int n = 0; n < 5000; ++n) {
    Conic c = random_conic(g);
    c.p = uni(g, -3 * c.r1 * c.r2, 0.95 * c.r1 * c.r2);
    const double t = uni(g, -2, 3), m1 = c.m[0], m2 = c.m[1];
    const double nx = m2, ny = -m1;  // normal of both lines
    const double on[2][2] = {{m1 * t, c.r2 + m2 * t}, {c.r1 + m1 * t, m2 * t}};
    const double limit[2][2] = {{1 / m1, 0}, {0, 1 / m2}};
    for (int l = 0; l < 2; ++l) {
      // Values 1e-9 off the line on both sides. The gradient is continuous with a square-root
      // modulus (∂_jBT ∝ (u_j - r_j) ∝ sqrt(distance) near a tangency point of the conic), so
      // it is probed 1e-12 off the line.
      const double e = 1e-9, eg = 1e-12;
      double ga[2], gb[2];
      const double va = c(on[l][0] + e * nx, on[l][1] + e * ny);
      const double vb = c(on[l][0] - e * nx, on[l][1] - e * ny);
      ASSERT_NEAR(va, vb, 1e-7) << "line " << l;
      c(on[l][0] + eg * nx, on[l][1] + eg * ny, ga);
      c(on[l][0] - eg * nx, on[l][1] - eg * ny, gb);
      for (int i = 0; i < 2; ++i) {
        const double tol = 1e-4 * (1 + std::abs(limit[l][i]));
        ASSERT_NEAR(ga[i], gb[i], tol) << "line " << l;
        ASSERT_NEAR(ga[i], limit[l][i], tol) << "line " << l;
      }
    }
  }
}

TEST(BT2, UnitWeightsGiveTheDisplacementForm) {  // [BT2-3], §6.2
  Rng g(19);
  int in_ii = 0;
  for (int n = 0; n < 30000; ++n) {
    Conic c = random_conic(g);
    c.m[0] = c.m[1] = 1;
    const double x1 = uni(g, -2, 6), x2 = uni(g, -2, 6), v = c(x1, x2);
    if (c.in_ii(x1, x2)) {
      ++in_ii;  // the level set BD = v is Hoffmann's blend of the shifted primitives f_i - v
      ASSERT_LT(std::abs(hoffmann_conic(x1 - v, x2 - v, c.r1, c.r2, c.p)),
                1e-7 * std::pow(std::max(1.0, c.r1 * c.r2), 2));
    } else {
      ASSERT_EQ(v, std::min(x1, x2));
    }
  }
  EXPECT_GT(in_ii, 5000);
}

TEST(BT2, ConicWithZeroPEqualsHyperEllipsoidWithSquares) {  // [BT2-4]
  Rng g(20);
  for (int n = 0; n < 30000; ++n) {
    Conic c = random_conic(g);
    c.p = 0;
    const Hyper h{2, {c.r1, c.r2}, {2, 2}, {c.m[0], c.m[1]}};
    const double x[2] = {uni(g, -2, 5), uni(g, -2, 5)};
    double dc[2], dh[2];
    const double a = c(x[0], x[1], dc), b = h(x, dh);
    ASSERT_NEAR(a, b, 1e-8 * (1 + std::abs(a)));
    if (std::abs(x[0] / c.m[0] - x[1] / c.m[1]) > 1e-6) {  // away from the kink of min
      ASSERT_NEAR(dc[0], dh[0], 1e-6 * (1 + std::abs(dc[0])));
      ASSERT_NEAR(dc[1], dh[1], 1e-6 * (1 + std::abs(dc[1])));
    }
  }
}

TEST(BTK, BracketEnclosesTheRoot) {  // [BTK-1]
  Rng g(21);
  for (int n = 0; n < 30000; ++n) {
    const int k = 2 + n % 5;
    const Hyper h = random_hyper(g, k);
    double x[6];
    for (int i = 0; i < k; ++i) x[i] = uni(g, -2, 5);
    const double lo = bt_lower(x, k, h.r, h.m), hi = bt_upper(x, k, h.m);
    ASSERT_NEAR(hyper_T(x, k, h.r, h.p, h.m, lo), -1, 1e-12);
    ASSERT_GE(hyper_T(x, k, h.r, h.p, h.m, hi), -1e-12);
    const double v = h(x);
    ASSERT_TRUE(lo <= v && v <= hi);
  }
}

// Newton's steps use T' from hyper_T_slope: its T has hyper_T's bits, its T' central differences'.
TEST(BTK, HyperTSlopeIsTsDerivative) {
  Rng g(24);
  for (int n = 0; n < 20000; ++n) {
    const int k = 2 + n % 5;
    const Hyper h = random_hyper(g, k);
    double x[6];
    for (int i = 0; i < k; ++i) x[i] = uni(g, -2, 5);
    const double lo = bt_lower(x, k, h.r, h.m), hi = bt_upper(x, k, h.m);
    const double t = uni(g, lo, hi + 0.5), e = 1e-6;
    // Central differences straddling a term's kink at 0 (t^p, p near 1) are off: not there.
    bool kink = false;
    for (int i = 0; i < k; ++i) kink |= std::abs((h.r[i] - x[i] + h.m[i] * t) / h.r[i]) < 1e-3;
    if (kink) continue;
    double slope;
    ASSERT_EQ(hyper_T_slope(x, k, h.r, h.p, h.m, t, &slope), hyper_T(x, k, h.r, h.p, h.m, t));
    const double fd =
        (hyper_T(x, k, h.r, h.p, h.m, t + e) - hyper_T(x, k, h.r, h.p, h.m, t - e)) / (2 * e);
    ASSERT_NEAR(slope, fd, 1e-5 * std::max(1.0, std::abs(fd))) << "n = " << n;
  }
}

// Also records the root finder's cost. Measured over these 60 000 inputs (k = 2..6, x_i ∈ [-2, 5],
// r_i ∈ [0.1, 3], p_i ∈ [1.1, 6], m_i ∈ [0.2, 3]): Newton from h_hi, mean 3.61 iterations over
// the 36 367 inputs that needed the solver, max 9; the Illinois Regula Falsi it replaced took 7.05
// over 37 271 (max 18), and one more evaluation of T at h_lo.
TEST(BTK, RootResidualAndIterationCounts) {  // [BTK-2]
  Rng g(22);
  long total = 0, solved = 0, total_solved = 0;
  int worst = 0;
  const int n_inputs = 60000;
  for (int n = 0; n < n_inputs; ++n) {
    const int k = 2 + n % 5;
    const Hyper h = random_hyper(g, k);
    double x[6];
    for (int i = 0; i < k; ++i) x[i] = uni(g, -2, 5);
    int it = 0;
    const double v = h(x, nullptr, &it);
    ASSERT_LT(std::abs(hyper_T(x, k, h.r, h.p, h.m, v)), 1e-9);
    total += it;
    worst = std::max(worst, it);
    if (it > 0) {
      ++solved;
      total_solved += it;
    }
  }
  const double mean = double(total) / n_inputs, mean_solved = double(total_solved) / solved;
  std::printf("Newton iterations: mean %.2f, mean where solved %.2f (%ld of %d), max %d\n", mean,
              mean_solved, solved, n_inputs, worst);
  EXPECT_LT(worst, 40) << "the 200-step cap must never be near";
  // Newton from h_hi took 3.61 (at most 9) where the Illinois Regula Falsi took 7.05 (18).
  EXPECT_LT(mean_solved, 5);
}

TEST(BTDuals, IntersectionAndDifferenceBoundMax) {  // [BD-1]
  Rng g(23);
  int far_i = 0, far_d = 0;
  for (int n = 0; n < 20000; ++n) {
    const double r1 = uni(g, 0.1, 1), r2 = uni(g, 0.1, 1);
    const Conic c{r1, r2, uni(g, -r1 * r2, 0.9 * r1 * r2), {1, 1}};
    const double f1 = uni(g, -5, 5), f2 = uni(g, -5, 5);
    const double I = -c(-f1, -f2), D = -c(-f1, f2);
    ASSERT_GE(I, std::max(f1, f2));
    ASSERT_GE(D, std::max(f1, -f2));
    if (std::abs(f1 - f2) > r1 + r2) {
      ++far_i;
      ASSERT_EQ(I, std::max(f1, f2));
    }
    if (std::abs(f1 + f2) > r1 + r2) {
      ++far_d;
      ASSERT_EQ(D, std::max(f1, -f2));
    }
    const Hyper h{2, {r1, r2}, {uni(g, 1.1, 5), uni(g, 1.1, 5)}, {1, 1}};
    const double a[2] = {-f1, -f2}, b[2] = {-f1, f2};
    ASSERT_GE(-h(a), std::max(f1, f2));
    ASSERT_GE(-h(b), std::max(f1, -f2));
  }
  EXPECT_GT(far_i, 5000);
  EXPECT_GT(far_d, 5000);
}

// Central differences of BT in x_i, step e.
double fd_conic(const Conic& c, double x1, double x2, int i, double e) {
  return i == 0 ? (c(x1 + e, x2) - c(x1 - e, x2)) / (2 * e)
                : (c(x1, x2 + e) - c(x1, x2 - e)) / (2 * e);
}

TEST(BTGradient, ImplicitFunctionGradientMatchesCentralDifferences) {  // [GR-1], [GR-2]
  Rng g(24);
  int near_boundary = 0;
  double worst = 0;
  for (int n = 0; n < 40000; ++n) {
    Conic c = random_conic(g);
    c.p = uni(g, -3 * c.r1 * c.r2, 0.95 * c.r1 * c.r2);
    c.m[0] = uni(g, 0.2, 3);
    c.m[1] = uni(g, 0.2, 3);
    double x1 = uni(g, -1, 5), x2 = uni(g, -1, 5);
    if (n % 2) {  // a point 1e-5..1e-2 off one of region II's boundary lines, either side
      const double t = uni(g, -1, 2), s = std::pow(10, uni(g, -5, -2)) * (n % 4 == 1 ? 1 : -1);
      const bool first = n % 8 < 4;
      x1 = (first ? 0 : c.r1) + c.m[0] * t + s * c.m[1];
      x2 = (first ? c.r2 : 0) + c.m[1] * t - s * c.m[0];
      ++near_boundary;
    }
    if (std::abs(x1 / c.m[0] - x2 / c.m[1]) < 1e-3) continue;  // the kink of min outside II
    double dx[2];
    c(x1, x2, dx);
    ASSERT_NEAR(c.m[0] * dx[0] + c.m[1] * dx[1], 1, 1e-9);  // [GR-2]
    for (int i = 0; i < 2; ++i) {
      const double fd = fd_conic(c, x1, x2, i, 1e-7);
      worst = std::max(worst, std::abs(fd - dx[i]));
      ASSERT_NEAR(dx[i], fd, 1e-4 * (1 + std::abs(dx[i]))) << "x = " << x1 << ", " << x2;
    }
  }
  EXPECT_GT(near_boundary, 15000);
  std::printf("BT2 gradient vs central differences: max abs error %.3g\n", worst);
  for (int n = 0; n < 30000; ++n) {
    const int k = 2 + n % 4;
    const Hyper h = random_hyper(g, k);
    double x[6], dx[6];
    for (int i = 0; i < k; ++i) x[i] = uni(g, -2, 5);
    h(x, dx);
    double s = 0;
    for (int i = 0; i < k; ++i) s += h.m[i] * dx[i];
    ASSERT_NEAR(s, 1, 1e-9);  // [GR-2]
    const int i = n % k;
    const double hh = min_ratio(x, h.m, k);
    if (std::abs(x[i] / h.m[i] - hh) < 1e-3 && x[i] / h.m[i] != hh) continue;
    double xp[6], xm[6];
    std::copy(x, x + k, xp);
    std::copy(x, x + k, xm);
    xp[i] += 1e-6;
    xm[i] -= 1e-6;
    const double fd = (h(xp) - h(xm)) / 2e-6;
    // Skip the kink of min where only term i is active at h_hi (one-sided derivatives differ).
    double dp[6], dm[6];
    h(xp, dp);
    h(xm, dm);
    if (std::abs(dp[i] - dm[i]) > 0.1) continue;
    ASSERT_NEAR(dx[i], fd, 1e-4 * (1 + std::abs(dx[i])));
  }
}

TEST(BTGradient, ConicParameterDerivativesMatchCentralDifferences) {  // [GR-3]
  Rng g(25);
  int checked = 0;
  for (int n = 0; n < 20000; ++n) {
    const double r1 = uni(g, 0.2, 3), r2 = uni(g, 0.2, 3), p = uni(g, -2 * r1 * r2, 0.9 * r1 * r2);
    const double m[2] = {uni(g, 0.3, 3), uni(g, 0.3, 3)}, x[2] = {uni(g, -1, 5), uni(g, -1, 5)};
    const double e = 1e-6;
    const double xs[2][2] = {{x[0], x[1] + e * 1e3}, {x[0], x[1] - e * 1e3}};
    if (!conic_region_ii(x, r1, r2, m) || !conic_region_ii(xs[0], r1, r2, m) ||
        !conic_region_ii(xs[1], r1, r2, m))
      continue;
    ++checked;
    const ConicParameterDerivatives d = bt2_conic_parameter_derivatives(x, r1, r2, p, m);
    auto B = [&](double R1, double R2, double P, double M1, double M2) {
      const double mm[2] = {M1, M2};
      return bt2_conic(x, R1, R2, P, mm, nullptr);
    };
    const double m1 = m[0], m2 = m[1];
    const double fd_r1 = (B(r1 + e, r2, p, m1, m2) - B(r1 - e, r2, p, m1, m2)) / (2 * e);
    const double fd_r2 = (B(r1, r2 + e, p, m1, m2) - B(r1, r2 - e, p, m1, m2)) / (2 * e);
    const double fd_p = (B(r1, r2, p + e, m1, m2) - B(r1, r2, p - e, m1, m2)) / (2 * e);
    const double fd_m1 = (B(r1, r2, p, m1 + e, m2) - B(r1, r2, p, m1 - e, m2)) / (2 * e);
    const double fd_m2 = (B(r1, r2, p, m1, m2 + e) - B(r1, r2, p, m1, m2 - e)) / (2 * e);
    ASSERT_NEAR(d.r1, fd_r1, 1e-4 * (1 + std::abs(d.r1)));
    ASSERT_NEAR(d.r2, fd_r2, 1e-4 * (1 + std::abs(d.r2)));
    ASSERT_NEAR(d.p, fd_p, 1e-4 * (1 + std::abs(d.p)));
    ASSERT_NEAR(d.m1, fd_m1, 1e-4 * (1 + std::abs(d.m1)));
    ASSERT_NEAR(d.m2, fd_m2, 1e-4 * (1 + std::abs(d.m2)));
  }
  EXPECT_GT(checked, 3000);
}

// "Every level set BT = h is the base surface translated by h·m" (§7.1): points u on the base
// arc, built without BT, satisfy BT(u + h·m) = h.
TEST(BT, LevelSetsAreTheBaseTranslatedAlongM) {
  Rng g(26);
  for (int n = 0; n < 20000; ++n) {
    const Conic c = random_conic(g);
    // The arc lies between the chord (H2 < 0) and the corner (H2 = r1²r2² > 0): bisect.
    const double t = uni(g, 0.01, 0.99);
    double lo = 0, hi = 1;  // fraction of the way from the chord point to the corner
    for (int it = 0; it < 200; ++it) {
      const double s = 0.5 * (lo + hi);
      (hoffmann_conic((1 - s) * t * c.r1, (1 - s) * (1 - t) * c.r2, c.r1, c.r2, c.p) < 0 ? lo
                                                                                         : hi) = s;
    }
    const double u1 = (1 - lo) * t * c.r1, u2 = (1 - lo) * (1 - t) * c.r2, h = uni(g, -3, 3);
    ASSERT_NEAR(c(u1 + h * c.m[0], u2 + h * c.m[1]), h, 1e-7 * (1 + std::abs(h)));

    const int k = 2 + n % 4;
    const Hyper hy = random_hyper(g, k);
    double q[6], rest = 1, x[6];  // Σ q_i^(p_i) = 1, q_i ∈ [0, 1]
    for (int i = 0; i < k - 1; ++i) {
      const double share = rest * uni(g, 0, 0.9);
      q[i] = std::pow(share, 1 / hy.p[i]);
      rest -= share;
    }
    q[k - 1] = std::pow(rest, 1 / hy.p[k - 1]);
    for (int i = 0; i < k; ++i) x[i] = hy.r[i] * (1 - q[i]) + h * hy.m[i];
    ASSERT_NEAR(hy(x), h, 1e-9 * (1 + std::abs(h)));
  }
}

TEST(BT, InfiniteArguments) {
  const double inf = std::numeric_limits<double>::infinity();
  const Conic c{0.5, 0.7, 0.1, {2, 0.5}};
  EXPECT_EQ(c(inf, 1), 1 / 0.5);
  EXPECT_EQ(c(1, inf), 1 / 2.0);
  EXPECT_EQ(c(-inf, 1), -inf);
  EXPECT_EQ(c(inf, inf), inf);
  EXPECT_EQ(c(inf, -inf), -inf);
  const Hyper h{3, {0.3, 0.4, 0.5}, {2, 3, 1.5}, {1, 2, 0.5}};
  const double a[3] = {inf, 0.1, 0.2}, b[3] = {0.1, -inf, 0.2}, all[3] = {inf, inf, inf};
  const Hyper h2{2, {0.4, 0.5}, {3, 1.5}, {2, 0.5}};
  const double a2[2] = {0.1, 0.2};
  EXPECT_EQ(h(a), h2(a2)) << "x_i = +inf drops argument i";
  EXPECT_EQ(h(b), -inf);
  EXPECT_EQ(h(all), inf);
}

}  // namespace
}  // namespace softtrace
