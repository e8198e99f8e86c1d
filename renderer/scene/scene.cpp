#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_set>
#include <vector>

#include "io/file_read.h"
#include "scene/csg_load.h"
#include "scene/image_load.h"
#include "scene/json_text.h"
#include "scene/mesh_load.h"
#include "scene/placement.h"
#include "scene/primitive_load.h"
#include "scene/ranges.h"
#include "scene/scene_keys.h"

namespace softtrace {

namespace {

using json = nlohmann::json;

// Every light and object costs work at every shaded point or ray; beyond these a scene is
// hostile rather than ambitious.
constexpr size_t kMaxLights = 1000;
constexpr size_t kMaxObjects = 10000;

Camera load_camera(const Params& p) {
  p.check_keys(scene_keys("camera"));
  Camera c;
  const std::string projection = p.string("projection", "perspective");
  if (projection == "orthographic")
    c.projection = Camera::Projection::Orthographic;
  else if (projection != "perspective")
    p.fail("projection",
           "unknown projection '" + projection + "' (expected perspective or orthographic)");
  c.eye = p.vec3("eye");
  c.target = p.vec3("target");
  c.up = p.vec3("up", c.up);
  c.fov = p.number("fov", c.fov);
  c.aspect = p.positive("aspect", c.aspect);
  c.aperture = p.number("aperture", c.aperture);
  c.focal_distance = p.number("focal_distance", c.focal_distance);
  c.blur_samples = p.integer("blur_samples", 1, 4096, c.blur_samples);
  const CameraProblem problem = camera_problem(c);
  if (!problem.key.empty()) p.fail(problem.key, problem.message);
  normalize_up(c);
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
    t.check(max_abs(a.axis) > 0, "axis", "expected a non-zero, finite axis");
    a.axis = unit(a.axis);  // [3e-162, 4e-162, 0] is [0.6, 0.8, 0]: its squares would underflow
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
  s.max_trace_level = p.integer("max_trace_level", 1, 256, s.max_trace_level);
  if (p.has("antialias")) s.antialias = load_antialias(p.object("antialias"));
  if (p.has("ambient_occlusion")) s.occlusion = load_occlusion(p.object("ambient_occlusion"));
  p.finish();
  return s;
}

Vec3 load_color(const Params& p, const std::string& key, const Vec3& fallback) {
  const Vec3 c = p.vec3(key, fallback);
  for (int i = 0; i < 3; ++i)
    p.check(c[i] >= 0, key + "/" + std::to_string(i), "expected a colour component >= 0");
  return c;
}

Convention load_convention(const Params& p) {
  const std::string c = p.string("convention", "soft");
  if (c == "soft") return Convention::Soft;
  if (c == "zero") return Convention::Zero;
  if (c == "constructive") return Convention::Constructive;
  p.fail("convention", "unknown convention '" + c + "' (expected soft, zero or constructive)");
}

// Whether any material of `o` (its own, its components', its operands') lets light through.
bool see_through(const SceneObject& o) {
  if (transparent(o.material)) return true;
  if (o.components)
    for (const Material& m : o.components->materials())
      if (transparent(m)) return true;
  if (o.csg)
    for (const SceneObject& operand : o.csg->operands)
      if (see_through(operand)) return true;
  return false;
}

// `inherited`: the material of the nearest enclosing CSG object that has one (null: none).
SceneObject load_object(const Params& p, size_t index, const Material* inherited = nullptr) {
  p.check_keys(scene_keys("object"));
  SceneObject o;
  o.name = p.string("name", "object" + std::to_string(index));
  const bool has_material = p.has("material");
  if (has_material)
    o.material = load_material(p.object("material"));
  else if (inherited)
    o.material = *inherited;
  if (p.has("mesh")) {
    for (const char* key : {"field", "shape", "csg", "convention", "iso", "bounds"})
      if (p.has(key)) p.fail(key, std::string("an object with a 'mesh' has no '") + key + "'");
    o.mesh = load_mesh(p, load_placement(p));
    o.bounds = o.mesh->world_box;
    p.finish();
    return o;
  }
  if (p.has("csg")) {
    for (const char* key : {"field", "shape", "convention", "iso", "bounds"})
      if (p.has(key))
        p.fail(key, std::string("an object with 'csg' has no '") + key + "' (its operands have)");
    load_csg(p, o, has_material ? &o.material : inherited, load_object);
    p.finish();
    return o;
  }
  if (p.has("operands")) p.fail("operands", "'operands' belong to an object with 'csg'");
  for (const char* key : {"scale", "rotate", "translate", "matrix"})
    if (p.has(key))
      p.fail(key, std::string("'") + key +
                      "' places a mesh or a CSG object (a shape's placement is in its 'shape', a "
                      "field's in its nodes)");
  if (p.has("shape")) {
    for (const char* key : {"field", "convention", "iso", "bounds"})
      if (p.has(key))
        p.fail(key,
               std::string("an object with a 'shape' has no '") + key + "' (that is a field's)");
    o.shape = load_primitive(p.object("shape"));
    o.bounds = o.shape->world_box;
    p.finish();
    return o;
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
  o.field = build_object_field(p.object("field"), ctx, o.material, &o.components);

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
    // Nothing is drawn outside the field's own region: a box of +-1e9 around a 30-unit object
    // once changed the picture (+-1e12 filled the frame, +-1e20 emptied it), the tracer's steps
    // and Embree's float culling working at the box's scale. Only cuts inside the region stay.
    const Box region = o.field->region(o.iso, o.inside_sign > 0 ? Side::Above : Side::Below);
    if (region.bounded()) {
      const Box inside = o.bounds.intersected(region);
      if (!inside.empty()) o.bounds = inside;
    }
  } else {
    o.bounds = o.field->region(o.iso, o.inside_sign > 0 ? Side::Above : Side::Below);
    if (!o.bounds.bounded())
      p.fail("field",
             "the field has no finite support box at this iso level; give the object 'bounds'");
  }
  if (!(std::max(max_abs(o.bounds.lo), max_abs(o.bounds.hi)) <= kMaxPosition))
    p.fail(p.has("bounds") ? "bounds" : "field",
           std::string("expected the object's box (bounds, or the field's own region) ") +
               kPositionRule + " (shading rays start there)");
  p.finish();
  return o;
}

// Shading divides by the distance from a shaded point to each point light: it must not overflow
// anywhere in the objects' boxes (distance is convex, so checking the corners suffices).
void check_point_light_distances(const Scene& s, const std::vector<Params>& lights) {
  const Box box = s.bounds();
  for (size_t i = 0; i < lights.size(); ++i) {
    if (s.lights[i].type != Light::Type::Point && s.lights[i].type != Light::Type::Spot) continue;
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

namespace {

Scene parse_scene_text(std::shared_ptr<const std::string> text_ptr, const std::string& name) {
  const std::string& text = *text_ptr;
  // Emptied from its leaves up (release_json) when the last owner lets go: the scene, or this
  // function on an error's way out.
  const std::shared_ptr<json> document(new json(parse_json_text(text, name)), [](json* d) {
    release_json(*d);
    delete d;
  });
  const json& doc = *document;
  const auto file = std::make_shared<const std::string>(name);
  const Params root(doc, "", file);
  root.check_keys(scene_keys("top level"));

  Scene s;
  s.path = name;
  s.text = std::move(text_ptr);
  s.document = document;
  const bool has_camera = root.has("camera");
  if (has_camera) s.camera = load_camera(root.object("camera"));
  if (root.has("animation")) s.animation = load_animation(root.object("animation"));
  if (root.has("image")) s.image = load_image(root.object("image"));
  if (root.has("background") && root.get("background").is_object())
    s.sky = load_sky_gradient(root.object("background"));
  else
    s.background = load_color(root, "background", s.background);
  std::vector<Params> lights;
  if (root.has("lights")) {
    lights = root.objects("lights");
    if (lights.size() > kMaxLights)
      root.fail("lights", "expected at most " + std::to_string(kMaxLights) + " lights");
    for (const Params& l : lights) s.lights.push_back(load_light(l));
  } else {
    s.default_lights = true;  // set once the camera is known
  }
  const std::vector<Params> objects = root.objects("objects");
  if (objects.empty()) root.fail("objects", "expected at least one object");
  if (objects.size() > kMaxObjects)
    root.fail("objects", "expected at most " + std::to_string(kMaxObjects) + " objects");
  std::unordered_set<std::string> names;
  for (size_t i = 0; i < objects.size(); ++i) {
    s.objects.push_back(load_object(objects[i], i));
    s.transparent = s.transparent || see_through(s.objects[i]);
    if (!names.insert(s.objects[i].name).second)
      objects[i].fail("name", "duplicate object name '" + s.objects[i].name + "'");
  }
  if (!has_camera) {
    Box framed;
    for (const SceneObject& o : s.objects)
      if (const std::optional<Box> b = framing_box(o)) framed = framed.united(*b);
    if (framed.empty())
      root.fail("camera", "expected a camera: there is nothing but infinite planes to frame");
    s.camera = camera_framing(framed, double(s.image.width) / s.image.height);
    s.default_camera = true;
  }
  if (s.default_lights) s.lights = default_lights(s.camera);
  check_point_light_distances(s, lights);
  root.finish();
  return s;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name) {
  return parse_scene_text(std::make_shared<const std::string>(text), name);
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
    // degrees * F / N, reduced modulo 360 before it is multiplied (1e308 * 2 overflowed to inf and
    // made the camera NaN): fmod is exact, so (d mod 360N) * F is d * F modulo 360N to rounding.
    const double turn = 360.0 * a.frames;
    const double angle = std::fmod(std::fmod(a.degrees, turn) * frame, turn) / a.frames;
    const Mat3 r = Mat3::rotation(a.axis, angle);
    Camera& c = scene.camera;
    c.eye = c.target + r * (c.eye - c.target);
    c.up = r * c.up;
    if (!(max_abs(c.eye) <= kMaxPosition))
      throw SceneError(scene.path + ": /animation/turntable: frame " + std::to_string(frame) +
                       " puts the eye beyond 1e12 of the origin (rays start there)");
  }
  if (scene.default_lights) scene.lights = default_lights(scene.camera);
}

void override_camera(Scene& scene, const CameraOverride& o) {
  Camera c = scene.camera;
  if (o.eye) c.eye = *o.eye;
  if (o.target) c.target = *o.target;
  if (o.fov) c.fov = *o.fov;
  const CameraProblem problem = camera_problem(c);
  if (!problem.key.empty()) {
    // The camera's other keys were valid: what made them wrong is the view the options moved.
    const std::string option =
        problem.key == "eye" || problem.key == "target" || problem.key == "fov" ? problem.key
        : o.eye                                                                 ? "eye"
        : o.target                                                              ? "target"
                                                                                : "fov";
    throw std::invalid_argument("--" + option + ": " + problem.message);
  }
  scene.camera = c;
  if (scene.default_lights) scene.lights = default_lights(scene.camera);
}

uint64_t Scene::file_hash() const {
  return text ? fnv1a(*text) : 0;
}

uint64_t fnv1a(const std::string& bytes, uint64_t hash) {
  for (const unsigned char b : bytes) hash = (hash ^ b) * 0x100000001b3ULL;
  return hash;
}

void check_pixel_count(const ImageSettings& image, const std::string& name) {
  if (static_cast<long long>(image.width) * image.height > (1LL << 26))
    throw SceneError(name + ": /image: more than 2^26 pixels requested");
}

Scene load_scene(const std::string& path) {
  // A NUL byte ends the read at its block: the parser then names its LINE:COL.
  std::string text;
  try {
    text = read_file_bounded(path, kMaxSceneBytes, "scene", AtNul::Stop);
  } catch (const FileReadError& e) {
    throw SceneError(e.what());
  }
  return parse_scene_text(std::make_shared<const std::string>(std::move(text)), path);
}

}  // namespace softtrace
