// One walk over a box: the value interval and Lipschitz bound of every instruction, and the
// program pruned to the box (libfive's intervalAndPush).
//
// Rounding. Instead of rounding every interval operation outward (nextafter), each instruction's
// result is widened once, by a bound on the rounding error of the few operations that made it:
// - translation: fl(x - t) is monotone in x, so [fl(lo - t), fl(hi - t)] holds every computed
//   local point; one ulp more (<= 2^-52 |v|, plus 1e-300 for subnormals) holds the exact ones;
// - rotation: centre and half extent through R and |R|, padded by 1e-12 of the magnitudes (the
//   few products and sums err by far less);
// - potentials are monotone and computed with O(1) operations on values of order 1: the ends'
//   values ± 2^-50 (about 4 ulps of 1) hold every computed value in between;
// - a sum of k terms errs by at most (k-1)·2^-53·Σ|terms| (recursive summation); widened by
//   k·2^-52·Σ|bounds| + 1e-300, the last also covering terms dropped as 0 that are subnormal.
// Oracles and their children keep the model nodes' own outward-rounded bounds.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "eval/eval.h"
#include "kernels/complement.h"
#include "kernels/generalized_distance.h"
#include "kernels/lp_metric.h"
#include "kernels/offset.h"
#include "kernels/perlin.h"
#include "kernels/planes.h"
#include "kernels/polar_prism.h"
#include "kernels/potentials.h"
#include "kernels/ricci.h"
#include "kernels/skeletal.h"
#include "kernels/spherical_product.h"
#include "kernels/strength.h"
#include "kernels/super_ellipsoidal.h"
#include "kernels/transformed_potential.h"
#include "math/bound_util.h"
#include "math/scratch.h"

