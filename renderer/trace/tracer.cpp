#include "trace/tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/illinois.h"
#include "trace/csg_trace.h"
#include "trace/tracer_limits.h"

namespace softtrace {

using namespace tracer_limits;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Sphere-tracing steps within one segment before it is cut short at the current point: the bound
// over a long segment's box can be far looser than over a short one (e.g. a modulated radius whose
// [d]/[f] decorrelates). Every step taken was certified, so stopping early skips nothing.
constexpr int kSegmentSteps = 4;
// The farthest probe, in tolerances (4 footprint radii): a bracket is refined to its one crossing
// only when it is that short.
constexpr double kProbeReach = 2;
}  // namespace

double ObjectTracer::value_error(double g) const {
  return 1e-12 * (std::abs(g) + std::abs(target_.iso)) + 1e-300;
}

double ObjectTracer::reach(double g, double rate) const {
  const double most = g + value_error(g);  // the true g is at most this
  if (!(most < 0)) return 0;
  return rate > 0 ? -most / rate : kInf;
}

Workspace& ObjectTracer::workspace() const {
  // One per thread, shared by every object's tracer: evaluations do not allocate once it has grown
  // to the largest program.
  thread_local Workspace ws;
  ws.fit(need_);
  return ws;
}

SceneTracers::SceneTracers(const std::vector<TracedObject>& objects, LipschitzMode mode)
    : objects_(&objects) {
  tracers_.reserve(objects.size());
  exits_.reserve(objects.size());
  for (const TracedObject& o : objects) {
    index_.push_back(o.field ? static_cast<int>(tracers_.size()) : -1);
    if (o.field) {
      tracers_.emplace_back(*o.field, mode);
      exits_.emplace_back(*o.field, mode, true);
    }
    csg_.push_back(o.csg() ? std::make_shared<const CsgTracer>(o, mode) : nullptr);
  }
}

ObjectTracer::ObjectTracer(const TraceTarget& target, LipschitzMode mode, bool complement)
    : target_(target),
      inside_sign_(complement ? -target.inside_sign : target.inside_sign),
      program_(*target_.program),
      need_(program_),
      mode_(mode) {
  global_L_ = target.lipschitz;
  g_empty_ = -inside_sign_ * target.iso;
  default_footprint_ = 1e-5 * target.bounds.diagonal();
  if (mode == LipschitzMode::Local && inside_sign_ > 0 && target.iso > 0)
    blobs_ = BlobSum::of(program_);
  if (blobs_) blocker_reach2_ = blocker_reach2(*blobs_, target.iso);
  const Box& b = target.bounds;
  scale_ = std::max(max_abs(b.lo), max_abs(b.hi));
}

double ObjectTracer::eval(const Vec3& p, Vec3* grad) const {
  return evaluate(program_, p, grad, workspace());
}

double ObjectTracer::g(const Vec3& p) const {
  return inside_sign_ * (eval(p, nullptr) - target_.iso);
}

double ObjectTracer::g_view(const Vec3& p) const {
  Workspace& ws = workspace();
  return inside_sign_ * (value(ws.view, p, ws) - target_.iso);
}

Vec3 ObjectTracer::normal(const Vec3& p, double* terms, const BlobBeam* list) const {
  Vec3 grad;
  if (blobs_) {
    grad = blob_gradient(p, terms, list);
  } else if (terms) {
    gradient_terms(program_, p, &grad, terms, workspace());
  } else {
    eval(p, &grad);
  }
  grad = grad * -inside_sign_;
  const double len = length(grad);
  return len > 0 && std::isfinite(len) ? grad / len : Vec3{};
}

Vec3 ObjectTracer::box_face_normal(const Vec3& p) const {
  const Box& b = target_.bounds;
  Vec3 n{-1, 0, 0};
  double best = std::abs(p.x - b.lo.x);
  for (int i = 0; i < 3; ++i)
    for (int side = 0; side < 2; ++side) {
      const double dist = std::abs(p[i] - (side ? b.hi[i] : b.lo[i]));
      if (dist < best) {
        best = dist;
        n = {};
        n[i] = side ? 1 : -1;
      }
    }
  return n;
}

