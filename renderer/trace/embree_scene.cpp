#include "trace/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>

#include "trace/csg_trace.h"
#include "trace/direct_paths.h"
#include "trace/embree_device.h"
#include "trace/mesh_hit.h"
#include "trace/primitive_trace.h"
#include "trace/unmet_rays.h"

namespace softtrace {

namespace {

// Extends Embree's context with what our callbacks report back; Embree passes the pointer to
// the callbacks unchanged, so the context must be the first member.
// The callbacks trace the double-precision ray kept here; Embree's float copy only culls.
struct RayContext {
  RTCIntersectContext rtc;
  Ray ray;
  double tnear = 0;
  double t = std::numeric_limits<double>::infinity();  // tfar, then the closest hit so far
  TraceCounters work;
  const BeamClear* beam = nullptr;
  const BlobBeam* shadow_blobs = nullptr;  // occluded()'s lists, one per object
  double beam_cos = 1;                     // the cosine between the ray and the beam's forward axis
  int object = -1;
  const Interiors* inside = nullptr;  // EmbreeScene::intersect's `inside`, if any
  bool on_box_face = false;
  Vec3 normal{0, 0, 0};
  int face = -1;
  Vec3 face_point{0, 0, 0};
  const BlobBeam* blobs = nullptr;  // TraceHit::blobs
};

struct GeometryData {
  const ObjectTracer* tracer;  // null for a primitive, a CSG or a mesh
  const ObjectTracer* exit;    // the complement's tracer, where `tracer` is set
  const CsgTracer* csg;        // null but for a CSG
  const TracedObject* object_data;
  int object;
  EmbreeDevice* device;  // where a callback's exception goes (guarded)
};

// Runs a callback's body: what it throws (an allocation failure in a tracer's scratch) is caught
// here and recorded on the device, which the call's check() then throws (embree_device.h), and
// the callback returns to Embree normally. Embree would catch it itself, but its frames' handlers
// belong to the shared C++ runtime and softtrace-core unwinds with its own, which aborts.
template <class Body>
void guarded(const GeometryData& data, const Body& body) noexcept {
  try {
    body();
  } catch (...) {
    data.device->fail_in_callback();
  }
}

void bounds_callback(const RTCBoundsFunctionArguments* args) {
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  const Box& b = data->object_data->bounds;
  // Round outward so the float box contains the double one.
  args->bounds_o->lower_x = std::nextafter(static_cast<float>(b.lo.x), -INFINITY);
  args->bounds_o->lower_y = std::nextafter(static_cast<float>(b.lo.y), -INFINITY);
  args->bounds_o->lower_z = std::nextafter(static_cast<float>(b.lo.z), -INFINITY);
  args->bounds_o->upper_x = std::nextafter(static_cast<float>(b.hi.x), INFINITY);
  args->bounds_o->upper_y = std::nextafter(static_cast<float>(b.hi.y), INFINITY);
  args->bounds_o->upper_z = std::nextafter(static_cast<float>(b.hi.z), INFINITY);
}

// Takes a hit nearer than any so far: what shading needs of it, and Embree's ray cut to it. Every
// field is set by every hit, so a nearer hit keeps nothing of a farther one's (Embree calls the
// geometries in its own order, not in depth order). `normal` and `face` are a primitive's or a
// CSG's; a field's normal is computed once, for the closest hit.
void record_hit(const RTCIntersectFunctionNArguments* args, RayContext* ctx, int object, double t,
                bool on_box_face, const Vec3& normal, int face,
                const Vec3& face_point = {0, 0, 0}) {
  ctx->t = t;
  ctx->object = object;
  ctx->on_box_face = on_box_face;
  ctx->normal = normal;
  ctx->face = face;
  ctx->face_point = face_point;
  ctx->blobs = nullptr;
  RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);  // N == 1 for rtcIntersect1
  rh->ray.tfar = static_cast<float>(t);
  rh->hit.geomID = args->geomID;
  rh->hit.primID = args->primID;
  rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rh->hit.u = rh->hit.v = 0;
  rh->hit.Ng_x = rh->hit.Ng_y = rh->hit.Ng_z = 0;
}

// A ray inside a field's solid: its hit is the first point of the complement, or where it leaves
// through the solid's box (a solid its bounds clip), which is a surface too.
void exit_callback(const RTCIntersectFunctionNArguments* args, const GeometryData* data,
                   RayContext* ctx) {
  const MarchResult m = data->exit->first_hit(ctx->ray, ctx->tnear, ctx->t, ctx->work);
  if (m.hit) {
    if (m.t < ctx->t) record_hit(args, ctx, data->object, m.t, false, Vec3{0, 0, 0}, -1);
    return;
  }
  double t0 = ctx->tnear, t1 = ctx->t;
  if (!clip_to_box(ctx->ray, data->object_data->bounds, t0, t1) || t1 >= ctx->t) return;
  record_hit(args, ctx, data->object, t1, true, Vec3{0, 0, 0}, -1);
}

// A field's first hit on `ray` in [tnear, t] (t: the closest hit so far, not this geometry's box
// exit: the tracer clips to its box), with the beam's help where it has one (beam_cos: the cosine
// between the ray and its forward axis), and the blob list its normal may take (TraceHit::blobs).
MarchResult field_hit(const GeometryData& data, const Ray& ray, double tnear, double t,
                      const BeamClear* beam, double beam_cos, TraceCounters& work,
                      const BlobBeam** list) {
  // The beam's depth along its axis is depth / cos along the ray.
  const double clear_to = beam ? beam->depth[data.object] / beam_cos : 0;
  const BlobBeam* blobs = beam && beam->blobs ? &beam->blobs[data.object] : nullptr;
  *list = blobs && blobs->from(ray.o) ? blobs : nullptr;
  return data.tracer->first_hit(ray, tnear, t, work, Query::Nearest, clear_to, blobs);
}

void intersect_callback(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  guarded(*data, [&] {
    auto* ctx = reinterpret_cast<RayContext*>(args->context);
    if (ctx->inside && ctx->inside->contains(data->object)) {
      exit_callback(args, data, ctx);
      return;
    }
    const BlobBeam* list;
    const MarchResult m =
        field_hit(*data, ctx->ray, ctx->tnear, ctx->t, ctx->beam, ctx->beam_cos, ctx->work, &list);
    if (!m.hit || m.t >= ctx->t) return;
    record_hit(args, ctx, data->object, m.t, m.on_box_face, Vec3{0, 0, 0}, -1);
    ctx->blobs = list;
  });
}

void occluded_callback(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  guarded(*data, [&] {
    auto* ctx = reinterpret_cast<RayContext*>(args->context);
    RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
    const BlobBeam* blobs = ctx->shadow_blobs ? &ctx->shadow_blobs[data->object] : nullptr;
    if (data->tracer->first_hit(ctx->ray, ctx->tnear, ctx->t, ctx->work, Query::Any, 0, blobs).hit)
      r->tfar = -INFINITY;
  });
}

void primitive_intersect_callback(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  guarded(*data, [&] {
    auto* ctx = reinterpret_cast<RayContext*>(args->context);
    const PrimitiveHit h = first_hit(*data->object_data->shape, ctx->ray, ctx->tnear, ctx->t);
    if (!h.hit || h.t >= ctx->t) return;
    record_hit(args, ctx, data->object, h.t, false, h.normal, -1);
  });
}

void primitive_occluded_callback(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  guarded(*data, [&] {
    auto* ctx = reinterpret_cast<RayContext*>(args->context);
    RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
    if (occludes(*data->object_data->shape, ctx->ray, ctx->tnear, ctx->t)) r->tfar = -INFINITY;
  });
}

void csg_intersect_callback(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  guarded(*data, [&] {
    auto* ctx = reinterpret_cast<RayContext*>(args->context);
    const CsgHit h = data->csg->first_hit(ctx->ray, ctx->tnear, ctx->t, ctx->work);
    if (!h.hit || h.t >= ctx->t) return;
    record_hit(args, ctx, data->object, h.t, false, h.normal, h.face, h.face_point);
  });
}

// A shadow ray asks the same question as a camera ray: the result's first surface in range.
void csg_occluded_callback(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  guarded(*data, [&] {
    auto* ctx = reinterpret_cast<RayContext*>(args->context);
    RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
    if (data->csg->first_hit(ctx->ray, ctx->tnear, ctx->t, ctx->work).hit) r->tfar = -INFINITY;
  });
}

// A mesh's triangles are Embree's own: it calls this for each hit nearer than the closest so far
// (its distance in the ray's tfar), which is then accepted. Recording it here keeps our context's
// closest hit, which the user geometries search up to, the same as Embree's.
void mesh_filter_callback(const RTCFilterFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;  // rtcIntersect1 only
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  guarded(*data, [&] {
    // Embree hands the context on unchanged: it is the RayContext that intersect() passed.
    auto* ctx = reinterpret_cast<RayContext*>(const_cast<RTCIntersectContext*>(args->context));
    RTCRay* ray = reinterpret_cast<RTCRay*>(args->ray);
    const RTCHit* hit = reinterpret_cast<const RTCHit*>(args->hit);
    const MeshHit h =
        mesh_hit(*data->object_data->mesh, hit->primID, ctx->ray, ray->tfar, hit->u, hit->v);
    ctx->t = h.t;
    ctx->object = data->object;
    ctx->on_box_face = false;
    ctx->normal = h.normal;
    ctx->face = -1;
    ctx->face_point = {0, 0, 0};
    ctx->blobs = nullptr;
  });
}

// The nearest hit of the primitives `which` in [0, h.t], into h (hit, t, object, normal; the rest
// left as it is): intersect()'s direct path's loop, the same tests in the same order, so the same
// hit to the bit (a tie goes to the first). Out of line: inline, its registers cost a lone
// field's unmet rays, which have no primitive, some 30 instructions each.
[[gnu::noinline]] void nearest_primitive(const std::vector<GeometryData>& data,
                                         const std::vector<int>& which, const Ray& ray,
                                         TraceHit& h) {
  for (const int o : which) {
    const PrimitiveHit p = first_hit(*data[size_t(o)].object_data->shape, ray, 0, h.t);
    if (!p.hit || p.t >= h.t) continue;
    h.hit = true;
    h.t = p.t;
    h.object = o;
    h.normal = p.normal;
  }
}

// nearest_primitive for the direct paths' floor (EmbreeScene::Impl::floor: the one primitive, an
// unplaced plane, the object `object`), without the loop and the look-ups that find it:
// first_hit's answer, as the loop takes it. Out of line, as nearest_primitive (inline, its
// registers cost a lone field's unmet rays 4 instructions each): the floor frame's 133,000 unmet
// rays took 83 instructions each in nearest_primitive's own test of a lone plane, 65 here.
[[gnu::noinline]] void nearest_floor(const Primitive& floor, int object, const Ray& ray,
                                     double reach, double gap, TraceHit& h) {
  const double t = unplaced_plane_end_within(floor, ray, 0, h.t, reach, gap);
  if (!(t < h.t)) return;  // NaN: none
  h.hit = true;
  h.t = t;
  h.object = object;
  h.normal = floor.world_normal;
}

// The mesh's triangles as Embree's triangle geometry (copied: Embree pads its buffers).
RTCGeometry mesh_geometry(EmbreeDevice& device, const TriangleMesh& mesh) {
  RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  device.check("creating a mesh's geometry");
  const size_t vertices = mesh.positions.size() / 3, triangles = mesh.triangles();
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
  auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
  if (!v || !t) {
    rtcReleaseGeometry(geom);
    device.check("allocating a mesh's buffers");
    throw EmbreeError("Embree: allocating a mesh's buffers failed");
  }
  std::copy(mesh.positions.begin(), mesh.positions.end(), v);
  std::copy(mesh.indices.begin(), mesh.indices.end(), t);
  rtcSetGeometryIntersectFilterFunction(geom, mesh_filter_callback);
  return geom;
}

}  // namespace

