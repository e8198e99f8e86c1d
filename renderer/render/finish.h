// POV-Ray 3.7's finish terms at one surface point for one light (docs/math.md, "Finishes"). The
// light's colour comes in already scaled by its intensity, spot, fading and shadow fraction.
#pragma once

#include <cmath>

#include "scene/material.h"

namespace softtrace {

// Component-wise product (colours).
inline Vec3 mul(const Vec3& a, const Vec3& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}

// The diffuse light that `light` brings, before the pigment's colour multiplies it:
// light * diffuse * cos^brilliance, cos = n . to_light (> 0). Inline, as highlights() below: both
// run for every light at every shaded point.
inline Vec3 diffuse_light(const Material& m, double cosine, const Vec3& light) {
  // brilliance 1 skips pow, as POV-Ray does: the Lambert scenes keep their bits.
  const double shape = m.brilliance == 1 ? cosine : std::pow(cosine, m.brilliance);
  return light * (m.diffuse * shape);
}

// highlights() where the material has a phong or a specular highlight.
Vec3 phong_and_specular(const Material& m, const Vec3& n, const Vec3& d, const Vec3& to_light,
                        const Vec3& light);

// The phong and specular highlights that `light` adds (not multiplied by the pigment; metallic
// tints them). `n` faces the viewer, `d` is the viewing ray's direction, `to_light` unit.
inline Vec3 highlights(const Material& m, const Vec3& n, const Vec3& d, const Vec3& to_light,
                       const Vec3& light) {
  if (!(m.phong > 0) && !(m.specular > 0)) return {0, 0, 0};  // a matte finish
  return phong_and_specular(m, n, d, to_light, light);
}

}  // namespace softtrace
