// Finding the first point of an object's solid along a ray: certified segment tracing.
// Pure fieldlib maths, no Embree: the Embree adapter only calls in here.
//
// The object's field is compiled once to a flat program (fieldlib/program.h). The ray is cut into
// segments; one bounds pass over a segment gives g's interval, its Lipschitz bound and its
// derivative along the segment, and the program pruned to the children the segment passes
// through, which every point of the segment then evaluates. Every advance is certified, never
// sampled:
// - a segment whose interval shows the solid cannot be reached is skipped whole (and the next
//   segment is twice as long); one where g cannot fall is decided by its end value;
// - otherwise the tracer steps by -g / rise, how fast g can rise along the ray, which cannot cross
//   the surface (a segment that needs many such steps is cut shorter: its bounds are loose);
// - once the step is below the ray's tolerance (a pixel's footprint there), probes ahead
//   decide: a sign change is a bracket; what the points clear, or intervals on halvings down to
//   1/1024 of the tolerance, certify the gap; a piece still undecided there is halved on, to
//   1e-9 of the tolerance, and what even that leaves is counted (`undecided`) and passed: no
//   surface is ever invented where none was certified.
// A bracket is narrowed to the first crossing in it: halved, each left half cleared or bracketed
// the same way, until its slope bounds show g rising through it (one crossing); then refined by
// regula falsi (Anderson-Bjorck) to 1/1000 of the footprint, the slope bounds narrowing it from
// both sides (docs/math.md, "How the tracer uses them").
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "eval/blob_ray.h"
#include "eval/eval.h"
#include "scene/trace_target.h"

