// Blend properties of docs/math.md §5 and §6.3: [PE-1..3], [RC-1..3], A5, [RS-1..3], [SC-1..4], the
// complement, min/max, and parameter validation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "describe/params.h"
#include "kernels/complement.h"
#include "model/blends.h"
#include "sweep.h"

namespace softtrace {
namespace {

using test::build_from_json;
using test::for_random_points;

const std::string kA =
    R"({"type":"soft_object","translate":[-0.4,0,0],"distance":{"type":"lp_metric","radii":[1,0.8,1.1],"n":2}})";
const std::string kB =
    R"({"type":"soft_object","translate":[0.5,0.2,0],"distance":{"type":"superquadric","radii":[0.9,1.2,0.8],"n1":2,"n2":4}})";
const std::string kC =
    R"({"type":"soft_object","translate":[0,-0.3,0.4],"distance":{"type":"lp_metric","radii":[0.7,0.7,1.3],"n":3}})";
const std::string kFar =
    R"({"type":"soft_object","translate":[50,0,0],"distance":{"type":"lp_metric","radii":[1,1,1],"n":2}})";
// Equal to 1 for |X| < 25 (the zero branch of T_n with w2 = 0.5 on a radius-100 sphere).
const std::string kOne =
    R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[100,100,100],"n":2},"radii":{"type":"T_n","w1":1,"w2":0.5}})";

std::string blend(const std::string& type, const std::vector<std::string>& c,
                  const std::string& extra = "") {
  std::string s = R"({"type":")" + type + "\"" + extra + R"(,"children":[)";
  for (size_t i = 0; i < c.size(); ++i) s += (i ? "," : "") + c[i];
  return s + "]}";
}
std::string comp(const std::string& c) {
  return blend("complement", {c});
}

void expect_same_field(const FieldNode& a, const FieldNode& b, double r, double tol) {
  for_random_points(2000, r, 7, [&](const Vec3& p) {
    Vec3 ga, gb;
    ASSERT_NEAR(a.eval(p, &ga), b.eval(p, &gb), tol);
    ASSERT_NEAR(length(ga - gb), 0, tol * 10);
  });
}

TEST(Perlin, DualitiesWithTheSoftComplement) {  // [PE-1]
  const auto pi = build_from_json(blend("perlin_intersection", {kA, kB, kC}));
  const auto pi_dual = build_from_json(comp(blend("perlin_union", {comp(kA), comp(kB), comp(kC)})));
  expect_same_field(*pi, *pi_dual, 2, 1e-14);
  const auto pd = build_from_json(blend("perlin_difference", {kA, kB, kC}));
  const auto pd_i = build_from_json(blend("perlin_intersection", {kA, comp(kB), comp(kC)}));
  const auto pd_u = build_from_json(comp(blend("perlin_union", {comp(kA), kB, kC})));
  expect_same_field(*pd, *pd_i, 2, 1e-14);
  expect_same_field(*pd, *pd_u, 2, 1e-14);
}

TEST(Perlin, NeutralElements) {  // [PE-2]
  const auto a = build_from_json(kA);
  expect_same_field(*build_from_json(blend("perlin_union", {kA, kFar})), *a, 2, 1e-15);
  expect_same_field(*build_from_json(blend("perlin_intersection", {kA, kOne})), *a, 2, 1e-15);
  expect_same_field(*build_from_json(blend("perlin_difference", {kA, kFar})), *a, 2, 1e-15);
  // Locality: the union's support is the union of the supports, the intersection's their
  // intersection.
  const Box ua = a->region(1e-300, Side::Above),
            ub = build_from_json(kB)->region(1e-300, Side::Above);
  const Box u = build_from_json(blend("perlin_union", {kA, kB}))->region(1e-300, Side::Above);
  const Box i =
      build_from_json(blend("perlin_intersection", {kA, kB}))->region(1e-300, Side::Above);
  EXPECT_DOUBLE_EQ(u.lo.x, std::min(ua.lo.x, ub.lo.x));
  EXPECT_DOUBLE_EQ(u.hi.x, std::max(ua.hi.x, ub.hi.x));
  EXPECT_DOUBLE_EQ(i.lo.x, std::max(ua.lo.x, ub.lo.x));
  EXPECT_DOUBLE_EQ(i.hi.x, std::min(ua.hi.x, ub.hi.x));
}

