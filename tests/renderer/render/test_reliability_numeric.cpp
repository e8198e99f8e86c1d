// Numeric robustness: random valid scenes built from every node kind, with edge-case parameters
// (exponents 0.1 and 50, tiny and huge radii, Blanc s = 0, zero-length segments), evaluated at
// random points and at the awkward ones (origin, axes, skeleton ends, placement centres) and
// rendered small. No value, gradient, interval, pixel or AOV may be NaN; pixels, alpha, normals
// and steps must be finite and depth finite wherever something was hit.
//
// The generators form one table keyed by node type; a new kind adds one entry, and the test
// fails until it does (every kind in node_kinds() must have a generator and be generated).
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <random>
#include <set>

#include "render/frame.h"

namespace softtrace {
namespace {

using json = nlohmann::json;
using Rng = std::mt19937_64;

double uniform(Rng& r, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(r);
}
int integer(Rng& r, int lo, int hi) {
  return std::uniform_int_distribution<int>(lo, hi)(r);
}
template <class T>
T pick(Rng& r, std::initializer_list<T> v) {
  return *(v.begin() + integer(r, 0, int(v.size()) - 1));
}
// Half the time an edge value, otherwise a typical one.
double exponent(Rng& r) {
  return integer(r, 0, 1) ? pick(r, {0.1, 0.5, 1.0, 2.0, 20.0, 50.0}) : uniform(r, 0.3, 8);
}
double radius(Rng& r) {
  return integer(r, 0, 3) ? uniform(r, 0.5, 4) : pick(r, {1e-6, 1e-3, 1e3, 1e6});
}
json vec(double x, double y, double z) {
  return json::array({x, y, z});
}
json point(Rng& r) {
  return integer(r, 0, 3) ? vec(uniform(r, -2, 2), uniform(r, -2, 2), uniform(r, -2, 2))
                          : pick(r, {vec(0, 0, 0), vec(1, 0, 0), vec(0, 0, -1)});
}
json unit(Rng& r) {
  for (;;) {
    const double x = uniform(r, -1, 1), y = uniform(r, -1, 1), z = uniform(r, -1, 1);
    const double l = std::sqrt(x * x + y * y + z * z);
    if (l > 0.1 && l <= 1) return vec(x / l, y / l, z / l);
  }
}
json radii3(Rng& r) {
  return json::array({radius(r), radius(r), radius(r)});
}
json sides6(Rng& r) {
  json t = json::array();
  for (int i = 0; i < 6; ++i) t.push_back(uniform(r, 1.05, 4));
  return t;
}

// Which conventions a kind may be used in, and how to make one.
struct Gen;
using Make = std::function<json(Rng&, const Gen&, Convention, int depth)>;
struct Kind {
  std::set<Convention> conventions;
  Make make;
};

constexpr Convention S = Convention::Soft, Z = Convention::Zero, C = Convention::Constructive;

struct Gen {
  std::map<std::string, Kind> kinds;
  mutable std::set<std::string> used;

