#include "scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "json_text.h"
#include "scene/scene_keys.h"

namespace softtrace {

namespace {

using json = nlohmann::json;

// Every light and object costs work at every shaded point or ray; beyond these a scene is
// hostile rather than ambitious.
constexpr size_t kMaxLights = 1000;
constexpr size_t kMaxObjects = 10000;

// Lengths and directions of vectors from the scene without overflow or underflow: a component
// of 1e308 squares to inf, one of 1e-200 to 0. Scaling by the largest component first keeps
// |v| and v / |v| exact to rounding for every finite v.
double scaled_length(const Vec3& v) {
  const double m = max_abs(v);
  return m > 0 ? m * length(v / m) : 0;
}
Vec3 unit(const Vec3& v) {  // v non-zero and finite
  return normalize(v / max_abs(v));
}

// Distances the renderer squares (camera to target, point light to objects) stay within this,
// and above its inverse, so that their squares are normal doubles.
constexpr double kMaxDistance = 1e150;

Camera load_camera(const Params& p) {
  p.check_keys(scene_keys("camera"));
  Camera c;
  c.eye = p.vec3("eye");
  c.target = p.vec3("target");
  const Vec3 up = p.vec3("up", c.up);
  c.fov = p.number("fov", c.fov);
  p.check(c.fov > 0 && c.fov < 180, "fov", "expected a vertical field of view in (0, 180) degrees");
  const Vec3 view = c.target - c.eye;
  p.check(max_abs(view) > 0, "target", "expected a target different from the eye");
  const double distance = scaled_length(view);
  p.check(distance >= 1 / kMaxDistance && distance <= kMaxDistance, "target",
          "expected a target between 1e-150 and 1e150 from the eye");
  p.check(max_abs(up) > 0, "up", "expected a non-zero up vector");
  c.up = unit(up);  // the camera's and the default light's cross products cannot overflow
  p.check(length(cross(unit(view), c.up)) > 1e-9, "up",
          "expected an up vector not parallel to the viewing direction");
  p.finish();
  return c;
}

Animation load_animation(const Params& p) {
  constexpr int kMaxFrames = 1000000;
  p.check_keys(scene_keys("animation"));
  Animation a;
  const bool list = p.has("cameras"), turntable = p.has("turntable");
  if (list == turntable) p.fail("", "expected either 'cameras' (a list) or 'turntable'");
  if (list) {
    const std::vector<Params> cameras = p.objects("cameras");
    p.check(!cameras.empty(), "cameras", "expected at least one camera");
    if (cameras.size() > size_t(kMaxFrames))
      p.fail("cameras", "expected at most " + std::to_string(kMaxFrames) + " cameras");
    for (const Params& c : cameras) a.cameras.push_back(load_camera(c));
    a.frames = static_cast<int>(a.cameras.size());
    if (p.has("frames"))
      p.check(p.integer("frames", 1, kMaxFrames) == a.frames, "frames",
              "expected the number of cameras (" + std::to_string(a.frames) + ")");
  } else {
    a.frames = p.integer("frames", 1, kMaxFrames);
    const Params t = p.object("turntable");
    t.check_keys(scene_keys("turntable"));
    a.axis = t.vec3("axis", a.axis);
    t.check(length(a.axis) > 0 && std::isfinite(length(a.axis)), "axis",
            "expected a non-zero, finite axis");
    a.degrees = t.number("degrees", a.degrees);
    t.check(std::isfinite(a.degrees), "degrees", "expected a finite angle");
    t.finish();
  }
  p.finish();
  return a;
}

ImageSettings load_image(const Params& p) {
  p.check_keys(scene_keys("image"));
  ImageSettings s;
  s.width = p.integer("width", 1, 16384, s.width);
  s.height = p.integer("height", 1, 16384, s.height);
  s.spp = p.integer("spp", 1, 4096, s.spp);
  p.finish();
  return s;
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
  for (const char* type : {"light: directional", "light: point", "light: ambient"})
    for (const std::string& key : scene_keys(type))
      if (std::find(all.begin(), all.end(), key) == all.end()) all.push_back(key);
  return all;
}

Light load_light(const Params& p) {
  static const std::vector<std::string> any_light = any_light_keys();
  p.check_keys(any_light);
  Light l;
  const std::string type = p.string("type");
  if (type == "directional" || type == "point" || type == "ambient")
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
    l.position = p.vec3("position");
    l.shadows = p.boolean("shadows", true);
  } else if (type == "ambient") {
    l.type = Light::Type::Ambient;
  } else {
    p.fail("type", "unknown light type '" + type + "' (expected directional, point or ambient)");
  }
  p.finish();
  return l;
}

// With no "lights" the scene gets a key light from over the camera's shoulder and some ambient.
std::vector<Light> default_lights(const Camera& c) {
  const Vec3 forward = unit(c.target - c.eye), right = unit(cross(forward, c.up));
  Light key;
  key.direction = unit(forward - right * 0.5 - c.up * 0.5);
  Light ambient;
  ambient.type = Light::Type::Ambient;
  ambient.intensity = 0.15;
  return {key, ambient};
}

Convention load_convention(const Params& p) {
  const std::string c = p.string("convention", "soft");
  if (c == "soft") return Convention::Soft;
  if (c == "zero") return Convention::Zero;
  if (c == "constructive") return Convention::Constructive;
  p.fail("convention", "unknown convention '" + c + "' (expected soft, zero or constructive)");
}

SceneObject load_object(const Params& p, size_t index) {
  p.check_keys(scene_keys("object"));
  SceneObject o;
  o.name = p.string("name", "object" + std::to_string(index));
  if (p.has("material")) {
    const Params m = p.object("material");
    m.check_keys(scene_keys("material"));
    o.color = load_color(m, "color", o.color);
    m.finish();
  }
  o.convention = load_convention(p);
  const double default_iso = o.convention == Convention::Soft   ? 0.5
                             : o.convention == Convention::Zero ? 0.0
                                                                : 1.0;
  o.iso = p.number("iso", default_iso);
  o.inside_sign = o.convention == Convention::Soft ? 1 : -1;

  BuildContext ctx;
  ctx.slot = Family::ConventionField;  // the field must be of the object's convention
  ctx.convention = o.convention;
  o.field = build_field(p.object("field"), ctx);

  if (p.has("bounds")) {
    const json& raw = p.get("bounds");
    const auto corner = [&](size_t k) {
      const bool ok = raw.is_array() && raw.size() == 2 && raw[k].is_array() &&
                      raw[k].size() == 3 &&
                      std::all_of(raw[k].begin(), raw[k].end(), [](const json& v) {
                        return v.is_number() && std::isfinite(v.get<double>());
                      });
      if (!ok) p.fail("bounds", "expected [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
      return Vec3{raw[k][0].get<double>(), raw[k][1].get<double>(), raw[k][2].get<double>()};
    };
    const Vec3 lo = corner(0), hi = corner(1);
    for (int i = 0; i < 3; ++i)
      p.check(lo[i] < hi[i], "bounds", "expected each minimum below its maximum");
    o.bounds = Box(lo, hi);
  } else {
    o.bounds = o.field->region(o.iso, o.inside_sign > 0 ? Side::Above : Side::Below);
    if (!o.bounds.bounded())
      p.fail("field",
             "the field has no finite support box at this iso level; give the object 'bounds'");
  }
  p.finish();
  return o;
}

// Shading divides by the distance from a shaded point to each point light: it must not overflow
// anywhere in the objects' boxes (distance is convex, so checking the corners suffices).
void check_point_light_distances(const Scene& s, const std::vector<Params>& lights) {
  const Box box = s.bounds();
  for (size_t i = 0; i < lights.size(); ++i) {
    if (s.lights[i].type != Light::Type::Point) continue;
    for (int corner = 0; corner < 8; ++corner) {
      lights[i].check(scaled_length(box.corner(corner) - s.lights[i].position) <= kMaxDistance,
                      "position",
                      "expected a point light within 1e150 of the objects (one farther away "
                      "is a directional light)");
    }
  }
}

}  // namespace

Box Scene::bounds() const {
  Box b;
  for (const auto& o : objects) b = b.united(o.bounds);
  return b;
}

Scene parse_scene(const std::string& text, const std::string& name) {
  const json doc = parse_json_text(text, name);
  const auto file = std::make_shared<const std::string>(name);
  const Params root(doc, "", file);
  root.check_keys(scene_keys("top level"));

  Scene s;
  s.path = name;
  s.file_hash = fnv1a(text);
  s.camera = load_camera(root.object("camera"));
  if (root.has("animation")) s.animation = load_animation(root.object("animation"));
  if (root.has("image")) s.image = load_image(root.object("image"));
  s.background = load_color(root, "background", s.background);
  std::vector<Params> lights;
  if (root.has("lights")) {
    lights = root.objects("lights");
    if (lights.size() > kMaxLights)
      root.fail("lights", "expected at most " + std::to_string(kMaxLights) + " lights");
    for (const Params& l : lights) s.lights.push_back(load_light(l));
  } else {
    s.lights = default_lights(s.camera);
    s.default_lights = true;
  }
  const std::vector<Params> objects = root.objects("objects");
  if (objects.empty()) root.fail("objects", "expected at least one object");
  if (objects.size() > kMaxObjects)
    root.fail("objects", "expected at most " + std::to_string(kMaxObjects) + " objects");
  std::unordered_set<std::string> names;
  for (size_t i = 0; i < objects.size(); ++i) {
    s.objects.push_back(load_object(objects[i], i));
    if (!names.insert(s.objects[i].name).second)
      objects[i].fail("name", "duplicate object name '" + s.objects[i].name + "'");
  }
  check_point_light_distances(s, lights);
  root.finish();
  return s;
}

void set_frame(Scene& scene, int frame) {
  const Animation& a = scene.animation;
  if (a.frames == 0) throw SceneError(scene.path + ": the scene has no /animation");
  if (frame < 0 || frame >= a.frames)
    throw SceneError(scene.path + ": /animation: there is no frame " + std::to_string(frame) +
                     " (frames 0 to " + std::to_string(a.frames - 1) + ")");
  if (!a.cameras.empty()) {
    scene.camera = a.cameras[frame];
  } else {
    // Rotations keep the angle between the view and `up`, so every frame's camera is valid.
    const Mat3 r = Mat3::rotation(a.axis, a.degrees * frame / a.frames);
    Camera& c = scene.camera;
    c.eye = c.target + r * (c.eye - c.target);
    c.up = r * c.up;
  }
  if (scene.default_lights) scene.lights = default_lights(scene.camera);
}

uint64_t fnv1a(const std::string& bytes, uint64_t hash) {
  for (const unsigned char b : bytes) hash = (hash ^ b) * 0x100000001b3ULL;
  return hash;
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path);
}

}  // namespace softtrace
