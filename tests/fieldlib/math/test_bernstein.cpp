// first_rise and refine_rise (fieldlib/math/bernstein.h) against the search and refinement they
// were written as: one loop for any degree, each piece copied off the stack and its halves built
// apart. The unrolled ones per degree must give the same answers to the bit: the same kind,
// bracket and count of undecided pieces, the same refined bracket in the same steps, on
// polynomials with crossings, tangencies within rounding and clusters of roots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "math/bernstein.h"
#include "math/illinois.h"

namespace softtrace::test {

namespace {

// The search for any degree, as first_rise was before it was unrolled per degree.
Rise reference_first_rise(const double* a, int degree, double err, double tol, double finest) {
  const auto& weight = bernstein_detail::kWeights.w[degree];
  struct Piece {
    double lo, hi, b[kMaxDegree + 1];
  };
  constexpr int kDepth = 64;
  Piece stack[kDepth];
  int top = 0, undecided = 0;
  Piece& whole = stack[top++];
  whole.lo = 0;
  whole.hi = 1;
  for (int i = 0; i <= degree; ++i) {
    double s = 0;
    for (int j = 0; j <= i; ++j) s += weight[i][j] * a[j];
    whole.b[i] = s;
  }
  if (whole.b[0] >= 0) return {Rise::AtStart, 0, 0};
  while (top > 0) {
    const Piece p = stack[--top];
    const double* b = p.b;
    if (*std::max_element(b, b + degree + 1) + err < 0) continue;
    bool rising = true;
    for (int i = 0; i < degree && rising; ++i) rising = b[i + 1] - b[i] > 2 * err;
    if (b[degree] >= 0 && (rising || p.hi - p.lo <= tol))
      return {Rise::Bracket, p.lo, p.hi, undecided};
    if (rising && b[degree] < 0) continue;
    if (p.hi - p.lo <= finest || top + 2 > kDepth) {
      ++undecided;
      continue;
    }
    Piece left{p.lo, 0.5 * (p.lo + p.hi), {}}, right{left.hi, p.hi, {}};
    double row[kMaxDegree + 1];
    std::copy(b, b + degree + 1, row);
    for (int k = 0; k <= degree; ++k) {
      left.b[k] = row[0];
      right.b[degree - k] = row[degree - k];
      for (int i = 0; i < degree - k; ++i) row[i] = 0.5 * (row[i] + row[i + 1]);
    }
    stack[top++] = right;
    stack[top++] = left;
  }
  return {Rise::Clear, 1, 1, undecided};
}

// refine_rise for any degree, as it was before it was unrolled per degree.
Rise reference_refine_rise(const double* a, int degree, Rise r, double tol, int* steps) {
  IllinoisBracket br{r.lo, power_value(a, degree, r.lo), r.hi, power_value(a, degree, r.hi)};
  br.anderson_bjorck = true;
  for (int i = 0; i < 100 && br.hi - br.lo > tol; ++i) {
    double m = std::clamp(br.false_position(), br.lo + 0.5 * tol, br.hi - 0.5 * tol);
    if (!(m > br.lo && m < br.hi)) m = 0.5 * (br.lo + br.hi);
    ++*steps;
    const double hm = power_value(a, degree, m);
    br.update(m, hm, hm >= 0);
  }
  return {Rise::Bracket, br.lo, br.hi};
}

bool same_bits(double x, double y) {
  return std::memcmp(&x, &y, sizeof x) == 0;
}

// c (x - r_1) ... (x - r_degree) + shift, in the power basis.
void from_roots(const double* roots, int degree, double c, double shift, double* a) {
  std::fill(a, a + kMaxDegree + 1, 0.0);
  a[0] = c;
  for (int k = 0; k < degree; ++k) {
    for (int j = k + 1; j > 0; --j) a[j] = a[j - 1] - roots[k] * a[j];
    a[0] = -roots[k] * a[0];
  }
  a[0] += shift;
}

}  // namespace

TEST(FirstRise, EachDegreeGivesTheGenericSearchsAndRefinementsAnswerToTheBit) {
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> u(0, 1), root(-0.2, 1.2);
  int kinds[3] = {}, undecided = 0, deep = 0, refined = 0;
  for (int i = 0; i < 60000; ++i) {
    const int degree = i % (kMaxDegree + 1);
    double roots[kMaxDegree], a[kMaxDegree + 1];
    for (int k = 0; k < degree; ++k) roots[k] = root(rng);
    // A third of the cases pair their roots (tangencies, double roots nudged within rounding).
    if (i % 3 == 1)
      for (int k = 1; k < degree; k += 2) roots[k] = roots[k - 1] + (u(rng) - 0.5) * 1e-7;
    const double c = (u(rng) < 0.5 ? -1 : 1) * (0.1 + 10 * u(rng));
    const double shift = i % 3 == 2 ? (u(rng) - 0.5) * 1e-13 : 0;
    from_roots(roots, degree, c, shift, a);
    const double err = i % 5 == 0 ? 0 : std::ldexp(1.0, -40 - static_cast<int>(12 * u(rng)));
    const double tol = std::ldexp(1.0, -8 - static_cast<int>(13 * u(rng)));
    // Not much finer than tol: a tangency's hull straddles 0 over about sqrt(err / |c|), and
    // every finest piece there is searched.
    const double finest = tol * std::ldexp(1.0, -static_cast<int>(5 * u(rng)));
    const Rise got = first_rise(a, degree, err, tol, finest);
    const Rise want = reference_first_rise(a, degree, err, tol, finest);
    ASSERT_EQ(got.kind, want.kind) << "case " << i << ", degree " << degree;
    ASSERT_TRUE(same_bits(got.lo, want.lo)) << "case " << i << ": " << got.lo << " " << want.lo;
    ASSERT_TRUE(same_bits(got.hi, want.hi)) << "case " << i << ": " << got.hi << " " << want.hi;
    ASSERT_EQ(got.undecided, want.undecided) << "case " << i;
    if (want.kind == Rise::Bracket) {
      // Its refinement too, to a millionth of the bracket: the same points, so the same steps.
      int got_steps = 0, want_steps = 0;
      const double close = 1e-6 * (want.hi - want.lo);
      const Rise g = refine_rise(a, degree, got, close, &got_steps);
      const Rise w = reference_refine_rise(a, degree, want, close, &want_steps);
      ASSERT_TRUE(same_bits(g.lo, w.lo) && same_bits(g.hi, w.hi)) << "case " << i;
      ASSERT_EQ(got_steps, want_steps) << "case " << i;
      refined += want_steps > 3;
    }
    ++kinds[want.kind];
    undecided += want.undecided > 0;
    deep += want.kind == Rise::Bracket && want.hi - want.lo <= 1.0 / 64;
  }
  // Every outcome is exercised, and many searches halve deep and pass undecided pieces.
  EXPECT_GT(kinds[Rise::Clear], 5000);
  EXPECT_GT(kinds[Rise::AtStart], 5000);
  EXPECT_GT(kinds[Rise::Bracket], 5000);
  EXPECT_GT(undecided, 500);
  EXPECT_GT(deep, 1000) << deep;
  EXPECT_GT(refined, 5000) << refined;
}

}  // namespace softtrace::test
