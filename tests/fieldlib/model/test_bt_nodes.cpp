// The BT_k nodes and offset (blends_bt.h, offset.h): convention and parameter checks with
// located errors, the duals and BD_k against the scalar operator, per-box Lipschitz tightening,
// and bulge elimination ([BE-1]..[BE-5], value continuity, the true gradient,
// interval and region soundness).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "describe/params.h"
#include "kernels/bt_base.h"
#include "sweep.h"

namespace softtrace::test {
namespace {

using Rng = std::mt19937_64;
double uni(Rng& g, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(g);
}
Vec3 point_in(Rng& g, const Box& b) {
  return {uni(g, b.lo.x, b.hi.x), uni(g, b.lo.y, b.hi.y), uni(g, b.lo.z, b.hi.z)};
}

constexpr Convention kZero = Convention::Zero;
const char* const kBall1 =
    R"({"type":"offset","translate":[-0.3,0,0],"children":[{"type":"lp_metric","radii":[0.5,0.5,0.5],"n":2}]})";
const char* const kBall2 =
    R"({"type":"offset","translate":[0.3,0.1,0],"children":[{"type":"lp_metric","radii":[0.6,0.4,0.5],"n":3}]})";
#define ROD R"({"type":"segment","p0":[0,-1,0],"p1":[0,1,0.2],"radius":0.25})"
const char* const kRodDistance = ROD;
const char* const kRod = R"({"type":"offset","children":[)" ROD "]}";

std::string blend(const std::string& type, const std::string& params,
                  const std::vector<std::string>& children) {
  std::string s = R"({"type":")" + type + "\"," + params + R"(,"children":[)";
  for (size_t i = 0; i < children.size(); ++i) s += (i ? "," : "") + children[i];
  return s + "]}";
}

// The error message of building `json`, or "" when it builds.
std::string build_error(const std::string& json, Convention conv = kZero) {
  try {
    build_from_json(json, conv);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(BtNodes, OnlyTheZeroConvention) {
  for (const char* type : {"bt_union", "bt_intersection", "bt_difference", "displacement_union"}) {
    const std::string inner =
        blend(type, R"("base":"conic","r1":0.2,"r2":0.2,"p":0)", {kBall1, kRod});
    EXPECT_EQ(build_error(inner), "") << type;
    for (Convention c : {Convention::Soft, Convention::Constructive}) {
      const std::string e = build_error(inner, c);
      EXPECT_NE(e.find("<test>: /type:"), std::string::npos) << e;
      EXPECT_NE(e.find("zero convention"), std::string::npos) << e;
    }
  }
}

TEST(BtNodes, ParameterRangesAreCheckedWithTheirLocation) {
  struct Bad {
    std::string json, where;
  };
  const std::string c2 = R"("base":"conic","r1":0.2,"r2":0.3)";
  const Bad bad[] = {
      {blend("bt_union", c2 + R"(,"p":0.06)", {kBall1, kRod}), "/p"},  // p = r1 r2
      {blend("bt_union", R"("base":"conic","r1":0,"r2":0.3,"p":0)", {kBall1, kRod}), "/r1"},
      {blend("bt_union", c2 + R"(,"p":0)", {kBall1, kRod, kBall2}), "/children"},
      {blend("bt_union", c2 + R"(,"p":0,"m":[1,0])", {kBall1, kRod}), "/m/1"},
      {blend("bt_union", c2 + R"(,"p":0,"m":[1,1,1])", {kBall1, kRod}), "/m"},
      {blend("bt_union", R"("base":"cone","r1":0.2,"r2":0.3,"p":0)", {kBall1, kRod}), "/base"},
      {blend("bt_union", R"("base":"hyperellipsoid","r":[0.2,0.3],"p":[2,1])", {kBall1, kRod}),
       "/p"},
      {blend("bt_union", R"("base":"hyperellipsoid","r":[0.2,-0.3],"p":2)", {kBall1, kRod}),
       "/r/1"},
      {blend("bt_union", R"("base":"hyperellipsoid","r":[0.2,0.3,0.1],"p":2)", {kBall1, kRod}),
       "/r"},
      {blend("bt_union", R"("base":"hyperellipsoid","r":0.2,"p":2)", {kBall1}), "/children"},
      {blend("bt_union",
             R"("base":"hyperellipsoid","r":0.2,"p":2,"bulge_elimination":{"omega":0.1})",
             {kBall1, kRod, kBall2}),
       "/bulge_elimination"},
      {blend("bt_union", R"("base":"hyperellipsoid","r":0.2,"p":2,"bulge_elimination":{"omega":0})",
             {kBall1, kRod}),
       "/bulge_elimination/omega"},
      {blend("bt_union", R"("base":"hyperellipsoid","r":0.2,"p":2,"bulge_elimination":{})",
             {kBall1, kRod}),
       "/bulge_elimination/omega"},
      // An unknown key is named before the missing one (as everywhere in a scene).
      {blend("bt_union", R"("base":"hyperellipsoid","r":0.2,"p":2,"bulge_elimination":{"w":1})",
             {kBall1, kRod}),
       "/bulge_elimination/w"},
      {blend("bt_union", c2 + R"(,"p":0.01,"bulge_elimination":{"omega":0.1})", {kBall1, kRod}),
       "/p"},  // p >= omega² r1 r2
      {blend("displacement_union", c2 + R"(,"p":0,"m":[1,2])", {kBall1, kRod}), "/m"},
      {blend("bt_difference", c2 + R"(,"p":0,"k":2)", {kBall1, kRod}), "/k"},
      {blend("offset", R"("scale":0)", {kRodDistance}), "/scale"},
      {blend("offset", R"("level":0)", {kBall1, kRod}), "/children"},
  };
  for (const Bad& b : bad) {
    const std::string e = build_error(b.json);
    EXPECT_NE(e.find("<test>: " + b.where + ":"), std::string::npos)
        << "expected an error at " << b.where << " for " << b.json << "\ngot: " << e;
  }
  EXPECT_EQ(build_error(blend("bt_union", c2 + R"(,"p":0.0005,"bulge_elimination":{"omega":0.1})",
                              {kBall1, kRod})),
            "");
}

// The nodes are τ·BT(σ_i f_i) of §7.4 on their children's values.
TEST(BtNodes, DualsAndDisplacementMatchTheScalarOperator) {
  const NodePtr f1 = build_from_json(kBall1, kZero), f2 = build_from_json(kRod, kZero),
                f3 = build_from_json(kBall2, kZero);
  const std::string conic = R"("base":"conic","r1":0.3,"r2":0.2,"p":-0.02,"m":[1.5,0.7])";
  const std::string hyper =
      R"("base":"hyperellipsoid","r":[0.3,0.2,0.25],"p":[2,3,1.7],"m":[1.5,0.7,1])";
  const NodePtr u2 = build_from_json(blend("bt_union", conic, {kBall1, kRod}), kZero);
  const NodePtr i2 = build_from_json(blend("bt_intersection", conic, {kBall1, kRod}), kZero);
  const NodePtr d2 = build_from_json(blend("bt_difference", conic, {kBall1, kRod}), kZero);
  const NodePtr i3 =
      build_from_json(blend("bt_intersection", hyper, {kBall1, kRod, kBall2}), kZero);
  const NodePtr d3 = build_from_json(blend("bt_difference", hyper, {kBall1, kRod, kBall2}), kZero);
  const std::string unit = R"("base":"hyperellipsoid","r":[0.3,0.2,0.25],"p":[2,3,1.7])";
  const NodePtr bd =
      build_from_json(blend("displacement_union", unit, {kBall1, kRod, kBall2}), kZero);
  const NodePtr bt1 =
      build_from_json(blend("bt_union", unit + R"(,"m":[1,1,1])", {kBall1, kRod, kBall2}), kZero);
  const double m2[2] = {1.5, 0.7}, r3[3] = {0.3, 0.2, 0.25}, p3[3] = {2, 3, 1.7},
               m3[3] = {1.5, 0.7, 1}, one[3] = {1, 1, 1};
  Rng g(31);
  int blending = 0;
  for (int n = 0; n < 5000; ++n) {
    const Vec3 X = point_in(g, Box({-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2}));
    const double a = f1->value(X), b = f2->value(X), c = f3->value(X);
    const double xu[2] = {a, b}, xi[2] = {-a, -b}, xd[2] = {-a, b};
    const double vu = bt2_conic(xu, 0.3, 0.2, -0.02, m2, nullptr);
    if (vu != std::min(a / 1.5, b / 0.7)) ++blending;
    EXPECT_EQ(u2->value(X), vu);
    EXPECT_EQ(i2->value(X), -bt2_conic(xi, 0.3, 0.2, -0.02, m2, nullptr));
    EXPECT_EQ(d2->value(X), -bt2_conic(xd, 0.3, 0.2, -0.02, m2, nullptr));
    const double yi[3] = {-a, -b, -c}, yd[3] = {-a, b, c}, yu[3] = {a, b, c};
    EXPECT_EQ(i3->value(X), -bt_hyper(yi, 3, r3, p3, m3, nullptr, nullptr));
    EXPECT_EQ(d3->value(X), -bt_hyper(yd, 3, r3, p3, m3, nullptr, nullptr));
    EXPECT_EQ(bd->value(X), bt_hyper(yu, 3, r3, p3, one, nullptr, nullptr));
    EXPECT_EQ(bd->value(X), bt1->value(X));
  }
  EXPECT_GT(blending, 100);
}

TEST(BtNodes, BoxLipschitzDropsChildrenThatCannotBeActive) {
  // Two balls far apart with slopes 2 and 4, m = 1: globally max(2, 4) = 4; near the first ball
  // the second one's term is 0 over the whole box, so the bound there is the first's alone.
  const char* a =
      R"({"type":"offset","children":[{"type":"lp_metric","radii":[0.5,0.5,0.5],"n":2}]})";
  const char* b =
      R"({"type":"offset","translate":[3,0,0],"children":[{"type":"lp_metric","radii":[0.25,0.25,0.25],"n":2}]})";
  for (const char* base : {R"("base":"conic","r1":0.3,"r2":0.3,"p":0)",
                           R"("base":"hyperellipsoid","r":0.3,"p":2.5)"}) {
    const NodePtr u = build_from_json(blend("bt_union", base, {a, b}), kZero);
    EXPECT_DOUBLE_EQ(u->lipschitz(), 4);
    const Box near_a({-0.6, -0.6, -0.6}, {0.6, 0.6, 0.6});
    EXPECT_LE(u->lipschitz(near_a), 2 * (1 + 1e-12));
    const Box between({1, -0.2, -0.2}, {2, 0.2, 0.2});  // both terms may be active
    EXPECT_DOUBLE_EQ(u->lipschitz(between), 4);
  }
}

TEST(BtNodes, IntervalIsTheMonotoneImage) {
  const NodePtr u = build_from_json(
      blend("bt_union", R"("base":"hyperellipsoid","r":[0.3,0.2],"p":[2,3],"m":[1,2])",
            {kBall1, kRod}),
      kZero);
  const NodePtr f1 = build_from_json(kBall1, kZero), f2 = build_from_json(kRod, kZero);
  const double r[2] = {0.3, 0.2}, p[2] = {2, 3}, m[2] = {1, 2};
  Rng g(32);
  for (int n = 0; n < 200; ++n) {
    const Vec3 c = point_in(g, Box({-1, -1, -1}, {1, 1, 1}));
    const Box b = Box::around(c, uni(g, 1e-4, 0.2));
    const Interval A = f1->interval(b), B = f2->interval(b), I = u->interval(b);
    const double lo[2] = {A.lo, B.lo}, hi[2] = {A.hi, B.hi};
    const double vlo = bt_hyper(lo, 2, r, p, m, nullptr, nullptr);
    const double vhi = bt_hyper(hi, 2, r, p, m, nullptr, nullptr);
    EXPECT_LE(I.lo, vlo);
    EXPECT_GE(I.hi, vhi);
    EXPECT_NEAR(I.lo, vlo, 1e-8);  // only the documented padding
    EXPECT_NEAR(I.hi, vhi, 1e-8);
  }
}

TEST(Offset, ValueGradientAndRegion) {
  const NodePtr d = build_from_json(kRodDistance, Convention::Soft);
  const NodePtr o = build_from_json(
      R"({"type":"offset","scale":-2,"level":0.5,"children":[)" + std::string(kRodDistance) + "]}",
      kZero);
  Rng g(33);
  for (int n = 0; n < 1000; ++n) {
    const Vec3 X = point_in(g, Box({-1, -1, -1}, {1, 1, 1}));
    Vec3 gd, go;
    const double vd = d->eval(X, &gd), vo = o->eval(X, &go);
    EXPECT_DOUBLE_EQ(vo, -2 * (vd - 0.5));
    EXPECT_DOUBLE_EQ(go.x, -2 * gd.x);
    EXPECT_DOUBLE_EQ(go.z, -2 * gd.z);
  }
  EXPECT_DOUBLE_EQ(o->lipschitz(), 2 * d->lipschitz());
  // -2(d - 0.5) >= 0 ⇔ d <= 0.5: the child's Below region; the other side is unbounded.
  const Box r = o->region(0, Side::Above), rd = d->region(0.5, Side::Below);
  EXPECT_TRUE(r.bounded());
  EXPECT_LE(r.lo.x, rd.lo.x);
  EXPECT_GE(r.hi.y, rd.hi.y);
  EXPECT_FALSE(o->region(0, Side::Below).bounded());
}

// ---- Bulge elimination (docs/math.md §7.6)

TEST(BulgeElimination, PositionFunctionProperties) {  // [BE-1]..[BE-5]
  Rng g(34);
  for (int n = 0; n < 20000; ++n) {
    const double m1 = uni(g, 0.1, 3), m2 = uni(g, 0.1, 3), G = uni(g, 0.05, 20);
    double M[2];
    bulge_weights(m1, m2, G, 1.0, M);
    ASSERT_NEAR(M[0], G * M[1], 1e-12 * (1 + M[0]));  // [BE-1]
    bulge_weights(m1, m2, G, uni(g, -1, 0), M);
    ASSERT_EQ(M[0], m1);  // [BE-2]
    ASSERT_EQ(M[1], m2);
    const double c = uni(g, 0, 1);
    bulge_weights(m1, m2, G, c, M);
    ASSERT_GE(M[0], m1);  // [BE-3]
    ASSERT_GE(M[1], m2);
    double A[2], B[2];  // [BE-4]: across m1 = m2 G
    bulge_weights(m1, m2, m1 / m2 * (1 + 1e-12), c, A);
    bulge_weights(m1, m2, m1 / m2 * (1 - 1e-12), c, B);
    ASSERT_NEAR(A[0], B[0], 1e-9);
    ASSERT_NEAR(A[1], B[1], 1e-9);
    // [BE-5] and the range of P_i, including antiparallel and vanishing gradients.
    const Vec3 g1{uni(g, -1, 1), uni(g, -1, 1), uni(g, -1, 1)};
    const Vec3 g2 =
        n % 3 == 0 ? g1 * -uni(g, 0.1, 3) : (n % 3 == 1 ? Vec3{} : Vec3{uni(g, -1, 1), 0.3, 0});
    const double r[2] = {uni(g, 0.01, 2), uni(g, 0.01, 2)}, m[2] = {m1, m2}, w = uni(g, 1e-3, 0.2);
    const BulgeParameters b = bulge_parameters(g1, g2, r, m, w);
    for (int i = 0; i < 2; ++i) {
      ASSERT_GT(b.P[i], 0);
      ASSERT_GE(b.P[i], r[i] * w * (1 - 1e-12));
      ASSERT_LE(b.P[i], r[i] * (2 + w));
      ASSERT_TRUE(std::isfinite(b.M[i]) && b.M[i] >= m[i]);
    }
  }
}

// 003 Fig. 9(a): crossing cylinders (along z and along x), offset to zero-surface functions.
const char* const kCylZ =
    R"({"type":"offset","children":[{"type":"lp_metric","radii":[0.4,0.4,100],"n":2}]})";
const char* const kCylX =
    R"({"type":"offset","children":[{"type":"lp_metric","radii":[100,0.3,0.3],"n":2}]})";
const std::string kBulge = R"(,"bulge_elimination":{"omega":0.1})";
const std::string kBulgeBases[] = {
    R"("base":"conic","r1":0.3,"r2":0.2,"p":0,"m":[1,0.5])" + kBulge,
    R"("base":"hyperellipsoid","r":[0.3,0.2],"p":[2,3],"m":[0.7,1.2])" + kBulge,
    R"("base":"conic","r1":0.3,"r2":0.4,"p":-0.05,"m":[0.8,1])" + kBulge,
};

// The field is continuous away from the cylinders' axes (where ∇f_i, hence cosθ, jumps): along
// random segments in y >= 0.05, refining the step tenfold shrinks the largest jump accordingly.
TEST(BulgeElimination, ValueContinuity) {
  Rng g(35);
  for (const std::string& base : kBulgeBases)
    for (const char* type : {"bt_union", "bt_intersection", "bt_difference"}) {
      const NodePtr n = build_from_json(blend(type, base, {kCylZ, kCylX}), kZero);
      for (int s = 0; s < 10; ++s) {
        const Box dom({-1, 0.05, -1}, {1, 1, 1});
        const Vec3 a = point_in(g, dom), b = point_in(g, dom);
        double jump[2] = {0, 0};
        for (int level = 0; level < 2; ++level) {
          const int steps = level == 0 ? 1000 : 10000;
          double prev = n->value(a);
          for (int i = 1; i <= steps; ++i) {
            const double v = n->value(a + (b - a) * (double(i) / steps));
            jump[level] = std::max(jump[level], std::abs(v - prev));
            prev = v;
          }
        }
        const double step = length(b - a) / 1000;
        ASSERT_LT(jump[0], 20 * step) << type << " " << base;
        ASSERT_LT(jump[1], 0.2 * jump[0] + 1e-12) << type << " " << base;
      }
    }
}

// The value is BT(f(X); P(X), M(X)) with the position functions of bt_base.h at X, and the
// gradient is the true one (docs/math.md §7.6): the partial gradient with P and M frozen at X0
// (central differences of the frozen function) plus the position terms, so it differs from the
// frozen partial where the normals' angle varies.
TEST(BulgeElimination, ValueUsesThePositionFunctionsAndTheGradientTheirSlopes) {
  const NodePtr f1 = build_from_json(kCylZ, kZero), f2 = build_from_json(kCylX, kZero);
  const NodePtr n = build_from_json(blend("bt_union", kBulgeBases[0], {kCylZ, kCylX}), kZero);
  const double r[2] = {0.3, 0.2}, m[2] = {1, 0.5};
  Rng g(36);
  int blending = 0, apart = 0;
  for (int s = 0; s < 3000; ++s) {
    const Vec3 X0 = point_in(g, Box({-0.8, 0.05, -0.8}, {0.8, 0.8, 0.8}));
    Vec3 g1, g2;
    const double x0[2] = {f1->eval(X0, &g1), f2->eval(X0, &g2)};
    const BulgeParameters b = bulge_parameters(g1, g2, r, m, 0.1);
    auto frozen = [&](const Vec3& X) {
      const double x[2] = {f1->value(X), f2->value(X)};
      return bt2_conic(x, b.P[0], b.P[1], 0, b.M, nullptr);
    };
    ASSERT_EQ(n->value(X0), frozen(X0));
    if (!conic_region_ii(x0, b.P[0], b.P[1], b.M)) continue;
    ++blending;
    Vec3 partial;
    for (int i = 0; i < 3; ++i) {
      Vec3 a = X0, c = X0;
      a[i] += 1e-6;
      c[i] -= 1e-6;
      partial[i] = (frozen(a) - frozen(c)) / 2e-6;
    }
    if (length(n->gradient(X0) - partial) > 1e-3 * length(partial)) ++apart;
  }
  EXPECT_GT(blending, 100);
  EXPECT_GT(apart, blending / 2) << "the position terms are part of the gradient";
}

// The gradient is the true gradient of the evaluated field (docs/math.md §7.6): near the zero
// surface of the crossing cylinders it matches the central differences of the value to 0.1
// degrees for every base and dual, skipping points within ~1e-5 of a kink (two steps disagree).
TEST(BulgeElimination, GradientMatchesCentralDifferencesNearTheSurface) {
  for (const std::string& base : kBulgeBases)
    for (const char* type : {"bt_union", "bt_intersection", "bt_difference"}) {
      const NodePtr n = build_from_json(blend(type, base, {kCylZ, kCylX}), kZero);
      Rng g(38);
      double worst = 0;
      int count = 0, skipped = 0;
      for (int s = 0; s < 200000 && count < 1000; ++s) {
        const Vec3 X = point_in(g, Box({-0.8, -0.8, -0.8}, {0.8, 0.8, 0.8}));
        if (std::abs(n->value(X)) > 0.01) continue;
        Vec3 fd[2];
        for (int k = 0; k < 2; ++k)
          for (int i = 0; i < 3; ++i) {
            const double h = k == 0 ? 1e-6 : 4e-6;
            Vec3 a = X, c = X;
            a[i] += h;
            c[i] -= h;
            fd[k][i] = (n->value(a) - n->value(c)) / (2 * h);
          }
        const auto angle = [](const Vec3& u, const Vec3& v) {
          const double cosine = dot(u, v) / (length(u) * length(v));
          return std::acos(std::min(1.0, cosine)) * 180 / M_PI;
        };
        ++count;
        if (angle(fd[0], fd[1]) > 0.01) {
          ++skipped;
          continue;
        }
        const double degrees = angle(n->gradient(X), fd[0]);
        worst = std::max(worst, degrees);
        ASSERT_LT(degrees, 0.1) << type << " " << base << " at " << X.x << " " << X.y << " " << X.z;
      }
      EXPECT_GE(count, 500) << type << " " << base;  // the thinnest dual has ~560 in the box
      EXPECT_LE(skipped, count / 50) << type << " " << base;
    }
}

TEST(BulgeElimination, BoundsAreSound) {
  Rng g(37);
  const Box dom({-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2});
  for (const std::string& base : kBulgeBases)
    for (const char* type : {"bt_union", "bt_intersection", "bt_difference"}) {
      const NodePtr n = build_from_json(blend(type, base, {kCylZ, kCylX}), kZero);
      EXPECT_EQ(n->lipschitz(), std::numeric_limits<double>::infinity());
      int excluded = 0, bounded = 0;
      for (int k = 0; k < 300; ++k) {
        const Box b = Box::around(point_in(g, dom), std::exp(uni(g, -6, -1.5)));
        const Interval I = n->interval(b);
        const double L = n->lipschitz(b);
        if (I.lo > 0 || I.hi < 0) ++excluded;
        if (std::isfinite(L)) ++bounded;
        for (int j = 0; j < 30; ++j) {
          const Vec3 p = point_in(g, b), q = point_in(g, b);
          const double v = n->value(p);
          ASSERT_TRUE(I.contains(v))
              << type << ": " << v << " outside [" << I.lo << ", " << I.hi << "]";
          ASSERT_LE(std::abs(v - n->value(q)), L * length(p - q) * (1 + 1e-9) + 1e-12) << type;
        }
      }
      EXPECT_GT(excluded, 50) << type << ": the enclosure must let the renderer skip space";
      // Box bounds exist away from the cylinders' axes (where the children's Hessians blow up),
      // except for a conic base with p != 0 (blends_bt.h).
      if (base.find("\"p\":-0.05") != std::string::npos)
        EXPECT_EQ(bounded, 0) << type;
      else
        EXPECT_GT(bounded, 200) << type;
      const Box r = n->region(0, Side::Below);
      ASSERT_TRUE(r.bounded() || std::string(type) == "bt_difference");
      if (r.bounded()) {
        int inside = 0;
        for (int k = 0; k < 20000; ++k) {
          const Vec3 X = point_in(g, Box(r.lo - r.extent() * 0.5, r.hi + r.extent() * 0.5));
          if (n->value(X) > 0) continue;
          ++inside;
          ASSERT_TRUE(r.contains(X)) << type;
        }
        EXPECT_GT(inside, 0);
      }
      EXPECT_FALSE(n->region(0.1, Side::Below).bounded())
          << "documented: no finite bound above level 0 with M_i unbounded";
    }
}

// [003] Fig. 9's hub: crossing spokes offset(segment) with bulge elimination. Over boxes near the
// surface (within 0.3 of it, off the axes) the box Lipschitz bound of blends_bt.h is finite and
// bounds every sampled difference quotient; its looseness is measured, not asserted.
TEST(BulgeElimination, WheelHubBoxLipschitzBound) {
  const char* spoke_x =
      R"({"type":"offset","children":[{"type":"segment","p0":[-1.85,0,0],"p1":[1.85,0,0],"radius":0.16}]})";
  const char* spoke_y =
      R"({"type":"offset","children":[{"type":"segment","p0":[0,-1.85,0],"p1":[0,1.85,0],"radius":0.16}]})";
  Rng g(39);
  for (const char* m : {"[1,1]", "[0.3,1]", "[1,0.3]"}) {
    const NodePtr n = build_from_json(
        blend("bt_union",
              std::string(R"("base":"hyperellipsoid","r":[0.8,0.8],"p":[2,2],"m":)") + m + kBulge,
              {spoke_x, spoke_y}),
        kZero);
    double ratio_sum = 0, worst = 0;
    int boxes = 0;
    while (boxes < 400) {
      const Vec3 c = point_in(g, Box({-0.6, -0.6, -0.4}, {0.6, 0.6, 0.4}));
      if (std::abs(n->value(c)) > 0.3 / 0.16) continue;
      const Box b = Box::around(c, std::exp(uni(g, -7, -3)));
      const double reach = 0.5 * b.diagonal() * (1 + 1e-9);  // keep the boxes off the axes
      if (std::hypot(c.y, c.z) <= reach || std::hypot(c.x, c.z) <= reach) continue;
      const double L = n->lipschitz(b);
      ASSERT_TRUE(std::isfinite(L)) << m << " at " << c.x << " " << c.y << " " << c.z;
      double slope = 0;
      for (int j = 0; j < 40; ++j) {
        const Vec3 p = point_in(g, b), q = point_in(g, b);
        const double quotient = std::abs(n->value(p) - n->value(q)) / length(p - q);
        ASSERT_LE(quotient, L * (1 + 1e-9)) << m;
        slope = std::max(slope, quotient);
      }
      ratio_sum += L / slope;
      worst = std::max(worst, L / slope);
      ++boxes;
    }
    std::printf("m = %s: box bound / largest sampled slope, mean %.2f, max %.2f\n", m,
                ratio_sum / boxes, worst);
  }
}

}  // namespace
}  // namespace softtrace::test
