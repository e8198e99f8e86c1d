// Axis-aligned boxes: the domain of interval evaluation and the shape of support boxes.
#pragma once

#include <algorithm>
#include <limits>

#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

struct Box {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};

  Box() = default;  // empty
  Box(const Vec3& l, const Vec3& h) : lo(l), hi(h) {}

  static Box unbounded() {
    const double inf = std::numeric_limits<double>::infinity();
    return {{-inf, -inf, -inf}, {inf, inf, inf}};
  }
  static Box around(const Vec3& c, double r) { return {c - Vec3{r, r, r}, c + Vec3{r, r, r}}; }

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  bool bounded() const {
    return !empty() && std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(lo.z) &&
           std::isfinite(hi.x) && std::isfinite(hi.y) && std::isfinite(hi.z);
  }
  bool contains(const Vec3& p) const {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
  }
  Interval axis(int i) const { return {lo[i], hi[i]}; }
  // Corner c (0..7): bit 0 picks hi.x over lo.x, bit 1 hi.y, bit 2 hi.z.
  Vec3 corner(int c) const {
    return {c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z};
  }
  Vec3 center() const { return (lo + hi) * 0.5; }
  Vec3 extent() const { return hi - lo; }
  double diagonal() const { return length(hi - lo); }

  void extend(const Vec3& p) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
  Box united(const Box& o) const {
    Box b = *this;
    if (o.empty()) return b;
    b.extend(o.lo);
    b.extend(o.hi);
    return b;
  }
  Box intersected(const Box& o) const {
    Box b;
    for (int i = 0; i < 3; ++i) {
      b.lo[i] = std::max(lo[i], o.lo[i]);
      b.hi[i] = std::min(hi[i], o.hi[i]);
    }
    return b;
  }
};

// The box around the segment [a, b], grown by pad.
inline Box segment_box(const Vec3& a, const Vec3& b, double pad) {
  Box box;
  box.extend(a);
  box.extend(b);
  return {box.lo - Vec3{pad, pad, pad}, box.hi + Vec3{pad, pad, pad}};
}

}  // namespace softtrace
