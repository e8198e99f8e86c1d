// The only code that sees Embree (with embree_device.h, which turns its errors into ours): one
// user geometry per scene object, whose bounds callback returns the object's box and whose
// intersect/occluded callbacks call the object's tracer, a primitive's exact intersection or a
// CSG's tracer (Mitsuba's thin adapter; the objects never see Embree); a triangle mesh is
// Embree's own triangle geometry.
#pragma once

#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "scene/primitive.h"
#include "scene/ranges.h"
#include "trace/interiors.h"
#include "trace/tracer.h"

namespace softtrace {

struct UnmetRays;  // unmet_rays.h

struct TraceHit {
  // User-provided, so that a TraceHit made for each ray is filled field by field: the implicit
  // constructor was folded into a clear of all 112 bytes then the non-zero fields, which GCC
  // expands as `rep stos` (38 % of EmbreeScene::intersect's own cycles, for 14 quadwords).
  TraceHit() {}
  bool hit = false;
  double t = std::numeric_limits<double>::infinity();
  int object = -1;           // index into Scene::objects
  bool on_box_face = false;  // see MarchResult
  Vec3 normal{0, 0, 0};      // a primitive's, a CSG's or a mesh's unit normal (fields: not set)
  // A CSG's hit: the face (TracedObject::face) of the operand whose surface it is (its material
  // is the face's); otherwise -1.
  int face = -1;
  Vec3 face_point{0, 0, 0};  // a CSG's hit: the point in the face's own frame (CsgHit)
  TraceCounters work;        // what the ray cost, over every object it met
  // A blob sum's hit by a camera ray of a beam with a list (BlobBeam::from the ray's origin):
  // the list, which holds every blob whose support holds the hit (its normal's blobs); else null.
  const BlobBeam* blobs = nullptr;
};

// What a beam certified for the rays through its block of pixels: per object, the forward depth
// before which they meet no solid (ObjectTracer::clear_depth).
struct BeamClear {
  Vec3 forward;                     // the camera's, unit length
  const double* depth;              // one per object
  const BlobBeam* blobs = nullptr;  // one per object, or none: the blob sums' lists
  // Whether the beam certifies that none of its rays meets the blob sum (EmbreeScene::unmet):
  // its rays from the eye are then traced by EmbreeScene::intersect_unmet.
  bool unmet = false;
  // Otherwise whether its list of the blob sum is short, of balls alone (EmbreeScene::passable):
  // its rays are then traced by EmbreeScene::intersect_passing first.
  bool passable = false;
  // How far along a ray of the beam its points are surely within kMaxPosition (reach_from), so
  // that the floor's test skips the point's max_abs there (unplaced_plane_end); -1: no bound.
  double reach = -1;
  // The floor's unplaced_plane_gap from the beam's eye, where the caller took it once for its
  // rays (every one from that eye: a pinhole camera's), else NaN: the floor's test on each ray
  // then takes it itself (unplaced_plane_end_within).
  double floor_gap = std::numeric_limits<double>::quiet_NaN();

  // reach for rays from `eye` whose directions have unit length (a pinhole camera's, normalised):
  // with M = max_abs(eye) and |t| <= kMaxPosition / 2 - M, each component of o + d * t as rounded
  // is at most (M + (1 + 1e-15) |t| (1 + 2^-53)) (1 + 2^-53) < kMaxPosition (|d_i| <= 1 but
  // for the normalisation's few ulps).
  static double reach_from(const Vec3& eye) {
    const double m = max_abs(eye);
    return m <= kMaxPosition / 4 ? kMaxPosition / 2 - m : -1;  // NaN or too far: none
  }
};

// An error Embree reported (embree_device.h), in Embree's words: out of memory while building
// the scene, for one. The command line reports it as one line and exits with status 2.
class EmbreeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class EmbreeScene {
 public:
  // The tracers must outlive this object. Throws EmbreeError if Embree fails to build the scene.
  // `interiors`: whether a ray may start inside an object's solid (intersect's `inside`; only a
  // scene with a transparent material has such rays). Without them, a scene of one field and at
  // most a few primitives is traced by the direct paths alone and gets no Embree device or scene
  // (their construction was about 0.7 ms of CPU, a tenth of a small render's process); it must
  // then never be asked with `inside`.
  explicit EmbreeScene(const SceneTracers& tracers, bool interiors = true);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Closest hit along the ray in [tnear, tfar]; thread-safe. Throws EmbreeError if Embree
  // reported an error while tracing it (so no ray passes for one Embree could not trace). `beam`,
  // if given, holds for this ray: each object's search starts where it certified. `inside`: the
  // objects whose solids the ray starts in (a refracted or shadow ray through transparent
  // objects: interiors.h); a field object's hit is then where the ray leaves it (its solid's
  // complement's first point, or its box's face, on_box_face); CSGs and primitives find their
  // exits from inside on their own.
  TraceHit intersect(const Ray& ray, double tnear, double tfar, const BeamClear* beam,
                     const Interiors& inside) const {
    return nearest(ray, tnear, tfar, beam, inside.empty() ? nullptr : &inside);
  }
  // The same for a ray inside at most one object's solid, `inside` (-1: none). Inline, a camera
  // ray's call goes straight to nearest(): the wrapper's guarded static and extra call were some
  // 30 instructions a ray.
  TraceHit intersect(const Ray& ray, double tnear, double tfar, const BeamClear* beam = nullptr,
                     int inside = -1) const {
    if (inside < 0) return nearest(ray, tnear, tfar, beam, nullptr);
    Interiors in;
    in.push(inside, 1);
    return nearest(ray, tnear, tfar, beam, &in);
  }
  // Whether anything lies along the ray in [tnear, tfar]; thread-safe. The ray's work is added to
  // `work`. Throws EmbreeError as intersect() does. `blobs`, if given, one per object: the blob
  // sums' shadow lists of a block of rays (ObjectTracer::shadow_beam); a list holding no such ray
  // is ignored.
  bool occluded(const Ray& ray, double tnear, double tfar, TraceCounters& work,
                const BlobBeam* blobs = nullptr) const;

