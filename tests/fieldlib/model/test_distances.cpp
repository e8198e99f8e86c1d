// Distance-function properties of docs/math.md §2: ray-linearity [RL-1]..[RL-3], the modulation
// surfaces' side lengths [DF-1]..[DF-5], [DF-7], the segment [DF-6], and parameter validation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "describe/params.h"
#include "sweep.h"

namespace softtrace::test {
namespace {

Vec3 random_point(std::mt19937_64& rng, double r) {
  std::uniform_real_distribution<double> u(-r, r);
  return {u(rng), u(rng), u(rng)};
}

// Nodes ray-linear about the origin (docs/math.md §2.1 [RL-1] list, plus the polar prisms and the
// super-ellipsoidal blends of ray-linear children, §2.1 "Closure").
const char* const kRayLinear[] = {
    R"({"type":"parallel_planes","normal":[1,2,-0.5],"a":0.7})",
    R"({"type":"one_branch_plane","normal":[0.3,-1,0.4],"a":0.5})",
    R"({"type":"lp_metric","radii":[1,2,0.5],"n":3})",
    R"({"type":"superquadric","radii":[1,0.8,1.2],"n1":0.6,"n2":3,"t":[1.5,0.7,2,1,1.2,0.6]})",
    R"({"type":"generalized_distance","normals":[[1,1,1],[1,-1,1],[-1,1,1],[1,1,-1]],"a":0.8,
        "n":4,"t_pos":[1,1.5,2,1],"t_neg":[1.2,1,1,0.7]})",
    R"({"type":"superelliptic_cylinder","radii":[0.5,0.7,0.4],"n":2,"half_length":0,
        "t":[1.2,2,1,1.5,1.3,0.7]})",
    R"({"type":"polar_prism","radius":8,"lobes":5,"amplitude":0.3,"profile":"cosine",
        "half_height":24})",
    R"({"type":"polar_prism","radius":13,"lobes":5,"amplitude":0.35,"profile":"triangle",
        "half_height":24,"n":3})",
    R"({"type":"super_ellipsoidal_union","n":4,"children":[
         {"type":"lp_metric","radii":[1,0.5,0.5],"n":2},
         {"type":"superquadric","radii":[0.4,0.8,0.6],"n1":1.5,"n2":3,"t":[1,1,2,1,1,1]}]})",
    R"({"type":"super_ellipsoidal_intersection","n":0.8,"children":[
         {"type":"one_branch_plane","normal":[1,0,0],"a":1},
         {"type":"lp_metric","radii":[1,1,0.6],"n":2},
         {"type":"polar_prism","radius":0.8,"lobes":4,"amplitude":0.2,"profile":"cosine",
          "half_height":1}]})",
};

class RayLinear : public testing::TestWithParam<const char*> {};

TEST_P(RayLinear, HomogeneousOfDegreeOne) {  // [RL-1]
  const NodePtr f = build_from_json(GetParam());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> scale(0, 4);
  for (int i = 0; i < 500; ++i) {
    const Vec3 X = random_point(rng, 2);
    const double a = i == 0 ? 0.0 : scale(rng);
    EXPECT_NEAR(f->value(X * a), a * f->value(X), 1e-12 * (1 + a * f->value(X)));
  }
  EXPECT_EQ(f->value({0, 0, 0}), 0);
}

TEST_P(RayLinear, InfluentialRadiusReachesTheSurface) {  // [RL-2], [RL-3]
  const NodePtr f = build_from_json(GetParam());
  std::mt19937_64 rng(12);
  int checked = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 X = random_point(rng, 2);
    const double fx = f->value(X), rho = length(X);
    if (!(fx > 1e-9)) continue;  // I_f = ∞: the ray never meets f = 1 (one-branch planes)
    ++checked;
    const double I = rho / fx;
    EXPECT_NEAR(f->value(X * (I / rho)), 1, 1e-12);
    for (double a : {0.25, 3.0}) EXPECT_NEAR(rho * a / f->value(X * a), I, 1e-12 * I);
  }
  EXPECT_GT(checked, 100);
}

INSTANTIATE_TEST_SUITE_P(Distances, RayLinear, testing::ValuesIn(kRayLinear));

