// The claims of [002] Figs. 6, 8 and 9, checked numerically on the committed scene files
// (scenes/fig002_*.json), so a scene that stops showing what its figure is about fails here.
// The distance and modulation functions are re-evaluated independently of fieldlib from the
// paper's formulas; Blanc's potential with s = 0 (docs/math.md §3.2) is the scenes' potential.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "scene/scene.h"

namespace softtrace {
namespace {

Scene load(const std::string& name) {
  return load_scene(std::string(SOFTTRACE_SOURCE_DIR) + "/scenes/" + name + ".json");
}

const SceneObject& object(const Scene& s, const std::string& name) {
  for (const SceneObject& o : s.objects)
    if (o.name == name) return o;
  throw std::runtime_error("no object " + name + " in " + s.path);
}

// Blanc's potential, s = 0 (docs/math.md §3.2), and its inverse on [0, 1] by bisection.
double blanc(double d) {
  if (d >= 1) return 0;
  if (d <= 0.5) return 1 - 2 * d * d;
  const double u = 1 - d * d;
  return u * u / (0.75 + 1.5 * d * d);
}
double blanc_inverse(double l) {
  double a = 0, b = 1;  // blanc decreases from 1 to 0
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b);
    (blanc(m) > l ? a : b) = m;
  }
  return 0.5 * (a + b);
}

double pw(double v, double n) {
  return std::pow(std::abs(v), n);
}
// Fig. 6's elliptic cylinder d, modulations f_a (Fig. 6(c)) and f_s (Fig. 6(e)).
double fig6_d(const Vec3& p) {
  return std::pow(pw(std::sqrt(pw(p.x / 10, 2) + pw(p.y / 6, 2)), 10) + pw(p.z / 25, 10), 0.1);
}
double fig6_fa(const Vec3& p) {
  return std::pow(pw(p.x / 24, 10) + pw(p.y / 15, 10) + pw(p.z / 50, 10), 0.1);
}
double fig6_fs(const Vec3& p) {
  return std::pow(pw(std::sqrt(pw(p.x / 4, 2) + pw(p.y / 4, 2)), 10) + pw(p.z / 12.5, 10), 0.1);
}

// Where an object's field crosses its iso level along the ray centre + ρu, ρ in (lo, hi), for a
// field that is above the level at lo and below it at hi.
double crossing(const SceneObject& o, const Vec3& centre, const Vec3& u, double lo, double hi) {
  EXPECT_GE(o.field->value(centre + u * lo), o.iso);
  EXPECT_LT(o.field->value(centre + u * hi), o.iso);
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (lo + hi);
    (o.field->value(centre + u * m) >= o.iso ? lo : hi) = m;
  }
  return 0.5 * (lo + hi);
}

std::vector<Vec3> directions() {
  std::mt19937 rng(2002);
  std::normal_distribution<double> g;
  std::vector<Vec3> dirs{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {-2, 1, 0.3}};
  for (int i = 0; i < 40; ++i) dirs.push_back({g(rng), g(rng), g(rng)});
  for (Vec3& v : dirs) v = v / length(v);
  return dirs;
}

// The objects of a Fig. 6 scene sit 28 apart along x, in the order of their levels.
Vec3 fig6_centre(int i) {
  return {28.0 * i, 0, 0};
}

// [TA-4]: along every ray from the centre, P_b∘T_an∘d = l lies at
// ρ = I_d/2 + (τ - 1/2)(I_fa - I_d), τ = P_b^-1(l): linear from d = 0.5 to f_a = 0.5.
TEST(Fig002Fig6, TanLevelsInterpolateLinearlyFromDToFa) {
  const Scene s = load("fig002_6d_levels_T_an");
  const char* names[] = {"l050", "l035", "l015", "l001"};
  const double levels[] = {0.5, 0.35, 0.15, 0.01};
  for (int i = 0; i < 4; ++i) {
    const SceneObject& o = object(s, names[i]);
    ASSERT_EQ(o.iso, levels[i]) << "the caption's levels";
    const double tau = blanc_inverse(levels[i]);
    for (const Vec3& u : directions()) {
      const double Id = 1 / fig6_d(u), Ifa = 1 / fig6_fa(u);
      const double expected = 0.5 * Id + (tau - 0.5) * (Ifa - Id);
      const double rho = crossing(o, fig6_centre(i), u, 0.25 * Id, 0.6 * Ifa);
      EXPECT_NEAR(rho, expected, 1e-7 * Ifa)
          << names[i] << " along " << u.x << " " << u.y << " " << u.z;
    }
  }
}

