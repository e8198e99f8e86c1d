// Reading lights from the scene file; the semantics are POV-Ray 3.7's (docs/math.md, "Lights").
#include <algorithm>
#include <cmath>

#include "scene/light.h"
#include "scene/scene.h"
#include "scene/scene_keys.h"

namespace softtrace {

namespace {

constexpr double kPi = 3.14159265358979323846;

// v / |v| without overflow for any finite non-zero v (scene.cpp's rule for directions).
Vec3 unit(const Vec3& v) {
  return normalize(v / max_abs(v));
}

Vec3 load_color(const Params& p, const std::string& key, const Vec3& fallback) {
  const Vec3 c = p.vec3(key, fallback);
  for (int i = 0; i < 3; ++i)
    p.check(c[i] >= 0, key + "/" + std::to_string(i), "expected a colour component >= 0");
  return c;
}

// Every key some light type has: checked before the type is read, so that a misspelled key is
// named before a missing or unknown type.
std::vector<std::string> any_light_keys() {
  std::vector<std::string> all;
  for (const char* type : {"light: directional", "light: point", "light: spot", "light: ambient"})
    for (const std::string& key : scene_keys(type))
      if (std::find(all.begin(), all.end(), key) == all.end()) all.push_back(key);
  return all;
}

// A sample count per axis: 4096 samples at most, each a shadow ray per shaded point.
constexpr int kMaxAreaSize = 64;

AreaLight load_area(const Params& a) {
  a.check_keys(scene_keys("area light"));
  AreaLight area;
  area.axis1 = a.vec3("axis1");
  area.axis2 = a.vec3("axis2");
  for (const char* key : {"axis1", "axis2"})
    a.check(max_abs(a.vec3(key)) <= 1e12, key, "expected an axis within 1e12 in every coordinate");
  area.size1 = a.integer("size1", 1, kMaxAreaSize);
  area.size2 = a.integer("size2", 1, kMaxAreaSize);
  if (a.has("adaptive")) area.adaptive = a.integer("adaptive", 0, 10);
  area.jitter = a.boolean("jitter", false);
  a.finish();
  return area;
}

// An angle in degrees in [0, 90], as its cosine.
double cos_degrees(const Params& p, const std::string& key, double fallback_cos) {
  if (!p.has(key)) return fallback_cos;
  const double deg = p.number(key);
  p.check(deg >= 0 && deg <= 90, key, "expected an angle in [0, 90] degrees");
  return std::cos(deg * kPi / 180);
}

// fade_distance and fade_power, and the area, which point and spot lights share.
void load_positional(const Params& p, Light& l) {
  l.position = p.vec3("position");
  l.shadows = p.boolean("shadows", true);
  if (p.has("fade_distance") || p.has("fade_power")) {
    l.fade_distance = p.positive("fade_distance");
    l.fade_power = p.number("fade_power", 2);
    p.check(l.fade_power > 0 && l.fade_power <= 100, "fade_power",
            "expected a fade_power in (0, 100]");
  }
  if (p.has("area")) {
    l.has_area = true;
    l.area = load_area(p.object("area"));
  }
}

}  // namespace

Light load_light(const Params& p) {
  static const std::vector<std::string> any_light = any_light_keys();
  p.check_keys(any_light);
  Light l;
  const std::string type = p.string("type");
  if (type == "directional" || type == "point" || type == "spot" || type == "ambient")
    p.check_keys(scene_keys("light: " + type),
                 " for " + std::string(type == "ambient" ? "an " : "a ") + type + " light");
  l.intensity = p.number("intensity", 1.0);
  p.check(l.intensity >= 0, "intensity", "expected an intensity >= 0");
  l.color = load_color(p, "color", l.color);
  if (type == "directional") {
    l.type = Light::Type::Directional;
    l.direction = p.vec3("direction");
    p.check(max_abs(l.direction) > 0, "direction", "expected a non-zero direction");
    l.direction = unit(l.direction);
    l.shadows = p.boolean("shadows", true);
  } else if (type == "point") {
    l.type = Light::Type::Point;
    load_positional(p, l);
  } else if (type == "spot") {
    l.type = Light::Type::Spot;
    load_positional(p, l);
    const Vec3 axis = p.vec3("point_at") - l.position;
    p.check(max_abs(axis) > 0, "point_at", "expected a point_at different from the position");
    l.direction = unit(axis);
    l.cos_radius = cos_degrees(p, "radius", l.cos_radius);
    l.cos_falloff = cos_degrees(p, "falloff", l.cos_falloff);
    p.check(l.cos_falloff <= l.cos_radius, "falloff", "expected a falloff >= the radius");
    l.tightness = p.number("tightness", 0);
    p.check(l.tightness >= 0 && l.tightness <= 1000, "tightness",
            "expected a tightness in [0, 1000]");
  } else if (type == "ambient") {
    l.type = Light::Type::Ambient;
  } else {
    p.fail("type",
           "unknown light type '" + type + "' (expected directional, point, spot or ambient)");
  }
  p.finish();
  return l;
}

std::vector<Light> default_lights(const Camera& c) {
  const Vec3 forward = unit(c.target - c.eye), right = unit(cross(forward, c.up));
  Light key;
  key.direction = unit(forward - right * 0.5 - c.up * 0.5);
  Light ambient;
  ambient.type = Light::Type::Ambient;
  ambient.intensity = 0.15;
  return {key, ambient};
}

}  // namespace softtrace
