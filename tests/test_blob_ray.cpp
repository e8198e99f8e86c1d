// Sums of polynomial blobs along a ray (fieldlib/blob_ray.h) and the Bernstein root search
// (fieldlib/bernstein.h): which programs are such sums, that the polynomial of each piece of a
// stretch is the field there, and that first_rise finds the first crossing.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <string>

#include "eval/blob_ray.h"
#include "eval/eval.h"
#include "model/program_builder.h"
#include "sweep.h"

namespace softtrace::test {

namespace {

// n blobs in [-6, 6]^3: ellipsoids of radii 2..5 (every fourth a ball), every third rotated,
// every other one Wyvill's potential, the translation on the soft object or on its distance.
std::string blob_cloud(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-6, 6), r(2, 5), a(-1, 1);
  const auto num = [](double v) { return std::to_string(v); };
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < n; ++i) {
    // Every fourth one has equal radii: a ball where it is not rotated (BlobSum's short path).
    const double r0 = r(rng), r1 = i % 4 == 1 ? r0 : r(rng), r2 = i % 4 == 1 ? r0 : r(rng);
    std::string distance =
        R"({"type":"lp_metric","n":2,"radii":[)" + num(r0) + "," + num(r1) + "," + num(r2) + "]";
    if (i % 3 == 0)
      distance += R"(,"rotate":{"axis":[)" + num(a(rng)) + "," + num(a(rng)) +
                  ",1],\"deg\":" + num(90 * a(rng)) + "}";
    distance += "}";
    s += (i ? "," : "") + std::string(R"({"type":"soft_object","potential":{"type":")") +
         (i % 2 ? "wyvill" : "murakami") + R"("},"distance":)" + distance + R"(,"translate":[)" +
         num(c(rng)) + "," + num(c(rng)) + "," + num(c(rng)) + "]}";
  }
  return s + "]}";
}

// n blobs as POV-Ray writes them: balls and capsule-free ellipsoids made by a non-uniform
// `scale` after a rotation (sheared) or by a `matrix`, strengths in [-1, 2] (a third negative),
// Murakami's, Wyvill's and the cubic potential.
std::string affine_cloud(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-6, 6), r(2, 5), a(-1, 1), sc(0.4, 1.6);
  const auto num = [](double v) { return std::to_string(v); };
  const char* const potentials[] = {"murakami", "wyvill", "cubic"};
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < n; ++i) {
    const double r0 = r(rng);
    std::string place;
    if (i % 2 == 0) {
      place = R"("scale":[)" + num(sc(rng)) + "," + num(sc(rng)) + "," + num(sc(rng)) +
              R"(],"rotate":{"axis":[)" + num(a(rng)) + "," + num(a(rng)) +
              ",1],\"deg\":" + num(90 * a(rng)) + R"(},"translate":[)" + num(c(rng)) + "," +
              num(c(rng)) + "," + num(c(rng)) + "]";
    } else {
      place = R"("matrix":[)";
      for (int row = 0; row < 3; ++row)
        place += std::string(row ? "," : "") + "[" + num((row == 0) + 0.4 * a(rng)) + "," +
                 num((row == 1) + 0.4 * a(rng)) + "," + num((row == 2) + 0.4 * a(rng)) + "," +
                 num(c(rng)) + "]";
      place += "]";
    }
    const double strength =
        i % 3 == 2 ? -0.4 - 0.6 * std::abs(a(rng)) : 0.5 + 1.5 * std::abs(a(rng));
    s += (i ? "," : "") + std::string(R"({"type":"soft_object","potential":{"type":")") +
         potentials[i % 3] + R"("},"strength":)" + num(strength) + "," + place +
         R"(,"distance":{"type":"lp_metric","n":2,"radii":[)" + num(r0) + "," + num(r0) + "," +
         num(r0) + "]}}";
  }
  return s + "]}";
}

