// The scale operators BSA2 / BSS2 on two numbers (docs/math.md §6.3; 000 §II.C.3, Eq. 8): h
// solving G(h) = h^2 B_H(σ(x/h - 1)) = a h^2 + b h + c = 0 on region III, min/max elsewhere. Shared
// by the model node (model/blends_scale.cpp, which derives its bounds) and the program's Scale
// instruction, so both compute the same bits.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/interval.h"

namespace softtrace {

// BSA2 (bsa) or BSS2, and ∂h/∂x_i into dh. Parameters are not validated here (the node's creator
// does): r_i > 0, p < r1 r2, BSS2 r_i < 1.
class ScaleOperator {
 public:
  ScaleOperator(double r1, double r2, double p, bool bsa);
  // Its derived coefficients as a program's constants, and back without recomputing them (the
  // instruction reads them per lane).
  std::vector<double> constants() const;
  static ScaleOperator load(const double* c);
  double operator()(double x1, double x2, double dh[2]) const;
  bool region3(double x1, double x2) const;

  // The range over the arguments' intervals: h is non-decreasing in both arguments
  // (blends_scale.cpp derives it), so it is h at the ends, widened for rounding.
  Interval range(Interval x1, Interval x2) const;
  // The bound on |∇h| from the children's bounds L1, L2 (blends_scale.cpp): max L_k times gain().
  double gain() const { return gain_; }
  // 0 or 1 where h is x1 or x2 all over x1 × x2 (outside region III, the sharp pick), else -1.
  int sharp_everywhere(Interval x1, Interval x2) const;
  // range(), and with D1, D2 (non-null) into *slope d h(x1(t), x2(t))/dt over a segment where the
  // arguments lie in x1, x2 and their slopes in D1, D2 (docs/math.md §8, "Slopes along a
  // segment"): the one argument's slope where h is that argument all along (sharp_everywhere);
  // else h' = a1 x1' + a2 x2' with a_k = ∂h/∂x_k >= 0 and a1 + a2 in [sum_lo, sum_hi], so h' =
  // (a1 + a2)(λ x1' + (1 - λ) x2'), λ in [0, 1], lies in [sum_lo, sum_hi] · hull(D1, D2). The sharp
  // pick is decided once for both: where it holds, the range is that argument's ends widened as
  // range() widens h at them (the same bits: h is that argument at both corners), no quadratic.
  Interval range_and_slope(Interval x1, Interval x2, const Interval* D1, const Interval* D2,
                           Interval* slope) const {
    return range_and_slope(x1, x2, D1, D2, slope, sharp_everywhere(x1, x2));
  }
  // The same with sharp_everywhere(x1, x2) already decided (the program's walk also prunes by it).
  Interval range_and_slope(Interval x1, Interval x2, const Interval* D1, const Interval* D2,
                           Interval* slope, int sharp) const;

 private:
  ScaleOperator() = default;

