// A scene's light sources (docs/scene-format.md, "light"): POV-Ray 3.7's point, spot and parallel
// (directional) lights with its fading and rectangular area lights, plus ambient light, which
// materials scale by their `ambient` (POV's global ambient_light).
#pragma once

#include <vector>

#include "describe/params.h"
#include "math/vec.h"

namespace softtrace {

struct Camera;

// POV-Ray's area_light: size1 x size2 point lights spread evenly over the rectangle
// position +- axis1 / 2 +- axis2 / 2; they decide shadows only (the light's direction, spot and
// fading are the centre's).
struct AreaLight {
  Vec3 axis1, axis2;
  int size1 = 1, size2 = 1;
  int adaptive = -1;    // -1: every sample; n >= 0: POV's adaptive sampling from level n
  bool jitter = false;  // each sample moved within its cell, the same way for the same point
};

struct Light {
  enum class Type { Directional, Point, Spot, Ambient };
  Type type = Type::Directional;
  Vec3 direction;  // directional: the direction light travels; spot: unit, towards point_at
  Vec3 position;   // point and spot
  Vec3 color{1, 1, 1};
  double intensity = 1;
  bool shadows = true;  // without, no shadows and (as in POV-Ray) no highlights
  // Spot: the cosines of POV's radius (30 degrees) and falloff (45), and its tightness.
  double cos_radius = 0.8660254037844387, cos_falloff = 0.7071067811865476, tightness = 0;
  // POV's fade_distance and fade_power (point and spot); fade_power 0: no fading.
  double fade_distance = 1, fade_power = 0;
  bool has_area = false;
  AreaLight area;
};

// The light at `p` (keys from scene_keys("light: <type>")); SceneError names the key.
Light load_light(const Params& p);

// With no "lights" the scene gets a key light from over the camera's shoulder and some ambient.
std::vector<Light> default_lights(const Camera& c);

}  // namespace softtrace