// Eq. 3 written out independently of the implementation.
double superquadric(const Vec3& p, const Vec3& a, double n1, double n2) {
  const double h =
      std::pow(std::pow(std::abs(p.x / a.x), n1) + std::pow(std::abs(p.y / a.y), n1), n2 / n1);
  return std::pow(h + std::pow(std::abs(p.z / a.z), n2), 1 / n2);
}

// Eq. 17 written out: m(h(x, y), ζ_L(z)) with one exponent n.
double cylinder(const Vec3& p, const Vec3& a, double n, double L) {
  const double zeta = std::max(std::abs(p.z) - L, 0.0);
  return std::pow(
      std::pow(std::abs(p.x / a.x), n) + std::pow(std::abs(p.y / a.y), n) + std::pow(zeta / a.z, n),
      1 / n);
}

TEST(ModulatedDistances, AllSideLengthsOneGiveThePrimitive) {  // [DF-1]
  const NodePtr sq = build_from_json(
      R"({"type":"superquadric","radii":[1,0.8,1.2],"n1":0.6,"n2":3,"t":[1,1,1,1,1,1]})");
  const NodePtr gd = build_from_json(
      R"({"type":"generalized_distance","normals":[[1,1,0],[0,1,-1],[1,0,2]],"a":[1,0.5,2],
          "n":2.5,"t_pos":[1,1,1],"t_neg":[1,1,1]})");
  const NodePtr gd0 = build_from_json(
      R"({"type":"generalized_distance","normals":[[1,1,0],[0,1,-1],[1,0,2]],"a":[1,0.5,2],
          "n":2.5})");
  const NodePtr cy = build_from_json(
      R"({"type":"superelliptic_cylinder","radii":[0.5,0.7,0.4],"n":3,"half_length":0.6,
          "t":[1,1,1,1,1,1]})");
  const Vec3 n[3] = {normalize({1, 1, 0}), normalize({0, 1, -1}), normalize({1, 0, 2})};
  const double a[3] = {1, 0.5, 2};
  std::mt19937_64 rng(13);
  for (int i = 0; i < 500; ++i) {
    const Vec3 X = random_point(rng, 2);
    EXPECT_NEAR(sq->value(X), superquadric(X, {1, 0.8, 1.2}, 0.6, 3), 1e-13);
    double s = 0;
    for (int k = 0; k < 3; ++k) s += std::pow(std::abs(dot(X, n[k])) / a[k], 2.5);
    EXPECT_NEAR(gd->value(X), std::pow(s, 1 / 2.5), 1e-13);
    EXPECT_EQ(gd->value(X), gd0->value(X));
    EXPECT_NEAR(cy->value(X), cylinder(X, {0.5, 0.7, 0.4}, 3, 0.6), 1e-13);
  }
}

TEST(ModulatedDistances, AllSideLengthsTwoHalveTheDistance) {  // [DF-2]
  const std::pair<const char*, const char*> pairs[] = {
      {R"({"type":"superquadric","radii":[1,0.8,1.2],"n1":1.5,"n2":3})",
       R"({"type":"superquadric","radii":[1,0.8,1.2],"n1":1.5,"n2":3,"t":[2,2,2,2,2,2]})"},
      {R"({"type":"generalized_distance","normals":[[1,1,0],[0,1,-1],[1,0,2],[1,1,1]],"a":0.7,
           "n":6})",
       R"({"type":"generalized_distance","normals":[[1,1,0],[0,1,-1],[1,0,2],[1,1,1]],"a":0.7,
           "n":6,"t_pos":[2,2,2,2],"t_neg":[2,2,2,2]})"},
      {R"({"type":"superelliptic_cylinder","radii":[0.5,0.7,0.4],"n":3,"half_length":0.6})",
       R"({"type":"superelliptic_cylinder","radii":[0.5,0.7,0.4],"n":3,"half_length":0.6,
           "t":[2,2,2,2,2,2]})"},
  };
  std::mt19937_64 rng(14);
  for (const auto& [plain, halved] : pairs) {
    const NodePtr d = build_from_json(plain), fa = build_from_json(halved);
    for (int i = 0; i < 300; ++i) {
      const Vec3 X = random_point(rng, 2);
      EXPECT_NEAR(fa->value(X), d->value(X) / 2, 1e-14 * (1 + d->value(X))) << halved;
    }
  }
}