namespace softtrace {

namespace {

constexpr double kTiny = 1e-300;
constexpr double kEps = 0x1p-52;

double widen_down(double v, double rel) {
  return v - (std::abs(v) * rel + kTiny);
}
double widen_up(double v, double rel) {
  return v + (std::abs(v) * rel + kTiny);
}

Box translate_box(const Box& b, const double* t) {
  Box o;
  for (int i = 0; i < 3; ++i) {
    o.lo[i] = widen_down(b.lo[i] - t[i], kEps);
    o.hi[i] = widen_up(b.hi[i] - t[i], kEps);
  }
  return o;
}

// The box around Rt (b - t): centre through Rt, half extent through |Rt|.
Box place_box(const Box& b, const double* t) {
  if (!b.bounded()) return Box::unbounded();
  const double* M = t + 3;
  const Vec3 c = b.center() - Vec3{t[0], t[1], t[2]}, h = b.extent() * 0.5;
  Box o;
  for (int i = 0; i < 3; ++i) {
    const double ci = M[3 * i] * c.x + M[3 * i + 1] * c.y + M[3 * i + 2] * c.z;
    const double hi =
        std::abs(M[3 * i]) * h.x + std::abs(M[3 * i + 1]) * h.y + std::abs(M[3 * i + 2]) * h.z;
    const double pad = 1e-12 * (std::abs(ci) + hi) + kTiny;
    o.lo[i] = ci - hi - pad;
    o.hi[i] = ci + hi + pad;
  }
  return o;
}

// How far a computed point may stray from the segment after a step with these magnitudes (each
// step's rounding is a few ulps of its operands; 1e-12 is thousands).
constexpr double kSegmentRounding = 1e-12;

// The ellipsoidal distance d = |q|, q = p / a, along the segment [A, B] of length `len`, with q(s)
// = q0 + s qe for s in [0, 1]:
// - its range (grown by pad): d^2 is a quadratic in s, least at its vertex or an end;
// - the range of dd/dt (t = s len): q · qe / (|q| len) is |qe| cos(angle between q and qe) / len,
//   and that angle only shrinks as s grows, so the ends bound it (where q passes through 0, d has
//   a kink and that end's value is -|qe| or |qe|);
// - the first s where d may be below 1 (the support's entry): the nearer root of |q(s)|^2 = r^2,
//   r = 1 plus the range's growth, so that no computed point before it has d < 1.
// The ends' lengths serve all three. Reciprocals and the few operations err by a few ulps, far
// inside the 1e-12 (range) and 1e-9 (slope, entry) widening.
void ellipsoid_on_segment(const Vec3& a, const Vec3& ia, const Vec3& A, const Vec3& B, double pad,
                          double len, Interval* range, Interval* slope, double* entry) {
  const Vec3 q0{A.x * ia.x, A.y * ia.y, A.z * ia.z}, q1{B.x * ia.x, B.y * ia.y, B.z * ia.z};
  // From B - A, not q1 - q0: a short segment far out must not lose its direction to cancellation.
  const Vec3 qe{(B.x - A.x) * ia.x, (B.y - A.y) * ia.y, (B.z - A.z) * ia.z};
  const double ee = dot(qe, qe), n0 = length(q0), n1 = length(q1);
  const double s = ee > 0 ? std::clamp(-dot(q0, qe) / ee, 0.0, 1.0) : 0.0;
  const double near = length(q0 + qe * s), far = std::max(n0, n1);
  // The vertex's s carries the ends' rounding (eps |q0| / |qe|): at most eps far off in d.
  const double grow = pad / std::min({a.x, a.y, a.z}) + 1e-12 * far;
  *range = {std::max(0.0, widen_down(near - grow, 1e-12)), widen_up(far + grow, 1e-12)};
  // |q0 + s qe|^2 = r^2: ee s^2 + 2 B s + c = 0 with c > 0 (the start is outside); the nearer
  // root c / (-B + sqrt(B^2 - ee c)) has no cancellation.
  const double r = widen_up(1 + grow, 1e-12), B0 = dot(q0, qe), c = (n0 - r) * (n0 + r);
  const double disc = B0 * B0 - ee * c;
  if (!(c > 0))
    *entry = 0;
  else if (B0 >= 0 || disc < 0)
    *entry = 1;  // moving away from the centre, or passing outside the support
  else
    *entry = std::min(1.0, c / (-B0 + std::sqrt(disc)) * (1 - 1e-9));
  if (!(len > 0)) {
    *slope = Interval::entire();
    return;
  }
  const double ne = std::sqrt(ee);
  const double lo = n0 > 0 ? dot(q0, qe) / n0 : -ne, hi = n1 > 0 ? dot(q1, qe) / n1 : ne;
  const double spad = 1e-9 * ne + kTiny;
  *slope = {std::max(-ne, lo - spad) / len * (1 + 1e-12),
            std::min(ne, hi + spad) / len * (1 + 1e-12)};
}

// Whether an instruction's quiet start (Workspace::quiet) means its value is 0 there: a
// potential's (transformed or not) or a sum's, not a distance's (>= 1).
bool zero_when_quiet(Op op) {
  return op == Op::Sum || op == Op::Blanc || op == Op::Wyvill || op == Op::Murakami ||
         op == Op::Cubic || op == Op::RadiusTransform || op == Op::Strength;
}

// P over [d] for a non-increasing potential, and its slope bound (0 where d >= 1).
template <class P>
void potential_bounds(P pot, double max_slope, Interval d, double Ld, Interval* out, double* L) {
  const double lo = pot(d.hi), hi = pot(std::max(0.0, d.lo));
  *out = {std::max(0.0, lo - 0x1p-50), std::min(1.0, hi + 0x1p-50)};
  *L = flat_product(d.lo >= 1 ? 0.0 : max_slope, Ld);
}

class Walker {
 public:
  Walker(const Program& p, Workspace& ws, bool with_bounds, const Segment* seg)
      : p_(p),
        ws_(ws),
        bounds_(with_bounds),
        segment_(seg != nullptr),
        slopes_(seg && seg->slopes),
        K_(p.consts.data()),
        length_(seg ? length(ws.segs[1] - ws.segs[0]) : 0) {}

  // Walks code[begin, end) of the base program, appending what is kept to ws.view.
  void walk(int begin, int end) {
    for (int k = begin; k < end;) {
      const Instr& in = p_.code[k];
      if (in.op == Op::Group) {
        k = group(p_.groups[in.a]);
        continue;
      }
      step(in);
      ws_.view.code.push_back(in);
      ++k;
    }
  }