TEST(Perlin, UnionPartialsAreInUnitInterval) {  // [PE-3]
  const auto a = build_from_json(kA), b = build_from_json(kB);
  const auto u = build_from_json(blend("perlin_union", {kA, kB}));
  for_random_points(3000, 2, 7, [&](const Vec3& p) {
    Vec3 ga, gb, gu;
    const double fa = a->eval(p, &ga), fb = b->eval(p, &gb);
    u->eval(p, &gu);
    const double da = 1 - fb, db = 1 - fa;  // ∂B/∂f_a, ∂B/∂f_b
    ASSERT_GE(da, 0);
    ASSERT_LE(da, 1);
    ASSERT_GE(db, 0);
    ASSERT_LE(db, 1);
    ASSERT_NEAR(length(gu - (ga * da + gb * db)), 0, 1e-12);
  });
  // Soft children range over [0,1] globally, so the global bound is Σ L_i.
  EXPECT_NEAR(u->lipschitz(), a->lipschitz() + b->lipschitz(), 1e-9);
}

// Distance children about the origin, so the blends are ray-linear there ([RC-3]).
const std::string kDa = R"({"type":"lp_metric","radii":[1,0.8,1.1],"n":2})";
const std::string kDb = R"({"type":"superquadric","radii":[0.9,1.2,0.6],"n1":2,"n2":4})";

NodePtr cg(const std::string& json) {
  return build_from_json(json, Convention::Constructive);
}

TEST(RicciCG, BoundsAndLimits) {  // [RC-1]
  const auto a = cg(kDa), b = cg(kDb);
  for (double n : {1.0, 3.0, 200.0}) {
    const auto u = cg(blend("ricci_union", {kDa, kDb}, ",\"n\":" + std::to_string(n)));
    const auto i = cg(blend("ricci_intersection", {kDa, kDb}, ",\"n\":" + std::to_string(n)));
    for_random_points(2000, 2, 7, [&](const Vec3& p) {
      const double x1 = a->value(p), x2 = b->value(p);
      ASSERT_LE(u->value(p), std::min(x1, x2) * (1 + 1e-14));
      ASSERT_GE(i->value(p), std::max(x1, x2) * (1 - 1e-14));
      if (n == 200) {  // within the factor 2^(1/n) of min/max
        ASSERT_GE(u->value(p), std::min(x1, x2) * std::pow(2, -1 / n) * (1 - 1e-14));
        ASSERT_LE(i->value(p), std::max(x1, x2) * std::pow(2, 1 / n) * (1 + 1e-14));
      }
    });
  }
}

TEST(RicciCG, DualsAndTheA5Difference) {  // [RC-2], A5
  const std::string n = ",\"n\":3";
  // Children kept away from their centres so 1/x needs no guard.
  const std::string da = R"({"type":"lp_metric","translate":[5,0,0],"radii":[1,0.8,1.1],"n":2})";
  const std::string db = R"({"type":"lp_metric","translate":[0,5,0],"radii":[1.3,1,0.9],"n":3})";
  expect_same_field(*cg(blend("ricci_intersection", {da, db}, n)),
                    *cg(comp(blend("ricci_union", {comp(da), comp(db)}, n))), 2, 1e-12);
  expect_same_field(*cg(blend("ricci_difference", {da, db}, n)),
                    *cg(comp(blend("ricci_union", {comp(da), db}, n))), 2, 1e-12);
  // A5's numbers with n = 20: x = 0.5 and 2 from lp metrics of radius 2 and 0.5 at (1,0,0).
  const std::string half = R"({"type":"lp_metric","radii":[2,1,1],"n":2})";
  const std::string two = R"({"type":"lp_metric","radii":[0.5,1,1],"n":2})";
  const Vec3 X{1, 0, 0};
  EXPECT_NEAR(cg(blend("ricci_difference", {half, half}, ",\"n\":20"))->value(X), 2.0, 1e-3);
  EXPECT_NEAR(cg(blend("ricci_difference", {half, two}, ",\"n\":20"))->value(X), 0.518, 1e-3);
  EXPECT_NEAR(cg(blend("ricci_difference", {two, two}, ",\"n\":20"))->value(X), 2.0, 1e-3);
}