TEST(ModulatedDistances, GeneralizedWithTheAxesIsTheLpMetric) {  // [DF-3]
  for (double n : {0.7, 1.0, 1.5, 2.0, 20.0}) {
    const std::string e = std::to_string(n);
    const NodePtr gd = build_from_json(
        R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[1,2,0.5],"n":)" +
        e + "}");
    const NodePtr lp = build_from_json(R"({"type":"lp_metric","radii":[1,2,0.5],"n":)" + e + "}");
    std::mt19937_64 rng(15);
    for (int i = 0; i < 300; ++i) {
      const Vec3 X = random_point(rng, 2);
      EXPECT_NEAR(gd->value(X), lp->value(X), 1e-14 * (1 + lp->value(X)));
      EXPECT_LE(length(gd->gradient(X) - lp->gradient(X)), 1e-12 * (1 + length(lp->gradient(X))));
    }
    // The operator-norm bound reduces to the LP metric's exactly (σ_max = 1 for the axes).
    if (n >= 1) {
      EXPECT_NEAR(gd->lipschitz(), lp->lipschitz(), 1e-10 * lp->lipschitz()) << n;
    } else {
      EXPECT_FALSE(std::isfinite(gd->lipschitz())) << "no global bound below exponent 1";
    }
  }
}

// Bisection for f(p0 + s·dir) = level, f increasing in s on [0, s_max].
double crossing(const FieldNode& f, const Vec3& p0, const Vec3& dir, double level, double s_max) {
  double lo = 0, hi = s_max;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f.value(p0 + dir * mid) < level ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(ModulatedDistances, SmallSideLengthLeavesABandOfHalfOmega) {  // [DF-4]
  const double L = 10;
  for (double omega : {0.05, 0.1, 0.2}) {
    const double t = 1 + omega / 6;
    // Side 1 (+x), side 4 (-y) and side 6 (-z) suppressed; the others keep the blend (t = 2).
    char ts[32];
    std::snprintf(ts, sizeof ts, "%.17g", t);
    const NodePtr d = build_from_json(
        R"({"type":"superelliptic_cylinder","radii":[6,6,6],"n":4,"half_length":10})");
    const NodePtr fa = build_from_json(
        R"({"type":"superelliptic_cylinder","radii":[6,6,6],"n":4,"half_length":10,"t":[)" +
        std::string(ts) + ",2,2," + ts + ",2," + ts + "]}");
    struct Ray {
      Vec3 origin, dir;
      bool suppressed;
    };
    const Ray rays[] = {{{0, 0, 3}, {1, 0, 0}, true},   {{0, 0, -7}, {-1, 0, 0}, false},
                        {{0, 0, 0}, {0, -1, 0}, true},  {{0, 0, 9}, {0, 1, 0}, false},
                        {{0, 0, -L}, {0, 0, -1}, true}, {{0, 0, L}, {0, 0, 1}, false}};
    for (const Ray& r : rays) {
      const double sd = crossing(*d, r.origin, r.dir, 0.5, 20);
      const double sa = crossing(*fa, r.origin, r.dir, 0.5, 20);
      EXPECT_NEAR(sd, 3, 1e-9);
      EXPECT_NEAR(sa - sd, r.suppressed ? omega / 2 : 3, 1e-9) << omega;
    }
  }
}

TEST(ModulatedDistances, RegionBoxIsTheSideLengthBox) {  // [DF-5]
  const NodePtr sq = build_from_json(
      R"({"type":"superquadric","radii":[1,0.8,1.2],"n1":0.6,"n2":3,"t":[1.5,0.7,2,1,1.2,0.6]})");
  const NodePtr cy = build_from_json(
      R"({"type":"superelliptic_cylinder","radii":[1,0.8,1.2],"n":0.7,"half_length":2,
          "t":[1.5,0.7,2,1,1.2,0.6]})");
  const double c = 0.5, t[6] = {1.5, 0.7, 2, 1, 1.2, 0.6}, a[3] = {1, 0.8, 1.2};
  const Box bs = sq->region(c, Side::Below), bc = cy->region(c, Side::Below);
  for (int i = 0; i < 3; ++i) {
    const double grow = i == 2 ? 2 : 0;
    EXPECT_NEAR(bs.hi[i], c * t[2 * i] * a[i], 1e-10);
    EXPECT_NEAR(bs.lo[i], -c * t[2 * i + 1] * a[i], 1e-10);
    EXPECT_NEAR(bc.hi[i], c * t[2 * i] * a[i] + grow, 1e-10);
    EXPECT_NEAR(bc.lo[i], -c * t[2 * i + 1] * a[i] - grow, 1e-10);
    // The box is tight: its faces touch {f <= c} on the axes.
    Vec3 hi, lo;
    hi[i] = c * t[2 * i] * a[i] + grow;
    lo[i] = -c * t[2 * i + 1] * a[i] - grow;
    EXPECT_NEAR(cy->value(hi), c, 1e-12);
    EXPECT_NEAR(cy->value(lo), c, 1e-12);
    if (grow == 0) {
      EXPECT_NEAR(sq->value(hi), c, 1e-12);
      EXPECT_NEAR(sq->value(lo), c, 1e-12);
    }
  }
  EXPECT_TRUE(sq->region(-0.1, Side::Below).empty());
}

