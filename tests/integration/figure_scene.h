// A figure scene for the claim tests (test_fig*_catalogue.cpp): the scene file as the renderer
// loads it, and the nodes inside its objects built again from the same file's JSON, so that a
// claim about a primitive inside a blend is checked on exactly what the scene says.
#pragma once

#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "describe/params.h"
#include "scene/scene.h"

namespace softtrace::figure {

inline std::string scene_path(const std::string& name) {
  return std::string(SOFTTRACE_SOURCE_DIR) + "/scenes/" + name + ".json";
}

// The scene's JSON (comments allowed), to reach the primitives inside an object's blend.
inline nlohmann::json scene_json(const std::string& name) {
  std::ifstream in(scene_path(name));
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str(), nullptr, true, /*ignore_comments=*/true);
}

// A point written in a scene as [x, y, z].
inline Vec3 vec(const nlohmann::json& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

class FigureScene {
 public:
  explicit FigureScene(const std::string& name)
      : scene_(load_scene(scene_path(name))),
        file_(std::make_shared<const std::string>(name)),
        json_(scene_json(name)) {}
  const Scene& scene() const { return scene_; }
  const nlohmann::json& json() const { return json_; }
  const SceneObject& object(const std::string& name) const {
    for (const SceneObject& o : scene_.objects)
      if (o.name == name) return o;
    throw std::runtime_error("no object " + name + " in " + *file_);
  }
  // The JSON at a pointer, e.g. "/objects/1/field/children/0".
  const nlohmann::json& at(const std::string& pointer) const {
    return json_.at(nlohmann::json::json_pointer(pointer));
  }
  // The node at a pointer, built in the given object's convention.
  NodePtr node(const std::string& pointer, Convention convention) const {
    BuildContext ctx;
    ctx.convention = convention;
    return build_field(Params(at(pointer), pointer, file_), ctx);
  }

 private:
  Scene scene_;
  std::shared_ptr<const std::string> file_;
  nlohmann::json json_;
};

// Uniform points in the box [lo, hi], fixed seed.
inline std::vector<Vec3> samples(const Vec3& lo, const Vec3& hi, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> out(n);
  for (Vec3& p : out)
    p = {lo.x + (hi.x - lo.x) * u(rng), lo.y + (hi.y - lo.y) * u(rng),
         lo.z + (hi.z - lo.z) * u(rng)};
  return out;
}

// Where g changes sign on the segment a→b (g(a) and g(b) of opposite signs), by bisection.
template <class G>
Vec3 sign_change(const G& g, Vec3 a, Vec3 b) {
  const bool a_negative = g(a) < 0;
  for (int i = 0; i < 200 && length(b - a) > 1e-14 * (1 + length(a)); ++i) {
    const Vec3 m = (a + b) * 0.5;
    ((g(m) < 0) == a_negative ? a : b) = m;
  }
  return (a + b) * 0.5;
}

// The first sign change of g along from + dir * t, t in (0, t_max], found by `steps` samples and
// then bisected; t_max when there is none.
template <class G>
double first_crossing(const G& g, const Vec3& from, const Vec3& dir, double t_max, int steps) {
  const bool start_negative = g(from) < 0;
  for (int i = 1; i <= steps; ++i) {
    const double t = t_max * i / steps;
    if ((g(from + dir * t) < 0) != start_negative) {
      const Vec3 p = sign_change(g, from + dir * (t_max * (i - 1) / steps), from + dir * t);
      return length(p - from);
    }
  }
  return t_max;
}

}  // namespace softtrace::figure