// For T_sn (w1 = w2 = 1 - d/f_s) the inner branch of T_n is linear, so P_b∘T_sn∘d = l lies at
// ρ = I_d/2 + (1/2 - τ)(I_fs - I_d): linear from d = 0.5 (τ = 1/2) to f_s = 0.5 (τ = 0).
// [TS-1]: inside d = 0.5, T > 0 only where f_s > 0.5, so the field is P_b(0) = 1 inside f_s = 0.5.
TEST(Fig002Fig6, TsnLevelsInterpolateLinearlyFromDToFs) {
  const Scene s = load("fig002_6f_levels_T_sn");
  const char* names[] = {"l050", "l065", "l085", "l099"};
  const double levels[] = {0.5, 0.65, 0.85, 0.99};
  for (int i = 0; i < 4; ++i) {
    const SceneObject& o = object(s, names[i]);
    ASSERT_EQ(o.iso, levels[i]) << "the caption's levels";
    const double tau = blanc_inverse(levels[i]);
    for (const Vec3& u : directions()) {
      const double Id = 1 / fig6_d(u), Ifs = 1 / fig6_fs(u);
      ASSERT_LT(Ifs, Id) << "condition (c) of §4.6: f_s = 0.5 inside d = 0.5";
      const double expected = 0.5 * Id + (0.5 - tau) * (Ifs - Id);
      const double rho = crossing(o, fig6_centre(i), u, 0.4 * Ifs, 0.75 * Id);
      EXPECT_NEAR(rho, expected, 1e-7 * Id) << names[i];
      // [TS-1] at points inside f_s = 0.5 and between the two surfaces.
      EXPECT_EQ(o.field->value(fig6_centre(i) + u * (0.45 * Ifs)), 1);
      const Vec3 between = fig6_centre(i) + u * (0.5 * (0.5 * Ifs + 0.5 * Id));
      EXPECT_LT(o.field->value(between), 1);
    }
  }
}

// [TA-3]/[TS-2]: the transforms never move the soft object: the l = 0.5 objects of (b), (d) and
// (f) are the same surface d = 0.5, and so are inside at exactly the same points.
TEST(Fig002Fig6, TheHalfLevelIsTheSameSurfaceInBDF) {
  const Scene b = load("fig002_6b_levels"), d = load("fig002_6d_levels_T_an"),
              f = load("fig002_6f_levels_T_sn");
  const SceneObject* objs[] = {&object(b, "l050"), &object(d, "l050"), &object(f, "l050")};
  for (const Vec3& u : directions()) {
    const double Id = 1 / fig6_d(u);
    for (const SceneObject* o : objs)
      EXPECT_NEAR(crossing(*o, {0, 0, 0}, u, 0.3 * Id, 0.99 * Id), 0.5 * Id, 1e-9 * Id);
  }
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> x(-14, 14), y(-9, 9), z(-30, 30);
  int near_surface = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p{x(rng), y(rng), z(rng)};
    const double dp = fig6_d(p);
    if (std::abs(dp - 0.5) < 1e-9) {
      ++near_surface;
      continue;
    }
    for (const SceneObject* o : objs) EXPECT_EQ(o->field->value(p) >= 0.5, dp < 0.5);
  }
  EXPECT_LT(near_surface, 10);
}

// The levels of (b) are similar copies of d = 0.5 (each is d = P_b^-1(l)); those of (d) are not
// (they approach f_a = 0.5), which is what the figure contrasts.
TEST(Fig002Fig6, PlainLevelsAreScaledCopies) {
  const Scene b = load("fig002_6b_levels");
  const char* names[] = {"l050", "l035", "l015", "l001"};
  for (int i = 0; i < 4; ++i) {
    const SceneObject& o = object(b, names[i]);
    const double tau = blanc_inverse(o.iso);
    for (const Vec3& u : directions()) {
      const double Id = 1 / fig6_d(u);
      EXPECT_NEAR(crossing(o, fig6_centre(i), u, 0.3 * Id, 0.999 * Id), tau * Id, 1e-7 * Id);
    }
  }
}