struct EmbreeScene::Impl {
  EmbreeDevice device;
  RTCScene scene = nullptr;
  std::vector<GeometryData> data;
  // The scene is one field (no primitive, CSG or mesh beside it): a camera ray's nearest hit is
  // that field's, asked directly. Embree's walk to its one box, in float, and the callback's
  // round trip were 8 % of a dense blob cloud's frame (1000 blobs, 640x480); the tracer clips the
  // ray to the box in double itself.
  bool lone_field = false;
  // The scene is one field and a few primitives (a blob on a floor): a camera or shadow ray asks
  // each of them directly, the primitives first. Embree's walk and its callbacks' round trips were
  // a third of what a ground plane added to the 1000-blob frame (callgrind: 108 M of the camera
  // rays' instructions, 105 M of the shadow rays', against 2,190 M for the cloud alone), and an
  // unbounded plane's box culls nothing. The field is searched up to the nearest primitive hit,
  // as Embree's walk asks it when it has visited the primitives first; the same pictures to the
  // bit on the scenes with a field and primitives (61 scenes and the floor frame checked).
  std::vector<int> direct_primitives;
  int direct_field = -1;
  // The direct paths' one primitive where it is an unplaced plane (a floor), and its object:
  // every camera and shadow ray of such a frame tests it, and the primitives' loop, its pointer
  // chase to the shape and the shape's kind cost 15 to 30 instructions a ray beside the test
  // (unplaced_plane_end, the same arithmetic: the same answer to the bit).
  const Primitive* floor = nullptr;
  int floor_object = -1;
  // Without Embree (`device` and `scene` null): every ray takes one of the paths above.
  explicit Impl(bool embree) : device(nullptr, embree) {}
  ~Impl() {
    if (scene) rtcReleaseScene(scene);  // before the device (`device` is destroyed after)
  }
};

