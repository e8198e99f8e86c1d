// The scale operators BSA2 / BSS2 (scale_operator.h; docs/math.md §6.3, §8 "Slopes along a
// segment").
#include "kernels/scale_operator.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

ScaleOperator::ScaleOperator(double r1, double r2, double p, bool bsa)
    : r1_(r1), r2_(r2), p_(p), s_(bsa ? 1 : -1) {
  a_ = (1 + 2 * s_ * r2_) * r1_ * r1_ + (1 + s_ * r1_) * (1 + s_ * r1_) * r2_ * r2_ + 2 * p_;
  b1_ = -2 * ((1 + s_ * r1_) * r2_ * r2_ + p_);
  b2_ = -2 * ((1 + s_ * r2_) * r1_ * r1_ + p_);
  const double r = std::max(r1, r2);
  gain_ = bsa ? 1.0 : 1 / (1 - r);
  // a_k >= 0 and Euler's Σ (x_k/h) a_k = 1 on region III; a1 + a2 = 1 outside it (min/max).
  // BSS2: x_k/h in [1 - r_k, 1] gives 1 <= a1 + a2 <= 1/(1 - max r).
  // BSA2: x_k/h >= 1 gives a1 + a2 <= 1; a1 + a2 >= h / max x >= κ_A min x / max x, and region III
  // keeps the ratio min x / max x above 1/(1 + max r): a1 + a2 >= κ_A / (1 + max r).
  if (bsa) {
    const double kappa = (r1 + r2) / (r1 * r2 + r1 + r2);
    sum_lo_ = kappa / (1 + r) * (1 - 1e-12);
    sum_hi_ = 1;
  } else {
    sum_lo_ = 1;
    sum_hi_ = gain_ * (1 + 1e-12);
  }
}

std::vector<double> ScaleOperator::constants() const {
  return {r1_, r2_, p_, static_cast<double>(s_), a_, b1_, b2_, gain_, sum_lo_, sum_hi_};
}

ScaleOperator ScaleOperator::load(const double* c) {
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

bool ScaleOperator::region3(double x1, double x2) const {
  if (!(x1 > 0 && x2 > 0)) return false;
  if (s_ > 0) return x1 / (1 + r1_) < x2 && x2 < (1 + r2_) * x1;
  return (1 - r1_) * x2 < x1 && (1 - r2_) * x1 < x2;
}

double ScaleOperator::operator()(double x1, double x2, double dh[2]) const {
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

Interval ScaleOperator::range(Interval x1, Interval x2) const {
  const double lo = (*this)(x1.lo, x2.lo, nullptr), hi = (*this)(x1.hi, x2.hi, nullptr);
  return iv::out(lo - 1e-13 * std::abs(lo), hi + 1e-13 * std::abs(hi));
}

int ScaleOperator::sharp_everywhere(Interval x1, Interval x2) const {
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

Interval ScaleOperator::range_and_slope(Interval x1, Interval x2, const Interval* D1,
                                        const Interval* D2, Interval* slope) const {
  const int sharp = sharp_everywhere(x1, x2);
  if (D1) *slope = sharp < 0 ? Interval(sum_lo_, sum_hi_) * hull(*D1, *D2) : sharp == 0 ? *D1 : *D2;
  if (sharp < 0) return range(x1, x2);
  // sharp_everywhere's margin keeps both corners outside region III, so h there is the argument.
  const Interval x = sharp == 0 ? x1 : x2;
  return iv::out(x.lo - 1e-13 * std::abs(x.lo), x.hi + 1e-13 * std::abs(x.hi));
}

}  // namespace softtrace
