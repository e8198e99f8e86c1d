// POV-Ray's blob components: strength (docs/math.md §4.10, [ST-1]..[ST-3]), affine placement
// (§2.15, [AF-1]..[AF-4]) and the cubic potential (§3.4, [PC-1], [PC-2]); and the loader's
// refusals for each.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "describe/params.h"
#include "eval/eval.h"
#include "kernels/potentials.h"
#include "math/affine.h"
#include "model/program_builder.h"
#include "sweep.h"

namespace softtrace::test {
namespace {

const char* const kBall = R"({"type":"lp_metric","radii":[1,1,1],"n":2})";

std::string soft(double strength, const std::string& extra = "", double radius = 1) {
  const std::string r = std::to_string(radius);
  return std::string(R"({"type":"soft_object","potential":{"type":"murakami"},"strength":)") +
         std::to_string(strength) + extra + R"(,"distance":{"type":"lp_metric","radii":[)" + r +
         "," + r + "," + r + R"(],"n":2}})";
}

// [ST-1]: s·P(d), its gradient and its bounds are the unit-strength object's times s.
TEST(Strength, ScalesValueGradientAndBounds) {
  const NodePtr one = build_from_json(soft(1));
  for (double s : {2.5, -0.75, -40.0}) {
    const NodePtr n = build_from_json(soft(s));
    std::mt19937_64 rng(3);
    const Box dom({-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2});
    int nonzero = 0;
    for (int i = 0; i < 500; ++i) {
      const Vec3 p = uniform_in(rng, dom);
      Vec3 g1, gs;
      const double v1 = one->eval(p, &g1), vs = n->eval(p, &gs);
      EXPECT_EQ(vs, s * v1);
      EXPECT_EQ(length(gs - g1 * s), 0.0);
      nonzero += v1 > 0;
      const Box b = random_box(rng, dom);
      const Interval I1 = one->interval(b), Is = n->interval(b);
      EXPECT_LE(Is.lo, std::min(s * I1.lo, s * I1.hi));
      EXPECT_GE(Is.hi, std::max(s * I1.lo, s * I1.hi));
      EXPECT_LE(n->lipschitz(b), std::abs(s) * one->lipschitz(b) * (1 + 1e-15) + 1e-300);
      EXPECT_GE(n->lipschitz(b), std::abs(s) * one->lipschitz(b));
    }
    EXPECT_GT(nonzero, 50);
    EXPECT_GE(n->lipschitz(), std::abs(s) * one->lipschitz());
    EXPECT_LE(n->lipschitz(), std::abs(s) * one->lipschitz() * (1 + 1e-15));
  }
}

// [ST-2], [ST-3]: a negative term has its soft object's support, and adds no surface.
TEST(Strength, NegativeTermsKeepTheirSupportAndAddNoSurface) {
  const NodePtr neg = build_from_json(soft(-2));
  EXPECT_TRUE(neg->region(0.25, Side::Above).empty());
  const Box below = neg->region(-1e-300, Side::Below);
  ASSERT_TRUE(below.bounded());
  EXPECT_LE(below.hi.x, 1 + 1e-9);
  EXPECT_GE(below.hi.x, 1);
  // A large blob with a hole punched in it: the sum's region is the large blob's support.
  const std::string sum = R"({"type":"soft_blend","children":[)" + soft(2, "", 3) + "," +
                          soft(-3, R"(,"translate":[2.5,0,0])") + "]}";
  const NodePtr blend = build_from_json(sum);
  const Box r = blend->region(0.5, Side::Above);
  ASSERT_TRUE(r.bounded());
  EXPECT_NEAR(r.hi.x, 3, 1e-9);
  EXPECT_NEAR(r.lo.x, -3, 1e-9);
  EXPECT_LT(blend->value({2.5, 0, 0}), 0.5);  // the hole
  EXPECT_GT(blend->value({0, 0, 0}), 0.5);
  // The compiled sum drops the negative term where a box misses its support: it is prunable.
  const Program prog = compile(*blend);
  ASSERT_EQ(prog.groups.size(), 1u);
  EXPECT_TRUE(prog.groups[0].always.empty());
  Workspace ws;
  ws.fit(prog);
  prune(prog, Box({-2.9, -0.1, -0.1}, {-2.8, 0.1, 0.1}), ws);
  int strengths = 0;
  for (const Instr& in : ws.view.code) strengths += in.op == Op::Strength;
  EXPECT_EQ(strengths, 1);  // the large blob's; the hole's term is gone
  prune(prog, Box({2.4, -0.1, -0.1}, {2.6, 0.1, 0.1}), ws);
  strengths = 0;
  for (const Instr& in : ws.view.code) strengths += in.op == Op::Strength;
  EXPECT_EQ(strengths, 2);
}

TEST(Strength, BlendsThatNeedFieldsInTheUnitIntervalRefuseNegativeOnes) {
  const std::string neg = soft(-1), pos = soft(2);
  for (const char* blend : {"perlin_union", "perlin_intersection", "perlin_difference"})
    EXPECT_EQ(build_error(std::string(R"({"type":")") + blend + R"(","children":[)" + pos + "," +
                          R"({"type":"soft_blend","children":[)" + pos + "," + neg + "]}]}"),
              std::string("<test>: /children/1/children/1/strength: a negative strength cannot "
                          "enter ") +
                  blend +
                  ", whose formula needs its soft fields in [0, 1] (soft_blend, min, max and "
                  "complement take any strength; docs/scene-format.md \"soft_object\")");
  EXPECT_NE(build_error(R"({"type":"ricci_union","n":2,"children":[)" + pos + "," + neg + "]}")
                .find("/children/1/strength: a negative strength cannot enter ricci_union"),
            std::string::npos);
  EXPECT_NE(build_error(R"({"type":"scale_union","r1":0.5,"r2":0.5,"p":0.1,"children":[)" + neg +
                        "," + pos + "]}")
                .find("/children/0/strength: a negative strength cannot enter scale_union"),
            std::string::npos);
  for (const char* fine : {"soft_blend", "min", "max"})
    EXPECT_EQ(build_error(std::string(R"({"type":")") + fine + R"(","children":[)" + pos + "," +
                          neg + "]}"),
              "");
  EXPECT_EQ(build_error(R"({"type":"complement","children":[)" + neg + "]}"), "");
  EXPECT_EQ(build_error(R"({"type":"soft_blend","children":[)" + neg + "]}"), "");
  EXPECT_EQ(build_error(soft(0)),
            "<test>: /strength: expected strength != 0 (s = 0 gives no field)");
}

// [AF-2]: the operator norm bound is the largest singular value to within 1e-11, never below it.
TEST(Affine, OperatorNormBoundIsTightAndSound) {
  Mat3 d;
  d.r[0] = {2, 0, 0};
  d.r[1] = {0, -1, 0};
  d.r[2] = {0, 0, 0.5};
  EXPECT_GE(operator_norm_bound(d), 2);
  EXPECT_LE(operator_norm_bound(d), 2 * (1 + 1e-11));
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0, 1);
  for (int k = 0; k < 2000; ++k) {
    Mat3 m;
    const double scale = std::exp(g(rng) * 5);
    for (int i = 0; i < 3; ++i) m.r[i] = Vec3{g(rng), g(rng), g(rng)} * scale;
    if (k % 3 == 0) m.r[2] = m.r[0] * 0.5 + m.r[1] * 1e-3;  // nearly rank 2
    // Power iteration on m^T m converges to the largest singular value from below.
    Vec3 v{g(rng), g(rng), g(rng)};
    double sigma = 0;
    for (int it = 0; it < 200; ++it) {
      v = normalize(transposed(m) * (m * v));
      sigma = length(m * v);
    }
    const double bound = operator_norm_bound(m);
    ASSERT_GE(bound, sigma) << k;
    ASSERT_LE(bound, sigma * (1 + 1e-9)) << k;
  }
}

// [AF-1]: a scaled unit ball is the ellipsoid of those radii, value and gradient; the Lipschitz
// bound is the inverse's norm.
TEST(Affine, ScaledBallIsTheEllipsoid) {
  const NodePtr scaled =
      build_from_json(R"({"type":"lp_metric","radii":[1,1,1],"n":2,"scale":[2,-0.5,4]})");
  const NodePtr direct = build_from_json(R"({"type":"lp_metric","radii":[2,0.5,4],"n":2})");
  std::mt19937_64 rng(7);
  const Box dom({-5, -5, -5}, {5, 5, 5});
  for (int i = 0; i < 300; ++i) {
    const Vec3 p = uniform_in(rng, dom);
    Vec3 ga, gb;
    const double a = scaled->eval(p, &ga), b = direct->eval(p, &gb);
    ASSERT_NEAR(a, b, 1e-14 * std::max(1.0, b));
    ASSERT_LE(length(ga - gb), 1e-14 * std::max(1.0, length(gb)));
  }
  EXPECT_GE(scaled->lipschitz(), 2.0);  // 1 / 0.5
  EXPECT_LE(scaled->lipschitz(), 2.0 * (1 + 1e-11));
  const Box r = scaled->region(1, Side::Below);
  EXPECT_NEAR(r.hi.x, 2, 1e-9);
  EXPECT_NEAR(r.hi.y, 0.5, 1e-9);
  EXPECT_NEAR(r.hi.z, 4, 1e-9);
}

// A matrix is the same map as scale, rotate and translate composed in that order.
TEST(Affine, MatrixIsScaleThenRotateThenTranslate) {
  const Mat3 R = Mat3::rotation({0, 0, 1}, 90);
  const Vec3 s{2, 1, 0.5}, t{1, -2, 3};
  std::string rows = "[";
  for (int i = 0; i < 3; ++i) {
    char row[160];
    std::snprintf(row, sizeof row, "%s[%.17g,%.17g,%.17g,%.17g]", i ? "," : "", R.r[i].x * s.x,
                  R.r[i].y * s.y, R.r[i].z * s.z, t[i]);
    rows += row;
  }
  rows += "]";
  const std::string seg =
      R"("distance":{"type":"segment","p0":[-1,0,0],"p1":[1,0.5,0],"radius":1})";
  const NodePtr a = build_from_json(R"({"type":"soft_object","matrix":)" + rows + "," + seg + "}");
  const NodePtr b = build_from_json(
      R"({"type":"soft_object","scale":[2,1,0.5],"rotate":{"axis":[0,0,1],"deg":90},
          "translate":[1,-2,3],)" +
      seg + "}");
  std::mt19937_64 rng(9);
  const Box dom({-1, -6.5, 2}, {2.5, 2.5, 4});
  int inside = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 p = uniform_in(rng, dom);
    Vec3 ga, gb;
    ASSERT_NEAR(a->eval(p, &ga), b->eval(p, &gb), 1e-14);
    ASSERT_LE(length(ga - gb), 1e-13);
    inside += a->value(p) > 0;
  }
  EXPECT_GT(inside, 10);
  // The capsule's image: x from the rotated y, y from the rotated x (scaled by 2).
  const Box r = a->region(1e-300, Side::Above);
  EXPECT_NEAR(r.lo.y, -2 - 2 * 2, 1e-9);
  EXPECT_NEAR(r.hi.y, -2 + 2 * 2, 1e-9);
}

// [AF-4] and the keys' rules.
TEST(Affine, RefusesSingularMatricesAndMixedKeys) {
  const std::string body = R"("type":"lp_metric","radii":[1,1,1],"n":2)";
  EXPECT_NE(build_error("{" + body + R"(,"matrix":[[1,2,3,0],[2,4,6,0],[0,0,1,0]]})")
                .find("<test>: /matrix: expected an invertible linear part with condition number "
                      "at most 1e12 (got a singular one"),
            std::string::npos);
  EXPECT_NE(build_error("{" + body + R"(,"matrix":[[1,0,0,0],[0,1e-13,0,0],[0,0,1,0]]})")
                .find("<test>: /matrix: expected an invertible linear part"),
            std::string::npos);
  EXPECT_EQ(build_error("{" + body + R"(,"scale":[1,0,1]})"),
            "<test>: /scale/1: expected a non-zero scale factor");
  EXPECT_NE(build_error("{" + body + R"(,"scale":[1e-7,1e7,1]})")
                .find("<test>: /scale: expected an invertible linear part"),
            std::string::npos);
  EXPECT_EQ(
      build_error("{" + body + R"(,"matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0]],"translate":[1,0,0]})"),
      "<test>: /matrix: 'matrix' cannot be combined with 'translate' (fold it into the "
      "matrix; docs/scene-format.md \"Placement\")");
  EXPECT_EQ(build_error("{" + body + R"(,"matrix":[[1,0,0,0],[0,1,0,0],[0,0,1]]})"),
            "<test>: /matrix/2: expected a row of 4 numbers");
  EXPECT_EQ(build_error("{" + body + R"(,"matrix":[[1,0,0,0],[0,1,"x",0],[0,0,1,0]]})"),
            "<test>: /matrix/1/2: expected a number");
  // offset keeps its own `scale`.
  EXPECT_EQ(build_error(std::string(R"({"type":"offset","scale":2,"children":[)") + kBall + "]}",
                        Convention::Zero),
            "");
}