EmbreeScene::EmbreeScene(const SceneTracers& tracers, bool interiors) {
  // The direct paths (Impl): their rule is direct_paths.h's.
  ObjectKinds kinds;
  int field = -1;
  std::vector<int> primitives;
  for (int i = 0; i < tracers.size(); ++i) {
    const TracedObject& o = tracers.object(i);
    if (tracers.tracer(i) && !o.mesh) {
      ++kinds.fields;
      field = i;
    } else if (o.shape && !o.mesh && !o.csg()) {
      ++kinds.primitives;
      primitives.push_back(i);
    } else {
      ++kinds.others;
    }
  }
  const bool direct = traced_directly(kinds);
  // Embree takes only the rays the direct paths leave: those that start inside a solid.
  impl_ = std::make_unique<Impl>(needs_embree_device(kinds, interiors));
  impl_->lone_field = direct && primitives.empty();
  if (direct) {
    impl_->direct_field = field;
    impl_->direct_primitives = primitives;
    if (primitives.size() == 1 && unplaced_plane(*tracers.object(primitives[0]).shape)) {
      impl_->floor = &*tracers.object(primitives[0]).shape;
      impl_->floor_object = primitives[0];
    }
  }
  impl_->data.reserve(tracers.size());  // the callbacks hold pointers into it
  for (int i = 0; i < tracers.size(); ++i)
    impl_->data.push_back({tracers.tracer(i), tracers.exit_tracer(i), tracers.csg(i),
                           &tracers.object(i), i, &impl_->device});
  if (!impl_->device.get()) return;

  EmbreeDevice& device = impl_->device;
  impl_->scene = rtcNewScene(device.get());
  device.check("creating the scene");
  for (int i = 0; i < tracers.size(); ++i) {
    GeometryData& data = impl_->data[i];
    if (const TriangleMesh* mesh = tracers.object(i).mesh.get()) {
      RTCGeometry geom = mesh_geometry(device, *mesh);
      rtcSetGeometryUserData(geom, &data);
      rtcCommitGeometry(geom);
      rtcAttachGeometry(impl_->scene, geom);
      rtcReleaseGeometry(geom);
      device.check("setting up a mesh's geometry");
      continue;
    }
    RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER);
    device.check("creating an object's geometry");
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, &data);
    rtcSetGeometryBoundsFunction(geom, bounds_callback, nullptr);
    rtcSetGeometryIntersectFunction(geom, data.tracer ? intersect_callback
                                          : data.csg  ? csg_intersect_callback
                                                      : primitive_intersect_callback);
    rtcSetGeometryOccludedFunction(geom, data.tracer ? occluded_callback
                                         : data.csg  ? csg_occluded_callback
                                                     : primitive_occluded_callback);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);  // the scene holds the reference now
    device.check("setting up an object's geometry");
  }
  rtcCommitScene(impl_->scene);
  device.check("building the scene");
}

