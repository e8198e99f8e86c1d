// The Illinois variant of regula falsi (Dowell and Jarratt 1971) on a bracket of a sign change:
// false position converges superlinearly on smooth roots, and an end kept twice in a row has its
// value halved so that the other end moves too. The Anderson-Bjorck variant (1973) scales it by
// 1 - f_new / f_replaced instead (halving where that is not positive): on convex stretches, as
// near a blob's surface, it takes fewer steps. The callers choose the next point and when to
// stop; this only keeps the bracket.
#pragma once

namespace softtrace {

struct IllinoisBracket {
  double lo, f_lo;  // the end on the negative side
  double hi, f_hi;  // the end on the other side
  int side = 0;     // which end the last update replaced: -1 lo, +1 hi
  bool anderson_bjorck = false;

  double false_position() const { return (lo * f_hi - hi * f_lo) / (f_hi - f_lo); }

  // Replaces the end on x's side (`upper`: hi's) with (x, fx).
  void update(double x, double fx, bool upper) {
    if (upper) {
      if (side == +1) f_lo *= kept_scale(fx, f_hi);
      hi = x;
      f_hi = fx;
      side = +1;
    } else {
      if (side == -1) f_hi *= kept_scale(fx, f_lo);
      lo = x;
      f_lo = fx;
      side = -1;
    }
  }

 private:
  double kept_scale(double f_new, double f_replaced) const {
    const double m = anderson_bjorck ? 1 - f_new / f_replaced : 0.5;
    return m > 0 ? m : 0.5;
  }
};

}  // namespace softtrace
