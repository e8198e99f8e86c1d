// The claims of [002] Figs. 1, 3 and 7(a), checked on their scene files: the wheel is the CSG
// tree of Fig. 1 (two unions and a difference of Perlin's set operations), the six cylinders of
// Fig. 3 bulge with plain fields and keep only their fillets with modulated ones, and the two
// crossing cylinders of Fig. 7(a) bulge over and under the crossing. Layouts are ours (each
// scene's header says which).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "figure_scene.h"

namespace softtrace {
namespace {

using figure::FigureScene;
using figure::first_crossing;
using figure::samples;

// Perlin's union and difference of soft fields (002 Eqs. 4, 6).
double perlin_union(double f, double g) {
  return f + g - f * g;
}
double perlin_difference(double f, double g) {
  return f * (1 - g);
}

// Fig. 1: the wheel is B_D2(B_U2(B_U2(f1, f2), f3), f4), evaluated here from its four
// primitives; the unions add fillets where the spokes meet the rim, and the difference opens the
// axle hole through the spokes' crossing.
TEST(Fig002Fig1, WheelIsTheCsgTree) {
  const FigureScene s("fig002_1_wheel_csg");
  const FieldNode& wheel = *s.object("wheel").field;
  const std::string root = "/objects/0/field";
  ASSERT_EQ(s.at(root)["type"], "perlin_difference");
  ASSERT_EQ(s.at(root + "/children/0")["type"], "perlin_union");
  ASSERT_EQ(s.at(root + "/children/0/children/0")["type"], "perlin_union");
  const NodePtr f1 = s.node(root + "/children/0/children/0/children/0", Convention::Soft);
  const NodePtr f2 = s.node(root + "/children/0/children/0/children/1", Convention::Soft);
  const NodePtr f3 = s.node(root + "/children/0/children/1", Convention::Soft);
  const NodePtr f4 = s.node(root + "/children/1", Convention::Soft);
  int fillet = 0;
  for (const Vec3& p : samples({-13, -13, -4}, {13, 13, 4}, 40000, 1)) {
    const double a = f1->value(p), b = f2->value(p), c = f3->value(p), d = f4->value(p);
    const double unions = perlin_union(perlin_union(a, b), c);
    ASSERT_NEAR(wheel.value(p), perlin_difference(unions, d), 1e-12);
    // Added material where a spoke meets the rim: inside the wheel, outside every primitive.
    const double rho = std::hypot(p.x, p.y);
    fillet += rho > 5 && wheel.value(p) >= 0.5 && std::max({a, b, c}) < 0.5;
  }
  EXPECT_GT(fillet, 20);
  // The axle hole: on the axis through the crossing the spokes' union is solid, the wheel not.
  for (double z : {-1.0, 0.0, 0.8}) {
    const Vec3 p{0, 0, z};
    EXPECT_GE(perlin_union(f1->value(p), f2->value(p)), 0.5);
    EXPECT_LT(wheel.value(p), 0.5) << "z = " << z;
  }
  // The spokes and the rim are solid away from the hub.
  for (const Vec3& p : {Vec3{5, 0, 0}, Vec3{0, -5, 0}, Vec3{9 / std::sqrt(2), 9 / std::sqrt(2), 0}})
    EXPECT_GE(wheel.value(p), 0.5);
}

struct Probe {
  const char* where;
  Vec3 p;
};

// Fig. 3: six cylinders (members 6 thick on a 32-unit grid in the plane z = 0; each probe lies
// 0.5 outside the members' surfaces). Plain fields bulge over the crossing, across the T joints
// and around the frame's corners; the modulated ones do not. Both keep the fillets in the inner
// corners, and neither adds material mid-span.
TEST(Fig002Fig3, BulgesGoFilletsStay) {
  const FigureScene a("fig002_3a_six_cylinders_bulges"), b("fig002_3b_six_cylinders_no_bulges");
  const FieldNode& with = *a.object("cylinders").field;
  const FieldNode& without = *b.object("cylinders").field;
  const Probe bulges[] = {
      {"over the crossing", {0, 0, 3.5}},
      {"under the crossing", {0, 0, -3.5}},
      {"on the back member's outer face across the T joint", {0, 19.5, 0}},
      {"on the right member's outer face across the T joint", {19.5, 0, 0}},
      {"on the right member's outer face at the back corner", {19.5, 16, 0}},
      {"on the back member's outer face at the right corner", {16, 19.5, 0}},
      {"over the back-right corner", {16, 16, 3.5}},
      {"over the back T joint", {0, 16, 3.5}},
  };
  for (const Probe& q : bulges) {
    EXPECT_GE(with.value(q.p), 0.5) << "(with) bulges " << q.where;
    EXPECT_LT(without.value(q.p), 0.5) << "(without) has no bulge " << q.where;
  }
  const Probe fillets[] = {
      {"in an inner corner of the crossing", {3.5, 3.5, 0}},
      {"in an inner corner of the crossing", {-3.5, -3.5, 0}},
      {"beside the back T joint", {3.5, 12.5, 0}},
      {"beside the left T joint", {-12.5, -3.5, 0}},
      {"in the back-right corner", {12.5, 12.5, 0}},
      {"in the front-left corner", {-12.5, -12.5, 0}},
  };
  for (const Probe& q : fillets) {
    EXPECT_GE(with.value(q.p), 0.5) << "(with) fillet " << q.where;
    EXPECT_GE(without.value(q.p), 0.5) << "(without) keeps the fillet " << q.where;
  }
  for (const Vec3& p : {Vec3{8, 19.5, 0}, Vec3{-19.5, 8, 0}, Vec3{8, 0, 3.5}}) {
    EXPECT_LT(with.value(p), 0.5);
    EXPECT_LT(without.value(p), 0.5);
  }
}

// Fig. 7(a): over the crossing the solid rises above the cylinders' tops (3), a bulge in the top
// and bottom regions; away from the crossing the top is the cylinder's own.
TEST(Fig002Fig7, CrossingBulgesAboveAndBelow) {
  const FigureScene s("fig002_7a_bulge");
  const FieldNode& f = *s.object("cylinders").field;
  const auto top = [&](double x, double y, double dz) {
    return first_crossing([&](const Vec3& p) { return 0.5 - f.value(p); }, {x, y, 0}, {0, 0, dz},
                          10, 10000);
  };
  EXPECT_GT(top(0, 0, 1), 3.5);
  EXPECT_GT(top(0, 0, -1), 3.5);
  EXPECT_NEAR(top(12, 0, 1), 3, 1e-9);
  EXPECT_NEAR(top(0, -12, -1), 3, 1e-9);
  // The fillets in the inner corners are the wanted blend: there too the union adds material.
  EXPECT_GE(f.value({3.5, 3.5, 0}), 0.5);
}

}  // namespace
}  // namespace softtrace
