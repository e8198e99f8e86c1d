#include "tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softtrace {

namespace {
// A ray that needs more evaluations than this is given up as a miss; no test scene comes close.
constexpr int kMaxSteps = 200000;
// Sphere-tracing steps within one stretch before it is cut short at the current point: the
// bound over a long stretch's box can be far looser than over a short one (e.g. a modulated
// radius whose [d]/[f] decorrelates), and finishing the stretch with it would cost b-t divided by
// a tiny step. Every step taken was certified, so stopping early skips nothing.
constexpr int kStretchSteps = 16;
// One workspace per thread, shared by every object's tracer: evaluations do not allocate once it
// has grown to the largest program.
Workspace& workspace(const Program& p) {
  thread_local Workspace ws;
  ws.fit(p);
  return ws;
}
}  // namespace

SceneTracers::SceneTracers(const Scene& scene, LipschitzMode mode) {
  tracers_.reserve(scene.objects.size());
  for (const auto& o : scene.objects) tracers_.emplace_back(o, mode);
}

bool clip_to_box(const Ray& ray, const Box& box, double& t0, double& t1) {
  for (int i = 0; i < 3; ++i) {
    if (ray.d[i] == 0) {
      if (ray.o[i] < box.lo[i] || ray.o[i] > box.hi[i]) return false;
      continue;
    }
    const double inv = 1 / ray.d[i];
    double a = (box.lo[i] - ray.o[i]) * inv, b = (box.hi[i] - ray.o[i]) * inv;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

ObjectTracer::ObjectTracer(const SceneObject& object, LipschitzMode mode)
    : object_(&object), program_(compile(*object.field)), mode_(mode) {
  global_L_ = object.field->lipschitz();
  min_step_ = 1e-5 * object.bounds.diagonal();
}

double ObjectTracer::eval(const Vec3& p, Vec3* grad) const {
  return evaluate(program_, p, grad, workspace(program_));
}

double ObjectTracer::g(const Vec3& p) const {
  return object_->inside_sign * (eval(p, nullptr) - object_->iso);
}

double ObjectTracer::g_view(const Vec3& p) const {
  Workspace& ws = workspace(program_);
  return object_->inside_sign * (value(ws.view, p, ws) - object_->iso);
}

Vec3 ObjectTracer::normal(const Vec3& p) const {
  Vec3 grad;
  eval(p, &grad);
  grad = grad * -object_->inside_sign;
  const double len = length(grad);
  return len > 0 && std::isfinite(len) ? grad / len : Vec3{};
}

Vec3 ObjectTracer::box_face_normal(const Vec3& p) const {
  const Box& b = object_->bounds;
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

double ObjectTracer::bisect(const Ray& ray, double a, double b, TraceCounters& work) const {
  // Invariant: g(a) < 0 <= g(b). Stop far below a pixel's footprint.
  Box box;
  box.extend(ray.o + ray.d * a);
  box.extend(ray.o + ray.d * b);
  ++work.box_evals;
  prune(program_, box, workspace(program_));
  for (int i = 0; i < 60 && b - a > 1e-3 * min_step_; ++i) {
    const double m = 0.5 * (a + b);
    ++work.point_evals;
    ++work.refine_iterations;
    (g_view(ray.o + ray.d * m) >= 0 ? b : a) = m;
  }
  return b;
}

MarchResult ObjectTracer::first_hit(const Ray& ray, double tnear, double tfar,
                                    TraceCounters& work) const {
  double t0 = tnear, t1 = tfar;
  if (!clip_to_box(ray, object_->bounds, t0, t1)) return {};
  work.entered_box = true;
  const auto at = [&](double t) { return ray.o + ray.d * t; };
  const auto stretch_box = [&](double a, double b) {
    Box box;
    box.extend(at(a));
    box.extend(at(b));
    return box;
  };

  double t = t0, h = std::max((t1 - t0) / 8, min_step_);
  ++work.point_evals;
  double gt = g(at(t));
  bool gt_known = true;
  if (gt >= 0) return {true, t, t > tnear};
  // The latest point known to be outside: the left end for bisection. A stretch may end on a
  // step shortened to min_step_ (not certified), so a new stretch can start inside the solid.
  double prev = t;

  while (t < t1 && work.evaluations() < kMaxSteps) {
    const double b = std::min(t + h, t1);
    const Box box = stretch_box(t, b);
    ++work.box_evals;
    // One pass: the interval, the slope bound and the program pruned to the stretch's box, which
    // the points of this stretch evaluate below.
    const BoxBounds bb = bounds(program_, box, workspace(program_));
    const Interval f = bb.value;
    const double ghi = object_->inside_sign > 0 ? f.hi - object_->iso : object_->iso - f.lo;
    if (ghi < 0) {  // the solid cannot be reached anywhere in this stretch
      t = b;
      gt_known = false;
      h *= 2;
      continue;
    }
    const double L = mode_ == LipschitzMode::Global ? global_L_ : bb.lipschitz;
    if (!std::isfinite(L)) {
      if (b - t > min_step_) {  // no slope bound here: decide on shorter stretches
        h = 0.5 * (b - t);
        continue;
      }
      if (!gt_known) {
        ++work.point_evals;
        gt = g_view(at(t));
        if (gt >= 0) return {true, bisect(ray, prev, t, work)};
      }
      prev = t;
      ++work.point_evals;
      const double gb = g_view(at(b));
      if (gb >= 0) return {true, bisect(ray, t, b, work)};
      t = b;
      gt = gb;
      gt_known = true;
      continue;
    }
    // Sphere tracing inside the stretch: from a point with g < 0, g stays negative for at least
    // -g/L along any path inside the box, so a step of that length cannot cross the surface.
    int stretch_steps = 0;
    while (work.evaluations() < kMaxSteps) {
      if (!gt_known) {
        ++work.point_evals;
        gt = g_view(at(t));
        gt_known = true;
      }
      if (gt >= 0) return {true, bisect(ray, prev, t, work)};
      if (++stretch_steps > kStretchSteps)
        break;  // a loose bound: re-bound a shorter stretch from t
      const double step = L > 0 ? std::max(-gt / L, min_step_) : b - t;
      prev = t;
      if (t + step >= b) {
        // The bound certifies the rest of the stretch; at its end, g is not known yet.
        t = b;
        gt_known = false;
        break;
      }
      t += step;
      gt_known = false;
    }
    // Many steps mean a loose bound: shorter stretches give tighter box bounds.
    h = stretch_steps > kStretchSteps ? std::max(0.5 * h, min_step_) : h;
  }
  return {};
}

}  // namespace softtrace
