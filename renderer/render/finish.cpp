#include "render/finish.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

namespace {

constexpr double kHalfPi = 1.57079632679489661923;

// The colour a highlight takes: the light's, pulled towards the pigment's by `metallic` where
// POV-Ray's empirical Fresnel curve F (1 at grazing light, ~0 head on) is small.
Vec3 highlight_color(const Material& m, const Vec3& n, const Vec3& to_light, const Vec3& light) {
  if (m.metallic <= 0) return light;
  const double x = std::abs(std::acos(std::clamp(dot(n, to_light), -1.0, 1.0))) / kHalfPi;
  const double f = std::clamp(0.014567225 / ((x - 1.12) * (x - 1.12)) - 0.011612903, 0.0, 1.0);
  const double k = m.metallic * (1 - f);
  return mul(light, Vec3{1, 1, 1} + (m.color - Vec3{1, 1, 1}) * k);
}

}  // namespace

Vec3 phong_and_specular(const Material& m, const Vec3& n, const Vec3& d, const Vec3& to_light,
                        const Vec3& light) {
  Vec3 sum{0, 0, 0};
  if (m.phong > 0) {
    // Phong: the mirror direction of the view against the light's.
    const Vec3 mirror = d - n * (2 * dot(d, n));
    const double c = dot(mirror, to_light);
    // POV-Ray drops phong_size >= 60 highlights below cos 0.0008 (pow would underflow).
    if (c > 0 && (m.phong_size < 60 || c > 0.0008))
      sum += highlight_color(m, n, to_light, light) * (m.phong * std::pow(c, m.phong_size));
  }
  if (m.specular > 0) {
    // Blinn: the normal against the half-way vector of the view and the light.
    const Vec3 half = (to_light - d) * 0.5;
    const double len = length(half);
    if (len > 0) {
      const double c = dot(half, n) / len;
      if (c > 0)
        sum += highlight_color(m, n, to_light, light) * (m.specular * std::pow(c, 1 / m.roughness));
    }
  }
  return sum;
}

}  // namespace softtrace