TEST(SkeletalDistances, SegmentMatchesBruteForce) {  // [DF-6]
  const Vec3 A{-0.5, 0.2, 0.1}, B{0.7, -0.3, 0.4};
  const double Ir = 0.8;
  const NodePtr f =
      build_from_json(R"({"type":"segment","p0":[-0.5,0.2,0.1],"p1":[0.7,-0.3,0.4],"radius":0.8})");
  std::mt19937_64 rng(16);
  for (int i = 0; i < 200; ++i) {
    const Vec3 X = random_point(rng, 2);
    double best = 1e300;
    for (int j = 0; j <= 20000; ++j) best = std::min(best, length(X - (A + (B - A) * (j / 2e4))));
    // The grid's spacing |B - A|/2e4 bounds the brute force's excess over the true minimum.
    EXPECT_LE(f->value(X) * Ir, best + 1e-12);
    EXPECT_GE(f->value(X) * Ir, best - length(B - A) / 2e4);
  }
  const Vec3 side = normalize(cross(B - A, {0, 0, 1}));
  EXPECT_NEAR(f->value((A + B) * 0.5 + side * (Ir / 2)), 0.5, 1e-14);
  EXPECT_NEAR(f->value(B + normalize(B - A) * (Ir / 2)), 0.5, 1e-14);
}

TEST(SkeletalDistances, CylinderHalfLevel) {  // [DF-7]
  const NodePtr d = build_from_json(
      R"({"type":"superelliptic_cylinder","radii":[0.5,0.7,0.4],"n":3,"half_length":0.6})");
  for (double z : {-0.6, -0.3, 0.0, 0.45, 0.6}) {
    EXPECT_NEAR(d->value({0.25, 0, z}), 0.5, 1e-14);
    EXPECT_NEAR(d->value({0, -0.35, z}), 0.5, 1e-14);
  }
  EXPECT_NEAR(d->value({0, 0, 0.8}), 0.5, 1e-14);
  EXPECT_NEAR(d->value({0, 0, -0.8}), 0.5, 1e-14);
  EXPECT_EQ(d->value({0, 0, 0.3}), 0) << "the spine is the skeleton";
}

TEST(SkeletalDistances, TorusAboutItsCircle) {
  const NodePtr d = build_from_json(R"({"type":"torus","major_radius":2,"radii":[0.5,0.3]})");
  for (double phi : {0.0, 0.7, 2.5, -1.9}) {
    const Vec3 e{std::cos(phi), std::sin(phi), 0};
    EXPECT_NEAR(d->value(e * 2.25), 0.5, 1e-14);
    EXPECT_NEAR(d->value(e * 1.75), 0.5, 1e-14);
    EXPECT_NEAR(d->value(e * 2 + Vec3{0, 0, 0.15}), 0.5, 1e-14);
    EXPECT_EQ(d->value(e * 2), 0);
    // Ray-linear about the nearest skeleton point.
    const Vec3 q = e * 2, dir = normalize(Vec3{e.x, e.y, 0.8});
    EXPECT_NEAR(d->value(q + dir * 0.3), 3 * d->value(q + dir * 0.1), 1e-13);
  }
  const Vec3 g = d->gradient({0, 0, 0.2});  // on the axis: a kink, any subgradient, no NaN
  EXPECT_TRUE(isfinite(g));
  EXPECT_NEAR(d->value({0, 0, 0}), 4, 1e-14);
}

