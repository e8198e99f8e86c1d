// The camera hits on a floor (EmbreeScene::floor: an unplaced plane beside one field), shaded the
// short way (shades_plain) with the terms that are the same at every point of the plane, taken
// once for the frame: its normal facing either side, and for each directional light its cosine
// and diffuse term, for each ambient light its term. A point pays for its shadow rays alone, and
// a shadow ray whose block's list of the field is clear is answered by the plane's test inline,
// as occluded() answers it. shade_plain_hit's colour, normal, albedo and counters to the bit (the
// same operations on the same numbers; floating-point contraction is off in this build). Most of
// the 1000-blob frame's floor is such points: 171,000 of its 307,200 pixels.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "render/shading.h"
#include "render/shadow_beams.h"
#include "trace/primitive_trace.h"

namespace softtrace {

class PlainFloor {
  // The most shadowed lights a lean floor has (lean_colours).
  static constexpr size_t kLean = 3;

 public:
  // None (object() -1) unless the scene has a floor whose material shades_plain.
  PlainFloor(const Scene& scene, const EmbreeScene& rt) : floor_(rt.floor()) {
    if (!floor_.plane) return;
    const SceneObject& obj = scene.objects[size_t(floor_.object)];
    const Vec3 n = floor_.plane->world_normal;
    if (!shades_plain(scene, obj) || dot(n, n) == 0) return;
    m_ = &obj.material;
    normal_[0] = n;  // facing_normal's: the plane's normal, turned to face the viewer
    normal_[1] = -n;
    terms_.reserve(scene.lights.size());
    for (const Light& l : scene.lights) {
      Term t;
      t.light = l.color * l.intensity;  // light_arrival's
      t.shadows = l.shadows;
      if (l.type == Light::Type::Ambient) {
        t.kind = Term::Ambient;
        t.ambient = mul(m_->ambient, t.light);
      } else if (l.type == Light::Type::Directional && !l.has_area) {
        t.kind = Term::Directional;
        t.to_light = -l.direction;
        for (int i = 0; i < 3; ++i) t.inverse[i] = 1 / t.to_light[i];
        for (int side = 0; side < 2; ++side) {
          t.cosine[side] = dot(normal_[side], t.to_light);
          t.diffuse[side] = diffuse_light(*m_, t.cosine[side], t.light);
        }
      }
      terms_.push_back(t);
    }
    object_ = floor_.object;
    lean_colours();
  }

  // The floor's object, or -1.
  int object() const { return object_; }
  // Whether a point's colour is looked up by which of its shadow rays are blocked (lean_colours).
  bool lean() const { return !lean_.empty(); }

  // shade_plain_hit(scene, tracers, rt, ray, hit, material, secondary, cancel, shadow) for a
  // camera hit on object() (no CSG face), with its block's lists.
  [[gnu::always_inline]] Shaded shade(const Scene& scene, const EmbreeScene& rt, const Ray& ray,
                                      const TraceHit& hit, RayWork& secondary,
                                      const std::atomic<bool>* cancel,
                                      ShadowListsOnDemand& shadow) const {
    const Material& m = *m_;
    // facing_normal's test: the hit's normal is the plane's (first_hit's world_normal).
    const int side = dot(normal_[0], ray.d) > 0;
    const Vec3 n = normal_[side];
    const double cone0 = footprint_at(ray, hit);
    const Vec3 lifted = shadow.p() + n * shadow.offset();
    if (lean()) {
      // Only the shadow rays differ from point to point: which of the lights they find blocked
      // picks the colour the loop below would sum (lean_colours).
      unsigned blocked = 0;
      for (size_t j = 0; j < shadowed_.size(); ++j) {
        const size_t li = shadowed_[j];
        if (terms_[li].cosine[side] <= 0) continue;
        if (cancel_requested(cancel)) break;
        if (blocked_towards(terms_[li], li, lifted, cone0, ray, rt, secondary, shadow))
          blocked |= 1u << j;
      }
      return {lean_[size_t(side) << shadowed_.size() | blocked], n, m.color};
    }
    return shade_lights(scene, rt, ray, side, lifted, cone0, secondary, cancel, shadow);
  }

  // What unlisted_colour asks of each shadowed light's ray, taken once for the frame: the rays
  // from the floor's points towards a light share their direction, so clip_to_slabs' tests
  // against the field's box differ from point to point only in the ray's origin, and the
  // plane's test (unplaced_plane_end) in dot(n, o) alone.
  struct UnlistedRays {
    struct Light {
      Vec3 to_light{0, 0, 0};
      bool along[3] = {false, false, false};  // to_light[i] != 0
      double inverse[3] = {0, 0, 0};          // 1 / to_light[i] (Term::inverse)
      // clip_to_slabs' ends of each slab after its swap: where 1 / d[i] > 0 the box's lo then
      // hi, else hi then lo. Rounding keeps order, so on a box whose lo <= hi (lo - o) * inv <=
      // (hi - o) * inv exactly where inv > 0: the swap picks these ends at every point, the
      // same numbers (equal ends: the same either way). Where to_light[i] == 0: lo and hi.
      double near[3] = {0, 0, 0}, far[3] = {0, 0, 0};
      double plane_nd = 0;  // unplaced_plane_end's dot(n, d)

