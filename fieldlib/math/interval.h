// Closed interval arithmetic over doubles, as libfive's interval evaluator uses it: every result
// contains the exact image of its arguments. Each operation rounds outward by at least one ulp so
// the enclosure stays sound under floating-point rounding (pow/exp/log are faithfully rounded by
// glibc).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace softtrace {

struct Interval {
  double lo = 0, hi = 0;

  constexpr Interval() = default;
  constexpr Interval(double v) : lo(v), hi(v) {}  // NOLINT: a point is an interval
  constexpr Interval(double l, double h) : lo(l), hi(h) {}

  static constexpr Interval entire() {
    return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }
  bool contains(double v) const { return lo <= v && v <= hi; }
  double width() const { return hi - lo; }
};

namespace iv {
// One ulp or more below / above v, without a libm call: for finite normal v, ulp(v) <= 2^-52 |v|
// and v ∓ 2^-52 |v| is exact or rounds away from v past its neighbour (v ∓ ulp(v) is a double);
// 2^-1074 (the smallest subnormal) covers v = 0 and subnormals. Infinities and NaN take
// nextafter's answer (the rare path: -inf and +inf stay, +inf goes down to the largest double).
inline double down(double v) {
  if (!(std::abs(v) <= std::numeric_limits<double>::max()))
    return std::nextafter(v, -std::numeric_limits<double>::infinity());
  return v - (std::abs(v) * 0x1p-52 + 0x1p-1074);
}
inline double up(double v) {
  if (!(std::abs(v) <= std::numeric_limits<double>::max()))
    return std::nextafter(v, std::numeric_limits<double>::infinity());
  return v + (std::abs(v) * 0x1p-52 + 0x1p-1074);
}
inline Interval out(double l, double h) {
  // NaN from inf-inf or 0*inf means "no information".
  if (std::isnan(l) || std::isnan(h)) return Interval::entire();
  return {down(l), up(h)};
}
}  // namespace iv

inline Interval operator+(Interval a, Interval b) {
  return iv::out(a.lo + b.lo, a.hi + b.hi);
}
inline Interval operator-(Interval a, Interval b) {
  return iv::out(a.lo - b.hi, a.hi - b.lo);
}
inline Interval operator-(Interval a) {
  return {-a.hi, -a.lo};
}
inline Interval operator*(Interval a, Interval b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  double l = p[0], h = p[0];
  for (double v : p) {
    if (std::isnan(v)) return Interval::entire();
    l = std::min(l, v);
    h = std::max(h, v);
  }
  return iv::out(l, h);
}
inline Interval operator/(Interval a, Interval b) {
  if (b.lo <= 0 && b.hi >= 0) return Interval::entire();
  return a * Interval(iv::down(1 / b.hi), iv::up(1 / b.lo));
}

// The bounds pass's constant factors: the same bits as the general product and quotient above,
// from two products instead of four and without the loop. Rounding to nearest is monotone, so of
// the four rounded products the least and the greatest are those of the ends the signs pick; a
// NaN product (0·inf, a NaN end) gives entire() as there. For a.lo <= a.hi.
// s·a = Interval(s) * a (an offset's or a strength's scale).
inline Interval scaled(double s, Interval a) {
  return s >= 0 ? iv::out(s * a.lo, s * a.hi) : iv::out(s * a.hi, s * a.lo);
}
// a / Interval(b) (a plane's half-width b): a times [down(1/b), up(1/b)], which is > 0 for b > 0.
inline Interval divided(Interval a, double b) {
  if (!(b > 0)) return a / Interval(b);
  const double ql = iv::down(1 / b), qh = iv::up(1 / b);
  if (!(ql > 0 && qh <= std::numeric_limits<double>::max())) return a * Interval(ql, qh);
  return iv::out(a.lo >= 0 ? a.lo * ql : a.lo * qh, a.hi >= 0 ? a.hi * qh : a.hi * ql);
}

inline Interval abs(Interval a) {
  if (a.lo >= 0) return a;
  if (a.hi <= 0) return -a;
  return {0, std::max(-a.lo, a.hi)};
}
inline Interval sqr(Interval a) {
  const Interval m = abs(a);
  return {std::max(0.0, iv::down(m.lo * m.lo)), iv::up(m.hi * m.hi)};
}
inline Interval sqrt(Interval a) {
  return {std::max(0.0, iv::down(std::sqrt(std::max(0.0, a.lo)))),
          iv::up(std::sqrt(std::max(0.0, a.hi)))};
}
// x^p for x >= 0 (negative parts are clamped to 0) and p > 0: monotone increasing.
inline Interval pow_nonneg(Interval a, double p) {
  const double l = std::max(0.0, a.lo), h = std::max(0.0, a.hi);
  return {std::max(0.0, iv::down(std::pow(l, p))), iv::up(std::pow(h, p))};
}
inline Interval max(Interval a, Interval b) {
  return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)};
}
inline Interval min(Interval a, Interval b) {
  return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)};
}
inline Interval hull(Interval a, Interval b) {
  return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}
// Image of a monotone non-increasing function g over `a`.
template <class F>
Interval decreasing(F g, Interval a) {
  return iv::out(g(a.hi), g(a.lo));
}
// Image of a monotone non-decreasing function g over `a`.
template <class F>
Interval increasing(F g, Interval a) {
  return iv::out(g(a.lo), g(a.hi));
}

}  // namespace softtrace