TEST(RicciCG, UnionAndIntersectionAreRayLinear) {  // [RC-3]
  const auto u = cg(blend("ricci_union", {kDa, kDb}, ",\"n\":2.5"));
  const auto i = cg(blend("ricci_intersection", {kDa, kDb}, ",\"n\":2.5"));
  const auto d = cg(blend("ricci_difference", {kDa, kDb}, ",\"n\":2.5"));
  int not_linear = 0;
  for_random_points(1000, 2, 7, [&](const Vec3& p) {
    for (double l : {0.3, 2.7}) {
      ASSERT_NEAR(u->value(p * l), l * u->value(p), 1e-12 * (1 + l * u->value(p)));
      ASSERT_NEAR(i->value(p * l), l * i->value(p), 1e-12 * (1 + l * i->value(p)));
      if (std::abs(d->value(p * l) - l * d->value(p)) > 1e-6) ++not_linear;
    }
  });
  EXPECT_GT(not_linear, 1000) << "the difference is not ray-linear";
}

TEST(RicciSoft, BoundsNeutralAndSoftBlend) {  // [RS-1]
  const auto a = build_from_json(kA), b = build_from_json(kB);
  const auto u = build_from_json(blend("ricci_union", {kA, kB}, ",\"n\":3"));
  const auto i = build_from_json(blend("ricci_intersection", {kA, kB}, ",\"n\":3"));
  for_random_points(3000, 2, 7, [&](const Vec3& p) {
    const double fa = a->value(p), fb = b->value(p);
    ASSERT_GE(u->value(p), std::max(fa, fb) * (1 - 1e-14));
    ASSERT_LE(i->value(p), std::min(fa, fb) * (1 + 1e-14));
  });
  expect_same_field(*build_from_json(blend("ricci_union", {kA, kFar}, ",\"n\":3")), *a, 2, 1e-15);
  expect_same_field(*build_from_json(blend("ricci_union", {kA, kB, kC}, ",\"n\":1")),
                    *build_from_json(blend("soft_blend", {kA, kB, kC})), 2, 1e-14);
  // The difference is the intersection with the soft complements (R21).
  expect_same_field(
      *build_from_json(blend("ricci_difference", {kA, kB, kC}, ",\"n\":3")),
      *build_from_json(blend("ricci_intersection", {kA, comp(kB), comp(kC)}, ",\"n\":3")), 2,
      1e-14);
}

TEST(RicciSoft, IntersectionIsNotExactlyLocal) {  // [RS-2]
  // Where f2 = 1 the level 0.5 needs f1 = (2^n - 1)^(-1/n): 0.577, 0.508, 0.50024, 0.5000005.
  const auto a = build_from_json(kA);
  for (double n : {2.0, 4.0, 8.0, 16.0}) {
    const auto i =
        build_from_json(blend("ricci_intersection", {kA, kOne}, ",\"n\":" + std::to_string(n)));
    const double target = std::pow(std::pow(2, n) - 1, -1 / n);
    // Bisect along +x from kA's centre for the point where f1 = target (f1 decreases outward).
    double lo = -0.4, hi = 1.0;
    for (int k = 0; k < 200; ++k) {
      const double m = 0.5 * (lo + hi);
      (a->value({m, 0, 0}) > target ? lo : hi) = m;
    }
    EXPECT_NEAR(i->value({lo, 0, 0}), 0.5, 1e-9) << "n = " << n;
  }
}

TEST(RicciSoft, HolderLipschitzBound) {  // [RS-3]
  const auto a = build_from_json(kA), b = build_from_json(kB);
  const auto u = build_from_json(blend("ricci_union", {kA, kB}, ",\"n\":3"));
  const double La = a->lipschitz(), Lb = b->lipschitz();
  EXPECT_NEAR(u->lipschitz(), std::cbrt(La * La * La + Lb * Lb * Lb), 1e-9);
  EXPECT_LT(u->lipschitz(), La + Lb);
}

TEST(Ricci, ZeroConventionIsRejected) {
  try {
    build_from_json(blend("ricci_union", {kDa, kDb}, ",\"n\":2"), Convention::Zero);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("ricci_* applies to soft or constructive objects"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("/type"), std::string::npos) << e.what();
  }
}