 private:
  void step(const Instr& in) {
    Box* B = ws_.boxes.data();  // (off a segment: on one, box() makes them)
    Interval* I = ws_.ivals.data();
    double* L = ws_.lips.data();
    Interval* D = ws_.slopes.data();  // on a segment: d/dt along it
    double* Q = ws_.quiet.data();     // on a segment: its quiet start (Workspace::quiet)
    switch (in.op) {
      case Op::Translate:
        if (segment_) {
          place_segment(in, false);
        } else {
          B[in.out] = translate_box(B[in.in], K_ + in.a);
        }
        break;
      case Op::Place:
        if (segment_) {
          place_segment(in, true);
        } else {
          B[in.out] = place_box(B[in.in], K_ + in.a);
        }
        break;
      case Op::Oracle:
        if (bounds_) {
          const Box b = box(in.in);
          in.node->bounds(b, &I[in.out], &L[in.out]);
          D[in.out] = {-L[in.out], L[in.out]};
          Q[in.out] = 0;
        }
        break;
      case Op::LpMetric:
        if (bounds_) {
          const LpMetricParams m = LpMetricParams::load(K_ + in.a);
          if (segment_ && m.n == 2) {
            // Along a segment the ellipsoid's range and slope are exact; 1/min(a) bounds |∇d|.
            const Vec3* S = ws_.segs.data() + 2 * in.in;
            ellipsoid_on_segment(m.a, m.ia, S[0], S[1], ws_.seg_pads[in.in], length_, &I[in.out],
                                 &D[in.out], &Q[in.out]);
            L[in.out] = m.global_L;
          } else if (slopes_) {
            Interval rate[3];
            axis_rates(in.in, rate);
            lp_metric_bounds(m, box(in.in), &I[in.out], &L[in.out], rate, &D[in.out]);
            gauge_segment_facts(in.out);
          } else {
            lp_metric_bounds(m, box(in.in), &I[in.out], &L[in.out]);
            segment_facts_from_box(in.out);
          }
        }
        break;
      case Op::SphericalProduct:
        if (bounds_ && slopes_) {
          Interval rate[3];
          axis_rates(in.in, rate);
          spherical_product_bounds(spherical_product_params(K_ + in.a), box(in.in), &I[in.out],
                                   &L[in.out], rate, &D[in.out]);
          gauge_segment_facts(in.out);
        } else if (bounds_) {
          spherical_product_bounds(spherical_product_params(K_ + in.a), box(in.in), &I[in.out],
                                   &L[in.out]);
          segment_facts_from_box(in.out);
        }
        break;
      case Op::ParallelPlanes:
      case Op::OneBranchPlane:
        if (bounds_) {
          const PlaneParams m = plane_params(K_ + in.a);
          const Interval s = segment_ ? dot_on_segment(m.n, in.in) : dot_range(box(in.in), m.n);
          const bool both = in.op == Op::ParallelPlanes;
          (both ? parallel_planes_bounds : one_branch_plane_bounds)(m, s, &I[in.out], &L[in.out]);
          D[in.out] = segment_ ? plane_slope(m, s, in.in, both) : Interval(-L[in.out], L[in.out]);
          Q[in.out] = I[in.out].lo >= 1 ? 1 : 0;
        }
        break;
      case Op::LineSegment:
        if (bounds_) {
          const LineSegmentParams m = line_segment_params(K_ + in.a);
          I[in.out] = line_segment_interval(m, box(in.in));
          L[in.out] = 1 / m.r;
          segment_facts_from_box(in.out);
        }
        break;
      case Op::Torus:
        if (bounds_) {
          torus_bounds(torus_params(K_ + in.a), box(in.in), &I[in.out], &L[in.out]);
          segment_facts_from_box(in.out);
        }
        break;
      case Op::GenDistance:
        if (bounds_) {
          // The kernel on the ranges of X·n_i: over the register's box (the node's bits), or along
          // the segment, where X·n_i is affine, between its ends as for the planes.
          const GeneralizedDistanceParams m{K_ + in.a, in.n};
          Scratch<Interval> s(m.k), u(m.k);
          for (int i = 0; i < m.k; ++i)
            s[i] =
                segment_ ? dot_on_segment(m.normal(i), in.in) : dot_range(box(in.in), m.normal(i));
          generalized_distance_bounds(m, s.data(), u.data(), &I[in.out], &L[in.out]);
          D[in.out] = slopes_ ? generalized_distance_slope(m, s.data(), u.data(), I[in.out],
                                                           L[in.out], in.in)
                              : Interval(-L[in.out], L[in.out]);
          Q[in.out] = I[in.out].lo >= 1 ? 1 : 0;
        }
        break;
      case Op::PolarPrism:
        if (bounds_) {
          polar_prism_bounds(polar_prism_params(K_ + in.a), box(in.in), &I[in.out], &L[in.out]);
          segment_facts_from_box(in.out);
        }
        break;
      case Op::Blanc:
        if (bounds_) {
          const double s = K_[in.a];
          // Without slopes only the Lipschitz bound is wanted: the global one costs nothing.
          potential(
              in, [s](double d) { return blanc(d, s, nullptr); },
              slopes_ ? blanc_slope_range(s, I[in.in]) : Interval(0, blanc_lipschitz(s)));
        }
        break;
      case Op::Wyvill:
        if (bounds_)
          potential(
              in, [](double d) { return wyvill(d, nullptr); },
              slopes_ ? wyvill_slope_range(I[in.in]) : Interval(0, wyvill_lipschitz()));
        break;
      case Op::Murakami:  // a polynomial: its range costs little anywhere
        if (bounds_)
          potential(
              in, [](double d) { return murakami(d, nullptr); }, murakami_slope_range(I[in.in]));
        break;
      case Op::Cubic:  // a polynomial, as Murakami's
        if (bounds_)
          potential(
              in, [](double d) { return cubic(d, nullptr); }, cubic_slope_range(I[in.in]));
        break;
      case Op::Strength:
        if (bounds_) {
          // s·f of a soft object f: 0 exactly where f is, so f's quiet start is its own
          // (zero_when_quiet); d/dt (s f) = s df/dt, the ends swapped for s < 0.
          const double s = K_[in.a];
          I[in.out] = strength_interval(s, I[in.in]);
          L[in.out] = strength_lipschitz(s, L[in.in]);
          D[in.out] = Interval(s) * D[in.in];
          Q[in.out] = Q[in.in];
        }
        break;
      case Op::Offset:
        if (bounds_) {
          const double s = K_[in.a], c = K_[in.a + 1];
          I[in.out] = offset_interval(s, c, I[in.in]);
          L[in.out] = offset_lipschitz(s, L[in.in]);
          // d/dt s·(f - c) = s·df/dt: an interval product, so a negative s swaps the ends. The
          // offset of a distance is no soft field: no quiet start.
          D[in.out] = Interval(s) * D[in.in];
          Q[in.out] = 0;
        }
        break;
      case Op::Complement:
        if (bounds_) {
          const Convention conv = complement_convention(K_ + in.a);
          I[in.out] = complement_interval(conv, I[in.in]);
          L[in.out] = complement_lipschitz(conv, I[in.in], L[in.in]);
          // d/dt (1 - f) = d/dt (-f) = -df/dt exactly; for 1/f the bound either way. 1 - f and
          // -f are 0 nowhere in particular: no quiet start.
          D[in.out] =
              conv == Convention::Constructive ? Interval(-L[in.out], L[in.out]) : -D[in.in];
          Q[in.out] = 0;
        }
        break;
      case Op::RadiusTransform:
        if (bounds_) radius_transform(in);
        break;
      case Op::Group:
      case Op::Sum:
      case Op::Min:
      case Op::Max:
      case Op::SuperUnion:
      case Op::SuperIntersect:
      case Op::Perlin:
      case Op::Ricci:
        break;  // handled by group()
    }
  }