ObjectTracer::SegmentBounds ObjectTracer::segment_bounds(const Ray& ray, double a, double b,
                                                         TraceCounters& work) const {
  ++work.box_evals;
  // One pass: the interval, the slope bound and the program pruned to the segment (the children
  // whose supports it passes through), which the points of this segment evaluate afterwards.
  const BoxBounds bb = bounds(program_, segment(ray, a, b), workspace());
  const double iso = target_.iso;
  const bool up = inside_sign_ > 0;
  const Interval g = up ? Interval{bb.value.lo - iso, bb.value.hi - iso}
                        : Interval{iso - bb.value.hi, iso - bb.value.lo};
  // The global mode is the baseline the local bounds are measured against: its bound only.
  if (mode_ == LipschitzMode::Global) return {g, global_L_, global_L_};
  const Interval slope = up ? bb.slope : -bb.slope;
  return {g, std::min(bb.lipschitz, slope.hi), std::min(bb.lipschitz, -slope.lo),
          g_empty_ < 0 ? bb.quiet * (b - a) : 0.0};
}

double ObjectTracer::split(double lo, double glo, double hi, double ghi, const SegmentBounds& sb) {
  // Where g rises through the piece (as its ends' values say), a point x with g(x) ~ glo + s (x -
  // lo) clears -g(x)/fall behind it: the left part [lo, x] is cleared by the spheres of its ends
  // when -glo/rise - g(x)/fall >= x - lo, that is up to d below; 0.9 of it leaves room for g's
  // bend. Next to a crossing, where both spheres are a fraction k of the distance to it, that
  // takes the distance down by (1 - k)/(1 + k) a step instead of 1/2. Elsewhere, the middle.
  const double len = hi - lo, mid = lo + 0.5 * len;
  const double s = (ghi - glo) / len;
  if (!(s > 0) || !(sb.rise > 0) || !(sb.fall > 0) || !std::isfinite(sb.rise)) return mid;
  const double d = 0.9 * -glo * (1 / sb.rise + 1 / sb.fall) / (1 + s / sb.fall);
  return d > 0.5 * len && d < 0.95 * len ? lo + d : mid;
}

ObjectTracer::Scan ObjectTracer::scan(const Ray& ray, double a, double ga, double c, double gc,
                                      double finest, int budget, bool cut,
                                      TraceCounters& work) const {
  // Pieces of [a, c], leftmost first, so that a bracket is the first sign change. A piece is
  // cleared by its interval or by what its ends clear (reach, from the piece's rates); otherwise it
  // is halved, its middle's sign checked. g at a piece's ends: known < 0, or NaN until evaluated.
  // A half inherits its parent's rates, which hold on it too: most halves beside a crossing are
  // cleared by those alone, without a bounds pass of their own.
  struct Piece {
    double lo, glo, hi, ghi;
    double rise, fall;  // bounds on g's slope over a piece holding this one (kInf: none yet)
  };
  constexpr int kDepth = 128;
  Piece stack[kDepth];
  int top = 0;
  stack[top++] = {a, ga, c, gc, kInf, kInf};
  const auto g_at = [&](double t) {
    ++work.point_evals;
    return g_view(ray.o + ray.d * t);
  };
  while (top > 0) {
    Piece q = stack[--top];
    if (q.glo < 0 && q.ghi < 0 && reach(q.glo, q.rise) + reach(q.ghi, q.fall) >= q.hi - q.lo)
      continue;
    SegmentBounds sb = segment_bounds(ray, q.lo, q.hi, work);
    if (sb.g.hi < 0) continue;
    sb.rise = std::min(sb.rise, q.rise);
    sb.fall = std::min(sb.fall, q.fall);
    if (std::isnan(q.ghi) && (q.ghi = g_at(q.hi)) >= 0)
      return {Scan::Bracket, q.lo, q.glo, q.hi, q.ghi};
    if (std::isnan(q.glo)) q.glo = g_at(q.lo);
    if (!(q.glo < 0))
      return {Scan::Bracket, q.lo, NAN, q.lo, q.glo};  // on the surface, to rounding
    if (reach(q.glo, sb.rise) + reach(q.ghi, sb.fall) >= q.hi - q.lo) continue;
    if (q.hi - q.lo <= finest || top + 2 > kDepth || work.evaluations() >= budget)
      return {Scan::Undecided, q.lo, q.glo, q.hi, q.ghi};
    const double m = cut ? split(q.lo, q.glo, q.hi, q.ghi, sb) : 0.5 * (q.lo + q.hi);
    const double gm = g_at(m);
    if (gm >= 0) return {Scan::Bracket, q.lo, q.glo, m, gm};
    stack[top++] = {m, gm, q.hi, q.ghi, sb.rise, sb.fall};
    stack[top++] = {q.lo, q.glo, m, gm, sb.rise, sb.fall};
  }
  return {Scan::Clear, c, NAN, c, NAN};
}