EmbreeScene::~EmbreeScene() = default;

bool EmbreeScene::built() const {
  return impl_->scene != nullptr;
}

namespace {
RTCRay make_ray(const Ray& ray, double tnear, double tfar) {
  RTCRay r{};
  r.org_x = static_cast<float>(ray.o.x);
  r.org_y = static_cast<float>(ray.o.y);
  r.org_z = static_cast<float>(ray.o.z);
  r.dir_x = static_cast<float>(ray.d.x);
  r.dir_y = static_cast<float>(ray.d.y);
  r.dir_z = static_cast<float>(ray.d.z);
  r.tnear = static_cast<float>(tnear);
  r.tfar = std::isinf(tfar) ? INFINITY : static_cast<float>(tfar);
  r.mask = 0xFFFFFFFF;
  r.flags = 0;
  return r;
}
}  // namespace

TraceHit EmbreeScene::nearest(const Ray& ray, double tnear, double tfar, const BeamClear* beam,
                              const Interiors* inside) const {
  // A ray of the beam goes forward (cos_forward > 0); anything else gets no help from it.
  const double cos_forward = beam ? dot(ray.d, beam->forward) : 0;
  if (!(cos_forward > 0)) beam = nullptr;
  // The paths without Embree build their hit in the caller's (a lambda's one named result): a
  // TraceHit filled here and copied out cost about 15 instructions a camera ray.
  if (impl_->lone_field &&
      !(inside && inside->contains(0))) {  // no Embree, and none of its context to fill
    return [&] {
      TraceHit h;
      const BlobBeam* list;
      const MarchResult m =
          field_hit(impl_->data[0], ray, tnear, tfar, beam, cos_forward, h.work, &list);
      if (m.hit && m.t < tfar) {
        h.hit = true;
        h.t = m.t;
        h.object = 0;
        h.on_box_face = m.on_box_face;
        h.blobs = list;
      }
      return h;
    }();
  }
  if (impl_->direct_field >= 0 && !inside) {
    return [&] {
      TraceHit h;
      double t = tfar;
      const Primitive* floor = impl_->floor;
      bool on_floor = false;  // whether t is the floor's hit, written below unless the field's
      if (floor) {            // first_hit's answer, as the loop takes it
        const double reach = beam ? beam->reach : -1;
        const double gap = beam ? beam->floor_gap : std::numeric_limits<double>::quiet_NaN();
        const double p = unplaced_plane_end_within(*floor, ray, tnear, t, reach, gap);
        on_floor = p < t;  // not NaN
        if (on_floor) t = p;
      } else {
        for (const int o : impl_->direct_primitives) {
          const Primitive& shape = *impl_->data[o].object_data->shape;
          const PrimitiveHit p = first_hit(shape, ray, tnear, t);
          if (!p.hit || p.t >= t) continue;
          t = p.t;
          h.hit = true;
          h.t = p.t;
          h.object = o;
          h.normal = p.normal;
        }
      }
      const BlobBeam* list;
      const MarchResult m = field_hit(impl_->data[impl_->direct_field], ray, tnear, t, beam,
                                      cos_forward, h.work, &list);
      if (m.hit && m.t < t) {
        h.hit = true;
        h.t = m.t;
        h.object = impl_->direct_field;
        h.on_box_face = m.on_box_face;
        h.normal = {0, 0, 0};
        h.blobs = list;
      } else if (on_floor) {
        h.hit = true;
        h.t = t;
        h.object = impl_->floor_object;
        h.normal = floor->world_normal;
      }
      return h;
    }();
  }
  RayContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.ray = ray;
  ctx.inside = inside;
  if (beam) {
    ctx.beam = beam;
    ctx.beam_cos = cos_forward;
  }
  ctx.tnear = tnear;
  ctx.t = tfar;
  RTCRayHit rh{};
  rh.ray = make_ray(ray, tnear, tfar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx.rtc, &rh);
  if (impl_->device.failed()) impl_->device.check("tracing a ray");
  TraceHit h;
  h.work = ctx.work;
  if (ctx.object >= 0) {
    h.hit = true;
    h.t = ctx.t;
    h.object = ctx.object;
    h.on_box_face = ctx.on_box_face;
    h.normal = ctx.normal;
    h.face = ctx.face;
    h.face_point = ctx.face_point;
    h.blobs = ctx.blobs;
  }
  return h;
}

