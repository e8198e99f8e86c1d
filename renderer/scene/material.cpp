#include "scene/material.h"

#include "scene/scene_keys.h"

namespace softtrace {

namespace {

// A colour given as one number (grey) or [r, g, b], each component in [lo, hi].
Vec3 load_rgb(const Params& m, const std::string& key, const Vec3& fallback, double hi) {
  if (!m.has(key)) return fallback;
  const std::vector<double> v = m.numbers_or_scalar(key, 3);
  for (int i = 0; i < 3; ++i)
    m.check(v[i] >= 0 && v[i] <= hi,
            m.raw().at(key).is_number() ? key : key + "/" + std::to_string(i),
            "expected a value in [0, " + std::to_string(int(hi)) + "]");
  return {v[0], v[1], v[2]};
}

double load_in(const Params& m, const std::string& key, double fallback, double lo, double hi,
               const std::string& rule) {
  const double x = m.number(key, fallback);
  m.check(x >= lo && x <= hi, key, "expected " + rule);
  return x;
}

}  // namespace

Material load_material(const Params& m) {
  m.check_keys(scene_keys("material"));
  Material mat;
  mat.color = m.vec3("color", mat.color);
  for (int i = 0; i < 3; ++i)
    m.check(mat.color[i] >= 0, "color/" + std::to_string(i), "expected a colour component >= 0");
  mat.ambient = load_rgb(m, "ambient", mat.ambient, 1e6);
  mat.diffuse = load_in(m, "diffuse", mat.diffuse, 0, 1e6, "a diffuse amount in [0, 1e6]");
  mat.brilliance = load_in(m, "brilliance", mat.brilliance, 0, 1000, "a brilliance in [0, 1000]");
  mat.phong = load_in(m, "phong", mat.phong, 0, 1e6, "a phong amount in [0, 1e6]");
  mat.phong_size = load_in(m, "phong_size", mat.phong_size, 0, 1e6, "a phong_size in [0, 1e6]");
  mat.specular = load_in(m, "specular", mat.specular, 0, 1e6, "a specular amount in [0, 1e6]");
  if (m.has("roughness")) {
    mat.roughness = m.number("roughness");
    // POV-Ray's exponent is 1 / roughness: 0 would be an infinite exponent.
    m.check(mat.roughness >= 1e-6 && mat.roughness <= 1, "roughness",
            "expected a roughness in [1e-6, 1]");
  }
  mat.metallic = load_in(m, "metallic", mat.metallic, 0, 1, "a metallic amount in [0, 1]");
  mat.reflection = load_rgb(m, "reflection", mat.reflection, 1);
  mat.fresnel = m.boolean("fresnel", mat.fresnel);
  mat.reflection_min = load_rgb(m, "reflection_min", mat.reflection_min, 1);
  // Without fresnel POV-Ray's two reflection values follow another law (its falloff).
  m.check(mat.fresnel || !m.has("reflection_min"), "reflection_min",
          "expected \"fresnel\": true with reflection_min");
  mat.conserve_energy = m.boolean("conserve_energy", mat.conserve_energy);
  mat.filter = load_in(m, "filter", mat.filter, 0, 1, "a filter amount in [0, 1]");
  mat.transmit = load_in(m, "transmit", mat.transmit, 0, 1, "a transmit amount in [0, 1]");
  // POV-Ray adds the two; more than all the light cannot pass.
  m.check(mat.filter + mat.transmit <= 1, m.has("transmit") ? "transmit" : "filter",
          "expected filter + transmit <= 1");
  mat.ior = load_in(m, "ior", mat.ior, 0.01, 100, "an ior in [0.01, 100]");
  m.finish();
  return mat;
}

}  // namespace softtrace
