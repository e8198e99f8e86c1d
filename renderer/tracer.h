// Finding the first point of an object's solid along a ray: interval-guided sphere tracing.
// Pure fieldlib maths, no Embree: the Embree adapter only calls in here.
//
// The object's field is compiled once to a flat program (fieldlib/program.h). The ray is cut
// into stretches; one bounds pass over the box around a stretch gives its value interval, its
// Lipschitz bound and the program pruned to that box, which every point of the stretch then
// evaluates. A stretch whose interval shows the solid cannot be reached is skipped whole. Otherwise
// the tracer steps by |f - iso| / L with L the Lipschitz bound over that stretch's box, which can
// never step over the surface; where no finite bound exists the stretch is halved until it is short
// enough to decide by sign. A sign change is then refined by bisection.
#pragma once

#include "eval.h"
#include "scene.h"

namespace softtrace {

enum class LipschitzMode { Local, Global };

struct Ray {
  Vec3 o, d;  // d has unit length, so t is a distance
};

// The work one ray costs one object or the whole scene, counted as it is done. `steps` (the AOV
// and the ray limit) is their sum: point and box evaluations.
struct TraceCounters {
  int point_evals = 0;        // field values at a point (refinement's included)
  int box_evals = 0;          // bounds or pruning passes over a box around a stretch of the ray
  int refine_iterations = 0;  // bisection steps after a sign change (each one point evaluation)
  bool entered_box = false;  // the ray met some object's box (no work is spent on one that did not)
  int evaluations() const { return point_evals + box_evals; }
};

// TraceCounters summed over many rays of one kind (primary or shadow), for `softtrace bench`.
struct RayWork {
  long long rays = 0, entered_box = 0, point_evals = 0, box_evals = 0, refine_iterations = 0;
  void add(const TraceCounters& c) {
    ++rays;
    entered_box += c.entered_box;
    point_evals += c.point_evals;
    box_evals += c.box_evals;
    refine_iterations += c.refine_iterations;
  }
  RayWork& operator+=(const RayWork& o) {
    rays += o.rays;
    entered_box += o.entered_box;
    point_evals += o.point_evals;
    box_evals += o.box_evals;
    refine_iterations += o.refine_iterations;
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
};

class ObjectTracer {
 public:
  ObjectTracer(const SceneObject& object, LipschitzMode mode);

  // The first t in [tnear, tfar] where the ray is inside the solid, if any. The work is added to
  // `work`, which may already hold the ray's work on other objects: the ray's limit is on the sum.
  MarchResult first_hit(const Ray& ray, double tnear, double tfar, TraceCounters& work) const;

  const SceneObject& object() const { return *object_; }
  // The outward unit normal at p (from the gradient; the inside sign decides the orientation).
  Vec3 normal(const Vec3& p) const;
  // The outward normal of the object box's face nearest to p (for hits on_box_face).
  Vec3 box_face_normal(const Vec3& p) const;
  // Whether p is inside the solid.
  bool inside(const Vec3& p) const { return g(p) >= 0; }
  // f(p) and ∇f(p), evaluated on the program pruned to p.
  double eval(const Vec3& p, Vec3* grad) const;

  const Program& program() const { return program_; }

 private:
  // g = inside_sign (f - iso): the solid is g >= 0.
  double g(const Vec3& p) const;       // anywhere (prunes to p first)
  double g_view(const Vec3& p) const;  // inside the box of the last bounds/prune pass
  double bisect(const Ray& ray, double a, double b, TraceCounters& work) const;

  const SceneObject* object_;
  Program program_;
  LipschitzMode mode_;
  double global_L_;
  double min_step_;  // shortest step and stretch: 1e-5 of the object's box diagonal
};

// Every object's tracer, built once per scene. The Embree adapter (embree_scene.h) and the shading
// (shading.h) both use them and neither owns them, so shading never goes through Embree.
class SceneTracers {
 public:
  SceneTracers(const Scene& scene, LipschitzMode mode);
  const ObjectTracer& operator[](int object) const { return tracers_[object]; }
  int size() const { return static_cast<int>(tracers_.size()); }

 private:
  std::vector<ObjectTracer> tracers_;
};

// [t0, t1] ∩ the parameter range where the ray is inside the box; empty if t0 > t1.
bool clip_to_box(const Ray& ray, const Box& box, double& t0, double& t1);

}  // namespace softtrace