EmbreeScene::Floor EmbreeScene::floor() const {
  if (!impl_->floor) return {};
  return {impl_->floor, impl_->floor_object, impl_->direct_field};
}

const BlobBeam* EmbreeScene::direct_blob_list(const BeamClear& beam) const {
  // The direct paths only: one field, alone or with a few primitives (a cloud over a floor),
  // which intersect() asks for a camera ray (it starts inside no solid).
  const int f = impl_->direct_field;
  if (f < 0 || !beam.blobs) return nullptr;
  const ObjectTracer* tracer = impl_->data[size_t(f)].tracer;
  const BlobBeam& list = beam.blobs[f];
  return tracer && tracer->blob_sum() && list.valid ? &list : nullptr;
}

bool EmbreeScene::unmet(const BeamClear& beam) const {
  const BlobBeam* list = direct_blob_list(beam);
  return list && list->camera() && list->entries.empty();
}

bool EmbreeScene::passable(const BeamClear& beam) const {
  const BlobBeam* list = direct_blob_list(beam);
  return list && list->passing > 0;
}

bool EmbreeScene::intersect_passing(const Ray& ray, const BeamClear& beam, TraceHit& hit) const {
  const int f = impl_->direct_field;
  return impl_->data[size_t(f)].tracer->passes_listed_balls(ray, beam.blobs[f]) &&
         intersect_unmet(ray, beam, hit);
}