namespace softtrace {

enum class LipschitzMode { Local, Global };

struct Ray {
  Vec3 o, d;  // d has unit length, so t is a distance
  // The radius of the pixel's cone at distance t is cone0 + cone * t: how precisely a hit must be
  // placed. Zero for rays that come from no camera: the tracer then uses 1e-5 of the object box.
  double cone0 = 0, cone = 0;
  double cone_at(double t) const { return cone0 + cone * t; }
};

// The rays from one eye through a rectangle of the image (a block of pixels): at forward depth s
// (the distance along `forward`), they pass through the quadrilateral eye + s * corner[0..3].
struct Frustum {
  Vec3 eye, forward;  // forward has unit length
  Vec3 corner[4];     // directions through the rectangle's corners, with forward component 1
};

// For a sum of polynomial blobs, the blobs whose supports may meet a ray of a frustum (a block of
// pixels, from its eye): each ray of the block takes its stretches' blobs from this short list
// instead of a walk of the sum's BVH (the tile-level active list of Zanni's Synchronized Tracing,
// 2025). `near`, `far`: the range of distances from the eye at which the blob's support lies.
// The blobs are in the order the BVH's queries report them, so each stretch's terms, and the
// picture, are the same to the bit as the walk's.
// A block of shadow rays towards a directional light: rays of direction `along` (unit, to the
// bit the light's) from points whose coordinates x = (o - origin).u and y = (o - origin).v lie in
// [x0, x1] x [y0, y1] and z = (o - origin).along >= z0 (u, v and along orthonormal): the rays run
// inside the prism over that rectangle, each at z = its origin's z + t. A 4-pixel block's
// prism also bounds its points' balls' tops by z1 (-inf above that level): a shut list's rays start
// at most there (BlobBeam::shut).
// A block of shadow rays towards a point (a point or spot light's position) instead: `origin` is
// the point, and each ray runs from its start o to it inside the pyramid of the points q with
// q - origin = s (along + x u + y v), s > 0, (x, y) in [x0, x1] x [y0, y1] (z0 unused).
struct ShadowPrism {
  Vec3 origin, along, u, v;
  double x0, x1, y0, y1, z0;
  double z1 = std::numeric_limits<double>::infinity();
};

struct BlobBeam {
  struct Entry {
    double near, far;
    int32_t id;
  };
  bool valid = false;  // false: no list (the object is no blob sum, or no frustum holds the rays)
  Vec3 eye;
  std::vector<Entry> entries;
  // A camera list of a sum of more than BlobSum::kListed blobs, some of whose entries only
  // subtract (BlobSum::adds; a negative strength's): `sifted`, and `adders` the positions in
  // `entries`, in order, of those that may add (none, where all of them subtract). A ray's sweep
  // takes the adders first (first_hit_blobs).
  bool sifted = false;
  std::vector<int32_t> adders;
  // A shadow list (ObjectTracer::shadow_beam) instead of a camera list: `near`, `far` are the
  // range of z (ShadowPrism) where the blob's support lies.
  bool parallel = false;
  // A shadow list of rays towards a point (ObjectTracer::blob_beam over the pyramid from it,
  // ShadowPrism), instead: `near`, `far` are the range of minus the distance from the point where
  // the blob's support lies (-|x - origin| grows along each ray, as z along a prism's).
  bool toward = false;
  // A shadow list of a block whose rays meet none of the sum's blobs (render/shadow_beams.cpp: its
  // prism misses the sum's box, or its list holds no blob): a ray given it has no hit, with no
  // check of its own that it is one of the block's. The caller vouches for that: its origin within
  // the margin of one of the points the prism was built from, its direction the light's to the bit
  // (shade() lifts the very point ShadowBeams took, ShadowLists::p).
  bool clear = false;
  ShadowPrism prism;
  // A shadow list's entries' x and y (ShadowPrism) and how far from them the blob reaches: a
  // smaller block's list keeps those whose reach meets its rectangle, with no more arithmetic.
  // A toward list's: its sphere's centre's x, y and depth on the pyramid's axes (not divided by
  // the depth), and its radius with blob_beam's slack.
  struct Across {
    double x, y, reach, depth = 0;
  };
  std::vector<Across> across;
  // A shadow list of a 4-pixel block (ObjectTracer::shadow_blockers): balls each of which alone
  // lifts the field above iso near every ray of the block, where all the list's blobs are
  // positive (else none); and a bound of the rounding of any piece's polynomial made of them.
  std::vector<int32_t> blockers;
  double blockers_err = 0;
  // A directional light's block list whose blockers certainly decide every ray of the block
  // (ObjectTracer::shadow_blockers): a held ray from z <= prism.z1 whose footprint at the box's
  // exit is at most shut_footprint (and at its entry resolves the way, as blocked_by asks) is
  // answered as blocked_by would answer it, with the same work, but without its terms.
  bool shut = false;
  double shut_footprint = 0;
  // A camera list of at most kPassable blobs: per blob that adds, from the eye, what bounds the
  // peak of a ray's terms of it (ObjectTracer::passes_listed_balls, tracer_blob_beam.cpp),
  // `passing` of them; 0 for any other list.
  static constexpr int kPassable = 4;
  struct Passing {
    // A ball's: eye - centre, and 1 - |oc|^2 / r^2 raised by a bound of the rounding. A capsule's
    // or an ellipsoid's: the eye in its frame, L eye + k, and the bound of the rounding alone.
    Vec3 oc;
    double k;
    union {
      double inv_r2;  // a ball's
      int frame;      // a framed blob's id (a member more made every list longer: the balls'
                      // lists' rays +0.5 % of pov:molecule's and meets1's processes)
    };
    double mag;  // |c2| + |c3|
  };
  Passing passes[kPassable];
  int passing = 0;
  int passing_framed = 0;  // the last of the `passing`: the balls' loop takes the others alone
  // A camera list (ObjectTracer::blob_beam from the eye), neither kind of shadow list.
  bool camera() const { return !parallel && !toward; }
  // Whether the list holds for rays from o: from its eye, to the bit.
  bool from(const Vec3& o) const { return valid && o.x == eye.x && o.y == eye.y && o.z == eye.z; }
  // Whether the list holds for `ray` over [0, t1], and where on the entries' axis the ray starts:
  // its point at t is at distance t from a camera list's eye (*base = 0), at z = *base + t in a
  // shadow list's prism, at minus the distance *base + t from a toward list's point
  // (tracer_shadow_beam.cpp; t1 at most the distance to it). A shadow list's ray also gives its
  // origin's x and y on the prism's axes in `across`, where asked (first_hit_blobs' line filter).
  bool holds(const Ray& ray, double* base, double t1 = std::numeric_limits<double>::infinity(),
             double (*across)[2] = nullptr) const {
    if (camera()) {
      *base = 0;
      return from(ray.o);
    }
    return valid && (toward ? holds_toward(ray, t1, base) : holds_shadow(ray, base, across));
  }

