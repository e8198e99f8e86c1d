// The scale operators BSA2 / BSS2 on two numbers (docs/math.md §6.3; 000 §II.C.3, Eq. 8): h
// solving G(h) = h^2 B_H(σ(x/h - 1)) = a h^2 + b h + c = 0 on region III, min/max elsewhere. Shared
// by the model node (model/blends_scale.cpp, which derives its bounds) and the program's Scale
// instruction, so both compute the same bits.
#pragma once

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
                           Interval* slope) const;

 private:
  ScaleOperator() = default;

  double r1_, r2_, p_;
  int s_;  // +1: y = x/h - 1 (BSA2); -1: y = 1 - x/h (BSS2)
  double a_, b1_, b2_;
  double gain_;             // 1 (BSA2) or 1/(1 - max r) (BSS2)
  double sum_lo_, sum_hi_;  // the range of a1 + a2 (docs/math.md §8, "Slopes along a segment")
};

}  // namespace softtrace
