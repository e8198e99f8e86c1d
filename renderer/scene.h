// A loaded scene (SCENE.md): camera, image settings, lights and objects whose fields are built
// by fieldlib's registry. Loading validates everything; rendering never sees bad input.
#pragma once

#include <string>
#include <vector>

#include "node.h"
#include "registry.h"

namespace softtrace {

struct Camera {
  Vec3 eye, target, up{0, 0, 1};
  double fov = 30;  // vertical, degrees
};

struct ImageSettings {
  int width = 640, height = 480, spp = 1;
};

struct Light {
  enum class Type { Directional, Point, Ambient };
  Type type = Type::Directional;
  Vec3 direction;  // directional: the direction light travels
  Vec3 position;   // point
  Vec3 color{1, 1, 1};
  double intensity = 1;
  bool shadows = true;
};

struct SceneObject {
  std::string name;
  Vec3 color{0.8, 0.8, 0.8};
  Convention convention = Convention::Soft;
  double iso = 0.5;
  // +1 where inside means f >= iso (soft), -1 where it means f <= iso (zero, constructive).
  double inside_sign = 1;
  Box bounds;  // where the renderer looks for the surface: "bounds" or the field's region box
  NodePtr field;
};

struct Scene {
  std::string path;
  Camera camera;
  ImageSettings image;
  Vec3 background{0, 0, 0};
  std::vector<Light> lights;
  std::vector<SceneObject> objects;

  Box bounds() const;  // union of the objects' boxes
};

// Throws SceneError with "file:line:col: ..." for syntax and "file: /pointer: ..." for meaning.
Scene load_scene(const std::string& path);
Scene parse_scene(const std::string& text, const std::string& name);

}  // namespace softtrace
