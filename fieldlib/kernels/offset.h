// offset: s·(f - c) (docs/scene-format.md "Blends"; 003 §2.1): turns a distance function d, whose
// surface is d = 1, into a zero-convention defining function, e.g. s = 1, c = 1 gives d - 1 (inside
// <= 0). Bounds, derived from the child's: interval s·([f] - c) by interval arithmetic; Lipschitz
// |s|·L (globally and per box); region: s(f - c) <= l ⇔ f <= c + l/s for s > 0 and f >= c + l/s for
// s < 0 (sides swap for >=), with the level c + l/s rounded outward.
#pragma once

#include <cmath>

#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

// The kernels shared by the model node (offset.cpp) and the program's Offset instruction, so both
// compute the same bits from the child's value, gradient, interval and Lipschitz bound.
inline double offset_value(double s, double c, double f) {
  return s * (f - c);  // s·(f - c) — 003 §2.1
}
inline Vec3 offset_gradient(double s, const Vec3& g) {
  return g * s;
}
inline Interval offset_interval(double s, double c, Interval f) {
  return scaled(s, f - Interval(c));
}
inline double offset_lipschitz(double s, double L) {
  return iv::up(std::abs(s) * L);
}

}  // namespace softtrace