  // A non-increasing potential P of distance in.in, with |P'| in `slope` over the distance's
  // interval: dP/dt = P'(d) d' with P' in -slope.
  template <class P>
  void potential(const Instr& in, P pot, Interval slope) {
    potential_bounds(pot, slope.hi, ws_.ivals[in.in], ws_.lips[in.in], &ws_.ivals[in.out],
                     &ws_.lips[in.out]);
    if (!segment_) return;
    ws_.slopes[in.out] = -slope * ws_.slopes[in.in];
    ws_.quiet[in.out] = quiet_potential(in.in);
  }

  // A radius-transformed soft object over its register's box: 0 outside its support box, else
  // the model's bounds from its distance's and modulation's slots, unrefined. The model refines
  // small boxes where [d]/[f] is wide over octants, re-evaluating d and f on sub-boxes, which
  // their slots cannot give; asking the model node for those instead was measured
  // (fig000_13d_star_contour at 80x60, one thread, medians of 3 benches of 3 frames each): 0.256 s
  // against 0.157 s unrefined, for 19.82 against 19.97 evaluations per ray, and within 0.8 % of
  // the evaluations on every scene with radius transforms. Along a segment the slope is the chain
  // rule's on d's and f's slopes (TransformedPotential::slope_along) within [-L, L], and the field
  // is 0 until the segment may enter the support box, or while d >= 1 where that
  // makes T = 1.
  void radius_transform(const Instr& in) {
    Interval* I = ws_.ivals.data();
    double* L = ws_.lips.data();
    const TransformedPotential t = TransformedPotential::load(K_ + in.a);
    if (t.outside_support(box(in.reg))) {
      I[in.out] = Interval(0);
      L[in.out] = 0;
      ws_.slopes[in.out] = Interval(0);
      ws_.quiet[in.out] = 1;
      return;
    }
    const TransformedPotential::Bounds B = t.bounds(I[in.in], L[in.in], I[in.n], L[in.n]);
    I[in.out] = t.interval(B);
    L[in.out] = t.slope_bound(B);
    ws_.slopes[in.out] = {-L[in.out], L[in.out]};
    if (!segment_) return;
    if (slopes_)
      ws_.slopes[in.out] = capped(t.slope_along(B, ws_.slopes[in.in], ws_.slopes[in.n]), L[in.out]);
    double q = box_entry(t.support, in.reg);
    if (t.src == WSource::Constant && t.T.outer_end(t.w) <= 1)
      q = std::max(q, quiet_potential(in.in));
    ws_.quiet[in.out] = q;
  }

