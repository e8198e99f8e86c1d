#include "trace/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>

#include "trace/csg_trace.h"
#include "trace/embree_device.h"
#include "trace/mesh_hit.h"
#include "trace/primitive_trace.h"

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
  int inside = -1;  // EmbreeScene::intersect's `inside`
  bool on_box_face = false;
  Vec3 normal{0, 0, 0};
  int face = -1;
  Vec3 face_point{0, 0, 0};
};

struct GeometryData {
  const ObjectTracer* tracer;  // null for a primitive, a CSG or a mesh
  const ObjectTracer* exit;    // the complement's tracer, where `tracer` is set
  const CsgTracer* csg;        // null but for a CSG
  const TracedObject* object_data;
  int object;
};

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

void intersect_callback(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  auto* ctx = reinterpret_cast<RayContext*>(args->context);
  // ctx->t is the closest hit so far, not this geometry's box exit: the tracer clips to its box.
  // The beam's depth along its axis is depth / cos along the ray.
  const double clear_to = ctx->beam ? ctx->beam->depth[data->object] / ctx->beam_cos : 0;
  if (data->object == ctx->inside) {
    exit_callback(args, data, ctx);
    return;
  }
  const BlobBeam* blobs = ctx->beam && ctx->beam->blobs ? &ctx->beam->blobs[data->object] : nullptr;
  const MarchResult m = data->tracer->first_hit(ctx->ray, ctx->tnear, ctx->t, ctx->work,
                                                Query::Nearest, clear_to, blobs);
  if (!m.hit || m.t >= ctx->t) return;
  record_hit(args, ctx, data->object, m.t, m.on_box_face, Vec3{0, 0, 0}, -1);
}

void occluded_callback(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  auto* ctx = reinterpret_cast<RayContext*>(args->context);
  RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
  const BlobBeam* blobs = ctx->shadow_blobs ? &ctx->shadow_blobs[data->object] : nullptr;
  if (data->tracer->first_hit(ctx->ray, ctx->tnear, ctx->t, ctx->work, Query::Any, 0, blobs).hit)
    r->tfar = -INFINITY;
}

void primitive_intersect_callback(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  auto* ctx = reinterpret_cast<RayContext*>(args->context);
  const PrimitiveHit h = first_hit(*data->object_data->shape, ctx->ray, ctx->tnear, ctx->t);
  if (!h.hit || h.t >= ctx->t) return;
  record_hit(args, ctx, data->object, h.t, false, h.normal, -1);
}

void primitive_occluded_callback(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  auto* ctx = reinterpret_cast<RayContext*>(args->context);
  RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
  if (occludes(*data->object_data->shape, ctx->ray, ctx->tnear, ctx->t)) r->tfar = -INFINITY;
}

void csg_intersect_callback(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  auto* ctx = reinterpret_cast<RayContext*>(args->context);
  const CsgHit h = data->csg->first_hit(ctx->ray, ctx->tnear, ctx->t, ctx->work);
  if (!h.hit || h.t >= ctx->t) return;
  record_hit(args, ctx, data->object, h.t, false, h.normal, h.face, h.face_point);
}

// A shadow ray asks the same question as a camera ray: the result's first surface in range.
void csg_occluded_callback(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
  auto* ctx = reinterpret_cast<RayContext*>(args->context);
  RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
  if (data->csg->first_hit(ctx->ray, ctx->tnear, ctx->t, ctx->work).hit) r->tfar = -INFINITY;
}

// A mesh's triangles are Embree's own: it calls this for each hit nearer than the closest so far
// (its distance in the ray's tfar), which is then accepted. Recording it here keeps our context's
// closest hit, which the user geometries search up to, the same as Embree's.
void mesh_filter_callback(const RTCFilterFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;  // rtcIntersect1 only
  const auto* data = static_cast<const GeometryData*>(args->geometryUserPtr);
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
  ~Impl() {
    if (scene) rtcReleaseScene(scene);  // before the device (`device` is destroyed after)
  }
};

EmbreeScene::EmbreeScene(const SceneTracers& tracers) : impl_(std::make_unique<Impl>()) {
  impl_->data.reserve(tracers.size());  // the callbacks hold pointers into it

  EmbreeDevice& device = impl_->device;
  impl_->scene = rtcNewScene(device.get());
  device.check("creating the scene");
  for (int i = 0; i < tracers.size(); ++i) {
    const ObjectTracer* tracer = tracers.tracer(i);
    const CsgTracer* csg = tracers.csg(i);
    impl_->data.push_back({tracer, tracers.exit_tracer(i), csg, &tracers.object(i), i});
    if (const TriangleMesh* mesh = tracers.object(i).mesh.get()) {
      RTCGeometry geom = mesh_geometry(device, *mesh);
      rtcSetGeometryUserData(geom, &impl_->data.back());
      rtcCommitGeometry(geom);
      rtcAttachGeometry(impl_->scene, geom);
      rtcReleaseGeometry(geom);
      device.check("setting up a mesh's geometry");
      continue;
    }
    RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER);
    device.check("creating an object's geometry");
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, &impl_->data.back());
    rtcSetGeometryBoundsFunction(geom, bounds_callback, nullptr);
    rtcSetGeometryIntersectFunction(geom, tracer ? intersect_callback
                                          : csg  ? csg_intersect_callback
                                                 : primitive_intersect_callback);
    rtcSetGeometryOccludedFunction(geom, tracer ? occluded_callback
                                         : csg  ? csg_occluded_callback
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

TraceHit EmbreeScene::intersect(const Ray& ray, double tnear, double tfar, const BeamClear* beam,
                                int inside) const {
  RayContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.ray = ray;
  ctx.inside = inside;
  // A ray of the beam goes forward (cos > 0); anything else gets no help from it.
  if (beam) {
    const double cos = dot(ray.d, beam->forward);
    if (cos > 0) {
      ctx.beam = beam;
      ctx.beam_cos = cos;
    }
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
  }
  return h;
}

bool EmbreeScene::occluded(const Ray& ray, double tnear, double tfar, TraceCounters& work,
                           const BlobBeam* blobs) const {
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
