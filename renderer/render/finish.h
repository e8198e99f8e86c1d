// POV-Ray 3.7's finish terms at one surface point for one light (docs/math.md, "Finishes"). The
// light's colour comes in already scaled by its intensity, spot, fading and shadow fraction.
#pragma once

#include "scene/material.h"

namespace softtrace {

// Component-wise product (colours).
inline Vec3 mul(const Vec3& a, const Vec3& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}

// The diffuse light that `light` brings, before the pigment's colour multiplies it:
// light * diffuse * cos^brilliance, cos = n . to_light (> 0).
Vec3 diffuse_light(const Material& m, double cosine, const Vec3& light);

// The phong and specular highlights that `light` adds (not multiplied by the pigment; metallic
// tints them). `n` faces the viewer, `d` is the viewing ray's direction, `to_light` unit.
Vec3 highlights(const Material& m, const Vec3& n, const Vec3& d, const Vec3& to_light,
                const Vec3& light);

}  // namespace softtrace