TEST(PolarPrism, UnitLevelFollowsTheProfile) {
  const NodePtr rose = build_from_json(
      R"({"type":"polar_prism","radius":8,"lobes":5,"amplitude":0.3,"profile":"cosine",
          "half_height":24})");
  const NodePtr star = build_from_json(
      R"({"type":"polar_prism","radius":13,"lobes":5,"amplitude":0.35,"profile":"triangle",
          "half_height":24})");
  for (int i = 0; i < 100; ++i) {
    const double phi = -M_PI + 2 * M_PI * (i + 0.37) / 100;
    const Vec3 e{std::cos(phi), std::sin(phi), 0};
    const double Rr = 8 * (1 + 0.3 * std::cos(5 * phi));
    const double Rs = 13 * (1 + 0.35 * 2 / M_PI * std::asin(std::cos(5 * phi)));
    EXPECT_NEAR(rose->value(e * Rr), 1, 1e-13);
    EXPECT_NEAR(star->value(e * Rs), 1, 1e-12);
    EXPECT_NEAR(rose->value(e * Rr * 0.5 + Vec3{0, 0, 3}), 0.5,
                1e-6);  // (0.5^20 + 0.125^20)^(1/20)
  }
  EXPECT_NEAR(star->value({0, 0, 12}), 0.5, 1e-15);
  EXPECT_TRUE(isfinite(star->gradient({0, 0, 1})));
  // The star's kinks: the slope bound also covers the triangle wave's corners.
  EXPECT_GE(star->lipschitz(), 1 / (13 * 0.65));
}

TEST(PolarPrism, GlobalSlopeIsTheLargestCrossSectionGradient) {
  // On z = 0, f = h and ∇f = ∇h, which depends on φ only: the bound derived in the class comment
  // must cover the largest |∇h| over a fine φ grid and, being exact, match it.
  for (const char* profile : {"cosine", "triangle"})
    for (const auto& [k, A] : {std::pair{5, 0.3}, std::pair{2, 0.6}, std::pair{1, 0.9}}) {
      const NodePtr f =
          build_from_json(std::string(R"({"type":"polar_prism","radius":2,"lobes":)") +
                          std::to_string(k) + R"(,"amplitude":)" + std::to_string(A) +
                          R"(,"profile":")" + profile + R"(","half_height":100,"n":2})");
      double g_max = 0;
      for (int i = 0; i < 200000; ++i) {
        const double phi = 2 * M_PI * (i + 0.5) / 200000;
        g_max = std::max(g_max, length(f->gradient({std::cos(phi), std::sin(phi), 0})));
      }
      EXPECT_GE(f->lipschitz(), g_max) << profile << " k=" << k;
      // The star's largest slope is at its corners, which the grid approaches only to ~1e-4.
      const double tolerance = std::string(profile) == "cosine" ? 1e-6 : 1e-3;
      EXPECT_LE(f->lipschitz(), g_max * (1 + tolerance)) << profile << " k=" << k;
    }
}