 private:
  bool holds_shadow(const Ray& ray, double* base, double (*across)[2]) const;
  bool holds_toward(const Ray& ray, double t1, double* base) const;
};

// A camera ray wants the nearest hit; a shadow ray only whether there is any.
enum class Query { Nearest, Any };

// The work one ray costs one object or the whole scene, counted as it is done. `steps` (the AOV
// and the ray limit) is their sum: point and box evaluations.
struct TraceCounters {
  int point_evals = 0;  // field values at a point (refinement's included)
  // Bounds or pruning passes over a box around a stretch of the ray; for polynomial blobs, the
  // query of a stretch's blobs and each piece whose polynomial is read.
  int box_evals = 0;
  // Root refinement steps after a sign change: one point evaluation each, or for polynomial
  // blobs one value of the piece's polynomial (not counted as a point evaluation).
  int refine_iterations = 0;
  // Searches that reported a hit without a certificate: cut short by the evaluation limit.
  int give_ups = 0;
  // Pieces of the ray no interval (for sums of polynomial blobs: no Bernstein hull) could decide
  // down to 1e-9 of the tolerance: the surface may touch the ray there without entering. Passed,
  // not reported as hits.
  int undecided = 0;
  bool entered_box = false;  // the ray met some object's box (no work is spent on one that did not)
  int evaluations() const { return point_evals + box_evals; }
};

// TraceCounters summed over many rays of one kind (primary or shadow), for `softtrace bench`.
struct RayWork {
  long long rays = 0, entered_box = 0, point_evals = 0, box_evals = 0, refine_iterations = 0,
            give_ups = 0, undecided = 0;
  void add(const TraceCounters& c) {
    ++rays;
    entered_box += c.entered_box;
    point_evals += c.point_evals;
    box_evals += c.box_evals;
    refine_iterations += c.refine_iterations;
    give_ups += c.give_ups;
    undecided += c.undecided;
  }
  RayWork& operator+=(const RayWork& o) {
    rays += o.rays;
    entered_box += o.entered_box;
    point_evals += o.point_evals;
    box_evals += o.box_evals;
    refine_iterations += o.refine_iterations;
    give_ups += o.give_ups;
    undecided += o.undecided;
    return *this;
  }
  long long evaluations() const { return point_evals + box_evals; }
};

struct MarchResult {
  bool hit = false;
  double t = 0;
  // The ray entered the object's box already inside the solid: the box cuts the solid, and the
  // surface seen is the box face, not a level set of the field.
  bool on_box_face = false;
  // A search that reported a hit without a certificate (see TraceCounters::give_ups).
  bool gave_up = false;
};

class ObjectTracer {
 public:
  // `complement`: trace the complement of the target's solid (f on the other side of iso, still
  // within its box), whose first point is where a ray inside the solid leaves it (CSG's exits).
  // The tracer keeps a copy of the target (its program shared).
  ObjectTracer(const TraceTarget& target, LipschitzMode mode, bool complement = false);

  // The first t in [tnear, tfar] where the ray is inside the solid, if any (for Query::Any, some
  // t where it is: the search stops at the first sign change, unrefined, or for a sum of
  // polynomial blobs at a point a stretch's blobs certainly hold). The work is added to
  // `work`, which may already hold the ray's work on other objects: the ray's limit is on the sum.
  // `clear_to`: the caller has certified that the ray meets no solid before it (clear_depth).
  // `blob_beam`: for a sum of polynomial blobs, the list of a frustum holding the ray
  // (blob_beam()); any ray from another origin ignores it. A clear one (BlobBeam::clear) answers a
  // shadow ray's query (Query::Any) with no hit: the ray must be one of its block's.
  MarchResult first_hit(const Ray& ray, double tnear, double tfar, TraceCounters& work,
                        Query query = Query::Nearest, double clear_to = 0,
                        const BlobBeam* blob_beam = nullptr) const;
  // first_hit(ray, tnear, tfar, work, Query::Any) for a shadow ray with no list: the same answer
  // and work, a sum of at most BlobSum::kListed blobs by few_blobs_shadow (tracer_blobs.cpp).
  MarchResult shadow_hit(const Ray& ray, double tnear, double tfar, TraceCounters& work) const;
  // first_hit(ray, 0, tfar, work, Query::Nearest, clear_to, list) for a camera ray from the eye
  // of `list`, a camera list of this blob sum that holds no blob (EmbreeScene::intersect_unmet):
  // the same answer (a miss, or the ray limit) and the same counters, without the search's own
  // set-up, which such a ray only passed through (pov:chain at 640x480: 163,248 such rays, some
  // 300 instructions each).
  MarchResult first_hit_unlisted(const Ray& ray, double tfar, double clear_to,
                                 TraceCounters& work) const;
  // Whether `ray`, a camera ray from the eye of `list` (a camera list of this blob sum with
  // BlobBeam::passing balls) through its block, passes so far from the list's balls that their
  // terms' peaks sum below iso (tracer_blob_beam.cpp): first_hit_blobs then reads no piece, and
  // its answer and counters are first_hit_unlisted's. False where that is not certain.
  bool passes_listed_balls(const Ray& ray, const BlobBeam& list) const;