// A cloud's JSON compiled, its BlobSum, a workspace and an id buffer.
struct Cloud {
  NodePtr node;
  Program prog;
  std::optional<BlobSum> blobs;
  Workspace ws;
  std::vector<int32_t> ids;
  explicit Cloud(unsigned seed) : Cloud(blob_cloud(40, seed)) {}
  explicit Cloud(const std::string& json)
      : node(build_from_json(json)), prog(compile(*node)), blobs(BlobSum::of(prog)) {
    ws.fit(prog);
    if (blobs) ids.resize(blobs->size());
  }
};

bool is_blob_sum(const std::string& json) {
  return BlobSum::of(compile(*build_from_json(json))).has_value();
}

}  // namespace

TEST(BlobSum, RecognisesOnlySumsOfPolynomialBlobs) {
  const auto blobs = BlobSum::of(compile(*build_from_json(blob_cloud(12, 1))));
  ASSERT_TRUE(blobs.has_value());
  EXPECT_EQ(blobs->size(), 12);
  const std::string ball = R"({"type":"lp_metric","radii":[1,2,3],"n":2})";
  const auto soft = [&](const char* potential, const std::string& distance) {
    return R"({"type":"soft_object","potential":{"type":")" + std::string(potential) +
           R"("},"distance":)" + distance + "}";
  };
  const auto sum = [](const std::string& a, const std::string& b) {
    return R"({"type":"soft_blend","children":[)" + a + "," + b + "]}";
  };
  EXPECT_TRUE(is_blob_sum(sum(soft("murakami", ball), soft("wyvill", ball))));
  // Blanc's potential is not a polynomial in d^2; nor is an lp_metric with n = 3 quadratic.
  EXPECT_FALSE(is_blob_sum(sum(soft("murakami", ball), soft("blanc", ball))));
  EXPECT_FALSE(is_blob_sum(sum(soft("murakami", ball),
                               soft("murakami", R"({"type":"lp_metric","radii":[1,2,3],"n":3})"))));
  EXPECT_FALSE(is_blob_sum(
      sum(soft("murakami", ball),
          soft("murakami", R"({"type":"segment","p0":[0,0,0],"p1":[1,0,0],"radius":1})"))));
  // Radii whose squares' reciprocals underflow or overflow: the segment tracer's kernels rescale.
  EXPECT_FALSE(
      is_blob_sum(sum(soft("murakami", ball),
                      soft("murakami", R"({"type":"lp_metric","radii":[1e120,1,1],"n":2})"))));
  EXPECT_FALSE(
      is_blob_sum(sum(soft("murakami", ball),
                      soft("murakami", R"({"type":"lp_metric","radii":[1e-120,1,1],"n":2})"))));
  // One blob is no sum; a sum placed as a whole reads its children in another frame.
  EXPECT_FALSE(is_blob_sum(soft("murakami", ball)));
  EXPECT_FALSE(is_blob_sum(R"({"type":"soft_blend","translate":[1,0,0],"children":[)" +
                           soft("murakami", ball) + "," + soft("murakami", ball) + "]}"));
}