TEST(SuperEllipsoidal, UnionBelowMinIntersectionAboveMax) {  // [RC-1]
  const char* kids = R"([{"type":"lp_metric","radii":[1,0.5,0.5],"n":2},
                         {"type":"torus","major_radius":0.5,"radii":[0.2,0.3]},
                         {"type":"one_branch_plane","normal":[0,0,1],"a":0.4}])";
  const NodePtr u = build_from_json(
      std::string(R"({"type":"super_ellipsoidal_union","n":3,"children":)") + kids + "}");
  const NodePtr I = build_from_json(
      std::string(R"({"type":"super_ellipsoidal_intersection","n":3,"children":)") + kids + "}");
  const NodePtr c[3] = {build_from_json(R"({"type":"lp_metric","radii":[1,0.5,0.5],"n":2})"),
                        build_from_json(R"({"type":"torus","major_radius":0.5,"radii":[0.2,0.3]})"),
                        build_from_json(R"({"type":"one_branch_plane","normal":[0,0,1],"a":0.4})")};
  std::mt19937_64 rng(17);
  int zero_guarded = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 X = random_point(rng, 1.5);
    const double x[3] = {c[0]->value(X), c[1]->value(X), c[2]->value(X)};
    const double mn = std::min({x[0], x[1], x[2]}), mx = std::max({x[0], x[1], x[2]});
    EXPECT_LE(u->value(X), mn * (1 + 1e-15));
    EXPECT_GE(u->value(X), mn / std::cbrt(3.0) * (1 - 1e-15));
    EXPECT_GE(I->value(X), mx * (1 - 1e-15));
    EXPECT_LE(I->value(X), mx * std::cbrt(3.0) * (1 + 1e-15));
    if (x[2] == 0) {  // the one-branch plane is 0 below z = 0: the union's zero guard
      ++zero_guarded;
      EXPECT_EQ(u->value(X), 0);
      EXPECT_TRUE(isfinite(u->gradient(X)));
    }
  }
  EXPECT_GT(zero_guarded, 100);
}

TEST(DistanceBounds, FiniteOverBoxesAwayFromSingularPlanes) {  // docs/math.md §8, exponents < 1
  const std::pair<const char*, Box> cases[] = {
      {R"({"type":"superquadric","radii":[0.8,1,0.9],"n1":0.6,"n2":2.5,"t":[1,1.3,0.8,1,2,1]})",
       Box({0.2, 0.3, 0.1}, {0.4, 0.5, 0.3})},
      {R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1],[1,1,1]],"a":1,
          "n":0.7})",
       Box({-0.5, -0.4, -0.6}, {-0.3, -0.2, -0.4})},
      {R"({"type":"superelliptic_cylinder","radii":[0.6,0.6,0.5],"n":0.8,"half_length":0.3})",
       Box({0.1, 0.1, 0.5}, {0.3, 0.2, 0.7})},
      {R"({"type":"torus","major_radius":0.7,"radii":[0.4,0.4],"n":0.7})",
       Box({1.0, 0.1, 0.2}, {1.2, 0.3, 0.4})},
      {R"({"type":"super_ellipsoidal_intersection","n":0.8,"children":[
          {"type":"lp_metric","radii":[1,0.6,0.8],"n":2},
          {"type":"polar_prism","radius":0.8,"lobes":4,"amplitude":0.2,"profile":"cosine",
           "half_height":1}]})",
       Box({0.3, 0.3, 0.3}, {0.5, 0.5, 0.5})},
  };
  for (const auto& [json, box] : cases) {
    const NodePtr f = build_from_json(json);
    EXPECT_FALSE(std::isfinite(f->lipschitz())) << json;
    const double L = f->lipschitz(box);
    EXPECT_TRUE(std::isfinite(L)) << json;
    // ...and not absurdly loose: within 10x of the gradient at the box's centre.
    EXPECT_LT(L, 10 * length(f->gradient(box.center()))) << json;
  }
}

// The LP metric's interval over a box holds the exact value at every point of it (long double,
// 11 more bits): radii whose reciprocals are not doubles, tiny and huge magnitudes, point boxes
// (where only the widening of each rounding separates the ends from the value), n = 2 (the square
// root's path) and not.
TEST(DistanceBounds, LpMetricIntervalHoldsTheExactValue) {
  const struct {
    Vec3 a;
    double n;
  } cases[] = {{{3, 0.1, 7}, 2},
               {{3, 3, 3}, 2},
               {{0.3, 1e-3, 11}, 3},
               {{3, 0.7, 1.3}, 20},
               {{1e-6, 1e6, 0.9}, 2.5}};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1), mag(-8, 8);
  for (const auto& [a, n] : cases) {
    char json[160];
    std::snprintf(json, sizeof json,
                  R"({"type":"lp_metric","radii":[%.17g,%.17g,%.17g],"n":%.17g})", a.x, a.y, a.z,
                  n);
    const NodePtr f = build_from_json(json);
    for (int i = 0; i < 2000; ++i) {
      const double scale = std::pow(10.0, mag(rng));
      const Vec3 p = Vec3{unit(rng), unit(rng), unit(rng)} * scale;
      const Vec3 h = i % 2 ? Vec3{}
                           : Vec3{std::abs(unit(rng)), std::abs(unit(rng)), std::abs(unit(rng))} *
                                 (0.1 * scale);
      const Interval I = f->interval(Box(p - h, p + h));
      long double s = 0;
      for (int k = 0; k < 3; ++k)
        s += std::pow(std::abs(static_cast<long double>(p[k])) / a[k], static_cast<long double>(n));
      const long double exact = std::pow(s, 1 / static_cast<long double>(n));
      ASSERT_LE(I.lo, exact) << json << " at " << p.x << ", " << p.y << ", " << p.z;
      ASSERT_GE(I.hi, exact) << json << " at " << p.x << ", " << p.y << ", " << p.z;
    }
  }
}