// B_H(y) of docs/math.md §6.1.
double hoffmann(double y1, double y2, double r1, double r2, double p) {
  return r2 * r2 * y1 * y1 + r1 * r1 * y2 * y2 + r1 * r1 * r2 * r2 - 2 * r2 * r2 * r1 * y1 -
         2 * r1 * r1 * r2 * y2 + 2 * p * y1 * y2;
}

struct ScaleSample {
  double r1, r2, p, x1, x2;
};

// 10^5 random parameter sets and arguments, a < 0 included (very negative p).
template <class F>
void for_scale_samples(bool bsa, F&& fn) {
  std::mt19937_64 rng(bsa ? 21 : 22);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 100000; ++i) {
    const double r1 = bsa ? 0.05 + 2 * u(rng) : 0.03 + 0.94 * u(rng);
    const double r2 = bsa ? 0.05 + 2 * u(rng) : 0.03 + 0.94 * u(rng);
    const double p = r1 * r2 * (0.99 - 8 * u(rng));
    fn(ScaleSample{r1, r2, p, 0.01 + 3 * u(rng), 0.01 + 3 * u(rng)});
  }
}

TEST(Scale, RootLiesOnTheArcBetweenChordAndSharp) {  // [SC-1], [SC-3]
  for (bool bsa : {true, false}) {
    int in3 = 0, negative_a = 0;
    for_scale_samples(bsa, [&](const ScaleSample& s) {
      const ScaleOperator op(s.r1, s.r2, s.p, bsa);
      const double h = op(s.x1, s.x2, nullptr);
      const double lo = std::min(s.x1, s.x2), hi = std::max(s.x1, s.x2);
      if (!op.region3(s.x1, s.x2)) {
        ASSERT_EQ(h, bsa ? lo : hi);
        return;
      }
      ++in3;
      const double sg = bsa ? 1 : -1;
      const double a = (1 + 2 * sg * s.r2) * s.r1 * s.r1 +
                       (1 + sg * s.r1) * (1 + sg * s.r1) * s.r2 * s.r2 + 2 * s.p;
      if (a < 0) ++negative_a;
      const double hc = (s.r2 * s.x1 + s.r1 * s.x2) /
                        (bsa ? s.r1 * s.r2 + s.r1 + s.r2 : s.r1 + s.r2 - s.r1 * s.r2);
      if (bsa) {
        ASSERT_GT(h, hc * (1 - 1e-12));
        ASSERT_LE(h, lo * (1 + 1e-12));
      } else {
        ASSERT_GE(h, hi * (1 - 1e-12));
        ASSERT_LT(h, hc * (1 + 1e-12));
      }
      const double y1 = sg * (s.x1 / h - 1), y2 = sg * (s.x2 / h - 1);
      ASSERT_NEAR(hoffmann(y1, y2, s.r1, s.r2, s.p), 0, 1e-9 * (1 + s.r1 * s.r1 * s.r2 * s.r2));
      // The other root of a h^2 + b h + c is not in that interval.
      const double c =
          s.r1 * s.r1 * s.x2 * s.x2 + s.r2 * s.r2 * s.x1 * s.x1 + 2 * s.p * s.x1 * s.x2;
      if (a != 0) {
        const double other = c / (a * h);  // product of the roots is c/a
        if (bsa)
          ASSERT_FALSE(other > hc * (1 + 1e-9) && other < lo * (1 - 1e-9)) << other << " " << h;
        else
          ASSERT_FALSE(other > hi * (1 + 1e-9) && other < hc * (1 - 1e-9)) << other << " " << h;
      }
    });
    EXPECT_GT(in3, 20000);
    EXPECT_GT(negative_a, 1000) << "a < 0 must be covered";
  }
}

TEST(Scale, ContinuousAcrossRegionThree) {  // [SC-2]
  for (bool bsa : {true, false}) {
    for_scale_samples(bsa, [&](const ScaleSample& s) {
      const ScaleOperator op(s.r1, s.r2, s.p, bsa);
      // The two boundary rays of region III, x2 = t x1.
      const double t1 = bsa ? 1 / (1 + s.r1) : 1 - s.r2, t2 = bsa ? 1 + s.r2 : 1 / (1 - s.r1);
      for (double t : {t1, t2}) {
        const double x2 = t * s.x1, e = 1e-7 * s.x1;
        ASSERT_NEAR(op(s.x1, x2 - e, nullptr), op(s.x1, x2 + e, nullptr), 1e-5 * s.x1);
      }
    });
  }
}