  // The fraction of register r's segment before which it cannot be in box s (1 where it never
  // enters): the slab test, with the box grown by how far the computed points may stray and by
  // the rounding of the slab's quotients (a few ulps of the coordinates, far inside 1e-12).
  double box_entry(const Box& s, int r) const {
    if (!s.bounded()) return 0;
    const Vec3* S = ws_.segs.data() + 2 * r;
    const double grow =
        ws_.seg_pads[r] +
        kSegmentRounding * std::max({max_abs(S[0]), max_abs(S[1]), max_abs(s.lo), max_abs(s.hi)}) +
        kTiny;
    double enter = 0, leave = 1;
    for (int i = 0; i < 3; ++i) {
      const double lo = s.lo[i] - grow, hi = s.hi[i] + grow, a = S[0][i], e = S[1][i] - a;
      if (e == 0) {
        if (a < lo || a > hi) return 1;
        continue;
      }
      double ta = (lo - a) / e, tb = (hi - a) / e;
      if (e < 0) std::swap(ta, tb);
      // NaN ends compare false and leave [enter, leave] as it was.
      enter = std::max(enter, ta);
      leave = std::min(leave, tb);
    }
    if (enter > leave) return 1;
    return enter * (1 - 1e-9);
  }

  // A gauge with its slope along the segment in ws_.slopes[out] (uncapped): capped by its
  // Lipschitz bound; it stays >= 1 all along only where it does over the whole box.
  void gauge_segment_facts(int out) {
    ws_.slopes[out] = capped(ws_.slopes[out], ws_.lips[out]);
    ws_.quiet[out] = ws_.ivals[out].lo >= 1 ? 1 : 0;
  }

  // A distance bounded over its register's box only: its slope along the segment is the Lipschitz
  // bound either way, and it stays >= 1 all along only where it does over the whole box.
  void segment_facts_from_box(int out) {
    const double L = ws_.lips[out];
    ws_.slopes[out] = {-L, L};
    ws_.quiet[out] = ws_.ivals[out].lo >= 1 ? 1 : 0;
  }

  // X·n over register r's segment (n a unit vector): X·n is affine along it, so its range is that
  // between the ends, grown by how far the computed points may stray and the dot's rounding.
  Interval dot_on_segment(const Vec3& n, int r) const {
    const Vec3* S = ws_.segs.data() + 2 * r;
    const double d0 = dot(S[0], n), d1 = dot(S[1], n);
    const double grow =
        ws_.seg_pads[r] + kSegmentRounding * std::max(max_abs(S[0]), max_abs(S[1])) + kTiny;
    return {std::min(d0, d1) - grow, std::max(d0, d1) + grow};
  }

  // The rate of X·n along register r's segment per unit of the ray's t: (B - A)·n / len, padded
  // for the rounding of the register's segment ends (as ellipsoid_on_segment). Entire for a
  // degenerate segment.
  Interval rate_on_segment(const Vec3& n, int r) const {
    const Vec3 e = segment_step(r);
    return padded_rate(dot(e, n), rate_pad(e));
  }
  Vec3 segment_step(int r) const { return ws_.segs[2 * r + 1] - ws_.segs[2 * r]; }
  static double rate_pad(const Vec3& e) { return 1e-9 * length(e) + kTiny; }
  // k / len, grown by pad and by the division's rounding.
  Interval padded_rate(double k, double pad) const {
    const Interval rate{widen_down((k - pad) / length_, 1e-12),
                        widen_up((k + pad) / length_, 1e-12)};
    if (!(std::isfinite(rate.lo) && std::isfinite(rate.hi))) return Interval::entire();
    return rate;
  }

  // A plane's slope along register r's segment, where X·n lies in `s`: X·n has the rate
  // rate_on_segment, so f's slope is ± that rate / a where X·n keeps its sign, and between the
  // two (|X·n|) or between it and 0 ([X·n]_+) where it may change sign. Capped by the bound 1/a.
  Interval plane_slope(const PlaneParams& m, Interval s, int r, bool both_sides) const {
    const double L = 1 / m.a;
    const Interval k = rate_on_segment(m.n, r);
    if (!(std::isfinite(k.lo) && std::isfinite(k.hi))) return {-L, L};  // a degenerate segment
    const Interval rate{std::max(-L, widen_down(k.lo / m.a, 1e-12)),
                        std::min(L, widen_up(k.hi / m.a, 1e-12))};
    if (both_sides) {
      if (s.lo >= 0) return rate;
      if (s.hi <= 0) return -rate;
      const double most = std::max(-rate.lo, rate.hi);
      return {-most, most};
    }
    if (s.hi <= 0) return 0.0;
    return s.lo >= 0 ? rate : hull(rate, 0.0);
  }

  // A generalized distance's slope along register r's segment, where X·n_i lies in s[i], u_i in
  // u[i] and f in `f`: power_sum_slope over the terms, each u_i' the one-sided term's rate of
  // X·n_i (its side of the dead zone). Capped by the Lipschitz bound L.
  Interval generalized_distance_slope(const GeneralizedDistanceParams& m, const Interval* s,
                                      const Interval* u, Interval f, double L, int r) const {
    Scratch<Interval> du(m.k);
    for (int i = 0; i < m.k; ++i) du[i] = m.term(i).rate(s[i], rate_on_segment(m.normal(i), r));
    return capped(power_sum_slope(u, du.data(), m.k, f, m.n()), L);
  }