bool EmbreeScene::intersect_unmet(const Ray& ray, const BeamClear& beam, TraceHit& hit) const {
  // field_hit's clear_to and list, as intersect() takes them.
  const int f = impl_->direct_field;
  const double cos_forward = dot(ray.d, beam.forward);
  if (!(cos_forward > 0) || !beam.blobs[f].from(ray.o)) return false;
  // The primitives, as intersect()'s direct path asks them; the field is then searched up to
  // the nearest one's hit, as there (to infinity without one: TraceHit's t).
  hit = TraceHit{};
  if (!impl_->direct_primitives.empty()) {  // a lone field's asks no more than that
    if (const Primitive* floor = impl_->floor)
      nearest_floor(*floor, impl_->floor_object, ray, beam.reach, beam.floor_gap, hit);
    else
      nearest_primitive(impl_->data, impl_->direct_primitives, ray, hit);
  }
  // The list holds the ray (from its eye) and no blob (unmet).
  const MarchResult m = impl_->data[size_t(f)].tracer->first_hit_unlisted(
      ray, hit.t, beam.depth[f] / cos_forward, hit.work);
  return !m.hit;  // a hit is the ray limit (give_up): intersect() answers and counts
}

bool EmbreeScene::unmet_rays(const BeamClear& beam, const Vec3& eye, UnmetRays* out) const {
  if ((!beam.unmet && !beam.passable) || !impl_->direct_primitives.empty()) return false;
  const int f = impl_->direct_field;
  const BlobBeam& list = beam.blobs[f];
  if (!list.from(eye)) return false;
  const ObjectTracer* tracer = impl_->data[size_t(f)].tracer;
  const Box& box = tracer->box();
  *out = UnmetRays{};
  out->eye = eye;
  out->forward = beam.forward;
  out->box = box;
  out->lo_from_eye = box.lo - eye;
  out->hi_from_eye = box.hi - eye;
  out->depth = beam.depth[f];
  if (!beam.unmet) {
    out->passes = tracer;
    out->list = &list;
  }
  return true;
}

bool EmbreeScene::occluded(const Ray& ray, double tnear, double tfar, TraceCounters& work,
                           const BlobBeam* blobs) const {
  if (impl_->direct_field >= 0) {  // any object's hit answers: the order changes no answer
    if (const Primitive* floor = impl_->floor) {  // occludes' answer, without the loop
      if (!std::isnan(unplaced_plane_end(*floor, ray, tnear, tfar))) return true;
    } else {
      for (const int o : impl_->direct_primitives)
        if (occludes(*impl_->data[o].object_data->shape, ray, tnear, tfar)) return true;
    }
    const int o = impl_->direct_field;
    const BlobBeam* list = blobs ? &blobs[o] : nullptr;
    if (list && list->clear) return false;  // first_hit's answer, without its call
    const ObjectTracer& tracer = *impl_->data[o].tracer;
    if (!list) return tracer.shadow_hit(ray, tnear, tfar, work).hit;
    return tracer.first_hit(ray, tnear, tfar, work, Query::Any, 0, list).hit;
  }
  RayContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.ray = ray;
  ctx.shadow_blobs = blobs;
  ctx.tnear = tnear;
  ctx.t = tfar;
  RTCRay r = make_ray(ray, tnear, tfar);
  rtcOccluded1(impl_->scene, &ctx.rtc, &r);
  if (impl_->device.failed()) impl_->device.check("tracing a shadow ray");
  work.point_evals += ctx.work.point_evals;
  work.box_evals += ctx.work.box_evals;
  work.refine_iterations += ctx.work.refine_iterations;
  work.give_ups += ctx.work.give_ups;
  work.undecided += ctx.work.undecided;
  work.entered_box = work.entered_box || ctx.work.entered_box;
  return r.tfar < 0;
}

}  // namespace softtrace
