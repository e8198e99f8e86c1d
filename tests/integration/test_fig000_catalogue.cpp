// The claims of [000] Figs. 1-5 and 9, checked on their scene files (scenes/fig000_1*.json ...
// fig000_9*.json): the primitives' shapes (Fig. 1), a sharp crease against a smooth blend (Fig. 2),
// Ricci's total deformation against Hoffmann's local one (Figs. 3(b), 4(b)), the scale method's
// fillets confined to region III (Fig. 5) and a plain union's transition taking the blended
// primitive's contour (Fig. 9). Sizes and layouts are ours (each scene's header says which).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "figure_scene.h"

namespace softtrace {
namespace {

using figure::FigureScene;
using figure::first_crossing;
using figure::samples;
using figure::vec;

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0, 1.0)) * 180 / M_PI;
}

// ---- Fig. 1: the primitives -------------------------------------------------------------------

// (a) The skeletal primitive r/I_r: its value is the distance to the segment over I_r, so the
// surface f = 1 lies I_r from the segment everywhere (a capsule).
TEST(Fig000Fig1, SkeletalPrimitiveIsDistanceOverRadius) {
  const FigureScene s("fig000_1a_skeletal_segment");
  const SceneObject& o = s.object("segment");
  const nlohmann::json& f = s.at("/objects/0/field");
  const Vec3 a = vec(f["p0"]), b = vec(f["p1"]);
  const double ir = f["radius"];
  EXPECT_EQ(o.convention, Convention::Constructive);
  for (const Vec3& p : samples({-6, -3, -3}, {6, 3, 3}, 5000, 1)) {
    const double u = std::clamp(dot(p - a, b - a) / dot(b - a, b - a), 0.0, 1.0);
    ASSERT_NEAR(o.field->value(p), length(p - (a + (b - a) * u)) / ir, 1e-12);
  }
  EXPECT_DOUBLE_EQ(ir, 1.5);
  EXPECT_GT(length(b - a), 2 * ir) << "a capsule, longer than it is wide";
}

// The distance from `centre` along `dir` to where the constructive field crosses 1.
double surface_radius(const SceneObject& o, const Vec3& centre, const Vec3& dir) {
  return first_crossing([&](const Vec3& p) { return o.field->value(p) - 1; }, centre,
                        normalize(dir), 3, 3000);
}

// (b) Superquadrics: the surface meets the axes at the radius 1 and the x-y diagonal at
// 2^(-1/n1) per coordinate (n1 shapes the cross-section), the x-z diagonal at 2^(-1/n2) (n2
// the profile along z).
TEST(Fig000Fig1, SuperquadricExponentsShapeSectionAndProfile) {
  const FigureScene s("fig000_1b_superquadrics");
  int checked = 0;
  for (const nlohmann::json& oj : s.json()["objects"]) {
    const nlohmann::json& f = oj["field"];
    const double n1 = f["n1"], n2 = f["n2"];
    const SceneObject& o = s.object(oj["name"]);
    const Vec3 c = vec(f["translate"]);
    EXPECT_NEAR(surface_radius(o, c, {1, 0, 0}), 1, 1e-9);
    EXPECT_NEAR(surface_radius(o, c, {0, 0, 1}), 1, 1e-9);
    EXPECT_NEAR(surface_radius(o, c, {1, 1, 0}) / std::sqrt(2), std::pow(2, -1 / n1), 1e-9);
    EXPECT_NEAR(surface_radius(o, c, {1, 0, 1}) / std::sqrt(2), std::pow(2, -1 / n2), 1e-9);
    ++checked;
  }
  EXPECT_EQ(checked, 4);
}

// (c) LP metrics for the paper's n: the surface meets the main diagonal at 3^(-1/n) per
// coordinate, growing with n from an octahedron-like solid (n = 1.1: 0.37) to a cube (n = 20:
// 0.95), through the sphere (n = 2: 1/sqrt(3)).
TEST(Fig000Fig1, LpMetricsGoFromOctahedronToCube) {
  const FigureScene s("fig000_1c_lp_metrics");
  std::vector<double> ns;
  double previous = 0;
  for (const nlohmann::json& oj : s.json()["objects"]) {
    const double n = oj["field"]["n"];
    const double t =
        surface_radius(s.object(oj["name"]), vec(oj["field"]["translate"]), {1, 1, 1}) /
        std::sqrt(3);
    EXPECT_NEAR(t, std::pow(3, -1 / n), 1e-9) << "n = " << n;
    EXPECT_GT(t, previous) << "n = " << n;
    previous = t;
    ns.push_back(n);
  }
  EXPECT_EQ(ns, (std::vector<double>{1.1, 1.3, 1.5, 2, 3, 5, 10, 20}));
}