  // A forward depth before which no ray of the frustum meets the solid (inside the object's box),
  // certified by the interval of g over boxes around slices of the frustum: the work of the
  // approach, shared by every ray of a block of pixels. 0 where nothing is certified; +inf where
  // no ray of it meets the solid at all.
  // `from`: a depth already certified (by a beam holding this one); the search starts there.
  double clear_depth(const Frustum& f, double from, TraceCounters& work) const;
  // The blobs of frustum f (BlobBeam) into *out, from the BVH or, where given, from the list of a
  // frustum holding f (tracer_blob_beam.cpp). Not valid for a tracer that is no blob sum.
  // `passable`: whether its rays may be answered by passes_listed_balls (the frame's 4-pixel
  // blocks, EmbreeScene::passable): only then are its passes kept (BlobBeam::passing, else 0).
  void blob_beam(const Frustum& f, const BlobBeam* parent, BlobBeam* out,
                 bool passable = false) const;
  // The blobs a shadow ray of the prism p may meet (BlobBeam, parallel), into *out, from the BVH
  // or from the list of a prism holding p (tracer_shadow_beam.cpp). Not valid for a tracer that
  // is no blob sum.
  void shadow_beam(const ShadowPrism& p, const BlobBeam* parent, BlobBeam* out) const;
  // The blobs a shadow ray towards the point p.origin may meet inside the pyramid p (BlobBeam,
  // toward; f is the same pyramid as a frustum from that point), from the BVH (blob_beam) or from
  // the list of a pyramid on the same axes holding p (tracer_shadow_beam.cpp). Not valid for a
  // tracer that is no blob sum.
  void toward_beam(const Frustum& f, const ShadowPrism& p, const BlobBeam* parent,
                   BlobBeam* out) const;
  // The blockers of a shadow list (BlobBeam::blockers), picked for the rays of its prism
  // or pyramid.
  void shadow_blockers(BlobBeam* list) const;

  // The box its rays are clipped to before anything else (first_hit): a ray outside it meets the
  // solid nowhere and counts no work.
  const Box& box() const { return target_.bounds; }
  // The radius of the ray's footprint at t, as the searches take it (the tolerances scale by it).
  double resolution(const Ray& ray, double t) const { return footprint(ray, t); }
  // The outward unit normal at p (from the gradient; the inside sign decides the orientation).
  // With `terms`, the same walk leaves the program's terms (Program::terms: the values of the
  // components whose materials mix there) in terms[0, program terms). `list`: a blob sum's hit
  // by a camera ray of that list's beam (TraceHit::blobs), whose blobs replace the point query;
  // the same normal to the bit.
  Vec3 normal(const Vec3& p, double* terms = nullptr, const BlobBeam* list = nullptr) const;
  // The outward normal of the object box's face nearest to p (for hits on_box_face).
  Vec3 box_face_normal(const Vec3& p) const;
  // Whether p is inside the solid.
  bool inside(const Vec3& p) const { return g(p) >= 0; }
  // f(p) and ∇f(p), evaluated on the program pruned to p.
  double eval(const Vec3& p, Vec3* grad) const;

  const Program& program() const { return program_; }
  // Whether rays take the polynomial blob path (tracer_blobs.cpp).
  bool blob_sum() const { return blobs_.has_value(); }
  // How many blobs its sum has (0: no blob sum).
  int blob_count() const { return blobs_ ? blobs_->size() : 0; }

