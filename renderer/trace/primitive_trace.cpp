#include "trace/primitive_trace.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/ranges.h"

namespace softtrace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The span in the shape's own space, normals there (not unit).
struct LocalSpan {
  double t0 = kInf, t1 = -kInf;
  Vec3 n0, n1;
};

LocalSpan everywhere() {
  return {-kInf, kInf, {}, {}};
}

// The roots of A t^2 + B t + C = 0, r1 <= r2, by the stable formula (no cancellation); false when
// there is none.
bool roots(double A, double B, double C, double& r1, double& r2) {
  if (A == 0) {
    if (B == 0) return false;
    r1 = r2 = -C / B;
    return true;
  }
  const double disc = B * B - 4 * A * C;
  if (disc < 0) return false;
  const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
  r1 = q / A;
  r2 = q != 0 ? C / q : r1;
  if (r1 > r2) std::swap(r1, r2);
  return true;
}

LocalSpan sphere(const Primitive& s, const Vec3& o, const Vec3& d) {
  const Vec3 q = o - s.a;
  double r1, r2;
  LocalSpan span;
  if (!roots(dot(d, d), 2 * dot(q, d), dot(q, q) - s.r0 * s.r0, r1, r2)) return span;
  span = {r1, r2, q + d * r1, q + d * r2};
  return span;
}

LocalSpan box(const Primitive& s, const Vec3& o, const Vec3& d) {
  LocalSpan span = everywhere();
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      if (o[i] < s.a[i] || o[i] > s.b[i]) return {};
      continue;
    }
    double ta = (s.a[i] - o[i]) / d[i], tb = (s.b[i] - o[i]) / d[i];
    Vec3 na{0, 0, 0}, nb{0, 0, 0};
    na[i] = -1;
    nb[i] = 1;
    if (ta > tb) {
      std::swap(ta, tb);
      std::swap(na, nb);
    }
    if (ta > span.t0) {
      span.t0 = ta;
      span.n0 = na;
    }
    if (tb < span.t1) {
      span.t1 = tb;
      span.n1 = nb;
    }
  }
  return span;
}

// dot(normal, p) <= distance.
LocalSpan plane(const Primitive& s, const Vec3& o, const Vec3& d) {
  const double nd = dot(s.normal, d), no = dot(s.normal, o);
  if (nd == 0) return no <= s.distance ? everywhere() : LocalSpan{};
  const double t = (s.distance - no) / nd;
  if (nd > 0) return {-kInf, t, {}, s.normal};
  return {t, kInf, s.normal, {}};
}

LocalSpan disc(const Primitive& s, const Vec3& o, const Vec3& d) {
  const double nd = dot(s.normal, d);
  if (nd == 0) return {};
  const double t = dot(s.normal, s.a - o) / nd;
  const Vec3 w = o + d * t - s.a;
  const double r = length(w - s.normal * dot(w, s.normal));
  if (!(r <= s.r0 && r >= s.hole)) return {};
  return {t, t, s.normal, s.normal};
}

