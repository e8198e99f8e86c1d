// A soft object's strength: s·f for a soft field f = P(T(d)) in [0, 1] and any finite s != 0
// (POV-Ray's blob component strength; docs/math.md §4.10). Negative s subtracts. Bounds from the
// child's: interval s·[f] by interval arithmetic (a negative s swaps the ends); Lipschitz |s|·L;
// the value is 0 exactly where f is, so f's support is s·f's. The kernels are shared by the model
// node (model/strength.cpp) and the program's Strength instruction: both compute the same bits.
#pragma once

#include <cmath>

#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

inline double strength_value(double s, double f) {
  return s * f;
}
inline Vec3 strength_gradient(double s, const Vec3& g) {
  return g * s;
}
// One product per end, rounded outward unless the child's end is exactly 0 (then s·0 = 0 is
// exact): a negative term's interval stays <= 0, which is what lets a sum drop it outside its
// support (model/program_builder.cpp).
inline Interval strength_interval(double s, Interval f) {
  const double lo_f = s > 0 ? f.lo : f.hi, hi_f = s > 0 ? f.hi : f.lo;
  const double lo = s * lo_f, hi = s * hi_f;
  if (std::isnan(lo) || std::isnan(hi)) return Interval::entire();
  return {lo_f == 0 ? lo : iv::down(lo), hi_f == 0 ? hi : iv::up(hi)};
}
inline double strength_lipschitz(double s, double L) {
  return iv::up(std::abs(s) * L);
}

}  // namespace softtrace