 private:
  // How far a computed g may be from the true one: the program's rounding, a few ulps of the
  // field's terms, far inside this. Every certificate takes the true value anywhere within it
  // (where slope bounds are tiny, as along a flat face, rounding would otherwise carry a step).
  double value_error(double g) const;
  // How far along the ray from a point with computed g < 0 the solid cannot be, where g rises at
  // most `rate` per unit (0 where g may be >= 0).
  double reach(double g, double rate) const;
  // This thread's workspace, fitted to the program.
  Workspace& workspace() const;
  // g = inside_sign (f - iso): the solid is g >= 0.
  double g(const Vec3& p) const;       // anywhere (prunes to p first)
  double g_view(const Vec3& p) const;  // inside the box of the last bounds/prune pass
  Segment segment(const Ray& ray, double a, double b) const;
  // g's interval and Lipschitz bound over the segment [a, b] of the ray; prunes ws.view to it.
  // Over the segment: g's interval, and how fast g can rise along the ray and fall back against
  // it, from the slope bounds (the Lipschitz bound and the derivative along the segment): for
  // t <= u in it, g(u) <= g(t) + rise (u - t) and g(t) <= g(u) + fall (u - t). A point with
  // g < 0 thus clears -g/rise ahead of it and -g/fall behind it (all of it where the rate is <= 0).
  // `quiet`: from a, the stretch where the ray has entered no support, so that g is the empty
  // field's value there, known < 0 (0 where not known).
  struct SegmentBounds {
    Interval g;
    double rise, fall;
    double quiet = 0;
  };
  SegmentBounds segment_bounds(const Ray& ray, double a, double b, TraceCounters& work) const;
  // The radius of the ray's footprint at t (never below what rounding of t can resolve).
  double footprint(const Ray& ray, double t) const;
  // A point of [t0, t1] where one of the list's blockers certainly lifts the field above iso, by
  // far more than the search's rounding and over more than its finest pieces, if one does: the
  // search of Query::Any would have found a crossing there or before (tracer_shadow_beam.cpp).
  std::optional<double> blocked_by(const Ray& ray, double t0, double t1,
                                   const BlobBeam& list) const;
  // Whether the list's blocker entries[i] shuts its block (BlobBeam::shut): sets shut and
  // shut_footprint where it does (tracer_shadow_beam.cpp).
  void shut_by(BlobBeam* list, size_t i) const;
  // The widest square half-diagonal of a prism's rectangle over which any ball of `blobs` may be
  // picked as a blocker (shadow_blockers): 0 where none can be (tracer_shadow_beam.cpp).
  static double blocker_reach2(const BlobSum& blobs, double iso);
  // Whether a held ray of a shut list over [t0, t1], starting at `base` on its axis, is one whose
  // blocked_by answer the list certifies.
  bool shut_decides(const Ray& ray, double t0, double t1, double base, const BlobBeam& list) const;
  // Decides [a, c] (g(a) = ga < 0, g(c) = gc; either NaN where not known yet) by intervals and
  // spheres over halvings down to `finest` (and while the ray's work is below `budget`): clear,
  // the first sign change's bracket, or undecided where the halving stopped.
  struct Scan {
    enum Kind { Clear, Bracket, Undecided } kind;
    // Bracket: g(lo) = glo < 0 <= g(hi) = ghi (glo NaN: not known), ws.view holds [lo, hi].
    // Undecided: the piece [lo, hi], g < 0 at both ends (known), [a, lo] clear.
    double lo, glo, hi, ghi;
  };
  // `cut`: pieces are cut by split(), else halved (the deep halving of decide, whose pieces lie
  // within rounding of the surface, where the chord says little).
  Scan scan(const Ray& ray, double a, double ga, double c, double gc, double finest, int budget,
            bool cut, TraceCounters& work) const;
  // Where scan halves a piece [lo, hi] it could not decide (g(lo) = glo < 0, g(hi) = ghi < 0,
  // sb its bounds): the middle, or nearer hi where the left part should clear by its ends.
  static double split(double lo, double glo, double hi, double ghi, const SegmentBounds& sb);
  // scan down to kFinest of the tolerance `tol`, a piece undecided there once more down to
  // kFinestDeep of it, and on past it: Clear or Bracket. A piece that stays undecided is passed
  // (the surface may touch the ray there but no sign change shows it enters) and counted in
  // work.undecided.
  Scan decide(const Ray& ray, double a, double ga, double c, double gc, double tol,
              TraceCounters& work) const;
  // The first crossing in the bracket [a, b] (g(a) = ga < 0 <= g(b) = gb, ga NaN where not known;
  // ws.view holds [a, b]; `rates` its slope bounds if known), to 1/1000 of the footprint: refined,
  // then, where the bounds allow more than one crossing, the stretch before the root found is
  // certified clear by the spheres of the points refinement evaluated, and any gap between them
  // decided (a sign change there is an earlier bracket, searched the same way). Returns a t no
  // nearer than the first crossing and within that tolerance of it.
  double first_crossing(const Ray& ray, double a, double ga, double b, double gb,
                        SegmentBounds rates, TraceCounters& work) const;
  // The root of g in [a, b] to within 1/1000 of the footprint there, given g(a) = ga < 0 <= g(b) =
  // gb (ga NaN: not known yet), on ws.view pruned to a box holding [a, b], where `rates` show g
  // cannot fall (fall <= 0: one crossing); each value then narrows the root's range from both
  // sides. Returns the range's far end.
  // `below`, if given, receives the points it evaluated where g < 0, a's included.
  struct Below {
    static constexpr int kMax = 104;  // refine's 100 iterations, a, and room
    int n = 0;
    double t[kMax], g[kMax];
    void add(double at, double value) {
      if (n < kMax) t[n] = at, g[n++] = value;
    }
  };
  double refine(const Ray& ray, double a, double ga, double b, double gb, SegmentBounds rates,
                TraceCounters& work, Below* below = nullptr) const;
  // first_hit's and shadow_hit's start: [t0, t1], the part of [tnear, tfar] inside the object's
  // box from clear_to on, and whether t0 is where the ray enters the box from outside (`face`);
  // false where no part is left. A ray that meets the box counts as having entered it.
  bool enter_box(const Ray& ray, double tnear, double tfar, double clear_to, TraceCounters& work,
                 double& t0, double& t1, bool& face) const;
  // first_hit for a sum of polynomial blobs (tracer_blobs.cpp), over [t0, t1] inside the box.
  // `face`: t0 is where the ray enters the box from outside (a solid there is the box's face).
  // `taken`: the first stretch's terms, already taken (few_blobs_shadow), in a buffer with room
  // for max_terms(), which the walk then keeps its terms in.
  struct TakenTerms {
    BlobSum::Term* terms;
    int n;
  };
  MarchResult first_hit_blobs(const Ray& ray, bool face, double t0, double t1, TraceCounters& work,
                              Query query, const BlobBeam* beam,
                              const TakenTerms* taken = nullptr) const;
  // first_hit_blobs for a shadow ray with no list, of a sum of at most BlobSum::kListed blobs,
  // over [t0, t1] (t0 <= t1, shadow_hit): most such rays leave their lit point with the whole way's
  // terms' peaks summing below iso, answered here without first_hit_blobs' set-up for the pieces it
  // then never reads; the others are first_hit_blobs' with the terms taken (tracer_blobs.cpp).
  MarchResult few_blobs_shadow(const Ray& ray, bool face, double t0, double t1,
                               TraceCounters& work) const;
  // first_hit_blobs' stretches over [t0, t1] for a camera ray whose list holds no blob: the
  // same stretches, each counted, none read.
  MarchResult unlisted_stretches(double t0, double t1, TraceCounters& work) const;
  // BlobBeam::passing and passes of the camera list *out from `eye` (eye_scale: its largest
  // coordinate's magnitude), or passing 0 (tracer_blob_beam.cpp).
  void passing_balls(const Frustum& f, double eye_scale, BlobBeam* out) const;
  // ∇f at p for a sum of polynomial blobs, from the blobs that hold p (tracer_blobs.cpp).
  // With `list` (see normal), from its blobs whose ranges of distances hold p's from the eye.
  Vec3 blob_gradient(const Vec3& p, double* terms, const BlobBeam* list) const;