// The capped frustum of a cone (a cylinder when r0 = r1) from a (radius r0) to b (radius r1): the
// slab 0 <= s <= h along the axis u, and |w|^2 <= (r0 + k s)^2 with w the part of p - a across
// the axis, k = (r1 - r0) / h. The solid is convex: one span.
LocalSpan cone(const Primitive& s, const Vec3& o, const Vec3& d) {
  const Vec3 axis = s.b - s.a;
  const double h = length(axis);
  const Vec3 u = axis / h;
  const double k = (s.r1 - s.r0) / h;
  const Vec3 q = o - s.a;
  const double s0 = dot(q, u), sd = dot(d, u);
  // The slab.
  LocalSpan slab = everywhere();
  if (sd == 0) {
    if (s0 < 0 || s0 > h) return {};
  } else {
    double ta = -s0 / sd, tb = (h - s0) / sd;
    Vec3 na = -u, nb = u;
    if (ta > tb) {
      std::swap(ta, tb);
      std::swap(na, nb);
    }
    slab = {ta, tb, na, nb};
  }
  // The lateral surface's quadratic f(t) = A t^2 + B t + C <= 0.
  const double rs0 = s.r0 + k * s0;
  const double A = dot(d, d) - sd * sd - k * k * sd * sd;
  const double B = 2 * (dot(q, d) - s0 * sd - k * sd * rs0);
  const double C = dot(q, q) - s0 * s0 - rs0 * rs0;
  const auto lateral_normal = [&](double t) {
    const Vec3 p = q + d * t;
    const double sp = dot(p, u);
    const Vec3 w = p - u * sp;
    return w - u * ((s.r0 + k * sp) * k);
  };
  // The pieces where f <= 0, each [lo, hi] with a flag saying whether its ends are roots.
  struct Piece {
    double lo, hi;
    bool lo_root, hi_root;
  };
  Piece pieces[2];
  int n = 0;
  double r1, r2;
  if (!roots(A, B, C, r1, r2)) {
    if (C <= 0 && A <= 0) pieces[n++] = {-kInf, kInf, false, false};  // inside all along
  } else if (A > 0) {
    pieces[n++] = {r1, r2, true, true};
  } else if (A < 0) {
    pieces[n++] = {-kInf, r1, false, true};
    pieces[n++] = {r2, kInf, true, false};
  } else {  // linear: B t + C <= 0
    pieces[n++] = B > 0 ? Piece{-kInf, r1, false, true} : Piece{r1, kInf, true, false};
  }
  LocalSpan best;
  for (int i = 0; i < n; ++i) {
    LocalSpan span;
    if (pieces[i].lo > slab.t0) {
      span.t0 = pieces[i].lo;
      span.n0 = lateral_normal(span.t0);
    } else {
      span.t0 = slab.t0;
      span.n0 = slab.n0;
    }
    if (pieces[i].hi < slab.t1) {
      span.t1 = pieces[i].hi;
      span.n1 = lateral_normal(span.t1);
    } else {
      span.t1 = slab.t1;
      span.n1 = slab.n1;
    }
    if (span.t0 <= span.t1 && !(best.t0 <= best.t1 && best.t1 - best.t0 >= span.t1 - span.t0))
      best = span;
  }
  return best;
}

LocalSpan local_span(const Primitive& shape, const Ray& ray) {
  // The identity's products give the ray's own numbers (to the sign of a zero): a floor's test on
  // every camera and shadow ray (the floor frame: 560,000 of them) need not multiply by it.
  const Vec3 o = shape.unplaced ? ray.o : shape.to_object * (ray.o - shape.to_world.offset);
  const Vec3 d = shape.unplaced ? ray.d : shape.to_object * ray.d;
  LocalSpan local;
  switch (shape.shape) {
    case Primitive::Shape::Plane:
      local = plane(shape, o, d);
      break;
    case Primitive::Shape::Box:
      local = box(shape, o, d);
      break;
    case Primitive::Shape::Sphere:
      local = sphere(shape, o, d);
      break;
    case Primitive::Shape::Cylinder:
    case Primitive::Shape::Cone:
      local = cone(shape, o, d);
      break;
    case Primitive::Shape::Disc:
      local = disc(shape, o, d);
      break;
  }
  return local;
}

// Normals go to the world by the inverse transpose.
Vec3 world_normal(const Primitive& shape, const Vec3& n) {
  const Vec3 w = shape.to_object.transposed_times(n);
  const double l = length(w);
  return l > 0 ? w / l : w;
}

// The end of the span that is the first surface point in [tnear, tfar] (within kMaxPosition of
// the origin): 0 or 1, or -1 where there is none.
int first_end(const LocalSpan& span, const Ray& ray, double tnear, double tfar) {
  if (!(span.t0 <= span.t1)) return -1;
  if (reachable(ray, span.t0, tnear, tfar)) return 0;
  if (reachable(ray, span.t1, tnear, tfar)) return 1;
  return -1;
}

}  // namespace

SolidSpan solid_span(const Primitive& shape, const Ray& ray) {
  const LocalSpan local = local_span(shape, ray);
  return {local.t0, local.t1, world_normal(shape, local.n0), world_normal(shape, local.n1)};
}

PrimitiveHit spanned_first_hit(const Primitive& shape, const Ray& ray, double tnear, double tfar) {
  const LocalSpan span = local_span(shape, ray);
  const int end = first_end(span, ray, tnear, tfar);
  if (end == 0) return {true, span.t0, world_normal(shape, span.n0)};
  if (end == 1) return {true, span.t1, world_normal(shape, span.n1)};
  return {};
}

bool spanned_occludes(const Primitive& shape, const Ray& ray, double tnear, double tfar) {
  return first_end(local_span(shape, ray), ray, tnear, tfar) >= 0;
}

}  // namespace softtrace