ObjectTracer::Scan ObjectTracer::decide(const Ray& ray, double a, double ga, double c, double gc,
                                        double tol, TraceCounters& work) const {
  for (;;) {
    const Scan sc = scan(ray, a, ga, c, gc, kFinest * tol, kMaxSteps, true, work);
    if (sc.kind != Scan::Undecided) return sc;
    // A piece kFinest of the tolerance long that neither its interval nor its ends' spheres
    // clear: the surface passes close to the ray there, or the bounds are loose at this scale.
    // Halving on shrinks the bounds' excess with the piece, so a ray that only grazes the surface
    // is decided a few levels down (never finer than the points' rounding, which pads every
    // segment). The budget caps a ray that runs along a face, g within rounding of 0.
    const double deepest = std::max(kFinestDeep * tol, 4e-12 * (max_abs(ray.o) + std::abs(sc.hi)));
    const Scan deep = scan(ray, sc.lo, sc.glo, sc.hi, sc.ghi, deepest,
                           std::min(kMaxSteps, work.evaluations() + kDeepBudget), false, work);
    if (deep.kind == Scan::Bracket) return deep;
    if (deep.kind == Scan::Undecided) {
      // Most often the piece ends within rounding of a crossing just past it, which every
      // interval over it then holds: a sign change a little ahead (inside the object's box)
      // certifies that crossing, and [deep.lo, there] brackets the first one.
      for (double ahead = deep.hi - deep.lo; ahead <= kFinest * tol; ahead *= 4) {
        const Vec3 q = ray.o + ray.d * (deep.hi + ahead);
        if (!target_.bounds.contains(q)) break;
        ++work.point_evals;
        const double gq = g(q);
        if (gq >= 0) {
          segment_bounds(ray, deep.lo, deep.hi + ahead, work);  // ws.view holds the bracket
          return {Scan::Bracket, deep.lo, deep.glo, deep.hi + ahead, gq};
        }
      }
      // Undecided even there (counted): the surface may touch the ray in the piece but enters
      // the solid nowhere a sign or an interval shows. Pass it, and go on from its end.
      ++work.undecided;
    }
    if (sc.hi >= c) return {Scan::Clear, c, NAN, c, NAN};
    a = sc.hi;
    ga = sc.ghi;
  }
}

double ObjectTracer::refine(const Ray& ray, double a, double ga, double b, double gb,
                            SegmentBounds rates, TraceCounters& work, Below* below) const {
  // The Anderson-Bjorck variant of regula falsi, on the program pruned to a box holding the
  // bracket (ws.view): superlinear on smooth roots, and a bracket always, so it never leaves
  // [a, b]. Beside the bracket, [lo, hi] holds the first root: a value g(m) < 0 puts it at least
  // -g/rise past m, and where g rises at least -fall > 0 (one crossing), at most -g/-fall past m
  // (and a value >= 0 at least g/-fall before m). That range closes long before the bracket's
  // far end moves.
  const auto g_at = [&](double t) {
    ++work.point_evals;
    return g_view(ray.o + ray.d * t);
  };
  if (std::isnan(ga)) ga = g_at(a);
  if (!(ga < 0)) return a;  // rounding on the pruned program: a itself is on the surface
  const double least_rise = -rates.fall;  // > 0: g rises at least this fast on [a, b]
  double lo = a, hi = b;
  const auto narrow = [&](double m, double gm) {
    const double err = value_error(gm);
    if (gm < 0) {
      if (below) below->add(m, gm);
      lo = std::max(lo, m + reach(gm, rates.rise));
      if (least_rise > 0) hi = std::min(hi, m - (gm - err) / least_rise);
    } else {
      hi = std::min(hi, m);
      if (least_rise > 0) lo = std::max(lo, m - (gm + err) / least_rise);
    }
  };
  narrow(a, ga);
  IllinoisBracket br{a, ga, b, gb};
  br.anderson_bjorck = true;
  for (int i = 0; i < 100; ++i) {
    // The footprint at the near end, the nearest the root can be: a wide bracket must not take
    // its tolerance from its far end.
    const double tol = kRefine * footprint(ray, lo);
    if (hi - lo <= tol) break;
    // False position, kept half a tolerance inside the root's range: a root within that of an
    // end then ends the search at the next step.
    const double m = std::clamp(br.false_position(), lo + 0.5 * tol, hi - 0.5 * tol);
    ++work.refine_iterations;
    const double gm = g_at(m);
    br.update(m, gm, gm >= 0);
    narrow(m, gm);
  }
  return hi;
}