  // The local coordinates' rates along register r's segment (rate_on_segment along each axis),
  // for the axis-aligned gauges' slopes (lp_metric_bounds, spherical_product_bounds).
  void axis_rates(int r, Interval* rate) const {
    const Vec3 e = segment_step(r);
    const double pad = rate_pad(e);
    for (int i = 0; i < 3; ++i) rate[i] = padded_rate(e[i], pad);
  }

  static Interval capped(Interval slope, double L) {
    if (std::isnan(slope.lo) || std::isnan(slope.hi)) return {-L, L};
    return {std::max(-L, slope.lo), std::min(L, slope.hi)};
  }

  // How far along the segment a sum's child is exactly 0 (Workspace::quiet, where its result is a
  // field's: a distance's quiet start says nothing of 0).
  double zero_start(const Group::Child& c) const {
    return zero_when_quiet(p_.code[c.end - 1].op) ? ws_.quiet[c.slot] : 0.0;
  }

  // A potential is 0 where its distance is >= 1.
  double quiet_potential(int d) const { return ws_.ivals[d].lo >= 1 ? 1.0 : ws_.quiet[d]; }

  // Register r's box: on a segment, the segment's own box (grown by its pad), tighter than the
  // box carried through a rotation and only made where an instruction asks for it.
  Box box(int r) const {
    if (!segment_) return ws_.boxes[r];
    const Vec3* S = ws_.segs.data() + 2 * r;
    return segment_box(S[0], S[1], ws_.seg_pads[r]);
  }

  // The segment of register in.out from that of in.in: the same affine map as the points.
  void place_segment(const Instr& in, bool rotate) {
    const double* t = K_ + in.a;
    const Vec3 shift{t[0], t[1], t[2]};
    const Vec3* S = ws_.segs.data() + 2 * in.in;
    Vec3* O = ws_.segs.data() + 2 * in.out;
    double pad = ws_.seg_pads[in.in] +
                 kSegmentRounding * (max_abs(shift) + std::max(max_abs(S[0]), max_abs(S[1])));
    for (int e = 0; e < 2; ++e) O[e] = S[e] - shift;
    if (rotate) {
      const double* M = t + 3;
      double norm = 0;  // the largest row sum of |Rt|: how far it can move a point
      for (int e = 0; e < 2; ++e) {
        const Vec3 v = O[e];
        for (int i = 0; i < 3; ++i)
          O[e][i] = M[3 * i] * v.x + M[3 * i + 1] * v.y + M[3 * i + 2] * v.z;
      }
      for (int i = 0; i < 3; ++i)
        norm = std::max(norm, std::abs(M[3 * i]) + std::abs(M[3 * i + 1]) + std::abs(M[3 * i + 2]));
      pad = pad * norm * (1 + kSegmentRounding) +
            kSegmentRounding * std::max(max_abs(O[0]), max_abs(O[1]));
    }
    ws_.seg_pads[in.out] = pad;
  }

  // Chooses, walks and combines the children of a group; returns the index after it.
  int group(const Group& g) {
    const Instr& combine = p_.code[g.op_index];
    int32_t* kept = ws_.kept.data();
    const int first = top_;
    if (combine.op == Op::Sum && !g.bvh.empty()) {
      // The children that are never dropped, merged in order with those whose support meets the
      // box (both lists ascend).
      const Vec3* S = ws_.segs.data() + 2 * g.reg;
      const int mid = segment_
                          ? g.bvh.query(box(g.reg), S[0], S[1], ws_.seg_pads[g.reg], kept, first)
                          : g.bvh.query(ws_.boxes[g.reg], kept, first);
      top_ = first + g.merge_always(kept + first, mid - first);
    } else {
      for (size_t i = 0; i < g.children.size(); ++i) kept[top_++] = static_cast<int32_t>(i);
    }
    const int last = top_;
    int32_t* marks = ws_.marks.data();
    // A sum with a BVH may be large: its children kept in a box then lie in runs far apart in a
    // program too large for the cache (10,000 blobs: 2 MB of code, constants and slots). Their
    // addresses are known from the kept list, so their loads start a few children ahead: the code
    // four ahead, the constants (found from that code; 24 doubles hold a placement's and a
    // distance's) two ahead. blob_box_pass at N = 10,000: 0.95x the time; N = 100 unchanged.
    // (Written here, not as a function: GCC drops a call whose only effect is prefetching.)
    const bool indexed = !g.bvh.empty();
    for (int j = first; j < last; ++j) {
      const Group::Child& c = g.children[kept[j]];
      if (indexed && j + 4 < last) {
        const Group::Child& ahead = g.children[kept[j + 4]];
        __builtin_prefetch(&p_.code[ahead.begin]);
        __builtin_prefetch(&p_.code[ahead.end - 1]);
      }
      if (indexed && j + 2 < last) {
        const double* k = K_ + p_.code[g.children[kept[j + 2]].begin].a;
        for (int line = 0; line < 3; ++line) __builtin_prefetch(k + 8 * line);
      }
      marks[j] = static_cast<int32_t>(ws_.view.code.size());
      walk(c.begin, c.end);
    }
    // The power sums and products keep every child: each one's value moves theirs.
    const bool min_max = combine.op == Op::Min || combine.op == Op::Max;
    if (bounds_ && min_max) drop_inactive(g, combine.op == Op::Min, first, last);
    if (bounds_ && segment_ && combine.op == Op::Sum) drop_quiet(g, first, last);
    const int n = top_ - first;

    Instr out = combine;
    out.a = static_cast<int32_t>(ws_.view.args.size());
    out.n = n;
    for (int j = first; j < first + n; ++j) ws_.view.args.push_back(g.children[kept[j]].slot);
    ws_.view.code.push_back(out);
    if (bounds_) combine_bounds(out, g, first, n);
    top_ = first;
    return g.op_index + 1;
  }