  TraceTarget target_;
  double inside_sign_;      // the target's, or its opposite for the complement
  const Program& program_;  // *target_.program
  WorkspaceNeed need_;      // program_'s, for workspace()'s fit
  LipschitzMode mode_;
  double global_L_;
  double default_footprint_;  // for rays without a cone: 1e-5 of the object's box diagonal
  double scale_;              // the magnitude of coordinates near the object (for rounding)
  double g_empty_;            // g where f = 0: outside every support of a soft field
  // Set where the field is a sum of polynomial blobs and the solid is where it reaches iso > 0
  // (in the local mode; the global one keeps the segment tracer as the baseline).
  std::optional<BlobSum> blobs_;
  // blocker_reach2 of blobs_: a prism's list wider than that has no blocker, and is not searched.
  double blocker_reach2_ = 0;
};

// Inline: a blob ray calls each once or twice (first_hit_blobs), and the calls were 2 % of
// pov:blob1a's instructions at 320x240 (segment's second point, which it does not read, among
// them).
inline double ObjectTracer::footprint(const Ray& ray, double t) const {
  const double f = ray.cone_at(std::abs(t));
  // Points o + t d are only known to a few ulps of the coordinates' magnitude: a tolerance below
  // that would be decided by rounding.
  const double resolvable =
      64 * std::numeric_limits<double>::epsilon() * (scale_ + max_abs(ray.o) + std::abs(t));
  return std::max(f > 0 ? f : default_footprint_, resolvable);
}

inline Segment ObjectTracer::segment(const Ray& ray, double a, double b) const {
  // The points o + t d the tracer evaluates are rounded to a few ulps of |o| + |t|.
  const double pad = 1e-12 * (max_abs(ray.o) + std::max(std::abs(a), std::abs(b)));
  // The global mode steps by the global bound only: no slopes to derive.
  return {ray.o + ray.d * a, ray.o + ray.d * b, pad, mode_ == LipschitzMode::Local};
}

class CsgTracer;

// Every object's tracer, built once per scene from the objects as traced (scene/traced_objects.h),
// which must outlive it. The Embree adapter (embree_scene.h) and the shading (shading.h) both use
// them and neither owns them, so shading never goes through Embree. Objects with a `shape` (plain
// primitives) have no tracer: they are traced analytically (primitive_trace.h). A CSG object has
// a CsgTracer instead (csg_trace.h).
class SceneTracers {
 public:
  SceneTracers(const std::vector<TracedObject>& objects, LipschitzMode mode);
  // The tracer of object `object`, which must have a field (tracer() says).
  const ObjectTracer& operator[](int object) const { return tracers_[index_[object]]; }
  // The object's tracer, or null for a primitive, a CSG or a mesh.
  const ObjectTracer* tracer(int object) const {
    return index_[object] < 0 ? nullptr : &tracers_[index_[object]];
  }
  // The tracer of the complement of a field object's solid (null where tracer() is): from a point
  // inside the solid its first hit is where the ray leaves it (refracted and shadow rays through
  // transparent objects).
  const ObjectTracer* exit_tracer(int object) const {
    return index_[object] < 0 ? nullptr : &exits_[index_[object]];
  }
  // A CSG object's tracer, or null for any other.
  const CsgTracer* csg(int object) const { return csg_[object].get(); }
  const TracedObject& object(int object) const { return (*objects_)[object]; }
  int size() const { return static_cast<int>(index_.size()); }  // the number of objects