  // A random node valid in convention `conv`; leaves (plain distances) once `depth` runs out.
  json node(Rng& r, Convention conv, int depth) const {
    std::vector<std::string> options;
    for (const auto& [name, k] : kinds)
      if (k.conventions.count(conv) && (depth > 0 || is_leaf(name, conv))) options.push_back(name);
    const std::string name = options[integer(r, 0, int(options.size()) - 1)];
    used.insert(name);
    json j = kinds.at(name).make(r, *this, conv, depth - 1);
    j["type"] = name;
    if (integer(r, 0, 3) == 0) j["translate"] = point(r);
    if (integer(r, 0, 3) == 0) j["rotate"] = {{"axis", unit(r)}, {"deg", uniform(r, -180, 180)}};
    return j;
  }
  // A distance for soft_object, offset and radius modulations: built in the enclosing object's
  // convention, so only the convention-free distance kinds.
  json distance(Rng& r, int) const { return node(r, C, 0); }
  json children(Rng& r, Convention conv, int depth, int k) const {
    json c = json::array();
    for (int i = 0; i < k; ++i) c.push_back(node(r, conv, depth));
    return c;
  }
  bool is_leaf(const std::string& name, Convention conv) const {
    return conv == C ? kinds.at(name).conventions == std::set<Convention>{C}
                     : name == (conv == S ? "soft_object" : "offset");
  }
};

json potential(Rng& r) {
  switch (integer(r, 0, 3)) {
    case 0:
      return {{"type", "blanc"}, {"s", 0}};
    case 1:
      return {{"type", "blanc"}, {"s", pick(r, {0.0, 0.2, 1.0, 10.0})}};
    case 2:
      return {{"type", "wyvill"}};
    default:
      return {{"type", "murakami"}};
  }
}

// The distance `d` with every length multiplied by k: its value divided by k (every distance kind
// is homogeneous in its lengths), so the same skeleton on the required side (002 §4.1 (c)).
json scaled(json d, double k) {
  for (const char* key : {"radii", "radius", "a", "half_height"}) {
    if (!d.contains(key)) continue;
    if (d[key].is_array())
      for (auto& x : d[key]) x = x.get<double>() * k;
    else
      d[key] = d[key].get<double>() * k;
  }
  if (d.contains("children"))
    for (auto& c : d["children"]) c = scaled(c, k);
  return d;
}

json radius_transform(Rng& r, const json& d) {
  switch (integer(r, 0, 6)) {
    case 0: {
      const double w2 = uniform(r, 0.05, 1), w1 = uniform(r, w2 / 2, 3);
      return {{"type", "T_n"}, {"w1", w1}, {"w2", w2}};
    }
    case 1:
      return {{"type", "T_l"}, {"w1", pick(r, {0.3, 1.0, 2.5})}};
    case 2:
      return {{"type", "T_r"}, {"w2", uniform(r, 0.05, 1)}};
    case 3:  // f_a = d/k <= d
      return {{"type", pick(r, {"T_an", "T_al"})}, {"modulation", scaled(d, uniform(r, 1, 3))}};
    case 4:  // f_s = d/k >= d
      return {{"type", pick(r, {"T_sn", "T_sr"})}, {"modulation", scaled(d, uniform(r, 0.3, 1))}};
    case 5:  // fc = d/k <= 2d
      return {{"type", "contour"}, {"contour", scaled(d, uniform(r, 0.5, 1.5))}};
    default:
      return nullptr;
  }
}

json bt_params(Rng& r, int k, bool with_m) {
  json j;
  if (k == 2 && integer(r, 0, 1)) {
    const double r1 = uniform(r, 0.05, 1), r2 = uniform(r, 0.05, 1);
    j = {{"base", "conic"}, {"r1", r1}, {"r2", r2}, {"p", uniform(r, -1, 0.9) * r1 * r2}};
    if (integer(r, 0, 2) == 0) j["bulge_elimination"] = {{"omega", uniform(r, 1.2, 3)}};
  } else {
    j = {{"base", "hyperellipsoid"}, {"r", uniform(r, 0.05, 1)}, {"p", uniform(r, 1.2, 4)}};
  }
  if (with_m) j["m"] = uniform(r, 0.3, 3);
  return j;
}

const Gen& generators() {
  static const Gen g = [] {
    Gen g;
    auto& k = g.kinds;
    k["lp_metric"] = {{C}, [](Rng& r, const Gen&, Convention, int) {
                        return json{{"radii", radii3(r)}, {"n", exponent(r)}};
                      }};
    k["superquadric"] = {{C}, [](Rng& r, const Gen&, Convention, int) {
                           json j{{"radii", radii3(r)}, {"n1", exponent(r)}, {"n2", exponent(r)}};
                           if (integer(r, 0, 2) == 0) j["t"] = sides6(r);
                           return j;
                         }};
    k["segment"] = {
        {C}, [](Rng& r, const Gen&, Convention, int) {
          const json p0 = point(r);  // a zero-length segment a quarter of the time
          return json{{"p0", p0}, {"p1", integer(r, 0, 3) ? point(r) : p0}, {"radius", radius(r)}};
        }};
    k["parallel_planes"] = {{C}, [](Rng& r, const Gen&, Convention, int) {
                              return json{{"normal", unit(r)}, {"a", radius(r)}};
                            }};
    k["one_branch_plane"] = k["parallel_planes"];
    k["generalized_distance"] = {{C}, [](Rng& r, const Gen&, Convention, int) {
                                   const int m = integer(r, 1, 5);
                                   json n = json::array(), a = json::array();
                                   for (int i = 0; i < m; ++i)
                                     n.push_back(unit(r)), a.push_back(radius(r));
                                   json j{{"normals", n}, {"a", a}, {"n", exponent(r)}};
                                   if (integer(r, 0, 2) == 0) {
                                     j["t_pos"] = json::array(), j["t_neg"] = json::array();
                                     for (int i = 0; i < m; ++i)
                                       j["t_pos"].push_back(uniform(r, 0.3, 3)),
                                           j["t_neg"].push_back(uniform(r, 0.3, 3));
                                   }
                                   return j;
                                 }};
    k["superelliptic_cylinder"] = {{C}, [](Rng& r, const Gen&, Convention, int) {
                                     json j{{"radii", radii3(r)},
                                            {"n", exponent(r)},
                                            {"half_length", pick(r, {0.0, 1.0, 5.0})}};
                                     if (integer(r, 0, 2) == 0) j["t"] = sides6(r);
                                     return j;
                                   }};
    k["torus"] = {{C}, [](Rng& r, const Gen&, Convention, int) {
                    return json{{"major_radius", pick(r, {0.0, 0.5, 3.0})},
                                {"radii", json::array({radius(r), radius(r)})},
                                {"n", exponent(r)}};
                  }};
    k["polar_prism"] = {{C}, [](Rng& r, const Gen&, Convention, int) {
                          return json{{"radius", radius(r)},
                                      {"lobes", integer(r, 1, 9)},
                                      {"amplitude", pick(r, {0.0, 0.3, 0.99})},
                                      {"profile", pick(r, {"cosine", "triangle"})},
                                      {"half_height", radius(r)},
                                      {"n", exponent(r)}};
                        }};
    const Make sel = [](Rng& r, const Gen& g, Convention, int d) {
      return json{{"n", exponent(r)},
                  {"children", g.children(r, C, std::min(d, 0), integer(r, 2, 3))}};
    };
    k["super_ellipsoidal_union"] = {{C}, sel};
    k["super_ellipsoidal_intersection"] = {{C}, sel};
    k["soft_object"] = {{S}, [](Rng& r, const Gen& g, Convention, int d) {
                          json j{{"distance", g.distance(r, d)}};
                          if (integer(r, 0, 1)) j["potential"] = potential(r);
                          json t = radius_transform(r, j["distance"]);
                          if (!t.is_null()) j["radii"] = t;
                          return j;
                        }};
    const Make kids = [](Rng& r, const Gen& g, Convention c, int d) {
      return json{{"children", g.children(r, c, d, integer(r, 2, 4))}};
    };
    k["soft_blend"] = {{S}, kids};
    for (const char* n : {"perlin_union", "perlin_intersection", "perlin_difference"})
      k[n] = {{S}, kids};
    for (const char* n : {"min", "max"}) k[n] = {{S, Z, C}, kids};
    for (const char* n : {"ricci_union", "ricci_intersection", "ricci_difference"})
      k[n] = {
          {S, C}, [](Rng& r, const Gen& g, Convention c, int d) {
            return json{{"n", exponent(r)}, {"children", g.children(r, c, d, integer(r, 2, 3))}};
          }};
    for (const char* n : {"scale_union", "scale_intersection"})
      k[n] = {{S, C}, [](Rng& r, const Gen& g, Convention c, int d) {
                const double r1 = uniform(r, 0.05, 0.95), r2 = uniform(r, 0.05, 0.95);
                return json{{"r1", r1},
                            {"r2", r2},
                            {"p", uniform(r, -1, 0.9) * r1 * r2},
                            {"children", g.children(r, c, d, 2)}};
              }};
    k["complement"] = {{S, Z, C}, [](Rng& r, const Gen& g, Convention c, int d) {
                         return json{{"children", g.children(r, c, d, 1)}};
                       }};
    k["offset"] = {{Z}, [](Rng& r, const Gen& g, Convention, int d) {
                     return json{{"children", json::array({g.distance(r, d)})},
                                 {"scale", pick(r, {1.0, -1.0, 0.01, 100.0})},
                                 {"level", pick(r, {1.0, 0.0, 0.5})}};
                   }};
    for (const char* n : {"bt_union", "bt_intersection", "bt_difference", "displacement_union"})
      k[n] = {{Z}, [n](Rng& r, const Gen& g, Convention c, int d) {
                const int count = integer(r, 2, 3);
                json j = bt_params(r, count, std::string(n) != "displacement_union");
                j["children"] = g.children(r, c, d, count);
                return j;
              }};
    return g;
  }();
  return g;
}

json random_scene(Rng& r) {
  const Convention conv = pick(r, {S, S, Z, C});
  const char* names[] = {"soft", "zero", "constructive"};
  const double half = pick(r, {1.0, 4.0, 30.0});
  return {{"camera",
           {{"eye", vec(3 * half, -4 * half, 2.5 * half)}, {"target", vec(0, 0, 0)}, {"fov", 35}}},
          {"image", {{"width", 24}, {"height", 16}}},
          {"objects",
           {{{"convention", names[int(conv)]},
             {"bounds", {vec(-half, -half, -half), vec(half, half, half)}},
             {"field", generators().node(r, conv, integer(r, 1, 3))}}}}};
}

std::vector<std::string> node_kind_names() {
  std::vector<std::string> names;
  for (const auto& k : kinds())
    if (k.group == KindGroup::Node) names.push_back(k.name);
  return names;
}

TEST(NumericRobustness, EveryKindHasAGenerator) {
  for (const auto& name : node_kind_names())
    EXPECT_TRUE(generators().kinds.count(name)) << "no generator for node type " << name;
  for (const auto& [name, kind] : generators().kinds)
    EXPECT_TRUE(find_kind(name, KindGroup::Node)) << "generator for an unknown node type " << name;
}

void expect_no_nan(const FieldNode& f, const Vec3& p, const std::string& scene) {
  Vec3 g;
  const double v = f.eval(p, &g);
  ASSERT_FALSE(std::isnan(v) || std::isnan(g.x) || std::isnan(g.y) || std::isnan(g.z))
      << "NaN at (" << p.x << ", " << p.y << ", " << p.z << ") in\n"
      << scene;
}

// Under the sanitizers each scene costs about 4x (the model's interval bounds are mostly pow), and
// what they look for, memory errors and undefined behaviour, the first 40 scenes already reach
// with every kind generated; the plain build checks all 150 for NaN.
#ifdef SOFTTRACE_TESTS_SANITIZED
constexpr int kScenes = 40;
#else
constexpr int kScenes = 150;
#endif

TEST(NumericRobustness, RandomScenesGiveNoNaNInEvalIntervalsPixelsOrAovs) {
  Rng rng(20261125);
  int loaded = 0;
  for (int n = 0; n < kScenes; ++n) {
    const std::string text = random_scene(rng).dump();
    Scene scene;
    try {
      scene = parse_scene(text, "<random>");
    } catch (const SceneError& e) {
      FAIL() << "the generator made an invalid scene: " << e.what() << "\n" << text;
    }
    ++loaded;
    const SceneObject& o = scene.objects[0];
    const Box& b = o.bounds;
    std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0},     {0, 1, 0}, {0, 0, 1}, {0, 0, -1},
                                {2, 0, 0}, {0.5, 0.5, 0}, b.lo,      b.hi};
    for (int i = 0; i < 60; ++i)
      points.push_back({uniform(rng, b.lo.x, b.hi.x), uniform(rng, b.lo.y, b.hi.y),
                        uniform(rng, b.lo.z, b.hi.z)});
    for (const Vec3& p : points) {
      expect_no_nan(*o.field, p, text);
      if (HasFatalFailure()) return;
    }
    for (const Box& box : {b, Box::around({0, 0, 0}, 1e-9), Box::around({1, 0, 0}, 0.25)}) {
      const Interval i = o.field->interval(box);
      ASSERT_FALSE(std::isnan(i.lo) || std::isnan(i.hi)) << text;
      ASSERT_LE(i.lo, i.hi) << text;
      ASSERT_FALSE(std::isnan(o.field->lipschitz(box))) << text;
    }