// ---- Fig. 2: sharp vs blended union -------------------------------------------------------------

// The largest angle between the surface normals of neighbouring rays fanned in the x-z plane
// from inside the joint, (0, 0, 1), from nearly horizontal up to steep: the rays cross from the
// bar's top onto the post's side. The field is zero-convention (inside <= 0).
double largest_normal_jump(const SceneObject& o) {
  const Vec3 c{0, 0, 1};
  Vec3 previous{};
  double jump = 0;
  for (int i = 0; i <= 960; ++i) {
    const double a = (2 + 58.0 * i / 960) * M_PI / 180;
    const Vec3 dir{std::cos(a), 0, std::sin(a)};
    const double t =
        first_crossing([&](const Vec3& p) { return o.field->value(p); }, c, dir, 6, 600);
    const Vec3 n = o.field->gradient(c + dir * t);
    if (i > 0) jump = std::max(jump, angle_deg(n, previous));
    previous = n;
  }
  return jump;
}

// (a) min(f1, f2): the normal jumps where the post meets the bar (a sharp edge); (b) the blend
// turns it smoothly: rays 0.06 degrees apart, whose surface points lie about 0.001 apart, have
// normals at most a few degrees apart even in the tight fillet (r = 0.7).
TEST(Fig000Fig2, PureUnionHasASharpEdgeTheBlendNone) {
  const FigureScene a("fig000_2a_cylinders_sharp"), b("fig000_2b_cylinders_blended");
  EXPECT_GT(largest_normal_jump(a.object("cylinders")), 60);
  EXPECT_LT(largest_normal_jump(b.object("cylinders")), 2.5);
}

// (a) is min(f1, f2) everywhere; (b) has the same solid outside the blending region
// 0 <= f_i <= r_i and adds material inside it.
TEST(Fig000Fig2, BlendChangesTheSolidOnlyInsideItsRanges) {
  const FigureScene a("fig000_2a_cylinders_sharp"), b("fig000_2b_cylinders_blended");
  const NodePtr f1 = b.node("/objects/0/field/children/0", Convention::Zero);
  const NodePtr f2 = b.node("/objects/0/field/children/1", Convention::Zero);
  const double r1 = b.at("/objects/0/field/r1"), r2 = b.at("/objects/0/field/r2");
  const FieldNode& sharp = *a.object("cylinders").field;
  const FieldNode& blend = *b.object("cylinders").field;
  int added = 0;
  for (const Vec3& p : samples({-3, -2, -1}, {3, 2, 4}, 60000, 2)) {
    const double x1 = f1->value(p), x2 = f2->value(p), m = std::min(x1, x2);
    ASSERT_EQ(sharp.value(p), m);
    const bool in_ranges = x1 >= 0 && x1 <= r1 && x2 >= 0 && x2 <= r2;
    const double u = blend.value(p);
    ASSERT_LE(u, m + 1e-12);
    if (!in_ranges) {
      ASSERT_EQ(u <= 0, m <= 0) << "at " << p.x << " " << p.y << " " << p.z;
    } else {
      added += u <= 0 && m > 0;
    }
  }
  EXPECT_GT(added, 100);
}

// ---- Figs. 3(b) and 4(b): total vs local deformation --------------------------------------------