  double r1_, r2_, p_;
  int s_;  // +1: y = x/h - 1 (BSA2); -1: y = 1 - x/h (BSS2)
  double a_, b1_, b2_;
  double gain_;             // 1 (BSA2) or 1/(1 - max r) (BSS2)
  double sum_lo_, sum_hi_;  // the range of a1 + a2 (docs/math.md §8, "Slopes along a segment")
};

// Inline: the program's Scale instruction loads the operator and calls these per point and per
// bounds pass (five nested on fig000_5b), where the calls cost as much as the arithmetic.
inline ScaleOperator ScaleOperator::load(const double* c) {
  ScaleOperator op;
  op.r1_ = c[0];
  op.r2_ = c[1];
  op.p_ = c[2];
  op.s_ = static_cast<int>(c[3]);
  op.a_ = c[4];
  op.b1_ = c[5];
  op.b2_ = c[6];
  op.gain_ = c[7];
  op.sum_lo_ = c[8];
  op.sum_hi_ = c[9];
  return op;
}

inline bool ScaleOperator::region3(double x1, double x2) const {
  if (!(x1 > 0 && x2 > 0)) return false;
  if (s_ > 0) return x1 / (1 + r1_) < x2 && x2 < (1 + r2_) * x1;
  return (1 - r1_) * x2 < x1 && (1 - r2_) * x1 < x2;
}

inline double ScaleOperator::operator()(double x1, double x2, double dh[2]) const {
  const bool first = s_ > 0 ? x1 <= x2 : x1 >= x2;  // which argument min/max picks
  const double sharp = first ? x1 : x2;
  if (dh) {
    dh[0] = first ? 1 : 0;
    dh[1] = first ? 0 : 1;
  }
  if (!region3(x1, x2)) return sharp;
  const double b = b1_ * x1 + b2_ * x2;
  const double c = r1_ * r1_ * x2 * x2 + r2_ * r2_ * x1 * x1 + 2 * p_ * x1 * x2;
  const double q = std::sqrt(std::max(b * b - 4 * a_ * c, 0.0));
  // The "+" root for BSA2 and the "-" root for BSS2, each in its cancellation-free form (A6).
  double h;
  if (s_ > 0)
    h = b > 0 ? 2 * c / (-b - q) : (-b + q) / (2 * a_);
  else
    h = b < 0 ? 2 * c / (-b + q) : (-b - q) / (2 * a_);
  if (!std::isfinite(h)) return sharp;
  if (dh) {  // implicit function theorem on G(h; x) = a h^2 + b h + c
    const double Gh = 2 * a_ * h + b;
    const double G1 = h * b1_ + 2 * r2_ * r2_ * x1 + 2 * p_ * x2;
    const double G2 = h * b2_ + 2 * r1_ * r1_ * x2 + 2 * p_ * x1;
    const double d1 = -G1 / Gh, d2 = -G2 / Gh;
    if (std::isfinite(d1) && std::isfinite(d2)) {
      dh[0] = d1;
      dh[1] = d2;
    }
  }
  return h;
}

inline Interval ScaleOperator::range(Interval x1, Interval x2) const {
  const double lo = (*this)(x1.lo, x2.lo, nullptr), hi = (*this)(x1.hi, x2.hi, nullptr);
  return iv::out(lo - 1e-13 * std::abs(lo), hi + 1e-13 * std::abs(hi));
}

inline int ScaleOperator::sharp_everywhere(Interval x1, Interval x2) const {
  // Outside region III h is the sharp min (BSA2) or max (BSS2). The margin 1e-12 keeps the tests
  // true of the exact arguments, whose products here round by an ulp.
  const double m = 1 - 1e-12;
  if (s_ > 0) {  // x_j <= x_k / (1 + r_k) with x_k > 0: x_j < x_k outside region III, h = x_j
    if (x1.lo > 0 && x2.hi <= x1.lo / (1 + r1_) * m) return 1;
    if (x2.lo > 0 && x1.hi <= x2.lo / (1 + r2_) * m) return 0;
  } else {  // x_j <= (1 - r_j) x_k with x_k > 0: x_j < x_k outside region III, h = x_k
    if (x2.lo > 0 && x1.hi <= (1 - r1_) * x2.lo * m) return 1;
    if (x1.lo > 0 && x2.hi <= (1 - r2_) * x1.lo * m) return 0;
  }
  return -1;
}

inline Interval ScaleOperator::range_and_slope(Interval x1, Interval x2, const Interval* D1,
                                               const Interval* D2, Interval* slope,
                                               int sharp) const {
  if (D1) *slope = sharp < 0 ? Interval(sum_lo_, sum_hi_) * hull(*D1, *D2) : sharp == 0 ? *D1 : *D2;
  if (sharp < 0) return range(x1, x2);
  // sharp_everywhere's margin keeps both corners outside region III, so h there is the argument.
  const Interval x = sharp == 0 ? x1 : x2;
  return iv::out(x.lo - 1e-13 * std::abs(x.lo), x.hi + 1e-13 * std::abs(x.hi));
}

}  // namespace softtrace