// Along random stretches of random rays, each piece's polynomial (plus iso) is the compiled
// field, within the piece's err and the rounding of the points (the field is evaluated at the
// rounded o + u d, the polynomial at exact u: a few ulps of the coordinates, times a slope of
// at most ~1 per unit here).
// `slack` scales the rounding allowance: affine frames cancel more digits in L x + k, and their
// blobs are steeper (radii down to 0.8, strengths up to 2).
void expect_pieces_are_polynomials_of_the_field(Cloud& cloud, double slack) {
  ASSERT_TRUE(cloud.blobs.has_value());
  const Program& prog = cloud.prog;
  const auto& blobs = cloud.blobs;
  Workspace& ws = cloud.ws;
  std::vector<BlobSum::Term> terms(blobs->size());
  std::vector<int32_t>& ids = cloud.ids;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), x01(0, 1);
  int pieces = 0, outside = 0;
  for (int ray = 0; ray < 300; ++ray) {
    // Every third stretch starts 1e8 away and ends 1e8 beyond the cloud: the terms then lose
    // digits to w = L o + k as the points o + u d do to their own rounding, no more.
    const bool far = ray % 3 == 2;
    const Vec3 d = normalize({u(rng), u(rng), u(rng)});
    const Vec3 o = Vec3{u(rng), u(rng), u(rng)} * 12 - (far ? d * 1e8 : Vec3{});
    const double len = far ? 2e8 : 30 * x01(rng);
    const int n = blobs->terms(prog, o, d, len, 1e-12, terms.data(), ids.data());
    std::vector<double> cuts{0, len};
    for (int i = 0; i < n; ++i) {
      cuts.push_back(terms[i].enter);
      cuts.push_back(terms[i].exit);
    }
    std::sort(cuts.begin(), cuts.end());
    for (size_t c = 0; c + 1 < cuts.size(); ++c) {
      const double s0 = cuts[c], S = cuts[c + 1] - s0;
      if (!(S > 1e-9)) continue;
      std::vector<int> active;
      for (int i = 0; i < n; ++i)
        if (terms[i].enter <= s0 && terms[i].exit >= s0 + S) active.push_back(i);
      const StretchPolynomial sp =
          stretch_polynomial(terms.data(), active.data(), int(active.size()), s0, S, 0.5);
      for (int k = 0; k < 5; ++k) {
        const double x = x01(rng);
        const double field = value(prog, o + d * (s0 + x * S), ws);
        if (active.empty()) {
          ++outside;
          ASSERT_EQ(field, 0) << "a blob the query missed is non-zero at u = " << s0 + x * S;
          continue;
        }
        ++pieces;
        // The field is evaluated at the rounded o + u d: 1e-16 of |o| + u, over radii >= 2.
        const double rounding = slack * (1e-13 + 2e-16 * (length(o) + s0 + S));
        ASSERT_NEAR(power_value(sp.a, sp.degree, x) + 0.5, field, sp.err + rounding)
            << "ray " << ray << ", piece at " << s0 << " of length " << S;
      }
      // The peaks bound the piece from above.
      double peak = 0;
      for (int i : active) peak += terms[i].peak;
      ASSERT_LE(power_value(sp.a, sp.degree, 0.5) + 0.5, peak * (1 + 1e-12) + 1e-15);
    }
  }
  EXPECT_GT(pieces, 1000);
  EXPECT_GT(outside, 50);
}
TEST(BlobSum, EachPieceOfAStretchIsOnePolynomialOfTheField) {
  Cloud cloud(2);
  expect_pieces_are_polynomials_of_the_field(cloud, 1);
}
// Affinely placed blobs (one oracle instruction each) of any strength, and the cubic kernel.
TEST(BlobSum, AffineBlobsOfAnyStrengthAreOnePolynomialToo) {
  Cloud cloud(affine_cloud(40, 4));
  ASSERT_TRUE(cloud.blobs.has_value());
  EXPECT_EQ(cloud.blobs->size(), 40);
  expect_pieces_are_polynomials_of_the_field(cloud, 10);
}

// The normals of blob sums come from BlobSum::gradient: the compiled gradient's value and
// direction, to rounding, inside and between supports, and 0 outside all of them.
void expect_gradient_is_the_compiled_one(Cloud& cloud, double tol) {
  ASSERT_TRUE(cloud.blobs.has_value());
  const Program& prog = cloud.prog;
  const auto& blobs = cloud.blobs;
  Workspace& ws = cloud.ws;
  std::vector<int32_t>& ids = cloud.ids;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-12, 12);
  int inside = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 x{u(rng), u(rng), u(rng)};
    Vec3 g_blob, g_prog;
    const double f_blob = blobs->gradient(prog, x, &g_blob, ids.data());
    const double f_prog = gradient(prog, x, &g_prog, ws);
    ASSERT_NEAR(f_blob, f_prog, tol) << "at point " << i;
    ASSERT_LE(length(g_blob - g_prog), 100 * tol * (1 + length(g_prog))) << "at point " << i;
    inside += f_prog != 0;
  }
  EXPECT_GT(inside, 300);
  EXPECT_LT(inside, 1900);
}
TEST(BlobSum, GradientIsTheCompiledOne) {
  Cloud cloud(3);
  expect_gradient_is_the_compiled_one(cloud, 1e-14);
}
TEST(BlobSum, AffineBlobsGradientIsTheCompiledOne) {
  Cloud cloud(affine_cloud(40, 5));
  ASSERT_TRUE(cloud.blobs.has_value());
  expect_gradient_is_the_compiled_one(cloud, 1e-13);
}