  // min/max: a child whose interval lies wholly beyond the extreme's is never the extreme in the
  // box; its code is removed from the view.
  void drop_inactive(const Group& g, bool is_min, int first, int last) {
    const Interval* I = ws_.ivals.data();
    const int32_t* kept = ws_.kept.data();
    double bound =
        is_min ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    for (int j = first; j < last; ++j) {
      const Interval& a = I[g.children[kept[j]].slot];
      bound = is_min ? std::min(bound, a.hi) : std::max(bound, a.lo);
    }
    // NaN bounds count as active: nothing is known of them.
    drop_children(g, first, last, [&](const Group::Child& c) {
      return is_min ? I[c.slot].lo > bound : I[c.slot].hi < bound;
    });
  }

  // A sum on a segment: a child quiet all along it (its support never entered) is exactly 0
  // there, so the points of the segment need not evaluate it.
  void drop_quiet(const Group& g, int first, int last) {
    drop_children(g, first, last, [&](const Group::Child& c) { return zero_start(c) >= 1; });
  }

  // Removes the kept children [first, last) that `drop` picks, and their code from the view (the
  // others' code moves down).
  template <class Drop>
  void drop_children(const Group& g, int first, int last, const Drop& drop) {
    if (first == last) return;
    int32_t* kept = ws_.kept.data();
    const int32_t* marks = ws_.marks.data();
    auto& code = ws_.view.code;
    int w = first;
    size_t write = marks[first];
    for (int j = first; j < last; ++j) {
      const Group::Child& c = g.children[kept[j]];
      if (drop(c)) continue;
      const size_t from = marks[j], to = j + 1 < last ? marks[j + 1] : code.size();
      std::copy(code.begin() + from, code.begin() + to, code.begin() + write);
      write += to - from;
      kept[w++] = kept[j];
    }
    code.resize(write);
    top_ = w;
  }

  void combine_bounds(const Instr& out, const Group& g, int first, int n) {
    Interval* I = ws_.ivals.data();
    double* L = ws_.lips.data();
    const int32_t* kept = ws_.kept.data();
    if (out.op == Op::Sum) {
      double lo = 0, hi = 0, mag = 0, Ls = 0;
      for (int j = first; j < first + n; ++j) {
        const int s = g.children[kept[j]].slot;
        lo += I[s].lo;
        hi += I[s].hi;
        mag += std::max(std::abs(I[s].lo), std::abs(I[s].hi));
        Ls += L[s];
      }
      const double pad = n * kEps * mag + kTiny;
      I[out.out] =
          std::isnan(lo) || std::isnan(hi) ? Interval::entire() : Interval(lo - pad, hi + pad);
      L[out.out] = Ls;
      if (!segment_) return;  // slopes and quiet starts are the segments' (and scattered reads)
      // The derivative of a sum is the sum of the derivatives, rounded as the values are.
      double dlo = 0, dhi = 0, dmag = 0;
      for (int j = first; j < first + n; ++j) {
        const Interval& d = ws_.slopes[g.children[kept[j]].slot];
        dlo += d.lo;
        dhi += d.hi;
        dmag += std::max(std::abs(d.lo), std::abs(d.hi));
      }
      const double dpad = n * kEps * dmag + kTiny;
      ws_.slopes[out.out] = std::isnan(dlo) || std::isnan(dhi) ? Interval::entire()
                                                               : Interval(dlo - dpad, dhi + dpad);
      // The children dropped are 0 all along; the others until the first support entry.
      double quiet = 1;
      for (int j = first; j < first + n; ++j)
        quiet = std::min(quiet, zero_start(g.children[kept[j]]));
      ws_.quiet[out.out] = quiet;
      return;
    }
    if (out.op == Op::SuperUnion || out.op == Op::SuperIntersect || out.op == Op::Perlin ||
        out.op == Op::Ricci) {
      combination_bounds(out, g, first, n);
      return;
    }
    const bool is_min = out.op == Op::Min;
    Interval r = I[g.children[kept[first]].slot], D = ws_.slopes[g.children[kept[first]].slot];
    double Lm = 0;
    for (int j = first; j < first + n; ++j) {
      const int s = g.children[kept[j]].slot;
      r = is_min ? min(r, I[s]) : max(r, I[s]);
      Lm = std::max(Lm, L[s]);
      // min and max take some child's value at every point: their difference quotients lie in
      // the hull of the children's.
      D = hull(D, ws_.slopes[s]);
    }
    I[out.out] = r;
    L[out.out] = Lm;
    ws_.slopes[out.out] = D;
    ws_.quiet[out.out] = 0;
  }

