// The scene's background (docs/scene-format.md, "background"): a plain colour, or a gradient
// from a bottom colour straight down to a top colour straight up, as POV-Ray's
// `sky_sphere { pigment { gradient y color_map { [0 bottom] [1 top] } scale 2 translate -y } }`.
// A gradient depends on nothing but a ray's direction, so any split of the frame into tiles sees
// the same sky.
#pragma once

#include <algorithm>

#include "describe/params.h"
#include "math/vec.h"

namespace softtrace {

struct SkyGradient {
  Vec3 bottom, top;
  Vec3 up{0, 0, 1};  // unit: the direction that sees `top`

  // The colour seen along the direction `d` (non-zero): linear in its elevation,
  // t = (1 + d.up / |d|) / 2, bottom (1 - t) + top t.
  Vec3 seen(const Vec3& d) const {
    const double t = 0.5 + 0.5 * std::clamp(dot(d, up) / length(d), -1.0, 1.0);
    return bottom * (1 - t) + top * t;
  }
};

// The object `p` (the scene's "background" when it is not a colour): {"gradient": [bottom, top],
// "up": [x, y, z]}. Throws SceneError naming the key.
SkyGradient load_sky_gradient(const Params& p);

}  // namespace softtrace
