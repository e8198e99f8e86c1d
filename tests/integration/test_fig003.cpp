// The claims of [003]'s figures, checked numerically on the scene files themselves
// (scenes/fig003_*.json): each test loads a scene with load_scene and evaluates its objects'
// fields; where a claim is about a primitive inside a blend, the primitive is built from the
// same scene file's JSON. Pixels are the regression tests' business; these are the geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "describe/params.h"
#include "figure_scene.h"
#include "kernels/bt_base.h"
#include "scene/scene.h"

namespace softtrace {
namespace {

using json = nlohmann::json;
using Rng = std::mt19937_64;

using figure::scene_json;
using figure::scene_path;

NodePtr build_zero(const json& j) {
  BuildContext ctx;
  ctx.convention = Convention::Zero;
  return build_field(Params(j, "", std::make_shared<const std::string>("<test>")), ctx);
}

const SceneObject& object(const Scene& s, const std::string& name) {
  for (const SceneObject& o : s.objects)
    if (o.name == name) return o;
  throw std::runtime_error("no object " + name);
}

const json& object_json(const json& scene, const std::string& name) {
  for (const json& o : scene["objects"])
    if (o["name"] == name) return o;
  throw std::runtime_error("no object " + name);
}

// An object's field evaluated in the frame of its root node (whose `translate` places it).
struct Local {
  const SceneObject* obj;
  Vec3 t;
  double operator()(const Vec3& p) const { return obj->field->value(p + t); }
};
Local local(const Scene& s, const json& sj, const std::string& name) {
  const json& f = object_json(sj, name)["field"];
  Vec3 t;
  if (f.contains("translate")) t = {f["translate"][0], f["translate"][1], f["translate"][2]};
  return {&object(s, name), t};
}

double uni(Rng& g, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(g);
}
Vec3 random_dir(Rng& g) {
  for (;;) {
    const Vec3 v{uni(g, -1, 1), uni(g, -1, 1), uni(g, -1, 1)};
    if (length(v) > 0.1 && length(v) <= 1) return normalize(v);
  }
}

// A point where f crosses `level` on the segment a→b (f(a) < level < f(b)), by bisection.
template <class F>
Vec3 crossing(const F& f, Vec3 a, Vec3 b, double level = 0) {
  for (int i = 0; i < 200 && length(b - a) > 1e-13; ++i) {
    const Vec3 m = (a + b) * 0.5;
    (f(m) < level ? a : b) = m;
  }
  return (a + b) * 0.5;
}

// Fig. 2(a): the intersection of three slab pairs cuts each edge back by r(1 - 2^(-1/p)):
// on the edge x1 = x2 = 0 of -BT3(-f) only the two faces' terms are active and
// 2((r + h)/r)^p = 1. Near a face centre the blend is inactive and the field is f_i itself.
TEST(Fig003, Fig2aEdgesCutBackByTheCurvature) {
  const Scene s = load_scene(scene_path("fig003_2a_box_curvatures"));
  const json sj = scene_json("fig003_2a_box_curvatures");
  const double r = 1.2, a = 2.5;
  double previous = INFINITY;
  for (const auto& [name, p] : {std::pair{"p_1.2", 1.2}, {"p_2", 2.0}, {"p_6", 6.0}}) {
    const Local f = local(s, sj, name);
    const double edge = f({a, a, 0});
    EXPECT_NEAR(edge, r * (1 - std::pow(2.0, -1 / p)), 1e-9) << name;
    EXPECT_LT(edge, previous) << name << ": a larger p gives a sharper edge";
    previous = edge;
    for (double d : {-0.4, -0.1, 0.2, 0.5}) {
      EXPECT_NEAR(f({a + d, 0.3, -0.2}), d, 1e-12) << name;
      EXPECT_NEAR(f({0.1, -0.2, -a - d}), d, 1e-12) << name;
    }
  }
}

// Fig. 2(b): on the post's surface (f1 = 0) the fillet reaches exactly distance r2 from the bar
// (field < 0 for f2 < r2, = 0 beyond); on the bar's surface it reaches f1 = r1. Outside region
// II the union is min(f1, f2); everywhere it is <= min(f1, f2) ([BT-3]).
TEST(Fig003, Fig2bFilletReachesTheOtherPrimitivesRange) {
  const Scene s = load_scene(scene_path("fig003_2b_cylinder_ranges"));
  const json sj = scene_json("fig003_2b_cylinder_ranges");
  Rng g(2);
  for (const char* name : {"r_0.25_0.25", "r_1_1", "r_0.25_1.5"}) {
    const json& fj = object_json(sj, name)["field"];
    const double r[2] = {fj["r1"], fj["r2"]}, m[2] = {1, 1};
    const NodePtr prim[2] = {build_zero(fj["children"][0]), build_zero(fj["children"][1])};
    const Local f = local(s, sj, name);
    int near_fillet[2] = {0, 0}, beyond[2] = {0, 0};
    for (int i = 0; i < 400; ++i) {
      // A point on primitive j's surface: from its spine outwards to where f_j = 0.
      const int j = i % 2;
      const Vec3 d = random_dir(g);
      const Vec3 c = j == 0 ? Vec3{0, 0, uni(g, -2.5, 3.5)}
                            : Vec3{0.8192 * uni(g, -2.8, 2.8), -0.5736 * uni(g, -2.8, 2.8), 0.5};
      const Vec3 dir =
          j == 0 ? normalize(Vec3{d.x, d.y, 0})
                 : normalize(d - Vec3{0.8192, -0.5736, 0} * dot(d, Vec3{0.8192, -0.5736, 0}));
      const auto fj_at = [&](const Vec3& p) { return prim[j]->value(p); };
      if (fj_at(c) >= 0 || fj_at(c + dir * 3) <= 0) continue;
      const Vec3 p = crossing(fj_at, c, c + dir * 3);
      const double other = prim[1 - j]->value(p);
      if (other <= 0) continue;  // inside the other primitive: not on the union's surface
      const double v = f(p), reach = r[1 - j];
      if (other < reach - 1e-3) {
        EXPECT_LT(v, 0) << name << " on f" << j + 1 << " at distance " << other;
        ++near_fillet[j];
      } else if (other > reach + 1e-3) {
        EXPECT_NEAR(v, 0, 1e-9) << name << " on f" << j + 1 << " at distance " << other;
        ++beyond[j];
      }
    }
    for (int j = 0; j < 2; ++j) {
      EXPECT_GT(near_fillet[j], 3) << name;
      EXPECT_GT(beyond[j], 3) << name;
    }
    for (int i = 0; i < 2000; ++i) {
      const Vec3 p{uni(g, -4, 4), uni(g, -4, 4), uni(g, -3, 4)};
      const double x[2] = {prim[0]->value(p), prim[1]->value(p)};
      const double v = f(p), lo = std::min(x[0], x[1]);
      EXPECT_LE(v, lo + 1e-12) << name;
      if (!conic_region_ii(x, r[0], r[1], m)) {
        EXPECT_NEAR(v, lo, 1e-12) << name;
      }
    }
  }
}

// Fig. 6: the level surface BT2 = h is the base surface translated by h(m1, m2) = (h, 2h): on it
// (f1 - h, f2 - 2h) lies on the base curve (BT2 of it is 0), and away from the blend the post is
// the capsule dilated by h (f1 = h) and the bar the one dilated by 2h (f2 = 2h).
TEST(Fig003, Fig6LevelSurfacesAreTheBaseTranslatedByHm) {
  const Scene s = load_scene(scene_path("fig003_6_level_surfaces"));
  const json sj = scene_json("fig003_6_level_surfaces");
  Rng g(6);
  for (const auto& [name, h] :
       {std::pair{"h_0", 0.0}, {"h_0.25", 0.25}, {"h_0.5", 0.5}, {"h_0.75", 0.75}}) {
    EXPECT_EQ(object(s, name).iso, h);
    const json& fj = object_json(sj, name)["field"];
    const NodePtr f1 = build_zero(fj["children"][0]), f2 = build_zero(fj["children"][1]);
    const double r = 0.5, m[2] = {1, 2};
    const Local f = local(s, sj, name);
    int post = 0, bar = 0, blend = 0;
    for (int i = 0; i < 600; ++i) {
      const Vec3 c{0, 0, uni(g, -0.5, 1.2)};
      const Vec3 p = crossing(f, c, c + random_dir(g) * 9, h);
      const double x1 = f1->value(p), x2 = f2->value(p);
      const double shifted[2] = {x1 - m[0] * h, x2 - m[1] * h};
      EXPECT_NEAR(bt2_conic(shifted, r, r, 0, m, nullptr), 0, 1e-9) << name;
      if (x2 - m[1] * h > r + 1e-6) {
        EXPECT_NEAR(x1, m[0] * h, 1e-9) << name;
        ++post;
      } else if (x1 - m[0] * h > r + 1e-6) {
        EXPECT_NEAR(x2, m[1] * h, 1e-9) << name;
        ++bar;
      } else {
        ++blend;
      }
    }
    EXPECT_GT(post, 20) << name;
    EXPECT_GT(bar, 20) << name;
    EXPECT_GT(blend, 5) << name;
  }
}

// Fig. 7: the box -BT3(-f1, -f2, -f3) has the same zero set for every m2 ([BT-1]); in the union
// with the super-ellipsoid only the front-face (f2) fillet shrinks as m2 goes 1.2 -> 0.3, while
// the top-face (f3) fillet and the surface away from the super-ellipsoid stay.
TEST(Fig003, Fig7OnlyTheFrontFaceFilletShrinksWithM2) {
  const Scene s = load_scene(scene_path("fig003_7_subsequent_m2"));
  const json sj = scene_json("fig003_7_subsequent_m2");
  const char* names[] = {"m2_1.2", "m2_0.9", "m2_0.6", "m2_0.3"};
  Rng g(7);

  NodePtr boxes[4];
  for (int i = 0; i < 4; ++i)
    boxes[i] = build_zero(object_json(sj, names[i])["field"]["children"][0]);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p{uni(g, -3.5, 3.5), uni(g, -3, 3), uni(g, -2.5, 2.5)};
    const double v0 = boxes[0]->value(p);
    if (std::abs(v0) < 1e-9) continue;
    ++checked;
    for (int k = 1; k < 4; ++k)
      ASSERT_EQ(boxes[k]->value(p) < 0, v0 < 0)
          << names[k] << " at " << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_GT(checked, 19000);

  Local f[4];
  for (int k = 0; k < 4; ++k) f[k] = local(s, sj, names[k]);
  // Grid counts of inside points: in front of the front face left of the super-ellipsoid
  // (centre (2.5, -2, 0.3)), and above the top face behind it.
  const auto count = [&](const Local& fk, Vec3 lo, Vec3 hi) {
    int n = 0;
    for (int a = 0; a < 24; ++a)
      for (int b = 0; b < 24; ++b)
        for (int c = 0; c < 24; ++c) {
          const Vec3 p{lo.x + (hi.x - lo.x) * (a + 0.5) / 24, lo.y + (hi.y - lo.y) * (b + 0.5) / 24,
                       lo.z + (hi.z - lo.z) * (c + 0.5) / 24};
          n += fk(p) <= 0;
        }
    return n;
  };
  int front_prev = 1 << 30, top0 = -1;
  for (int k = 0; k < 4; ++k) {
    const int front = count(f[k], {-0.5, -2.9, -1.0}, {1.3, -2.0, 1.4});
    const int top = count(f[k], {0.5, -0.6, 1.5}, {3.0, 0.3, 2.2});
    EXPECT_LT(front, front_prev) << names[k];
    front_prev = front;
    if (k == 0) {
      EXPECT_GT(top, 0);
      top0 = top;
    }
    EXPECT_EQ(top, top0) << names[k];
  }
  // Surface points of the m2 = 1.2 object farther than 3.3 from the super-ellipsoid's centre
  // (where its field exceeds the union's range) lie on the other three objects' surfaces.
  int far = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec3 c{uni(g, -1, 1), uni(g, -1, 1), uni(g, -0.5, 0.5)};
    const Vec3 p = crossing(f[0], c, c + random_dir(g) * 6);
    if (length(p - Vec3{2.5, -2, 0.3}) < 3.3) continue;
    ++far;
    for (int k = 1; k < 4; ++k) EXPECT_NEAR(f[k](p), 0, 1e-9) << names[k];
  }
  EXPECT_GT(far, 100);
}

// Fig. 8: with all m = 1 the difference's blend between the pocket bottom f6 and the plate
// bottom f12 (0.4 apart, ranges 0.8) cuts through the floor; with m6 = m12 = 0.2 the floor is
// solid. b1 and b2 keep their zero sets, and the surface away from the pocket is the same.
TEST(Fig003, Fig8LoweringM6AndM12RemovesTheUnwantedBlend) {
  const Scene s = load_scene(scene_path("fig003_8_unwanted_blend"));
  const json sj = scene_json("fig003_8_unwanted_blend");
  const Local before = local(s, sj, "all_m_1"), after = local(s, sj, "m6_m12_0.2");
  for (double z : {-1.1, -1.0, -0.9})
    for (double x : {-0.6, 0.0, 0.6}) {
      EXPECT_GT(before({x, 0.3, z}), 0)
          << "the unwanted blend opens the floor at " << x << " " << z;
      EXPECT_LT(after({x, 0.3, z}), 0) << "the floor is solid at " << x << " " << z;
    }

  Rng g(8);
  for (int c = 0; c < 2; ++c) {  // b2 (the plate), b1 (the pocket block)
    const NodePtr b_before = build_zero(object_json(sj, "all_m_1")["field"]["children"][c]);
    const NodePtr b_after = build_zero(object_json(sj, "m6_m12_0.2")["field"]["children"][c]);
    for (int i = 0; i < 5000; ++i) {
      const Vec3 p{uni(g, -5, 5), uni(g, -4, 4), uni(g, -2, 3.5)};
      const double v = b_before->value(p);
      if (std::abs(v) > 1e-9) {
        ASSERT_EQ(b_after->value(p) < 0, v < 0) << "child " << c;
      }
    }
  }
  int far = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec3 c{uni(g, -3.5, 3.5), uni(g, -2.6, 2.6), uni(g, -0.9, 0.9)};
    if (std::abs(c.x) < 2.2 && std::abs(c.y) < 2.8) continue;  // start in the rim's material
    if (after(c) >= 0) continue;
    const Vec3 p = crossing(after, c, c + random_dir(g) * 8);
    if (std::abs(p.x) < 2.2 && std::abs(p.y) < 2.8 && p.z < 0) continue;  // the pocket's floor
    ++far;
    EXPECT_NEAR(before(p), 0, 1e-9) << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_GT(far, 100);
}

// Fig. 9(a): on top of the crossing (x1 = x2 = x, cosθ = 1) the plain blend's surface is at
// 2((r - x)/r)^2 = 1, a bulge of rho·r(1 - 2^(-1/2)) above the cylinders; with bulge
// elimination the ranges are r·omega there and the bulge nearly vanishes, while between the
// cylinders (cosθ = 0) the fillet keeps ranges r(1 + omega).
TEST(Fig003, Fig9aBulgeEliminationFlattensTheCrossing) {
  const Scene s = load_scene(scene_path("fig003_9a_crossing_cylinders"));
  const json sj = scene_json("fig003_9a_crossing_cylinders");
  const double rho = 0.5, r = 0.8, omega = 0.05, rise = 1 - 1 / std::sqrt(2.0);
  const Local plain = local(s, sj, "plain"), eliminated = local(s, sj, "bulge_eliminated");
  EXPECT_NEAR(crossing(plain, Vec3{0, 0, 0}, Vec3{0, 0, 2}).z, rho * (1 + r * rise), 1e-9);
  EXPECT_NEAR(crossing(eliminated, Vec3{0, 0, 0}, Vec3{0, 0, 2}).z, rho * (1 + r * omega * rise),
              1e-9);
  EXPECT_NEAR(crossing(plain, Vec3{0, 0, 0}, Vec3{2, 2, 0}).x, rho * (1 + r * rise), 1e-9);
  EXPECT_NEAR(crossing(eliminated, Vec3{0, 0, 0}, Vec3{2, 2, 0}).x,
              rho * (1 + r * (1 + omega) * rise), 1e-9);
  // Away from the crossing both are the capsules themselves: min(f1, f2).
  for (double x : {1.0, 1.5, -1.8})
    for (double d : {-0.2, 0.1, 0.4}) {
      EXPECT_NEAR(plain({x, 0, rho + d}), d / rho, 1e-9);
      EXPECT_NEAR(eliminated({0, x, rho + d}), d / rho, 1e-9);
    }
}

// Fig. 9: the wheel S(BT2(BT2(f1, f2), f3), 0) with bulge elimination in the inner blend.
// Spokes f_i = e_i/rho - 1 (rho = 0.16, f1 along x, f2 along y), rim f3, inner r = 0.8, p = 2,
// omega = 0.05; outer r = 1, m = 1. Claims:
// - the bulge is gone: on top of the crossing both normals agree (cosθ = 1), the ranges shrink to
//   r·omega and the top rises by rho·r·omega(1 - 2^(-1/2)) instead of rho·r(1 - 2^(-1/2));
//   between the spokes (cosθ = 0) the fillet stays, with ranges r(1 + omega);
// - the joint of the crossing spokes is the same for m1 = 1 and 0.3 ([BT-1]);
// - only the corners of spoke f1 with the rim change: on the rim's inner edge the outer fillet
//   reaches out to f1 = M1 = m1 (there cosθ = 0), i.e. |y| = rho(1 + m1), while spoke f2's corners
//   reach |x| = rho(1 + 1) on both wheels.
TEST(Fig003, Fig9BulgeGoneJointKeptOnlySpokeF1CornersChange) {
  const Scene s = load_scene(scene_path("fig003_9_wheel"));
  const json sj = scene_json("fig003_9_wheel");
  const double rho = 0.16, r = 0.8, omega = 0.05, rim_inner = 1.75;
  const double rise = 1 - 1 / std::sqrt(2.0);  // 2((P - x)/P)^2 = 1 at x1 = x2 = x
  const Local wheel[2] = {local(s, sj, "m1_1"), local(s, sj, "m1_0.3")};
  const double m1[2] = {1, 0.3};

  for (int w = 0; w < 2; ++w) {
    const json& inner_json = object_json(sj, w == 0 ? "m1_1" : "m1_0.3")["field"]["children"][0];
    json plain_json = inner_json;
    plain_json.erase("bulge_elimination");
    const NodePtr inner = build_zero(inner_json), plain = build_zero(plain_json);
    const auto top = [](const NodePtr& n) {
      return crossing([&](const Vec3& p) { return n->value(p); }, Vec3{0, 0, 0}, Vec3{0, 0, 1});
    };
    EXPECT_NEAR(top(inner).z, rho * (1 + r * omega * rise), 1e-9) << "bulge eliminated";
    EXPECT_NEAR(top(plain).z, rho * (1 + r * rise), 1e-9) << "the bulge of the plain blend";
    const Vec3 diagonal =
        crossing([&](const Vec3& p) { return inner->value(p); }, Vec3{0, 0, 0}, Vec3{1, 1, 0});
    EXPECT_NEAR(diagonal.x, rho * (1 + r * (1 + omega) * rise), 1e-9) << "the side fillet stays";
  }

  // The joint: around the hub, away from the rim's range, the two wheels agree in sign.
  int inside = 0, checked = 0;
  for (int a = 0; a < 60; ++a)
    for (int b = 0; b < 60; ++b)
      for (int c = 0; c < 20; ++c) {
        const Vec3 p{-1.2 + 2.4 * (a + 0.5) / 60, -1.2 + 2.4 * (b + 0.5) / 60,
                     -0.4 + 0.8 * (c + 0.5) / 20};
        const double v0 = wheel[0](p);
        if (std::abs(v0) < 1e-9) continue;
        ++checked;
        inside += v0 < 0;
        ASSERT_EQ(wheel[1](p) < 0, v0 < 0) << p.x << " " << p.y << " " << p.z;
      }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(checked, 70000);

  // The corners on the rim's inner edge (z = 0), 0.01 either side of where the fillet ends.
  const auto on_rim = [&](double along, bool x_spoke) {
    const double across = std::sqrt(rim_inner * rim_inner - along * along);
    return x_spoke ? Vec3{across, along, 0} : Vec3{along, across, 0};
  };
  for (int w = 0; w < 2; ++w)
    for (double side : {-1.0, 1.0}) {
      const double reach1 = rho * (1 + m1[w]), reach2 = rho * 2;
      EXPECT_LT(wheel[w](on_rim(side * (reach1 - 0.01), true)), -1e-4) << "m1 = " << m1[w];
      EXPECT_NEAR(wheel[w](on_rim(side * (reach1 + 0.01), true)), 0, 1e-9) << "m1 = " << m1[w];
      EXPECT_LT(wheel[w](on_rim(side * (reach2 - 0.01), false)), -1e-4) << "m1 = " << m1[w];
      EXPECT_NEAR(wheel[w](on_rim(side * (reach2 + 0.01), false)), 0, 1e-9) << "m1 = " << m1[w];
    }
  // Spoke f2's corner region has the same field on both wheels; spoke f1's does not.
  Rng g(9);
  double f1_corner_gap = 0;
  for (int i = 0; i < 2000; ++i) {
    const double along = uni(g, -0.6, 0.6), across = uni(g, 1.3, 1.8), z = uni(g, -0.45, 0.45);
    ASSERT_NEAR(wheel[0]({along, across, z}), wheel[1]({along, across, z}), 1e-9);
    f1_corner_gap = std::max(f1_corner_gap,
                             std::abs(wheel[0]({across, along, z}) - wheel[1]({across, along, z})));
  }
  EXPECT_GT(f1_corner_gap, 0.1);
}

}  // namespace
}  // namespace softtrace