void expect_error(const std::string& json, const std::string& where, const std::string& what) {
  try {
    build_from_json(json);
    ADD_FAILURE() << "accepted: " << json;
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(where), std::string::npos) << m;
    EXPECT_NE(m.find(what), std::string::npos) << m;
  }
}

TEST(DistanceParameters, RangesAreValidated) {
  expect_error(R"({"type":"parallel_planes","normal":[0,0,0],"a":1})", "/normal", "non-zero");
  expect_error(R"({"type":"one_branch_plane","normal":[0,0,1],"a":0})", "/a", "> 0");
  expect_error(R"({"type":"superquadric","radii":[1,1,1],"n1":1,"n2":2,"t":[1,1,1,1,1]})", "/t",
               "6 numbers");
  expect_error(R"({"type":"superquadric","radii":[1,1,1],"n1":1,"n2":2,"t":[1,1,1,1,0,1]})", "/t/4",
               "side length > 0");
  expect_error(R"({"type":"generalized_distance","normals":[[1,0,0],[0,0,0]],"a":1,"n":2})",
               "/normals/1", "non-zero");
  expect_error(R"({"type":"generalized_distance","normals":[[1,0,0],[0,1]],"a":1,"n":2})",
               "/normals/1", "[x, y, z]");
  expect_error(R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0]],"a":[1,2,3],"n":2})",
               "/a", "2 numbers");
  expect_error(R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0]],"a":[1,-2],"n":2})",
               "/a/1", "> 0");
  expect_error(
      R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0]],"a":1,"n":2,"t_neg":[1]})",
      "/t_neg", "2 side lengths");
  expect_error(R"({"type":"generalized_distance","normals":[[1,0,0]],"a":1,"n":-2})", "/n", "> 0");
  expect_error(R"({"type":"superelliptic_cylinder","radii":[1,1,1],"n":2,"half_length":-1})",
               "/half_length", "L >= 0");
  expect_error(R"({"type":"superelliptic_cylinder","radii":[1,0,1],"n":2,"half_length":1})",
               "/radii/1", "radius > 0");
  expect_error(R"({"type":"torus","major_radius":-1,"radii":[1,1]})", "/major_radius", "R >= 0");
  expect_error(R"({"type":"torus","major_radius":1,"radii":[1,1,1]})", "/radii", "2 numbers");
  expect_error(R"({"type":"torus","major_radius":1,"radii":[1,1],"n":0})", "/n", "> 0");
  const std::string prism =
      R"({"type":"polar_prism","radius":1,"half_height":1,"profile":"cosine",)";
  expect_error(prism + R"("lobes":3,"amplitude":1})", "/amplitude", "A in [0, 1)");
  expect_error(prism + R"("lobes":0,"amplitude":0.3})", "/lobes", "integer in [1,");
  expect_error(prism + R"("lobes":2.5,"amplitude":0.3})", "/lobes", "integer");
  expect_error(
      R"({"type":"polar_prism","radius":1,"half_height":1,"profile":"square","lobes":3,
          "amplitude":0.3})",
      "/profile", "\"triangle\"");
  expect_error(R"({"type":"super_ellipsoidal_union","n":2,"children":[{"type":"lp_metric",
                   "radii":[1,1,1],"n":2}]})",
               "/children", "at least 2");
  expect_error(R"({"type":"super_ellipsoidal_intersection","n":0,"children":[]})", "/n", "> 0");
}

}  // namespace
}  // namespace softtrace::test