      // !clip_to_slabs(ray from o along to_light, box, 0, +inf): clip_to_box's answer, in its
      // order, without the tests that the frame's direction decides.
      [[gnu::always_inline]] bool enters(const Vec3& o) const {
        double t0 = 0, t1 = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 3; ++i) {
          if (!along[i]) {
            if (o[i] < near[i] || o[i] > far[i]) return false;
            continue;
          }
          t0 = std::max(t0, (near[i] - o[i]) * inverse[i]);
          t1 = std::min(t1, (far[i] - o[i]) * inverse[i]);
        }
        return t0 <= t1;
      }
    };
    Light light[kLean];  // shadowed_'s, in its order
    size_t count = 0;
    unsigned lit[2] = {0, 0};  // per side, bit j: shadowed_[j]'s cosine is not <= 0
  };

  // The frame's UnlistedRays for the field's box `box` (its tracer's, ObjectTracer::box), into
  // `out`; false where the floor is not lean() or the box is empty (lo > hi on an axis: every
  // ray's clip then enters it, and every point takes its records).
  bool unlisted_rays(const Box& box, UnlistedRays& out) const {
    if (!lean()) return false;
    for (int i = 0; i < 3; ++i)
      if (!(box.lo[i] <= box.hi[i])) return false;
    out.count = shadowed_.size();
    for (size_t j = 0; j < shadowed_.size(); ++j) {
      const Term& t = terms_[shadowed_[j]];
      UnlistedRays::Light& l = out.light[j];
      l.to_light = t.to_light;
      for (int i = 0; i < 3; ++i) {
        l.along[i] = t.to_light[i] != 0;
        l.inverse[i] = t.inverse[i];
        const bool ascending = !l.along[i] || t.inverse[i] > 0;
        l.near[i] = ascending ? box.lo[i] : box.hi[i];
        l.far[i] = ascending ? box.hi[i] : box.lo[i];
      }
      l.plane_nd = dot(floor_.plane->normal, t.to_light);
      for (int side = 0; side < 2; ++side)
        if (!(t.cosine[side] <= 0)) out.lit[side] |= 1u << j;
    }
    return true;
  }

  // shade() of a lean() floor's camera hit whose shadow rays, from its point `at` (ShadowBeams'),
  // all miss the field's box (`rays`, unlisted_rays'), with no list: the index of its colour among
  // lean_colours' (lean_shaded(k) is its answer), its rays counted (they evaluate nothing); -1,
  // nothing counted, where one of them enters the box (shade() with its block's lists then
  // answers it). Such a ray's answer and counters are the same with any list or none: occluded()
  // tests the plane first, and the field's first_hit clips the ray to its box before anything else
  // and counts nothing for a ray outside it (a clear list's no is the same no, its ++rays the same
  // ray). So the point needs no list, and the frame writes its pixel as it traces it (frame.cpp,
  // floor_pixel), from the index alone (its table of the colours as the film stores them).
  [[gnu::always_inline]] int unlisted_colour(const Ray& ray, const ShadowBeams::Point& at,
                                             const UnlistedRays& rays, RayWork& secondary,
                                             const std::atomic<bool>* cancel) const {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const int side = dot(normal_[0], ray.d) > 0;  // shade()'s steps, in its order
    const Vec3 lifted = at.p + normal_[side] * at.margin;
    const unsigned lit = rays.lit[side];
    unsigned blocked = 0;
    long long count = 0;
    for (size_t j = 0; j < rays.count; ++j) {
      if (!(lit >> j & 1)) continue;  // shade()'s cosine <= 0
      if (cancel_requested(cancel)) break;
      const UnlistedRays::Light& l = rays.light[j];
      if (l.enters(lifted)) return -1;
      ++count;  // add() of no work
      const Ray towards{lifted, l.to_light};
      if (!std::isnan(unplaced_plane_end(*floor_.plane, towards, l.plane_nd, 0, kInf)))
        blocked |= 1u << j;
    }
    secondary.rays += count;
    return int(size_t(side) << rays.count | blocked);
  }

  // How many colours lean_colours keeps (2 sides times the shadowed lights' blocked sets), and
  // the answer of index k < lean_count(): its colour, the side's normal, the material's colour.
  size_t lean_count() const { return lean_.size(); }
  Shaded lean_shaded(int k) const {
    return {lean_[size_t(k)], normal_[size_t(k) >> shadowed_.size()], m_->color};
  }

 private:
  // A light's terms at every point of the floor, per side the normal faces (0: the plane's own).
  struct Term {
    enum Kind { Ambient, Directional, Other } kind = Other;
    bool shadows = true;
    Vec3 light{0, 0, 0};            // colour * intensity
    Vec3 ambient{0, 0, 0};          // an ambient light's: m.ambient * light
    Vec3 to_light{0, 0, 0};         // a directional light's: -direction
    double inverse[3] = {0, 0, 0};  // 1 / to_light[i]: clip_to_box's, taken once
    double cosine[2] = {0, 0};
    Vec3 diffuse[2];  // diffuse_light(m, cosine, light)
  };