double ObjectTracer::first_crossing(const Ray& ray, double a, double ga, double b, double gb,
                                    SegmentBounds rates, TraceCounters& work) const {
  // Regula falsi, and the narrowing from slope bounds, take the bracket's crossing to be its only
  // one: a value g(m) < 0 moves the near end to m, past whatever [a, m] holds. Where g may fall
  // in [a, b], a sliver of the solid thinner than the bracket may lie before the crossing found
  // (a pinched or high-exponent shape seen across its thin part). Each point refinement found
  // outside clears -g/fall behind it and -g/rise ahead (SegmentBounds): where those spheres
  // chain from a to the root found, nothing precedes it; a gap between them is decided, and a
  // sign change there is an earlier bracket, searched in turn. Each bracket is left of the last.
  for (int round = 0; round < 64; ++round) {
    // The bracket's own bounds, tighter than its segment's: most show g rising through it.
    if (rates.fall > 0) rates = segment_bounds(ray, a, b, work);  // prunes ws.view to [a, b]
    if (rates.fall <= 0) return refine(ray, a, ga, b, gb, rates, work);
    Below below;
    const double root = refine(ray, a, ga, b, gb, rates, work, &below);
    if (below.n == 0) return root;  // a itself is on the surface, to rounding
    // Sort the points (refinement visits them in no order; few, so insertion sort).
    for (int i = 1; i < below.n; ++i)
      for (int k = i; k > 0 && below.t[k] < below.t[k - 1]; --k) {
        std::swap(below.t[k], below.t[k - 1]);
        std::swap(below.g[k], below.g[k - 1]);
      }
    // Mostly g cannot fall on [a, m*], m* the last point found outside, short of the root: it
    // stays below g(m*) < 0 there, and m*'s sphere reaches the root's range. One bounds pass.
    const double last = below.t[below.n - 1];
    if (last > a) {
      const SegmentBounds before = segment_bounds(ray, a, last, work);
      if (before.fall <= 0 || before.g.hi < 0) return root;
    }
    // A crossing within refinement's tolerance before the root is as good as the root: only
    // [a, target] must be certified (refinement's points cluster past it, each sphere tiny).
    const double target = root - kRefine * footprint(ray, a);
    double cover = below.t[0] + reach(below.g[0], rates.rise);  // below.t[0] is a
    bool earlier = false;
    for (int i = 1; i < below.n && !earlier && cover < target; ++i) {
      const double behind = below.t[i] - reach(below.g[i], rates.fall);
      if (behind > cover) {  // a gap: decide it (up to the target), leftmost first
        const double tol = kDecide * footprint(ray, cover);
        const bool whole = below.t[i] <= target;
        const Scan sc = decide(ray, cover, NAN, whole ? below.t[i] : target,
                               whole ? below.g[i] : NAN, tol, work);
        if (sc.kind == Scan::Bracket) {
          if (!(sc.lo < sc.hi)) return sc.hi;
          a = sc.lo, ga = sc.glo, b = sc.hi, gb = sc.ghi;
          rates = {{}, kInf, kInf};
          earlier = true;
        }
      }
      cover = std::max(cover, below.t[i] + reach(below.g[i], rates.rise));
    }
    if (!earlier) return root;
  }
  return b;
}

