#include "trace/csg_trace.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/ranges.h"
#include "trace/mesh_crossings.h"
#include "trace/primitive_trace.h"
#include "trace/tracer_limits.h"

namespace softtrace {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Spans of one field operand along one ray: past this many the rest of the ray is dropped (and
// counted as a give-up); no scene comes close.
constexpr int kMaxSpans = 256;
}  // namespace

// One operand of the tree: a CSG (its operands), a field (the tracers of its solid and of the
// solid's complement), a shape, or a closed triangle mesh (its solid).
struct CsgNode {
  int face;  // TracedObject::face, reported by hits on its surface
  Box bounds;
  CsgOp op;
  std::optional<Primitive> shape;
  std::vector<CsgNode> operands;
  // A CSG's placement (TracedObject): `to_local` takes its parent's frame to its operands'.
  bool placed;
  Affine to_parent;
  Mat3 to_local;
  // A field's: the tracers of its solid and of the solid's complement.
  std::unique_ptr<ObjectTracer> inside, outside;
  // A mesh's solid: its crossings along a ray.
  std::unique_ptr<MeshSolid> mesh;
  // The frame the object is given in (its enclosing CSGs' placements undone): a point there is
  // from_world.apply(world point). `placed_frame`: not the world's.
  Affine from_world;
  bool placed_frame = false;