  // Whether no camera ray of `beam` from its lists' eye meets the blob sum: the scene is one blob
  // sum, alone or with a few primitives (the direct paths without Embree's walk), and the beam's
  // list of it holds no blob (no blob's support meets the beam's frustum, ObjectTracer::blob_beam).
  bool unmet(const BeamClear& beam) const;
  // intersect(ray, 0, inf, &beam) for a camera ray of a beam that is unmet(), into `hit`: the
  // primitives' nearest hit, if any, tested as intersect() tests them, and the sum's miss before
  // it with the same counters (ObjectTracer::first_hit with the empty list), without the sum's
  // search. False, `hit` then to be overwritten, for a ray intersect() must answer: one the list
  // does not hold (another origin, or not forward) or one at the ray limit. (Filled in place: a
  // TraceHit returned by value was copied, 25 instructions of a background ray's 200.)
  bool intersect_unmet(const Ray& ray, const BeamClear& beam, TraceHit& hit) const;
  // Whether `beam` takes unmet()'s direct paths, its list of the blob sum holding a few balls
  // (BlobBeam::passing): most of a sparse cloud's met blocks, most of whose rays pass between
  // the balls' surfaces (meets1 at 640x480: of the met blocks' 84,336 rays, 77,328 are passable
  // beams', and 59,972 of these pass).
  bool passable(const BeamClear& beam) const;
  // intersect_unmet for a camera ray of a passable() beam that passes far enough from every ball
  // of its list (ObjectTracer::passes_listed_balls): the sum's search would read no piece on its
  // way, so its answer and counters are the empty list's. False, `hit` then to be overwritten,
  // where that is not certain, and where intersect_unmet is false.
  bool intersect_passing(const Ray& ray, const BeamClear& beam, TraceHit& hit) const;
  // For a beam that is unmet() or passable() in a scene of its blob sum alone (no primitive: every
  // answer is no hit), whose list holds rays from `eye`: its rays' answers, as intersect_unmet and
  // intersect_passing give them, with what they share taken once (unmet_rays.h). False, `out`
  // then meaningless, for any other beam.
  bool unmet_rays(const BeamClear& beam, const Vec3& eye, UnmetRays* out) const;

  // Whether Embree's device and scene were built (false: every ray takes a direct path).
  bool built() const;

  // The direct paths' floor: the scene's one primitive, an unplaced plane, beside its one field
  // (plane null: none). occluded() tests the plane first, then the field; where the ray's list of
  // the field is clear (BlobBeam::clear) the field's answer is no, and the plane's test alone
  // (unplaced_plane_end over [tnear, tfar]) is occluded()'s answer, with no work counted.
  struct Floor {
    const Primitive* plane = nullptr;
    int object = -1, field = -1;
  };
  Floor floor() const;

 private:
  // intersect() with `inside` null where the ray starts inside no solid (never an empty list).
  TraceHit nearest(const Ray& ray, double tnear, double tfar, const BeamClear* beam,
                   const Interiors* inside) const;
  // The beam's valid list of the direct paths' field where that field is a blob sum (what
  // unmet() and passable() ask of), else null.
  const BlobBeam* direct_blob_list(const BeamClear& beam) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace softtrace