// Fig. 3(b): a die. The 21 spheres are its pips, 1 to 6 on the six faces with opposite faces
// summing to 7, and each pip's centre is outside the solid (a dimple). Ricci's operations have
// no ranges: every face is deformed all over, the solid's surface leaves the face plane
// everywhere off the face's centre lines (docs/math.md [RC-4]).
TEST(Fig000Fig3, DieFacesAreDeformedEverywhere) {
  const FigureScene s("fig000_3b_die");
  const FieldNode& die = *s.object("die").field;
  // The pips: the spheres of the two differences (the inner one's first child is the box).
  std::vector<nlohmann::json> spheres;
  for (const char* pointer :
       {"/objects/0/field/children/0/children", "/objects/0/field/children"}) {
    const nlohmann::json& children = s.at(pointer);
    for (size_t i = 1; i < children.size(); ++i) spheres.push_back(children[i]);
  }
  std::map<std::pair<int, int>, int> pips;  // (axis, side) -> count
  std::vector<Vec3> centres;
  for (size_t i = 0; i < spheres.size(); ++i) {
    ASSERT_EQ(spheres[i]["type"], "lp_metric");
    const Vec3 c = vec(spheres[i]["translate"]);
    centres.push_back(c);
    EXPECT_GT(die.value(c), 1) << "pip " << i << " is a dimple";
    const double v[3] = {c.x, c.y, c.z};
    for (int k = 0; k < 3; ++k)
      if (std::abs(v[k]) == 2) ++pips[{k, v[k] > 0 ? 1 : -1}];
  }
  ASSERT_EQ(centres.size(), 21u);
  ASSERT_EQ(pips.size(), 6u);
  std::vector<int> counts;
  for (int k = 0; k < 3; ++k) {
    const int plus = pips[{k, 1}], minus = pips[{k, -1}];
    EXPECT_EQ(plus + minus, 7) << "opposite faces of axis " << k;
    counts.push_back(plus);
    counts.push_back(minus);
  }
  std::sort(counts.begin(), counts.end());
  EXPECT_EQ(counts, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  // On the face planes, away from the pips and from the face's centre lines (where the other
  // planes' terms underflow), the die's field is never the plane's 1: no flat part; 0.8 from the
  // centre, where Hoffmann's box of Fig. 4(b) is exactly flat, the rounding is 1e-4 of the size.
  int checked = 0;
  for (const Vec3& q : samples({-1.4, -1.4, 0}, {1.4, 1.4, 0}, 4000, 3)) {
    if (std::max(std::abs(q.x), std::abs(q.y)) < 0.5) continue;
    const Vec3 p{q.x, q.y, 2};
    bool near_pip = false;
    for (const Vec3& c : centres) near_pip |= length(p - c) < 1.2;
    if (near_pip) continue;
    ++checked;
    ASSERT_GT(die.value(p), 1) << "at " << p.x << " " << p.y;
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(die.value({0.8, 0.8, 2}), 1 + 1e-4);
}

// Fig. 4(b): Hoffmann's intersection ((f_x, f_y), f_z) nested: each blend is the larger of its
// two arguments wherever they are at least r apart, so the box is its faces' planes except in
// bands along the edges: the middle of every face is exactly flat, where the die of Fig. 3(b) is
// already rounded, and material is removed only where the planes are within r of the surface.
TEST(Fig000Fig4, HoffmannBoxFacesStayFlat) {
  const FigureScene s("fig000_4b_hoffmann_box");
  const FieldNode& box = *s.object("box").field;
  const NodePtr inner = s.node("/objects/0/field/children/0", Convention::Zero);
  const double r = s.at("/objects/0/field/r1"), a = 2;
  int flat = 0, rounded = 0;
  for (const Vec3& p : samples({-2.6, -2.6, -2.6}, {2.6, 2.6, 2.6}, 60000, 4)) {
    const double fx = std::abs(p.x) - a, fy = std::abs(p.y) - a, fz = std::abs(p.z) - a;
    const double mx = std::max({fx, fy, fz}), in = inner->value(p), b = box.value(p);
    ASSERT_GE(b, mx - 1e-12) << "an intersection removes material, never adds it";
    if (std::abs(fx - fy) >= r && std::abs(in - fz) >= r) {
      ++flat;
      ASSERT_NEAR(b, mx, 1e-12) << "at " << p.x << " " << p.y << " " << p.z;
    } else if (b > 0 && mx <= 0) {
      ++rounded;
      const int near = (fx >= -2 * r) + (fy >= -2 * r) + (fz >= -2 * r);
      ASSERT_GE(near, 2) << "removed material away from an edge at " << p.x << " " << p.y << " "
                         << p.z;
    }
  }
  EXPECT_GT(flat, 10000);
  EXPECT_GT(rounded, 100);
  for (const Vec3& q : samples({-0.8, -0.8, 0}, {0.8, 0.8, 0}, 400, 5)) {
    EXPECT_EQ(box.value({q.x, q.y, 2}), 0);
    EXPECT_EQ(box.value({2, q.x, q.y}), 0);
    EXPECT_EQ(box.value({q.y, -2, q.x}), 0);
  }
  EXPECT_GT(box.value({2, 2, 0}), 0) << "the edge itself is cut back";
}

// ---- Fig. 5: scale unions ----------------------------------------------------------------------

// Every BSA2 of a nested chain (found by walking the scene's JSON from the root), checked on the
// samples: outside region III, x1/(1 + r1) < x2 < (1 + r2) x1, the union is min(x1, x2); inside
// it, never above min (it adds material, constructive inside <= 1).
// `unions` counts the unions checked.
void check_region_three(const FigureScene& s, const std::vector<Vec3>& points, int& unions) {
  std::string pointer = "/objects/0/field";
  unions = 0;
  while (s.at(pointer).value("type", "") == "scale_union") {
    const NodePtr b = s.node(pointer, Convention::Constructive);
    const NodePtr x1 = s.node(pointer + "/children/0", Convention::Constructive);
    const NodePtr x2 = s.node(pointer + "/children/1", Convention::Constructive);
    const double r1 = s.at(pointer + "/r1"), r2 = s.at(pointer + "/r2");
    int inside_three = 0;
    for (const Vec3& p : points) {
      const double u = x1->value(p), v = x2->value(p), m = std::min(u, v), h = b->value(p);
      const bool three = u > 0 && v > 0 && u / (1 + r1) < v && v < (1 + r2) * u;
      if (!three) {
        ASSERT_NEAR(h, m, 1e-12 * (1 + m)) << pointer << " at " << p.x << " " << p.y << " " << p.z;
      } else {
        ++inside_three;
        ASSERT_LE(h, m + 1e-12 * (1 + m)) << pointer;
      }
    }
    EXPECT_GT(inside_three, 100) << pointer;
    ++unions;
    pointer += "/children/0";
  }
}

// (a) BSA2(BSA2(BSA2(f1, f2), f3), f4) on four cylinders in a # pattern: each of the four
// crossings gets a fillet in its four inner corners (points outside both cylinders inside the
// union), and every union is min outside its region III.
TEST(Fig000Fig5, FourCylindersFilletEveryCrossing) {
  const FigureScene s("fig000_5a_scale_union_four");
  const FieldNode& f = *s.object("cylinders").field;
  int unions = 0;
  check_region_three(s, samples({-7, -7, -2}, {7, 7, 2}, 30000, 5), unions);
  EXPECT_EQ(unions, 3);
  const double lines = 2.5, radius = 1.2;  // the scene's cylinder axes and radius
  for (double cx : {-lines, lines})
    for (double cy : {-lines, lines})
      for (double sx : {-1.0, 1.0})
        for (double sy : {-1.0, 1.0}) {
          const double off = radius + 0.1;  // 0.1 outside both cylinders' surfaces
          const Vec3 p{cx + sx * off, cy + sy * off, 0};
          EXPECT_LE(f.value(p), 1) << "fillet at " << p.x << " " << p.y;
        }
  // Along a cylinder, away from the crossings, the surface is the cylinder's own.
  EXPECT_NEAR(f.value({0, lines + radius, 0}), 1, 1e-12);
  EXPECT_NEAR(f.value({lines, 0, radius}), 1, 1e-12);
}

// (b) Six skeletal cylinders end to end around a hexagon: every joint gets a fillet in its
// inner angle, and at each side's middle the surface is that cylinder's own.
TEST(Fig000Fig5, SixCylindersFilletEveryJoint) {
  const FigureScene s("fig000_5b_scale_union_six");
  const FieldNode& f = *s.object("ring").field;
  int unions = 0;
  check_region_three(s, samples({-6, -6, -1.5}, {6, 6, 1.5}, 30000, 6), unions);
  EXPECT_EQ(unions, 5);
  std::vector<Vec3> corners;
  std::string pointer = "/objects/0/field";
  while (s.at(pointer)["type"] == "scale_union") {
    const nlohmann::json& seg = s.at(pointer + "/children/1");
    corners.push_back(vec(seg["p0"]));
    pointer += "/children/0";
  }
  corners.push_back(vec(s.at(pointer)["p0"]));
  ASSERT_EQ(corners.size(), 6u);
  const double ir = s.at(pointer)["radius"];
  for (const Vec3& v : corners) {
    // 1 from the corner towards the ring's centre: 0.87 from both sides' axes (x1 = x2 = 1.08),
    // outside both capsules (I_r = 0.8) and inside the fillet, which meets that diagonal at
    // x = 1 + r (2 - sqrt(2)) / 2 = 1.146 (p = 0, r = 0.5; docs/math.md §6.1).
    const Vec3 p = v * (1 - 1.0 / length(v));
    EXPECT_LE(f.value(p), 1) << "fillet at the corner " << v.x << " " << v.y;
    for (size_t j = 0; j < corners.size(); ++j) {
      const Vec3 mid = (v + corners[j]) * 0.5;
      if (std::abs(length(v - corners[j]) - length(v)) > 1e-9) continue;  // neighbours only
      const Vec3 out = normalize(mid) * ir, up{0, 0, ir};
      EXPECT_NEAR(f.value(mid + out), 1, 1e-12);
      EXPECT_NEAR(f.value(mid + up), 1, 1e-12);
    }
  }
}

// ---- Fig. 9: the transition takes the blended primitive's contour ------------------------------

// The union's outer boundary at height z, along the direction at angle phi in x-y from the
// small primitive's axis (0, 0): the distance from the axis.
double contour_radius(const FieldNode& f, double z, double phi) {
  return first_crossing([&](const Vec3& p) { return 0.5 - f.value(p); }, {0, 0, z},
                        {std::cos(phi), std::sin(phi), 0}, 30, 3000);
}

// Near the slab's top face d2 depends on z alone, so the transition's outline at each height is
// a level set of the small primitive's d1 (the same d1 all round), and its shape is that of the
// primitive's own cross-section: the ratio of its radii at 45 and 0 degrees is sqrt(2) 2^(-1/20)
// for the cube (n = 20) and 1/sqrt(2) for the prism (n1 = 1), however wide the transition is.
void check_contour(const char* name, double expected_ratio) {
  const FigureScene s(name);
  const FieldNode& f = *s.object("union").field;
  const NodePtr d1 = s.node("/objects/0/field/children/0/distance", Convention::Soft);
  for (double z : {0.3, 1.0, 2.0}) {
    std::vector<double> levels;
    for (int i = 0; i <= 36; ++i) {
      const double phi = M_PI / 2 * i / 36, r = contour_radius(f, z, phi);
      levels.push_back(d1->value({r * std::cos(phi), r * std::sin(phi), z}));
    }
    const auto [lo, hi] = std::minmax_element(levels.begin(), levels.end());
    EXPECT_LT(*hi - *lo, 1e-6) << name << " at z = " << z;
    EXPECT_GT(*lo, 0.5) << name << ": the transition lies outside the primitive";
    EXPECT_LT(*hi, 1) << name << ": and inside its blending region";
    const double ratio = contour_radius(f, z, M_PI / 4) / contour_radius(f, z, 0);
    EXPECT_NEAR(ratio, expected_ratio, 1e-5) << name << " at z = " << z;
  }
}

TEST(Fig000Fig9, CubeAndCubeTransitionIsSquare) {
  check_contour("fig000_9c_cube_and_cube", std::sqrt(2) * std::pow(2, -1.0 / 20));
}

TEST(Fig000Fig9, CubeAndPrismTransitionIsADiamond) {
  check_contour("fig000_9e_cube_and_prism", 1 / std::sqrt(2));
}

// Fig. 9(a), (b), (d) shown apart are the primitives Fig. 9(c) and (e) unite.
TEST(Fig000Fig9, PrimitivesAreThoseOfTheUnions) {
  const FigureScene parts("fig000_9abd_primitives"), c("fig000_9c_cube_and_cube"),
      e("fig000_9e_cube_and_prism");
  const struct {
    const char* object;
    const FigureScene* in;
    const char* pointer;
  } pairs[] = {{"a_cube", &c, "/objects/0/field/children/1"},
               {"a_cube", &e, "/objects/0/field/children/1"},
               {"b_cube", &c, "/objects/0/field/children/0"},
               {"d_prism", &e, "/objects/0/field/children/0"}};
  for (const auto& q : pairs) {
    const FieldNode& shown = *parts.object(q.object).field;
    Vec3 shift;
    for (const nlohmann::json& oj : parts.json()["objects"])
      if (oj["name"] == q.object) shift = vec(oj["field"]["translate"]);
    const NodePtr inside = q.in->node(q.pointer, Convention::Soft);
    int solid = 0;
    for (const Vec3& p : samples({-40, -40, -14}, {40, 40, 20}, 20000, 9)) {
      const double v = inside->value(p);
      ASSERT_NEAR(shown.value(p + shift), v, 1e-12) << q.object;
      solid += v >= 0.5;
    }
    EXPECT_GT(solid, 50) << q.object;
  }
}

}  // namespace
}  // namespace softtrace