bool ObjectTracer::enter_box(const Ray& ray, double tnear, double tfar, double clear_to,
                             TraceCounters& work, double& t0, double& t1, bool& face) const {
  t0 = tnear;
  t1 = tfar;
  if (!clip_to_box(ray, target_.bounds, t0, t1)) return false;
  work.entered_box = true;
  // A solid where the ray enters the box from outside it is cut by the box: the hit is its face.
  face = t0 > tnear && t0 >= clear_to;
  t0 = std::max(t0, clear_to);
  return !(t0 > t1);  // a NaN end is not a miss
}

MarchResult ObjectTracer::shadow_hit(const Ray& ray, double tnear, double tfar,
                                     TraceCounters& work) const {
  if (!blobs_ || blobs_->size() > BlobSum::kListed)
    return first_hit(ray, tnear, tfar, work, Query::Any);
  // first_hit's start (clear_to 0), then few_blobs_shadow for first_hit_blobs. Apart
  // from first_hit: the test there cost every camera ray and listed shadow ray its branches
  // (callgrind, pov:golfball at 320x240, +0.5 M).
  double t0, t1;
  bool face;
  if (!enter_box(ray, tnear, tfar, 0, work, t0, t1, face)) return {};
  return few_blobs_shadow(ray, face, t0, t1, work);
}