  CsgNode(const TracedObject& o, LipschitzMode mode, const Affine& frame = {},
          bool in_placed = false)
      : face(o.face),
        bounds(o.bounds),
        op(o.op),
        shape(o.shape),
        placed(o.placed),
        to_parent(o.to_parent),
        to_local(o.to_local),
        from_world(frame),
        placed_frame(in_placed) {
    if (o.csg()) {
      // Its operands are in its own frame: its placement undone after its parent's.
      const Affine inner =
          o.placed ? compose({o.to_local, o.to_local * (o.to_parent.offset * -1.0)}, frame) : frame;
      operands.reserve(o.operands.size());
      for (const TracedObject& operand : o.operands)
        operands.emplace_back(operand, mode, inner, in_placed || o.placed);
    } else if (o.mesh) {
      mesh = std::make_unique<MeshSolid>(o.mesh);
    } else if (o.field) {
      inside = std::make_unique<ObjectTracer>(*o.field, mode);
      outside = std::make_unique<ObjectTracer>(*o.field, mode, true);
    }
  }
};

namespace {

using Spans = std::vector<CsgSpan>;

// A shape's one span (its solid is convex), within [lo, hi]; an end beyond kMaxPosition is no
// surface (an infinite plane is drawn to there, as on its own).
void shape_spans(const CsgNode& n, const Ray& ray, double lo, double hi, Spans& out) {
  const SolidSpan s = solid_span(*n.shape, ray);
  if (s.empty()) return;
  CsgSpan span{s.t0, s.t1, {&n, false, false, s.n0}, {&n, false, false, s.n1}};
  const auto far = [&](double t) { return !(max_abs(ray.o + ray.d * t) <= kMaxPosition); };
  if (span.t0 < lo || far(span.t0)) span.e0 = {};
  if (span.t1 > hi || far(span.t1)) span.e1 = {};
  span.t0 = std::max(span.t0, lo);
  span.t1 = std::min(span.t1, hi);
  if (span.t0 <= span.t1) out.push_back(span);
}

// A mesh's spans within [lo, hi]: from each entry to the exit after it, found along the whole
// line through its box (the ray may start inside); an end beyond the range is no surface.
void mesh_spans(const CsgNode& n, const Ray& ray, double lo, double hi, Spans& out) {
  thread_local std::vector<MeshCrossing> crossings;
  n.mesh->crossings(ray, crossings);
  for (size_t i = 0; i < crossings.size(); i += 2) {
    const MeshCrossing& in = crossings[i];
    const bool closed = i + 1 < crossings.size();
    const double t1 = closed ? crossings[i + 1].t : kInf;
    if (t1 < lo) continue;
    if (in.t > hi) break;
    CsgSpan span{std::max(in.t, lo), std::min(t1, hi), {&n, false, false, in.normal}, {}};
    if (in.t < lo) span.e0 = {};
    if (closed && t1 <= hi) span.e1 = {&n, false, false, crossings[i + 1].normal};
    out.push_back(span);
  }
}

// A field's spans within [lo, hi] from its successive certified crossings.
void field_spans(const CsgNode& n, const Ray& ray, double lo, double hi, TraceCounters& work,
                 Spans& out) {
  double e0 = -kInf, e1 = kInf;  // where the ray is inside the field's box
  if (!clip_to_box(ray, n.bounds, e0, e1)) return;
  const double end = std::min(hi, e1);
  // Just past a crossing: the tracer places it no nearer than the surface and within
  // kRefine of the footprint past it; as far again is past it for certain.
  const auto past = [&](double t) {
    return t + tracer_limits::kRefine * n.inside->resolution(ray, t);
  };
  double t = lo;
  for (int k = 0; t <= end; ++k) {
    if (k == kMaxSpans) {
      ++work.give_ups;
      return;
    }
    const MarchResult in = n.inside->first_hit(ray, t, end, work);
    if (!in.hit) return;
    CsgSpan span{in.t, end, {&n, in.on_box_face, false, {}}, {}};
    // Inside where the range begins: that is no surface.
    if (k == 0 && in.t <= lo && !in.on_box_face) span.e0 = {};
    const double from = past(in.t);
    const MarchResult x = from <= end ? n.outside->first_hit(ray, from, end, work) : MarchResult{};
    if (x.hit) {
      span.t1 = x.t;
      span.e1 = {&n, false, false, {}};
    } else if (e1 <= hi) {  // leaves through the box's face
      span.e1 = {&n, true, false, {}};
    }
    out.push_back(span);
    if (!x.hit) return;
    t = past(x.t);
  }
}

// The union of two sorted lists of spans.
Spans unite(const Spans& a, const Spans& b) {
  Spans all;
  all.reserve(a.size() + b.size());
  std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(all),
             [](const CsgSpan& x, const CsgSpan& y) { return x.t0 < y.t0; });
  Spans out;
  for (const CsgSpan& s : all) {
    if (!out.empty() && s.t0 <= out.back().t1) {
      if (s.t1 > out.back().t1) {
        out.back().t1 = s.t1;
        out.back().e1 = s.e1;
      }
      continue;
    }
    out.push_back(s);
  }
  return out;
}

// The intersection: where both hold, with the ends of whichever bounds it (a's on a tie: b may
// have been searched over a's range only, its ends there no surface). A span of no length is
// no solid.
Spans intersect(const Spans& a, const Spans& b) {
  Spans out;
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const CsgSpan &x = a[i], &y = b[j];
    CsgSpan s{x.t0, x.t1, x.e0, x.e1};
    if (y.t0 > s.t0) s.t0 = y.t0, s.e0 = y.e0;
    if (y.t1 < s.t1) s.t1 = y.t1, s.e1 = y.e1;
    if (s.t0 < s.t1) out.push_back(s);
    if (x.t1 < y.t1)
      ++i;
    else
      ++j;
  }
  return out;
}

CsgEnd turned(CsgEnd e) {
  e.flip = !e.flip;
  return e;
}

// Where the ray is outside every span, within [lo, hi]: the spans' surfaces face the other way.
Spans complement(const Spans& b, double lo, double hi) {
  Spans out;
  double from = lo;
  CsgEnd from_end;
  for (const CsgSpan& s : b) {
    if (s.t0 > from) out.push_back({from, s.t0, from_end, turned(s.e0)});
    from = std::max(from, s.t1);
    from_end = turned(s.e1);
  }
  if (from < hi) out.push_back({from, hi, from_end, {}});
  return out;
}

Spans node_spans(const CsgNode& n, const Ray& ray, double lo, double hi, TraceCounters& work);