TEST(Scale, RayLinearMonotoneAndEuler) {  // [SC-4], and the facts behind the Lipschitz bound
  for (bool bsa : {true, false}) {
    for_scale_samples(bsa, [&](const ScaleSample& s) {
      const ScaleOperator op(s.r1, s.r2, s.p, bsa);
      double dh[2];
      const double h = op(s.x1, s.x2, dh);
      for (double l : {0.1, 3.7})
        ASSERT_NEAR(op(l * s.x1, l * s.x2, nullptr), l * h, 1e-11 * l * h);
      ASSERT_GE(dh[0], -1e-12);
      ASSERT_GE(dh[1], -1e-12);
      ASSERT_NEAR(s.x1 * dh[0] + s.x2 * dh[1], h, 1e-8 * h);
      const double gain = bsa ? 1 : 1 / (1 - std::max(s.r1, s.r2));
      ASSERT_LE(dh[0] + dh[1], gain * (1 + 1e-9));
      if (op.region3(s.x1, s.x2)) {  // the IFT partials against central differences
        const double e = 1e-6 * std::min(s.x1, s.x2);
        const double f1 = (op(s.x1 + e, s.x2, nullptr) - op(s.x1 - e, s.x2, nullptr)) / (2 * e);
        const double f2 = (op(s.x1, s.x2 + e, nullptr) - op(s.x1, s.x2 - e, nullptr)) / (2 * e);
        if (op.region3(s.x1 + e, s.x2) && op.region3(s.x1 - e, s.x2) &&
            op.region3(s.x1, s.x2 + e) && op.region3(s.x1, s.x2 - e)) {
          ASSERT_NEAR(dh[0], f1, 1e-4 * (1 + std::abs(f1)));
          ASSERT_NEAR(dh[1], f2, 1e-4 * (1 + std::abs(f2)));
        }
      }
    });
  }
}

// range_and_slope: the range has range()'s bits (where the sharp pick holds it skips the
// quadratic), and the slope is the one argument's where the pick holds, else it holds
// (a1 + a2) · hull(D1, D2) for a1 + a2 up to the gain.
TEST(Scale, RangeAndSlopeAgreeWithRange) {
  for (bool bsa : {true, false}) {
    int sharp = 0, mixed = 0;
    for_scale_samples(bsa, [&](const ScaleSample& s) {
      const ScaleOperator op(s.r1, s.r2, s.p, bsa);
      const Interval x1{s.x1, s.x1 * 1.05}, x2{s.x2, s.x2 * 1.05};
      const Interval D1{-0.3, 0.7}, D2{0.2, 0.9};
      Interval slope;
      const Interval r = op.range_and_slope(x1, x2, &D1, &D2, &slope);
      const Interval ref = op.range(x1, x2);
      ASSERT_EQ(r.lo, ref.lo);
      ASSERT_EQ(r.hi, ref.hi);
      const Interval alone = op.range_and_slope(x1, x2, nullptr, nullptr, nullptr);
      ASSERT_EQ(alone.lo, ref.lo);
      ASSERT_EQ(alone.hi, ref.hi);
      const int pick = op.sharp_everywhere(x1, x2);
      if (pick >= 0) {
        ++sharp;
        const Interval D = pick == 0 ? D1 : D2;
        ASSERT_EQ(slope.lo, D.lo);
        ASSERT_EQ(slope.hi, D.hi);
      } else {
        ++mixed;
        // Holds a1 x1' + a2 x2' at its extremes: a1 + a2 at the gain with all weight on one end.
        const double gain = bsa ? 1.0 : 1 / (1 - std::max(s.r1, s.r2));
        ASSERT_LE(slope.lo, -0.3 * gain * (1 - 1e-9));
        ASSERT_GE(slope.hi, 0.9 * gain * (1 - 1e-9));
      }
    });
    EXPECT_GT(sharp, 1000);
    EXPECT_GT(mixed, 1000);
  }
}