MarchResult ObjectTracer::first_hit(const Ray& ray, double tnear, double tfar, TraceCounters& work,
                                    Query query, double clear_to, const BlobBeam* blob_beam) const {
  // A shadow ray of a block whose prism meets none of the blobs (its caller vouches that it is
  // one). The query first: a camera ray pays one comparison.
  if (query == Query::Any && blob_beam && blob_beam->clear) return {};
  double t0, t1;
  bool face;
  if (!enter_box(ray, tnear, tfar, clear_to, work, t0, t1, face)) return {};
  if (blobs_) return first_hit_blobs(ray, face, t0, t1, work, query, blob_beam);
  const auto at = [&](double t) { return ray.o + ray.d * t; };
  // g(a) < 0 <= g(b) = gb, ga = g(a) or NaN where not known; ws.view holds [a, b].
  // `rates`: slope bounds over [a, b], if known.
  const auto hit = [&](double a, double ga, double b, double gb,
                       SegmentBounds rates = {{}, kInf, kInf}) -> MarchResult {
    if (query == Query::Any) return {true, b};
    if (!(a < b)) return {true, b};  // on the surface, to rounding
    return {true, first_crossing(ray, a, ga, b, gb, rates, work)};
  };
  const auto give_up = [&](double t) {
    ++work.give_ups;
    return MarchResult{true, t, false, true};
  };

  double t = t0, gt = 0;
  // Whether gt is g(t). Past t0, g(t) < 0 is always known (from an interval or a value).
  bool gt_known = false;
  // The next segment's length: first, a quarter of the way through the box for a camera ray; for
  // a shadow ray all of it (most leave the object, and one pass may clear it all: over scenes/ at
  // 80x60, 4.08 evaluations per shadow ray against 4.75 with a quarter). A sixteenth would save
  // camera rays 8 % of their evaluations, but its other segmentation brackets a thin sliver with
  // the surface behind it in one short piece that refinement may settle past (the pinched_segment
  // hit mask, 0.4 of a tolerance deep), so a camera ray keeps the quarter.
  double s = query == Query::Any ? t1 - t0 : (t1 - t0) / 4;
  double probe = 0;  // how far ahead to probe near the surface
  // Whether s was halved because the last segment's bound was too loose to decide it: its first
  // half, once cleared, is followed by the second at the same length, not twice it (the surface
  // that kept the whole from clearing is likely there).
  bool halved = false;

  while (t < t1) {
    if (work.evaluations() >= kMaxSteps) return give_up(t);
    const double b = std::min(t + s, t1);
    const SegmentBounds sb = segment_bounds(ray, t, b, work);
    if (sb.g.hi < 0) {  // the solid cannot be reached anywhere in this segment
      t = b;
      gt_known = false;
      if (!halved) s *= 2;
      halved = false;
      continue;
    }
    const double tol = kDecide * footprint(ray, t);
    probe = std::max(probe, tol);
    if (sb.quiet >= tol) {
      // No support begins before t + quiet: g is the empty field's value up to there (and at
      // it: the entry is taken short of the support by more than rounding). Bound the rest of
      // the segment, now without that stretch (at least a tolerance: an entry at the segment's
      // very end leaves nothing of it).
      t += sb.quiet;
      gt = g_empty_;
      gt_known = true;
      s = std::max(b - t, tol);
      continue;
    }
    // No point of the segment can clear a tolerance by the slope bound (g >= g.lo everywhere):
    // sphere steps cannot move, so bisect on intervals before spending values on it.
    if (sb.fall > 0 && -sb.g.lo < tol * sb.rise && b - t > 4 * tol) {
      s = 0.5 * (b - t);
      halved = true;
      continue;
    }
    if (!gt_known) {
      ++work.point_evals;
      gt = g_view(at(t));
      gt_known = true;
      // Inside where the ray enters the box (the box cuts the solid: the hit is on its face), or
      // the previous piece ended on the surface, to rounding.
      if (gt >= 0) return {true, t, face && t == t0};
    }
    // g cannot fall along the segment: its value at the end decides the segment, and a sign
    // change there brackets the only crossing in it.
    if (sb.fall <= 0) {
      // Where g rises at least -fall per unit, the crossing is no farther than -g/-fall (unless
      // that is below what t can resolve).
      const double reach_max = sb.fall < 0 ? t + (gt - value_error(gt)) / sb.fall : b;
      const double e = reach_max > t ? std::min(b, reach_max) : b;
      ++work.point_evals;
      const double ge = g_view(at(e));
      if (ge >= 0) return hit(t, gt, e, ge, sb);
      if (e == b) s *= 2;
      t = e;
      gt = ge;
      continue;
    }
    if (!std::isfinite(sb.rise)) {
      if (b - t > 4 * tol) {  // no slope bound here: bound shorter segments
        s = 0.5 * (b - t);
        halved = true;
        continue;
      }
      const Scan sc = decide(ray, t, gt, b, NAN, tol, work);
      if (sc.kind == Scan::Bracket) return hit(sc.lo, sc.glo, sc.hi, sc.ghi);
      t = b;
      gt_known = false;
      continue;
    }
    // Sphere tracing inside the segment: from a point with g < 0, g stays negative for at least
    // -g/rise along the ray, so a step of that length cannot cross the surface.
    for (int steps = 0;; ++steps) {
      const double r = reach(gt, sb.rise);
      if (r >= b - t) {  // the bound clears the rest of the segment; g at its end is not known
        t = b;
        gt_known = false;
        s *= 2;
        break;
      }
      if (r < tol) {
        // Within a tolerance of the surface, perhaps: probe ahead, one tolerance first, then
        // twice as far after each probe that cleared its way, up to kProbeReach.
        double p = std::min(t + std::min(probe, kProbeReach * tol), t1);
        if (p > b && b - t >= tol) p = b;  // a probe this segment holds is far enough
        if (p > b) {  // the probe is outside this segment's box: bound a segment that holds it
          s = p - t;
          break;
        }
        ++work.point_evals;
        const double gp = g_view(at(p));
        if (gp >= 0) return hit(t, gt, p, gp, sb);
        if (r + reach(gp, sb.fall) >= p - t) {  // what t and p clear covers [t, p]
          probe = 2 * (p - t);
          t = p;
          gt = gp;
          continue;
        }
        const Scan sc = decide(ray, t, gt, p, gp, tol, work);
        if (sc.kind == Scan::Bracket) return hit(sc.lo, sc.glo, sc.hi, sc.ghi);
        t = p;  // scan re-pruned ws.view: bound the next segment afresh
        gt = gp;
        s = 4 * tol;
        break;
      }
      if (steps == kSegmentSteps) {  // a loose bound: bound a shorter segment from t
        s = 4 * r;
        break;
      }
      t += r;
      probe = tol;
      ++work.point_evals;
      gt = g_view(at(t));
      if (gt >= 0) return {true, t};  // a certified step ends on the surface at most
    }
  }
  return {};
}

}  // namespace softtrace