  // The super-ellipsoidal union and intersection, Perlin's and Ricci's blends: the kernels on the
  // children's intervals and bounds (the model's bits); along a segment the slope is the bound
  // [-L, L], and no quiet start (a combination of distances; 1 - Π(1 - f_i), the products and a
  // soft Ricci union could claim one, not taken here).
  void combination_bounds(const Instr& out, const Group& g, int first, int n) {
    const int32_t* kept = ws_.kept.data();
    // n (and the global bound), the mode and the global bound, or Ricci's parameters and bound
    const double* c = K_ + out.in;
    Scratch<Interval> x(n);
    Scratch<double> Lc(n);
    for (int j = 0; j < n; ++j) {
      const int s = g.children[kept[first + j]].slot;
      x[j] = ws_.ivals[s];
      Lc[j] = ws_.lips[s];
    }
    Interval f;
    double L;
    if (out.op == Op::Ricci) {
      f = ricci_interval(ricci_params(c), x.data(), n);
      L = ricci_lipschitz(ricci_params(c), x.data(), Lc.data(), n, c[3]);
    } else if (out.op == Op::Perlin) {
      f = perlin_interval(perlin_mode(c), x.data(), n);
      L = perlin_lipschitz(perlin_mode(c), x.data(), Lc.data(), n, c[1]);
    } else if (out.op == Op::SuperUnion) {
      f = super_union_interval(x.data(), n, c[0]);
      L = super_union_lipschitz(x.data(), Lc.data(), n, c[0], f);
    } else if (out.op == Op::SuperIntersect) {
      f = power_sum(x.data(), n, c[0]);
      L = super_intersection_lipschitz(x.data(), Lc.data(), n, c[0], f, c[1]);
    } else {
      std::abort();  // only the four combinations reach here: no other op's maths by default
    }
    ws_.ivals[out.out] = f;
    ws_.lips[out.out] = L;
    ws_.slopes[out.out] = {-L, L};
    ws_.quiet[out.out] = 0;
  }

  const Program& p_;
  Workspace& ws_;
  const bool bounds_, segment_;
  const bool slopes_;  // on a segment that asks for its slope (Segment::slopes)
  const double* K_;
  const double length_;  // the segment's length in the world: t runs over [0, length_]
  int top_ = 0;
};

void run(const Program& p, const Box& b, const Segment* seg, Workspace& ws, bool with_bounds) {
  ws.view.base = &p;
  ws.view.code.clear();
  ws.view.args.clear();
  ws.boxes[0] = b;
  if (seg) {
    ws.segs[0] = seg->a;
    ws.segs[1] = seg->b;
    ws.seg_pads[0] = seg->pad;
  }
  Walker(p, ws, with_bounds, seg).walk(0, static_cast<int>(p.code.size()));
  ws.view.result = p.result;
}

}  // namespace

BoxBounds bounds(const Program& p, const Box& b, Workspace& ws) {
  run(p, b, nullptr, ws, true);
  const double L = ws.lips[p.result];
  return {ws.ivals[p.result], L, {-L, L}};
}

BoxBounds bounds(const Program& p, const Segment& s, Workspace& ws) {
  run(p, segment_box(s.a, s.b, s.pad), &s, ws, true);
  return {ws.ivals[p.result], ws.lips[p.result], ws.slopes[p.result],
          zero_when_quiet(p.code.back().op) ? ws.quiet[p.result] : 0.0};
}

void prune(const Program& p, const Box& b, Workspace& ws) {
  run(p, b, nullptr, ws, false);
}

void prune(const Program& p, const Segment& s, Workspace& ws) {
  run(p, segment_box(s.a, s.b, s.pad), &s, ws, false);
}

}  // namespace softtrace
