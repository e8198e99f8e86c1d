// Potential functions P: R+ -> [0,1] (docs/math.md §3): P(0)=1, P(0.5)=0.5 (Blanc, Wyvill), P=0 for
// d >= 1, non-increasing, P'(0)=P'(1)=0. Monotonicity makes the interval image exact:
// [P(hi), P(lo)]; the Lipschitz constant max|P'| is derived per potential below and is 0 on
// d >= 1.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "math/interval.h"

namespace softtrace {

// The kernels, shared by the model classes below and the program evaluators (eval_*.cpp), inline
// so the evaluators' loops over a batch can vectorise them: P(max(d, 0)) with P' into *dP when
// dP is non-null.

// Blanc's potential, 002 Eq. 2 (signs of R1), docs/math.md §3.2
inline double blanc(double d, double s, double* dP) {
  d = std::max(d, 0.0);
  if (d >= 1) {
    if (dP) *dP = 0;
    return 0;
  }
  const double u = d * d;
  double P, dPdu;
  if (d <= 0.5) {
    if (s == 0) {  // the first branch is 0/0 at d = 0; its closed form for s = 0 is 1 - 2d^2
      P = 1 - 2 * u;
      dPdu = -2;
    } else {
      const double N = 9 * u * u, D = s + (4.5 - 4 * s) * u;  // D >= min(s, 1.125) > 0
      P = 1 - N / D;
      dPdu = -(18 * u * D - N * (4.5 - 4 * s)) / (D * D);
    }
  } else {
    const double N = (1 - u) * (1 - u), D = 0.75 - s + (1.5 + 4 * s) * u;  // D >= 1.125
    P = N / D;
    dPdu = (-2 * (1 - u) * D - N * (1.5 + 4 * s)) / (D * D);
  }
  if (dP) *dP = dPdu * 2 * d;
  return P;
}

// blanc(d[l], s) for l < n into P[l], the same bits, as selects around one division per lane
// (a loop GCC vectorises; blanc's branches, each with its own division, it does not):
// d <= 1/2: 1 - N/D (for s = 0 its closed form 1 - 2d^2, as 2d^2 / 1), 1/2 < d < 1: N/D, d >= 1:
// 0 / 1. NaN d takes the middle piece, as in blanc.
inline void blanc_lanes(const double* d, double s, int n, double* P) {
  for (int l = 0; l < n; ++l) {
    const double x = std::max(d[l], 0.0), u = x * x;
    const bool inner = x <= 0.5, outer = x >= 1;
    const double n_in = s == 0 ? 2 * u : 9 * u * u, d_in = s == 0 ? 1.0 : s + (4.5 - 4 * s) * u;
    const double n_mid = (1 - u) * (1 - u), d_mid = 0.75 - s + (1.5 + 4 * s) * u;
    const double num = inner ? n_in : outer ? 0.0 : n_mid;
    const double den = inner ? d_in : outer ? 1.0 : d_mid;
    const double q = num / den;
    P[l] = inner ? 1 - q : q;
  }
}

// Wyvill et al.'s sextic, docs/math.md §3.3
inline double wyvill(double d, double* dP) {
  d = std::max(d, 0.0);
  if (d >= 1) {
    if (dP) *dP = 0;
    return 0;
  }
  const double u = d * d;
  if (dP) *dP = d * (-24.0 / 9 * u * u + 68.0 / 9 * u - 44.0 / 9);
  return 1 + u * (-22.0 / 9 + u * (17.0 / 9 - 4.0 / 9 * u));
}

// (1 - d^2)^2, docs/math.md §3.3
inline double murakami(double d, double* dP) {
  d = std::max(d, 0.0);
  if (d >= 1) {
    if (dP) *dP = 0;
    return 0;
  }
  const double v = 1 - d * d;
  if (dP) *dP = -4 * d * v;
  return v * v;
}

// (1 - d^2)^3, Galin et al. 2020's kernel (Segment Tracing), docs/math.md §3.4
inline double cubic(double d, double* dP) {
  d = std::max(d, 0.0);
  if (d >= 1) {
    if (dP) *dP = 0;
    return 0;
  }
  const double v = 1 - d * d;
  if (dP) *dP = -6 * d * v * v;
  return v * v * v;
}

// max |P'| over d >= 0, each derived in potentials.cpp (rounded up by 1e-12 relative).
double blanc_lipschitz(double s);  // [PB-5]
double wyvill_lipschitz();
inline double murakami_lipschitz() {
  return 8 / (3 * 1.7320508075688772) * (1 + 1e-12);  // 8/(3 sqrt 3), sqrt 3 to within an ulp
}
// Cubic: |P'| = 6d(1 - d^2)^2 peaks where (1 - d^2)(1 - 5d^2) = 0, d = 1/sqrt(5): 96/(25 sqrt 5)
// ([PC-2]).
inline double cubic_lipschitz() {
  return 96 / (25 * 2.2360679774997897) * (1 + 1e-12);  // sqrt 5 to within an ulp
}
// [min |P'|, max |P'|] over d in [lo, hi] for a potential whose |P'| rises from d = 0 to its peak
// `peak` at d = `at` and falls after it to 0 at d = 1 (and is 0 beyond): the ends' values bound
// it, and the peak where [lo, hi] holds `at`. Rounded by 1e-12 relative (|P'| is computed to a
// few ulps; `at` is known to a few ulps, where |P'| is flat to second order).
// The same from |P'| already taken at the clamped ends: a at lo, b at hi, 0 <= lo <= hi <= 1.
inline Interval unimodal_slope_between(double a, double b, double at, double peak, double lo,
                                       double hi) {
  const double top =
      lo <= at && at <= hi ? peak : std::min(peak, std::max(a, b) * (1 + 1e-12) + 1e-300);
  return {std::max(0.0, std::min(a, b) * (1 - 1e-12) - 1e-300), top};
}
template <class AbsSlope>
Interval unimodal_slope_range(AbsSlope abs_slope, double at, double peak, double lo, double hi) {
  lo = std::clamp(lo, 0.0, 1.0);
  hi = std::clamp(hi, 0.0, 1.0);
  if (!(lo <= hi)) return {0, peak};
  return unimodal_slope_between(abs_slope(lo), abs_slope(hi), at, peak, lo, hi);
}
// Murakami: |P'| = 4d(1 - d^2), peak 8/(3 sqrt 3) at d = 1/sqrt(3).
inline Interval murakami_slope_range(Interval d) {
  constexpr double kPeak = 0.57735026918962576;  // 1/sqrt(3), to within an ulp
  return unimodal_slope_range([](double x) { return 4 * x * (1 - x * x); }, kPeak,
                              murakami_lipschitz(), d.lo, d.hi);
}
// Cubic: |P'| = 6d(1 - d^2)^2, unimodal with its peak at d = 1/sqrt(5) ([PC-2]).
inline Interval cubic_slope_range(Interval d) {
  constexpr double kPeak = 0.44721359549995794;  // 1/sqrt(5), to within an ulp
  return unimodal_slope_range(
      [](double x) {
        const double v = 1 - x * x;
        return 6 * x * v * v;
      },
      kPeak, cubic_lipschitz(), d.lo, d.hi);
}
// Blanc: unimodal with its peak [PB-5] at d = 0.5 for every s >= 0 (docs/math.md §3.2: P'' < 0
// on (0, 0.5) and > 0 on (0.5, 1)).
inline Interval blanc_slope_range(double s, Interval d) {
  const auto abs_slope = [s](double x) {
    double dP;
    blanc(x, s, &dP);
    return std::abs(dP);
  };
  return unimodal_slope_range(abs_slope, 0.5, blanc_lipschitz(s), d.lo, d.hi);
}
// Blanc over distances in [d] from one kernel call per end: P(d.hi) into *least and P(max(0,
// d.lo)) into *most (a potential's range, as potential_bounds takes it), and with `slope`,
// blanc_slope_range(s, d). The kernel clamps d below at 0 and is 0, flat, from 1 on, so at any d
// but NaN it gives the same P and |P'| as at d clamped to [0, 1], where the slope range takes
// |P'|: the same bits as the four calls apart (a NaN end's slope range reads no |P'|). Fig.
// 12(b)'s bounds passes called the kernel 4.2 times a potential, 28 instructions a call.
inline void blanc_ends(double s, Interval d, double* least, double* most, Interval* slope) {
  double at_hi, at_lo;
  *least = blanc(d.hi, s, slope ? &at_hi : nullptr);
  *most = blanc(std::max(0.0, d.lo), s, slope ? &at_lo : nullptr);
  if (!slope) return;
  const double lo = std::clamp(d.lo, 0.0, 1.0), hi = std::clamp(d.hi, 0.0, 1.0);
  *slope = lo <= hi ? unimodal_slope_between(std::abs(at_lo), std::abs(at_hi), 0.5,
                                             blanc_lipschitz(s), lo, hi)
                    : Interval(0, blanc_lipschitz(s));
}
// Wyvill: P'' changes sign once on [0, 1], where u = d^2 = (204 - sqrt(20496)) / 240.
double wyvill_peak();  // that d
inline Interval wyvill_slope_range(Interval d) {
  const auto abs_slope = [](double x) {
    double dP;
    wyvill(x, &dP);
    return std::abs(dP);
  };
  return unimodal_slope_range(abs_slope, wyvill_peak(), wyvill_lipschitz(), d.lo, d.hi);
}

// The potentials by name, and one as a value (Blanc with softness s, Wyvill, Murakami) for a kernel
// that applies it inside its own (RadiusTransform) without a virtual call.
enum class PotentialType { Blanc, Wyvill, Murakami, Cubic };

struct PotentialKind {
  PotentialType type;
  double s = 0;  // Blanc's softness

