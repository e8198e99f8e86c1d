// The claims of [003] Fig. 3(a, b), checked on their scene files: the objects shown apart in (a)
// are those (b) unites, and under the displacement method (BD, every m_i = 1) the box's top and
// front faces get the same subsequent fillet with the super-ellipsoid, which is [003]'s
// complaint about BD (Fig. 3(c), with BT's m_i, is fig003_7_subsequent_m2.json).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "figure_scene.h"

namespace softtrace {
namespace {

using figure::FigureScene;
using figure::first_crossing;
using figure::samples;
using figure::vec;

TEST(Fig003Fig3, ObjectsApartAreThoseUnited) {
  const FigureScene a("fig003_3a_box_and_superellipsoid"), b("fig003_3b_bd_union");
  const std::string u = "/objects/1/field";
  ASSERT_EQ(b.at(u)["type"], "displacement_union");
  const NodePtr box = b.node(u + "/children/0", Convention::Zero);
  const NodePtr ell = b.node(u + "/children/1", Convention::Zero);
  const Vec3 box_at = vec(a.at("/objects/1/field/translate"));
  const Vec3 ell_at = vec(a.at("/objects/2/field/translate"));
  const Vec3 ell_in_union = vec(b.at(u + "/children/1/translate"));
  const FieldNode& box_a = *a.object("box").field;
  const FieldNode& ell_a = *a.object("super_ellipsoid").field;
  for (const Vec3& p : samples({-4, -4, -3}, {4, 4, 3}, 20000, 3)) {
    ASSERT_NEAR(box_a.value(p + box_at), box->value(p), 1e-12);
    ASSERT_NEAR(ell_a.value(p - ell_in_union + ell_at), ell->value(p), 1e-12);
  }
}

// (b): on the super-ellipsoid's surface (e = 0) the union adds material exactly where the box's
// field b lies in (0, r1): the fillet climbs the super-ellipsoid to b = r1. Away from the box's
// own edge blends b is the face's f_i (BD behaves like min there), so the fillet reaches r1 from
// the top face (f1 = z - 1.5) and r1 from the front face (f2 = -y - 2) alike.
TEST(Fig003Fig3, DisplacementGivesBothFacesTheSameFillet) {
  const FigureScene s("fig003_3b_bd_union");
  const std::string u = "/objects/1/field";
  const FieldNode& f = *s.object("union").field;
  const NodePtr box = s.node(u + "/children/0", Convention::Zero);
  const NodePtr ell = s.node(u + "/children/1", Convention::Zero);
  const double r1 = s.at(u + "/r1");
  const Vec3 centre = vec(s.at(u + "/children/1/translate"));
  const double box_range = s.at(u + "/children/0/r");
  double reach_top = 0, reach_front = 0;
  int top = 0, front = 0;
  for (const Vec3& q : samples({-1, -1, -1}, {1, 1, 1}, 60000, 4)) {
    if (length(q) < 0.1) continue;
    const Vec3 dir = normalize(q);
    const double t =
        first_crossing([&](const Vec3& p) { return ell->value(p); }, centre, dir, 4, 400);
    const Vec3 p = centre + dir * t;
    const double f1 = std::abs(p.z) - 1.5, f2 = std::abs(p.y) - 2, f3 = std::abs(p.x) - 2.5;
    const bool added = f.value(p) < -1e-9;
    if (f1 > 0 && f2 <= -box_range && f3 <= -box_range) {
      ++top;
      ASSERT_NEAR(box->value(p), f1, 1e-12);
      if (added) reach_top = std::max(reach_top, f1);
    } else if (f2 > 0 && f1 <= -box_range && f3 <= -box_range) {
      ++front;
      ASSERT_NEAR(box->value(p), f2, 1e-12);
      if (added) reach_front = std::max(reach_front, f2);
    }
  }
  EXPECT_GT(top, 1000);
  EXPECT_GT(front, 1000);
  EXPECT_NEAR(reach_top, r1, 0.02);
  EXPECT_NEAR(reach_front, r1, 0.02);
  EXPECT_NEAR(reach_top, reach_front, 0.02);
}

}  // namespace
}  // namespace softtrace