  // shade()'s sum over the lights in their order, at the point lifted to `lifted`. Out of line:
  // inline, its registers cost every hit of the 1000-blob frame without the floor a few
  // instructions in the tile's loop (0.95 M of 1,147 M).
  [[gnu::noinline]] Shaded shade_lights(const Scene& scene, const EmbreeScene& rt, const Ray& ray,
                                        int side, const Vec3& lifted, double cone0,
                                        RayWork& secondary, const std::atomic<bool>* cancel,
                                        ShadowListsOnDemand& shadow) const {
    const Material& m = *m_;
    const Vec3 n = normal_[side];
    Vec3 light{0, 0, 0}, shine{0, 0, 0};
    const bool highlights = m.phong > 0 || m.specular > 0;
    const Term* const terms = terms_.data();
    const size_t count = terms_.size();
    for (size_t li = 0; li < count; ++li) {
      if (cancel_requested(cancel)) break;
      const Term& t = terms[li];
      if (t.kind == Term::Ambient) {
        light += t.ambient;
        continue;
      }
      if (t.kind == Term::Directional) {
        if (t.cosine[side] <= 0) continue;
        if (t.shadows && blocked_towards(t, li, lifted, cone0, ray, rt, secondary, shadow))
          continue;
        light += t.diffuse[side];
        if (t.shadows && highlights) shine += phong_and_specular(m, n, ray.d, t.to_light, t.light);
        continue;
      }
      // Point, spot and area lights: shade_plain's light, at this point.
      add_positional_light(scene.lights[li], m, ray.d, shadow.p(), n, lifted, cone0, ray.cone, rt,
                           secondary, cancel, &shadow, int(li), light, shine);
    }
    Vec3 color = mul(m.color, light);
    if (highlights && (shine.x != 0 || shine.y != 0 || shine.z != 0)) color += shine;
    return {color, n, m.color};
  }

  // Whether directional light li's shadow ray from `lifted` is blocked, its work counted.
  [[gnu::always_inline]] bool blocked_towards(const Term& t, size_t li, const Vec3& lifted,
                                              double cone0, const Ray& ray, const EmbreeScene& rt,
                                              RayWork& secondary,
                                              ShadowListsOnDemand& shadow) const {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const BlobBeam* lists = shadow.of(int(li));
    const Ray towards{lifted, t.to_light, cone0, ray.cone};
    if (lists && lists[floor_.field].clear) {
      // occluded(): the plane's test, then a clear list's no (EmbreeScene::Floor).
      ++secondary.rays;  // add() of no work
      return !std::isnan(unplaced_plane_end(*floor_.plane, towards, 0, kInf));
    }
    TraceCounters work;
    const bool blocked = rt.occluded(towards, 0, kInf, work, lists);
    secondary.add(work);
    return blocked;
  }

  // Where the floor's material has no highlight and its lights are ambient and directional ones
  // (at most kLean of them with shadows), a point's colour is one of a few, known for the frame:
  // per side, per set of shadowed lights whose rays are blocked, shade()'s loop's sum over the
  // lights in their order, the same operations on the same numbers (the same bits). A point then
  // pays for its shadow rays and a look-up (the 1000-blob frame's floor: the loop's dispatch and
  // sums were some 60 instructions of a floor point's 460).
  void lean_colours() {
    const Material& m = *m_;
    if (m.phong > 0 || m.specular > 0) return;
    for (size_t li = 0; li < terms_.size(); ++li) {
      if (terms_[li].kind == Term::Other) return;
      if (terms_[li].kind == Term::Directional && terms_[li].shadows) shadowed_.push_back(li);
    }
    if (shadowed_.size() > kLean) {
      shadowed_.clear();
      return;
    }
    const unsigned sets = 1u << shadowed_.size();
    lean_.resize(2 * sets);
    for (int side = 0; side < 2; ++side)
      for (unsigned blocked = 0; blocked < sets; ++blocked) {
        Vec3 light{0, 0, 0};
        for (size_t li = 0, j = 0; li < terms_.size(); ++li) {
          const Term& t = terms_[li];
          if (t.kind == Term::Ambient) {
            light += t.ambient;
            continue;
          }
          const bool shut = t.shadows && (blocked >> j++ & 1);
          if (t.cosine[side] <= 0 || shut) continue;
          light += t.diffuse[side];
        }
        lean_[size_t(side) * sets + blocked] = mul(m.color, light);
      }
  }

  EmbreeScene::Floor floor_;
  int object_ = -1;
  const Material* m_ = nullptr;
  Vec3 normal_[2];
  std::vector<Term> terms_;
  // lean_colours': the colours per side and blocked set (bit j: shadowed_[j]'s ray), or none.
  std::vector<size_t> shadowed_;
  std::vector<Vec3> lean_;
};

}  // namespace softtrace