// A CSG's spans from its operands' (`ray` in its operands' frame).
Spans combined_spans(const CsgNode& n, const Ray& ray, double lo, double hi, TraceCounters& work) {
  Spans acc = node_spans(n.operands[0], ray, lo, hi, work);
  for (size_t i = 1; i < n.operands.size(); ++i) {
    const CsgNode& next = n.operands[i];
    switch (n.op) {
      case CsgOp::Union:
      case CsgOp::Merge:
        acc = unite(acc, node_spans(next, ray, lo, hi, work));
        break;
      case CsgOp::Intersection:
      case CsgOp::Difference: {
        // Only where the result so far holds can the next operand change it.
        if (acc.empty()) return acc;
        const double a = acc.front().t0, b = acc.back().t1;
        const Spans other = node_spans(next, ray, a, b, work);
        acc = intersect(acc, n.op == CsgOp::Intersection ? other : complement(other, a, b));
        break;
      }
    }
  }
  return acc;
}

Spans node_spans(const CsgNode& n, const Ray& ray, double lo, double hi, TraceCounters& work) {
  Spans acc;
  if (n.shape) {
    shape_spans(n, ray, lo, hi, acc);
    return acc;
  }
  if (n.mesh) {
    mesh_spans(n, ray, lo, hi, acc);
    return acc;
  }
  if (n.operands.empty()) {
    field_spans(n, ray, lo, hi, work, acc);
    return acc;
  }
  if (!n.placed) return combined_spans(n, ray, lo, hi, work);
  // In the CSG's own frame the ray's direction is to_local d, s times as long: a distance t
  // along the ray there is s t; the footprint's radius scales by s too.
  const Vec3 d = n.to_local * ray.d;
  const double s = length(d);
  const Ray local{n.to_local * (ray.o - n.to_parent.offset), d / s, ray.cone0 * s, ray.cone};
  acc = combined_spans(n, local, lo * s, hi * s, work);
  for (CsgSpan& span : acc) {
    span.t0 = std::max(span.t0 / s, lo);
    span.t1 = std::min(span.t1 / s, hi);
  }
  return acc;
}

}  // namespace

CsgTracer::CsgTracer(const TracedObject& object, LipschitzMode mode)
    : bounds_(object.bounds), root_(std::make_unique<CsgNode>(object, mode)) {}

CsgTracer::~CsgTracer() = default;

std::vector<CsgSpan> CsgTracer::spans(const Ray& ray, double tnear, double tfar,
                                      TraceCounters& work) const {
  double b0 = tnear, b1 = tfar;
  if (!clip_to_box(ray, bounds_, b0, b1)) return {};
  work.entered_box = true;
  // The operands search [tnear, tfar], not the CSG's box: a face on the box (a field clipped by
  // its bounds, a box shape) must not be cut off by rounding.
  return node_spans(*root_, ray, tnear, tfar, work);
}

CsgHit CsgTracer::first_hit(const Ray& ray, double tnear, double tfar, TraceCounters& work) const {
  const auto hit_at = [&](double t, const CsgEnd& e) {
    const CsgNode& leaf = *e.leaf;
    // The point and the normal in the leaf's frame; a normal is a covector: it comes back to the
    // world through the transpose of the map from the world to that frame.
    const Vec3 world = ray.o + ray.d * t;
    const Vec3 p = leaf.placed_frame ? leaf.from_world.apply(world) : world;
    Vec3 n = !leaf.inside ? e.normal  // a shape's or a mesh's
             : e.on_box   ? leaf.inside->box_face_normal(p)
                          : leaf.inside->normal(p);
    if (leaf.placed_frame) {
      n = leaf.from_world.linear.transposed_times(n);
      if (max_abs(n) > 0) n = unit(n);
    }
    return CsgHit{true, t, e.flip ? -n : n, leaf.face, p};
  };
  for (const CsgSpan& s : spans(ray, tnear, tfar, work)) {
    if (s.e0.leaf && s.t0 >= tnear) return hit_at(s.t0, s.e0);
    if (s.e1.leaf && s.t1 <= tfar) return hit_at(s.t1, s.e1);
  }
  return {};
}

}  // namespace softtrace
