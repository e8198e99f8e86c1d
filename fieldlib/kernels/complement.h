// The complement of docs/math.md §1: soft 1 - f, zero -f, constructive 1/max(f, kCgFloor). The
// kernels are shared by the model node (blends_set.cpp) and the program's Complement instruction,
// so both compute the same bits from the child's value, gradient, interval and Lipschitz bound.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/convention.h"
#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

// The constructive-geometry complement 1/f is evaluated as 1/max(f, kCgFloor) (f <= 0 has no
// complement; CG fields are >= 0 and reach 0 only on a skeleton).
constexpr double kCgFloor = 1e-12;

// 1 - f, -f or 1/f (guarded at f <= kCgFloor), and the gradient in place when g is non-null.
inline double complement(Convention conv, double f, Vec3* g) {
  switch (conv) {
    case Convention::Soft:
      if (g) *g = -*g;
      return 1 - f;
    case Convention::Zero:
      if (g) *g = -*g;
      return -f;
    case Convention::Constructive:
      if (f <= kCgFloor) {
        if (g) *g = {};
        return 1 / kCgFloor;
      }
      // ∇(1/f) = -∇f/f^2. A NaN f gives its own NaN: a product of two NaNs keeps either's sign,
      // as the compiler orders the operands, and the model and the program must agree.
      if (g) *g = std::isnan(f) ? Vec3{f, f, f} : *g * (-1 / (f * f));
      return 1 / f;
  }
  return f;
}

// Interval arithmetic on the three forms (1/max(f, floor) is non-increasing in f).
inline Interval complement_interval(Convention conv, Interval f) {
  switch (conv) {
    case Convention::Soft:
      return Interval(1) - f;
    case Convention::Zero:
      return -f;
    case Convention::Constructive:
      return {iv::down(1 / std::max(f.hi, kCgFloor)), iv::up(1 / std::max(f.lo, kCgFloor))};
  }
  return f;
}

// The child's bound L over a box where it lies in f; |∇(1/f)| = |∇f|/f^2, and 0 where the guard
// holds.
inline double complement_lipschitz(Convention conv, Interval f, double L) {
  if (conv != Convention::Constructive) return L;
  const double lo = std::max(f.lo, kCgFloor);
  return L == 0 ? 0 : L / (lo * lo) * (1 + 1e-12);
}

// The global bound from the child's: none for 1/f.
inline double complement_lipschitz(Convention conv, double L) {
  return conv == Convention::Constructive ? std::numeric_limits<double>::infinity() : L;
}

}  // namespace softtrace
