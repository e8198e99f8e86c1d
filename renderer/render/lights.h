// What a light source brings to a shading point, POV-Ray 3.7's way (docs/math.md, "Lights"):
// its direction and distance, the spot cone and fading, and the fraction of it that shadows let
// through (0 or 1, or an area light's grid of samples, adaptively).
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>

#include "scene/light.h"
#include "trace/embree_scene.h"

namespace softtrace {

struct LightArrival {
  Vec3 to_light;    // unit, from the point towards the light (its centre)
  double distance;  // to the light's centre; +inf for a directional light
  Vec3 light;       // colour * intensity * spot * fading, before shadows
};

// Where sample (i, j) of the area light `l` lies for a point whose point_seed (point_hash.h) is
// `seed`: the grid spans the rectangle's edges (POV-Ray's layout); a jittered sample moves within
// +-half a cell by a hash of the point and the sample.
Vec3 area_sample(const Light& l, uint64_t seed, int i, int j);

// The light `l` (not ambient) at the surface point `p`, whose shadow rays start at `origin`: the
// direction and distance are taken from `origin`, the spot's cone and the fading at `p`. False
// when none of it can arrive (outside a spot's cone, or at the light's very position).
// Inline, as it runs for every light at every shaded point; only a spot's cone and the fading are
// out of line (spot_and_fade_at). Its call cost callgrind 1.25 M instructions of pov:golfball's
// process at 320x240 (two point lights) and 1.06 M of pov:blob1a's.
bool spot_and_fade_at(const Light& l, const Vec3& p, LightArrival& out);
inline bool positional_arrival(const Light& l, const Vec3& p, const Vec3& origin,
                               LightArrival& out) {
  const Vec3 v = l.position - origin;
  out.distance = length(v);
  if (out.distance == 0) return false;
  out.to_light = v / out.distance;
  return !(l.type == Light::Type::Spot || l.fade_power > 0) || spot_and_fade_at(l, p, out);
}
inline bool light_arrival(const Light& l, const Vec3& p, const Vec3& origin, LightArrival& out) {
  if (l.type == Light::Type::Ambient) return false;
  out.light = l.color * l.intensity;
  if (l.type != Light::Type::Directional) return positional_arrival(l, p, origin, out);
  out.to_light = -l.direction;
  out.distance = std::numeric_limits<double>::infinity();
  return true;
}

// The fraction of `l` that reaches `origin` past the scene's objects. Shadow rays keep the
// footprint (cone0, cone) of the ray being shaded; their work is added to `shadow`. Jittered
// area samples depend only on `origin`, so a pixel's result is the same in any tile or thread.
// Once `cancel` (render/cancel.h) is set no more shadow rays are cast; the result is then moot.
// `blobs`: the blob sums' shadow lists of the block of pixels the point is shaded for, one per
// object (EmbreeScene::occluded), or none.
// An area light's share (its grid of samples); light_visibility's for such a light.
double area_visibility(const Light& l, const Vec3& origin, double cone0, double cone,
                       const EmbreeScene& rt, RayWork& shadow, const std::atomic<bool>* cancel);
// Inline: the one shadow ray of a point or directional light is most of a shaded point's calls.
inline double light_visibility(const Light& l, const LightArrival& at, const Vec3& origin,
                               double cone0, double cone, const EmbreeScene& rt, RayWork& shadow,
                               const std::atomic<bool>* cancel = nullptr,
                               const BlobBeam* blobs = nullptr) {
  if (!l.shadows) return 1;
  if (l.has_area) return area_visibility(l, origin, cone0, cone, rt, shadow, cancel);
  TraceCounters work;
  const bool blocked = rt.occluded({origin, at.to_light, cone0, cone}, 0, at.distance, work, blobs);
  shadow.add(work);
  return blocked ? 0 : 1;
}

// The shadow lists of a block of pixels (render/shadow_beams.h): per scene light its lists' slot
// (-1: none), each slot one list per object; and the shaded point with its rays' offset as
// ShadowBeams took them (shade() lifts its shadow rays' origin from these very numbers, so a
// clear list's rays are its block's by construction: BlobBeam::clear). shade() takes them from
// their owner, which builds a block's when its first shadow ray asks (ShadowListsOnDemand).
struct ShadowLists {
  const int* slot;
  const BlobBeam* lists;
  int objects;
  Vec3 p;
  double offset;
  const BlobBeam* of(int light) const {
    return slot[light] < 0 ? nullptr : lists + size_t(slot[light]) * objects;
  }
};

}  // namespace softtrace
