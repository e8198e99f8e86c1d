#include "scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "json_nesting.h"

namespace softtrace {

namespace {

using json = nlohmann::json;

// Every light and object costs work at every shaded point or ray; beyond these a scene is
// hostile rather than ambitious.
constexpr size_t kMaxLights = 1000;
constexpr size_t kMaxObjects = 10000;

// nlohmann reports a byte offset; users want line and column.
std::string line_col(const std::string& text, size_t byte) {
  size_t line = 1, col = 1;
  for (size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

Camera load_camera(const Params& p) {
  Camera c;
  c.eye = p.vec3("eye");
  c.target = p.vec3("target");
  c.up = p.vec3("up", c.up);
  c.fov = p.number("fov", c.fov);
  p.check(c.fov > 0 && c.fov < 180, "fov", "expected a vertical field of view in (0, 180) degrees");
  const Vec3 view = c.target - c.eye;
  p.check(length(view) > 0, "target", "expected a target different from the eye");
  p.check(std::isfinite(length(view)), "target",
          "expected a target at a finite distance from the eye");
  p.check(length(c.up) > 0, "up", "expected a non-zero up vector");
  p.check(length(cross(normalize(view), normalize(c.up))) > 1e-9, "up",
          "expected an up vector not parallel to the viewing direction");
  p.finish();
  return c;
}

ImageSettings load_image(const Params& p) {
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

Light load_light(const Params& p) {
  Light l;
  const std::string type = p.string("type");
  l.intensity = p.number("intensity", 1.0);
  p.check(l.intensity >= 0, "intensity", "expected an intensity >= 0");
  l.color = load_color(p, "color", l.color);
  if (type == "directional") {
    l.type = Light::Type::Directional;
    l.direction = p.vec3("direction");
    p.check(length(l.direction) > 0, "direction", "expected a non-zero direction");
    l.direction = normalize(l.direction);
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
  Light key;
  key.direction =
      normalize((c.target - c.eye) +
                normalize(cross(c.target - c.eye, c.up)) * -0.5 * length(c.target - c.eye) -
                c.up * 0.5 * length(c.target - c.eye));
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
  SceneObject o;
  o.name = p.string("name", "object" + std::to_string(index));
  if (p.has("material")) {
    const Params m = p.object("material");
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

}  // namespace

Box Scene::bounds() const {
  Box b;
  for (const auto& o : objects) b = b.united(o.bounds);
  return b;
}

// nlohmann's DOM builder, keeping where a syntax error or an out-of-range number is: its own
// exception for "1e400" carries no position.
class LocatingParser : public nlohmann::detail::json_sax_dom_parser<json> {
 public:
  LocatingParser(json& root, const std::string& text)
      : json_sax_dom_parser(root, false), text_(text) {}

  bool parse_error(std::size_t position, const std::string& token,
                   const nlohmann::detail::exception& ex) {
    const std::string what = ex.what();
    unsigned line = 0, column = 0;
    const size_t at = what.find("at line ");
    if (at != std::string::npos &&
        std::sscanf(what.c_str() + at, "at line %u, column %u", &line, &column) == 2) {
      // Column 0: the offending character is the newline that ended the previous line.
      where = column > 0 ? std::to_string(line) + ":" + std::to_string(column)
                         : line_col(text_, position > 0 ? position - 1 : 0);
      message = what.substr(what.find(": ", at) + 2);
    } else {  // a number token: no escapes, so its length locates its start
      where = line_col(text_, position >= token.size() ? position - token.size() : 0);
      message = ex.id == 406 ? "number out of range: " + token : what;
    }
    return false;
  }

  std::string where, message;  // empty where: no error

 private:
  const std::string& text_;
};

Scene parse_scene(const std::string& text, const std::string& name) {
  check_json_nesting(text, name);
  json doc;
  LocatingParser parser(doc, text);
  json::sax_parse(text, &parser, nlohmann::detail::input_format_t::json, true,
                  /*ignore_comments=*/true);
  if (!parser.where.empty())
    throw SceneError(name + ":" + parser.where + ": invalid JSON: " + parser.message);
  const auto file = std::make_shared<const std::string>(name);
  const Params root(doc, "", file);

  Scene s;
  s.path = name;
  s.camera = load_camera(root.object("camera"));
  if (root.has("image")) s.image = load_image(root.object("image"));
  s.background = load_color(root, "background", s.background);
  if (root.has("lights")) {
    const std::vector<Params> lights = root.objects("lights");
    if (lights.size() > kMaxLights)
      root.fail("lights", "expected at most " + std::to_string(kMaxLights) + " lights");
    for (const Params& l : lights) s.lights.push_back(load_light(l));
  } else {
    s.lights = default_lights(s.camera);
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
  root.finish();
  return s;
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path);
}

}  // namespace softtrace