// Fig. 8: points on the flush faces and outer corners of the chair's joints are inside the
// Perlin union of plain cylinders (b: bulges) and outside it with the modulated ones (c); points
// in the inner-corner fillets are inside both. Coordinates follow the layout in the scene header
// (members 6 thick on a 32-unit grid; each point lies 0.5 outside the members' surfaces).
TEST(Fig002Fig8, BulgesGoFilletsStay) {
  const Scene b_scene = load("fig002_8b_chair_bulges"), c_scene = load("fig002_8c_chair_no_bulges");
  const SceneObject& bb = b_scene.objects.at(0);
  const SceneObject& c = c_scene.objects.at(0);
  struct Probe {
    const char* where;
    Vec3 p;
  };
  const Probe bulges[] = {
      {"front face of the front-left leg at the front rail", {-16, -19.5, 35}},
      {"over the front-left leg top, under the seat corner", {-16, -16, 38.5}},
      {"outer face of the back-left leg/post joint at the rail caps", {-19.5, 16, 35}},
      {"outer face of the front-left leg at the stretcher end", {-19.5, -16, 12}},
      {"back face of the left post at the low back rail", {-16, 19.5, 49}},
      {"back face of the right post at the high back rail", {16, 19.5, 63}},
      {"top of the front-right leg", {16, -16, 38.5}},
  };
  for (const Probe& q : bulges) {
    EXPECT_GE(bb.field->value(q.p), 0.5) << "(b) bulges " << q.where;
    EXPECT_LT(c.field->value(q.p), 0.5) << "(c) has no bulge " << q.where;
  }
  const Probe fillets[] = {
      {"under the front rail, beside the front-left leg", {-12.5, -16, 31.5}},
      {"over the left stretcher, beside the front-left leg", {-16, -12.5, 15.5}},
      {"under the left stretcher, beside the back-left leg", {-16, 12.5, 8.5}},
      {"under the low back rail, beside the left post", {-12.5, 16, 45.5}},
      {"over the high back rail, beside the right post", {12.5, 16, 66.5}},
      {"over the right seat rail, beside the right post", {16, 12.5, 38.5}},
  };
  for (const Probe& q : fillets) {
    EXPECT_GE(bb.field->value(q.p), 0.5) << "(b) fillet " << q.where;
    EXPECT_GE(c.field->value(q.p), 0.5) << "(c) keeps the fillet " << q.where;
  }
  // Away from every joint (mid-span, 0.5 outside a member), neither picture adds material.
  const Vec3 plain[] = {{0, -19.5, 35}, {-19.5, -16, 24}, {0, 16, 52.5}};
  for (const Vec3& p : plain) {
    EXPECT_LT(bb.field->value(p), 0.5);
    EXPECT_LT(c.field->value(p), 0.5);
  }
}

// Fig. 9: the new f_a1 (t5 = t6 = 1 + 0.2/6) removes the blend between f_1's cap and the toroid
// (region b: the gap between them, 1 wide, around (0, 0, 19.5)) and changes nothing where
// |z| <= 16, since there ζ_L(z) = 0 and the t5, t6 terms of Eq. 18 vanish (region a included).
TEST(Fig002Fig9, NewModulationRemovesOnlyTheToroidBlend) {
  const Scene old_s = load("fig002_9d_toroid_blend"), new_s = load("fig002_9g_no_toroid_blend");
  const SceneObject& o = old_s.objects.at(0);
  const SceneObject& n = new_s.objects.at(0);
  for (double x : {-1.0, 0.0, 1.5}) {
    const Vec3 b{x, 0, 19.5};
    EXPECT_GE(o.field->value(b), 0.5) << "old f_a1: the bridge at region b";
    EXPECT_LT(n.field->value(b), 0.5) << "new f_a1: no bridge at region b";
  }
  // Region a: the fillets between f_2 and f_1's +x side, above and below f_2.
  for (const Vec3& a : {Vec3{3.5, 0, 3.5}, Vec3{3.5, 0, -3.5}}) {
    EXPECT_GE(o.field->value(a), 0.5);
    EXPECT_EQ(o.field->value(a), n.field->value(a));
  }
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> x(-20, 45), y(-12, 12), z(-16, 16), zc(-30, 50);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p{x(rng), y(rng), z(rng)};
    ASSERT_EQ(o.field->value(p), n.field->value(p)) << p.x << " " << p.y << " " << p.z;
  }
  // Beyond f_1's cap the two differ only within f_1's old outer zone (ζ < 3 + 3 = 6 there), so the
  // toroid's far side and f_2 are untouched.
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p{x(rng), y(rng), zc(rng)};
    const double zeta = std::max(std::abs(p.z) - 16, 0.0);
    const bool in_old_zone = zeta < 6 && std::abs(p.x) < 6 && std::abs(p.y) < 6;
    if (!in_old_zone) {
      ASSERT_EQ(o.field->value(p), n.field->value(p)) << p.x << " " << p.y << " " << p.z;
    }
  }
}

}  // namespace
}  // namespace softtrace
