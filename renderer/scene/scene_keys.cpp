#include "scene/scene_keys.h"

#include <stdexcept>

namespace softtrace {

const std::vector<SceneKeyList>& scene_key_lists() {
  static const std::vector<SceneKeyList> lists = {
      {"top level", {"camera", "image", "background", "lights", "objects", "animation"}},
      {"camera",
       {"projection", "eye", "target", "up", "fov", "aspect", "aperture", "focal_distance",
        "blur_samples"}},
      {"image", {"width", "height", "spp", "max_trace_level", "antialias", "ambient_occlusion"}},
      {"antialias", {"threshold", "depth", "gamma"}},
      {"ambient_occlusion", {"samples", "distance"}},
      {"background", {"gradient", "up"}},
      {"light: directional", {"type", "direction", "intensity", "color", "shadows"}},
      {"light: point",
       {"type", "position", "intensity", "color", "shadows", "fade_distance", "fade_power",
        "area"}},
      {"light: spot",
       {"type", "position", "point_at", "radius", "falloff", "tightness", "intensity", "color",
        "shadows", "fade_distance", "fade_power", "area"}},
      {"light: ambient", {"type", "intensity", "color"}},
      {"area light", {"axis1", "axis2", "size1", "size2", "adaptive", "jitter"}},
      {"object",
       {"name", "material", "convention", "iso", "bounds", "field", "shape", "csg", "operands",
        "cutaway_textures", "mesh", "scale", "rotate", "translate", "matrix"}},
      {"material",
       {"color", "ambient", "diffuse", "brilliance", "phong", "phong_size", "specular", "roughness",
        "metallic", "reflection", "fresnel", "reflection_min", "conserve_energy", "filter",
        "transmit", "ior"}},
      {"shape: plane", {"type", "normal", "distance", "scale", "rotate", "translate", "matrix"}},
      {"shape: box", {"type", "corner1", "corner2", "scale", "rotate", "translate", "matrix"}},
      {"shape: sphere", {"type", "center", "radius", "scale", "rotate", "translate", "matrix"}},
      {"shape: cylinder",
       {"type", "base", "cap", "radius", "scale", "rotate", "translate", "matrix"}},
      {"shape: cone",
       {"type", "base", "base_radius", "cap", "cap_radius", "scale", "rotate", "translate",
        "matrix"}},
      {"shape: disc",
       {"type", "center", "normal", "radius", "hole_radius", "scale", "rotate", "translate",
        "matrix"}},
      {"animation", {"frames", "cameras", "turntable"}},
      {"turntable", {"axis", "degrees"}},
  };
  return lists;
}

const std::vector<std::string>& scene_keys(const std::string& name) {
  for (const SceneKeyList& list : scene_key_lists())
    if (list.name == name) return list.keys;
  throw std::logic_error("no scene key list '" + name + "'");
}

}  // namespace softtrace
