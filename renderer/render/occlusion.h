// Ambient occlusion (docs/scene-format.md "ambient_occlusion", docs/math.md "Ambient
// occlusion"): the fraction of the sky over a shaded point that its surroundings leave open,
// which scales what the ambient lights bring there (the "clay render" look).
#pragma once

#include <atomic>

#include "scene/scene.h"
#include "trace/embree_scene.h"

namespace softtrace {

// The fraction of `ao.samples` rays from `origin` over the hemisphere about the unit normal `n`,
// cosine-weighted (stratified in cos^2 of the angle to n, turned by the golden angle), that
// travel `ao.distance` unblocked. The samples are placed by a hash of `origin`, so a pixel's
// result is the same in any tile or thread. The rays keep the footprint (cone0, cone) of the ray
// being shaded; their work is added to `shadow`. Once `cancel` is set no more rays are cast.
double open_sky(const AmbientOcclusion& ao, const Vec3& origin, const Vec3& n, double cone0,
                double cone, const EmbreeScene& rt, RayWork& shadow,
                const std::atomic<bool>* cancel = nullptr);

}  // namespace softtrace