TEST(Scale, ConventionDecidesTheOperator) {  // [CONV-2], §6.3.4
  const std::string prm = R"(,"r1":0.5,"r2":0.4,"p":0.1)";
  const Vec3 X{0.1, 0.2, 0};
  const auto a = build_from_json(kA), b = build_from_json(kB);
  const double fa = a->value(X), fb = b->value(X);
  // Soft: the union is BSS2 (>= max), the intersection BSA2 (<= min).
  EXPECT_DOUBLE_EQ(build_from_json(blend("scale_union", {kA, kB}, prm))->value(X),
                   ScaleOperator(0.5, 0.4, 0.1, false)(fa, fb, nullptr));
  EXPECT_DOUBLE_EQ(build_from_json(blend("scale_intersection", {kA, kB}, prm))->value(X),
                   ScaleOperator(0.5, 0.4, 0.1, true)(fa, fb, nullptr));
  const double xa = cg(kDa)->value(X), xb = cg(kDb)->value(X);
  EXPECT_DOUBLE_EQ(cg(blend("scale_union", {kDa, kDb}, prm))->value(X),
                   ScaleOperator(0.5, 0.4, 0.1, true)(xa, xb, nullptr));
  EXPECT_THROW(build_from_json(blend("scale_union", {kDa, kDb}, prm), Convention::Zero),
               SceneError);
}

TEST(Complement, EachConvention) {
  const auto a = build_from_json(kA);
  const auto s = build_from_json(comp(kA));
  const auto z = build_from_json(comp(R"({"type":"offset","children":[)" + kDa + "]}"),
                                 Convention::Zero);  // the zero convention takes d - 1
  const auto c = build_from_json(comp(kDa), Convention::Constructive);
  const auto d = cg(kDa);
  for_random_points(500, 2, 7, [&](const Vec3& p) {
    ASSERT_DOUBLE_EQ(s->value(p), 1 - a->value(p));
    ASSERT_DOUBLE_EQ(z->value(p), -(d->value(p) - 1));
    ASSERT_DOUBLE_EQ(c->value(p), 1 / d->value(p));
  });
  EXPECT_EQ(c->value({0, 0, 0}), 1 / kCgFloor) << "1/f is guarded at f = 0";
  EXPECT_EQ(c->gradient({0, 0, 0}).x, 0);
}

TEST(MinMax, SharpBaselines) {
  const auto a = build_from_json(kA), b = build_from_json(kB);
  const auto mn = build_from_json(blend("min", {kA, kB})),
             mx = build_from_json(blend("max", {kA, kB}));
  for_random_points(500, 2, 7, [&](const Vec3& p) {
    ASSERT_EQ(mn->value(p), std::min(a->value(p), b->value(p)));
    ASSERT_EQ(mx->value(p), std::max(a->value(p), b->value(p)));
  });
  EXPECT_EQ(mx->lipschitz(), std::max(a->lipschitz(), b->lipschitz()));
}

TEST(Blends, ParametersAreValidated) {
  const std::string sc = R"(,"r1":0.5,"r2":0.4,"p":0.1)";
  for (const auto& bad :
       {blend("scale_union", {kA, kB}, R"(,"r1":1.2,"r2":0.4,"p":0.1)"),  // soft union = BSS2
        blend("scale_union", {kA, kB}, R"(,"r1":0.5,"r2":0.4,"p":0.2)"),  // p >= r1 r2
        blend("scale_union", {kA, kB}, R"(,"r1":0,"r2":0.4,"p":0)"),
        blend("scale_union", {kA, kB, kC}, sc), blend("ricci_union", {kA, kB}, R"(,"n":0)"),
        blend("ricci_union", {kA, kB}), blend("complement", {kA, kB}),
        blend("perlin_union", {kA})}) {
    EXPECT_THROW(build_from_json(bad), SceneError) << bad;
  }
  EXPECT_NO_THROW(
      build_from_json(blend("scale_intersection", {kA, kB}, R"(,"r1":1.2,"r2":0.4,"p":0.1)")))
      << "soft intersection = BSA2 accepts r >= 1";
}

}  // namespace
}  // namespace softtrace