    const TracedScene rt(scene, LipschitzMode::Local);
    Film film(scene.image.width, scene.image.height);
    ASSERT_TRUE(render_frame(scene, rt, RenderOptions{}, film, nullptr, nullptr));
    for (size_t i = 0; i < size_t(film.width) * film.height; ++i) {
      for (int k = 0; k < 4; ++k) ASSERT_TRUE(std::isfinite(film.rgba[i * 4 + k])) << text;
      for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(film.normal[i * 3 + k])) << text;
      ASSERT_TRUE(std::isfinite(film.steps[i])) << text;
      ASSERT_FALSE(std::isnan(film.depth[i])) << text;
      if (film.rgba[i * 4 + 3] > 0) {
        ASSERT_TRUE(std::isfinite(film.depth[i])) << text;
      }
    }
  }
  EXPECT_EQ(loaded, kScenes);
  for (const auto& name : node_kind_names())
    EXPECT_TRUE(generators().used.count(name)) << name << " was never generated";
}

// Huge finite numbers at the documented bounds (docs/scene-format.md "Numbers"): accepted scenes
// with rotations of 1e308 degrees, coordinates of 1e150 and radii of 1e-150 or 1e150 evaluate
// without NaN in values, gradients, intervals and Lipschitz bounds.
TEST(NumericRobustness, HugeFiniteParametersGiveNoNaN) {
  const std::string ball = R"({"type":"lp_metric","radii":[2,2,2],"n":2})";
  const std::string fields[] = {
      R"({"type":"soft_object","rotate":{"axis":[1,2,3],"deg":1e308},"distance":)" + ball + "}",
      R"({"type":"soft_object","rotate":{"axis":[0,0,1e150],"deg":-1e308},"distance":)" + ball +
          "}",
      R"({"type":"soft_object","distance":{"type":"segment","p0":[0,0,-1e150],"p1":[0,0,1e150],"radius":1}})",
      R"({"type":"soft_object","distance":{"type":"segment","p0":[-1e150,-1e150,-1e150],"p1":[1e150,1e150,1e150],"radius":1e150}})",
      R"({"type":"soft_object","distance":{"type":"segment","p0":[0,0,0],"p1":[0,0,1],"radius":1e-150}})",
      R"({"type":"soft_object","translate":[1e150,-1e150,1e150],"distance":)" + ball + "}",
      R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[1e150,1e-150,1],"n":1e150}})",
  };
  for (const std::string& field : fields) {
    const std::string text =
        R"({"camera":{"eye":[10,0,0],"target":[0,0,0]},"objects":[{"bounds":[[-4,-4,-4],[4,4,4]],"field":)" +
        field + "}]}";
    Scene scene;
    try {
      scene = parse_scene(text, "<huge>");
    } catch (const SceneError& e) {
      ADD_FAILURE() << "refused a scene within the bounds: " << e.what();
      continue;
    }
    const FieldNode& f = *scene.objects[0].field;
    for (const Vec3& p : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0.3, -0.2, 1.5}, Vec3{1e150, 0, 0},
                          Vec3{-1e150, 1e150, 1e150}}) {
      expect_no_nan(f, p, field);
      if (HasFatalFailure()) return;
    }
    for (const Box& box : {Box({-4, -4, -4}, {4, 4, 4}), Box::around({0, 0, 0}, 1e-9),
                           Box::around({1e150, 0, 0}, 1e149)}) {
      const Interval i = f.interval(box);
      EXPECT_FALSE(std::isnan(i.lo) || std::isnan(i.hi)) << field;
      EXPECT_FALSE(std::isnan(f.lipschitz(box))) << field;
    }
  }
}

}  // namespace
}  // namespace softtrace