// [PC-1], [PC-2].
TEST(Cubic, PotentialFactsAndExactLipschitzBound) {
  EXPECT_EQ(cubic(0, nullptr), 1);
  EXPECT_EQ(cubic(1, nullptr), 0);
  EXPECT_EQ(cubic(1.5, nullptr), 0);
  EXPECT_EQ(cubic(0.5, nullptr), 27.0 / 64);
  EXPECT_NEAR(cubic(std::sqrt(1 - std::cbrt(0.5)), nullptr), 0.5, 1e-15);
  double most = 0, prev = 1;
  for (int i = 0; i <= 200000; ++i) {
    const double d = i / 200000.0;
    double dP;
    const double P = cubic(d, &dP);
    ASSERT_LE(P, prev);
    ASSERT_LE(dP, 0);
    prev = P;
    most = std::max(most, -dP);
  }
  EXPECT_GE(cubic_lipschitz(), most);
  EXPECT_LE(cubic_lipschitz(), most * (1 + 1e-9));
  EXPECT_NEAR(cubic_lipschitz(), 96 * std::sqrt(5.0) / 125, 1e-11);
  double dP;
  cubic(1 / std::sqrt(5.0), &dP);
  EXPECT_NEAR(-dP, cubic_lipschitz(), 1e-11);
}

}  // namespace
}  // namespace softtrace::test