TEST(FirstRise, FindsTheFirstCrossingOnly) {
  // (x - 0.3)(x - 0.6)(x - 0.9): up through 0 at 0.3, down at 0.6, up again at 0.9.
  const double three[4] = {-0.162, 0.99, -1.8, 1};
  Rise r = first_rise(three, 3, 1e-15, 1e-6, 1e-9);
  ASSERT_EQ(r.kind, Rise::Bracket);
  EXPECT_LE(r.lo, 0.3);
  EXPECT_GE(r.hi, 0.3);
  EXPECT_LT(power_value(three, 3, r.lo), 0);
  EXPECT_GE(power_value(three, 3, r.hi), 0);
  EXPECT_LT(r.hi, 0.6);
  // A bump that rises to 1e-4 between its two roots 0.49 and 0.51: 1e-4 - (x - 0.5)^2.
  const double bump[3] = {1e-4 - 0.25, 1, -1};
  r = first_rise(bump, 2, 1e-15, 1e-6, 1e-9);
  ASSERT_EQ(r.kind, Rise::Bracket);
  EXPECT_LE(r.lo, 0.49);
  EXPECT_GE(r.hi, 0.49 - 1e-12);
  // Stays below 0: -1e-6 - (x - 0.5)^2 touches -1e-6, well beyond err.
  const double below[3] = {-1e-6 - 0.25, 1, -1};
  EXPECT_EQ(first_rise(below, 2, 1e-15, 1e-6, 1e-9).kind, Rise::Clear);
  // Touching 0 within err: no certificate either way, down to the finest pieces. Passed and
  // counted, not a bracket; a later crossing is still found ((x - 0.5)^2 (x - 0.8) - 1e-16, whose
  // hull straddles 0 about 0.5 and which rises through 0 at 0.8).
  const double touch[3] = {-1e-16 - 0.25, 1, -1};
  r = first_rise(touch, 2, 1e-15, 1e-6, 1e-9);
  EXPECT_EQ(r.kind, Rise::Clear);
  EXPECT_GE(r.undecided, 1);
  const double later[4] = {-0.2 - 1e-16, 1.05, -1.8, 1};
  r = first_rise(later, 3, 1e-15, 1e-6, 1e-9);
  ASSERT_EQ(r.kind, Rise::Bracket);
  EXPECT_GE(r.undecided, 1);
  EXPECT_LE(r.lo, 0.8);
  EXPECT_GE(r.hi, 0.8);
  EXPECT_GT(r.lo, 0.5);
  const double start[2] = {0, 1};
  EXPECT_EQ(first_rise(start, 1, 1e-15, 1e-6, 1e-9).kind, Rise::AtStart);
}

// Refinement ends with a bracket of at most the tolerance, also where false position walks onto
// the root from one side and the value there rounds below 0 (then it would stall with the far
// end never moved: seen on 2 of the 1000 blobs' pixels before the points were kept inside).
TEST(FirstRise, RefinementClosesTheBracketFromBothSides) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int brackets = 0;
  for (int i = 0; i < 20000; ++i) {
    const int degree = 2 + i % 3;
    double a[kMaxDegree + 1] = {-u(rng)};
    for (int j = 1; j <= degree; ++j) a[j] = u(rng);  // rising on [0, 1] from a[0] < 0
    const Rise r = first_rise(a, degree, 1e-15, 1e-3, 1e-9);
    if (r.kind != Rise::Bracket) continue;
    ++brackets;
    int steps = 0;
    const Rise n = refine_rise(a, degree, r, 1e-9, &steps);
    ASSERT_LE(n.hi - n.lo, 1e-9) << "case " << i;
    ASSERT_LT(power_value(a, degree, n.lo), 0) << "case " << i;
    ASSERT_GE(power_value(a, degree, n.hi), 0) << "case " << i;
    ASSERT_GE(n.lo, r.lo);
    ASSERT_LE(n.hi, r.hi);
  }
  EXPECT_GT(brackets, 10000);
}

}  // namespace softtrace::test
