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

}  // namespace softtrace