  double eval(double d, double* dP) const {
    switch (type) {
      case PotentialType::Blanc:
        return blanc(d, s, dP);
      case PotentialType::Wyvill:
        return wyvill(d, dP);
      case PotentialType::Murakami:
        return murakami(d, dP);
      case PotentialType::Cubic:
        return cubic(d, dP);
    }
    std::abort();  // not reached: the switch names every type, and -Werror=switch keeps it so
  }
  double lipschitz() const;  // max over d of |P'(d)|
  // [P(hi), P(lo)] rounded outward: P is non-increasing.
  Interval interval(Interval d) const {
    return {std::max(0.0, iv::down(eval(d.hi, nullptr))),
            std::min(1.0, iv::up(eval(std::max(0.0, d.lo), nullptr)))};
  }
  double lipschitz(Interval d) const { return d.lo >= 1 ? 0.0 : lipschitz(); }
};

// A potential as c2 r^2 + c3 r^3 in r = 1 - d^2 (docs/math.md §8, "Sums of polynomial blobs"):
// Murakami's r^2, Wyvill's (5 r^2 + 4 r^3)/9 (its constant and linear terms cancel), the cubic
// r^3. Blanc's is no polynomial in r.
inline bool potential_in_r(PotentialType t, double* c2, double* c3) {
  switch (t) {
    case PotentialType::Murakami:
      *c2 = 1;
      *c3 = 0;
      return true;
    case PotentialType::Wyvill:
      *c2 = 5.0 / 9;
      *c3 = 4.0 / 9;
      return true;
    case PotentialType::Cubic:
      *c2 = 0;
      *c3 = 1;
      return true;
    case PotentialType::Blanc:
      return false;
  }
  return false;
}

// P(r) = c2 r^2 + c3 r^3 = r^2 (c2 + c3 r) at r = 1 - d^2 (0 < r <= 1 inside the support), with
// potential_in_r's coefficients times the blob's strength: Murakami's, Wyvill's or the cubic
// potential (docs/math.md §3.3-§3.4 and §8, "Sums of polynomial blobs"). The blob path, the
// tracer's shadow test and the mesher's leaves all sum it in this form.
inline double polynomial_potential(double r, double c2, double c3) {
  return r * r * (c2 + c3 * r);
}
// dP/dr = r (2 c2 + 3 c3 r): with ∇r = -2 L^T q (r = 1 - |q|^2, q = L x + k), a blob's gradient.
inline double polynomial_potential_slope(double r, double c2, double c3) {
  return r * (2 * c2 + 3 * c3 * r);
}

}  // namespace softtrace