 private:
  const std::vector<TracedObject>* objects_;
  std::vector<ObjectTracer> tracers_;
  std::vector<ObjectTracer> exits_;  // tracers_'s complements, in the same order
  std::vector<int> index_;  // per object: its tracer's index, -1 for a primitive, a CSG or a mesh
  std::vector<std::shared_ptr<const CsgTracer>> csg_;  // per object: a CSG's tracer, or null
};

// clip_to_box's slabs, each axis's 1 / ray.d[i] (where ray.d[i] != 0) from inverse(i): a caller
// whose rays share a direction takes its inverses once (PlainFloor's shadow rays), with the same
// arithmetic, so the same answer.
template <class Inverse>
inline bool clip_to_slabs(const Ray& ray, const Box& box, double& t0, double& t1,
                          const Inverse& inverse) {
  for (int i = 0; i < 3; ++i) {
    if (ray.d[i] == 0) {
      if (ray.o[i] < box.lo[i] || ray.o[i] > box.hi[i]) return false;
      continue;
    }
    const double inv = inverse(i);
    double a = (box.lo[i] - ray.o[i]) * inv, b = (box.hi[i] - ray.o[i]) * inv;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

// [t0, t1] ∩ the parameter range where the ray is inside the box; empty if t0 > t1.
// Inline: every camera and shadow ray of a blob sum clips once (pov:chain at 640x480: 366,000
// calls), and the call took about 21 of its 70 instructions (697.04 -> 689.27 M inline).
inline bool clip_to_box(const Ray& ray, const Box& box, double& t0, double& t1) {
  return clip_to_slabs(ray, box, t0, t1, [&](int i) { return 1 / ray.d[i]; });
}

}  // namespace softtrace
