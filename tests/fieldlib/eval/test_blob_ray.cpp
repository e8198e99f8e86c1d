// Sums of polynomial blobs along a ray (fieldlib/blob_ray.h) and the Bernstein root search
// (fieldlib/bernstein.h): which programs are such sums, that the polynomial of each piece of a
// stretch is the field there, and that first_rise finds the first crossing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <string>

#include "eval/blob_frame_terms.h"
#include "eval/blob_ray.h"
#include "eval/eval.h"
#include "kernels/potentials.h"
#include "model/program_builder.h"
#include "sweep.h"

namespace softtrace::test {

namespace {

// n blobs in [-spread, spread]^3: ellipsoids of radii 2..5 (every fourth a ball), every third
// rotated, every other one Wyvill's potential, the translation on the soft object or on its
// distance.
std::string blob_cloud(int n, unsigned seed, double spread = 6) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-spread, spread), r(2, 5), a(-1, 1);
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

// n capsules as POV-Ray's cylinder components come out of tools/pov2softtrace.py: segments in
// world coordinates (every fifth of zero length: a point skeleton), every third under a rotation
// and translation, every fourth sheared by a `matrix`; strengths in [-1, 2] (a third negative),
// Murakami's, Wyvill's and the cubic potential; every other child an ellipsoid between them.
std::string capsule_cloud(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-6, 6), r(1.5, 4), a(-1, 1), len(0.5, 6);
  const auto num = [](double v) { return std::to_string(v); };
  const auto vec = [&](const Vec3& v) {
    return "[" + num(v.x) + "," + num(v.y) + "," + num(v.z) + "]";
  };
  const char* const potentials[] = {"murakami", "wyvill", "cubic"};
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < n; ++i) {
    const Vec3 p0{c(rng), c(rng), c(rng)};
    const Vec3 p1 = i % 5 == 4 ? p0 : p0 + normalize({a(rng), a(rng), a(rng)}) * len(rng);
    std::string distance = R"({"type":"segment","p0":)" + vec(p0) + R"(,"p1":)" + vec(p1) +
                           R"(,"radius":)" + num(r(rng)) + "}";
    if (i % 2 == 1)
      distance = R"({"type":"lp_metric","n":2,"translate":)" + vec(p0) + R"(,"radii":[)" +
                 num(r(rng)) + "," + num(r(rng)) + "," + num(r(rng)) + "]}";
    std::string place;
    if (i % 4 == 0) {
      place = R"(,"matrix":[)";
      for (int row = 0; row < 3; ++row)
        place += std::string(row ? "," : "") + "[" + num((row == 0) + 0.4 * a(rng)) + "," +
                 num((row == 1) + 0.4 * a(rng)) + "," + num((row == 2) + 0.4 * a(rng)) + "," +
                 num(a(rng)) + "]";
      place += "]";
    } else if (i % 3 == 0) {
      place = R"(,"rotate":{"axis":[)" + num(a(rng)) + "," + num(a(rng)) +
              ",1],\"deg\":" + num(90 * a(rng)) + R"(},"translate":)" +
              vec({a(rng), a(rng), a(rng)});
    }
    const double strength =
        i % 3 == 2 ? -0.4 - 0.6 * std::abs(a(rng)) : 0.5 + 1.5 * std::abs(a(rng));
    s += (i ? "," : "") + std::string(R"({"type":"soft_object","potential":{"type":")") +
         potentials[i % 3] + R"("},"strength":)" + num(strength) + place + R"(,"distance":)" +
         distance + "}";
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
  // Capsules are (POV-Ray's cylinder components), also of zero length, rotated or sheared.
  EXPECT_TRUE(is_blob_sum(
      sum(soft("murakami", ball),
          soft("murakami", R"({"type":"segment","p0":[0,0,0],"p1":[1,0,0],"radius":1})"))));
  EXPECT_TRUE(
      is_blob_sum(sum(soft("cubic", ball),
                      soft("wyvill", R"({"type":"segment","p0":[1,2,3],"p1":[1,2,3],"radius":1,)"
                                     R"("rotate":{"axis":[0,0,1],"deg":30}})"))));
  EXPECT_TRUE(is_blob_sum(sum(
      soft("murakami", ball),
      R"({"type":"soft_object","potential":{"type":"murakami"},"matrix":[[1,0.5,0,0],[0,1,0,0],)"
      R"([0,0,2,1]],"distance":{"type":"segment","p0":[0,0,0],"p1":[1,0,0],"radius":1}})")));
  // A segment so long beside its radius that 1 / |axis|^2 underflows keeps the segment tracer.
  EXPECT_FALSE(is_blob_sum(
      sum(soft("murakami", ball),
          soft("murakami", R"({"type":"segment","p0":[0,0,0],"p1":[1e90,0,0],"radius":1e-20})"))));
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

// Along a stretch o + u d, u in [0, len], each piece's polynomial (plus iso) is the compiled
// field, within the piece's err and the rounding of the points (the field is evaluated at the
// rounded o + u d, the polynomial at exact u: a few ulps of the coordinates, times a slope of
// at most ~1 per unit here). Counts the points checked inside pieces and between them.
// `slack` scales the rounding allowance: affine frames cancel more digits in L x + k, and their
// blobs are steeper (radii down to 0.8, strengths up to 2).
void expect_stretch_is_polynomials_of_the_field(Cloud& cloud, const Vec3& o, const Vec3& d,
                                                double len, double slack, std::mt19937_64& rng,
                                                int* pieces, int* outside) {
  const Program& prog = cloud.prog;
  const auto& blobs = cloud.blobs;
  std::vector<BlobSum::Term> terms(blobs->max_terms());
  std::uniform_real_distribution<double> x01(0, 1);
  const int n = blobs->terms(prog, o, d, len, 1e-12, terms.data(), cloud.ids.data());
  std::vector<double> cuts{0, len};
  for (int i = 0; i < n; ++i) {
    cuts.push_back(terms[i].enter);
    cuts.push_back(terms[i].exit);
  }
  std::sort(cuts.begin(), cuts.end());
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    const double s0 = cuts[c], S = cuts[c + 1] - s0;
    if (!(S > 1e-9)) continue;
    std::vector<int> active;  // (s0 + S may round past the cut: compare with the cut itself)
    for (int i = 0; i < n; ++i)
      if (terms[i].enter <= s0 && terms[i].exit >= cuts[c + 1]) active.push_back(i);
    const StretchPolynomial sp =
        stretch_polynomial(terms.data(), active.data(), int(active.size()), s0, S, 0.5);
    // Each term's largest value over this piece, with negative blobs at their least depth.
    const double bound =
        piece_peak(terms.data(), active.data(), int(active.size()), s0, cuts[c + 1]);
    for (int k = 0; k < 5; ++k) {
      const double x = x01(rng);
      const double field = value(prog, o + d * (s0 + x * S), cloud.ws);
      ASSERT_LE(power_value(sp.a, sp.degree, x) + 0.5, bound + sp.err)
          << "piece_peak below the piece at " << s0 << " of length " << S;
      if (active.empty()) {
        ++*outside;
        ASSERT_EQ(field, 0) << "a blob the query missed is non-zero at u = " << s0 + x * S;
        continue;
      }
      ++*pieces;
      // The field is evaluated at the rounded o + u d: 1e-16 of |o| + u, over radii >= 2.
      const double rounding = slack * (1e-13 + 2e-16 * (length(o) + s0 + S));
      ASSERT_NEAR(power_value(sp.a, sp.degree, x) + 0.5, field, sp.err + rounding)
          << "piece at " << s0 << " of length " << S;
    }
    // The peaks bound the piece from above.
    double peak = 0;
    for (int i : active) peak += terms[i].peak;
    ASSERT_LE(power_value(sp.a, sp.degree, 0.5) + 0.5, peak * (1 + 1e-12) + 1e-15);
  }
}

// The same along random stretches of 300 random rays.
void expect_pieces_are_polynomials_of_the_field(Cloud& cloud, double slack) {
  ASSERT_TRUE(cloud.blobs.has_value());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), x01(0, 1);
  int pieces = 0, outside = 0;
  for (int ray = 0; ray < 300; ++ray) {
    SCOPED_TRACE("ray " + std::to_string(ray));
    // Every third stretch starts 1e8 away and ends 1e8 beyond the cloud: the terms then lose
    // digits to w = L o + k as the points o + u d do to their own rounding, no more.
    const bool far = ray % 3 == 2;
    const Vec3 d = normalize({u(rng), u(rng), u(rng)});
    const Vec3 o = Vec3{u(rng), u(rng), u(rng)} * 12 - (far ? d * 1e8 : Vec3{});
    const double len = far ? 2e8 : 30 * x01(rng);
    expect_stretch_is_polynomials_of_the_field(cloud, o, d, len, slack, rng, &pieces, &outside);
    if (testing::Test::HasFatalFailure()) return;
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

// Capsules (segments) of any strength and placement, among ellipsoids: each of a capsule's three
// parts along a ray (past either end plane, between them) is one quadratic in r.
TEST(BlobSum, CapsulesArePiecewiseOnePolynomialToo) {
  Cloud cloud(capsule_cloud(40, 6));
  ASSERT_TRUE(cloud.blobs.has_value());
  EXPECT_EQ(cloud.blobs->size(), 40);
  EXPECT_EQ(cloud.blobs->max_terms(), 40 + 2 * 16);  // 20 segments, 4 of them of zero length
  expect_pieces_are_polynomials_of_the_field(cloud, 10);
}

// A sum of at most BlobSum::kListed blobs lists them instead of querying its BVH: every blob then
// takes its own support test, which must keep exactly the blobs the query would (a term of a
// blob the stretch misses would be a piece the field is not).
TEST(BlobSum, ListedBlobsArePiecewiseOnePolynomialToo) {
  Cloud cloud(capsule_cloud(BlobSum::kListed, 8));
  ASSERT_TRUE(cloud.blobs.has_value());
  EXPECT_EQ(cloud.blobs->size(), BlobSum::kListed);
  expect_pieces_are_polynomials_of_the_field(cloud, 10);
}

// A listed sum of balls alone takes its list whole (every ball takes its own support test): the
// pieces must still be the field's, with no ball left out nor taken twice.
TEST(BlobSum, ListedBallsArePiecewiseOnePolynomialToo) {
  std::mt19937_64 rng(35);
  std::uniform_real_distribution<double> c(-5, 5), r(2, 5);
  std::string json = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < BlobSum::kListed; ++i) {
    const std::string radius = std::to_string(r(rng));
    json += (i ? "," : "") + std::string(R"({"type":"soft_object","potential":{"type":")") +
            (i % 2 ? "wyvill" : "murakami") + R"("},"distance":{"type":"lp_metric","n":2,)" +
            R"("radii":[)" + radius + "," + radius + "," + radius + R"(]},"translate":[)" +
            std::to_string(c(rng)) + "," + std::to_string(c(rng)) + "," + std::to_string(c(rng)) +
            "]}";
  }
  Cloud cloud(json + "]}");
  ASSERT_TRUE(cloud.blobs.has_value());
  EXPECT_EQ(cloud.blobs->size(), BlobSum::kListed);
  EXPECT_TRUE(cloud.blobs->all_balls());
  expect_pieces_are_polynomials_of_the_field(cloud, 10);
}

// A capsule's or ellipsoid's terms one blob at a time (terms_of_one, through BlobSum::frame_terms,
// and blob_frame::terms_of_one, the camera sweep's, inline) are those of a list's (terms_of, its
// own inline copy) to the bit, and a
// stretch that passes clear of a blob's bounding sphere gets no term of it: terms_of takes no
// sphere test before a frame, so that must come from the frame's own arithmetic.
TEST(BlobSum, FramedTermsOneAtATimeAreTheListsToTheBit) {
  Cloud cloud(capsule_cloud(40, 12));
  ASSERT_TRUE(cloud.blobs.has_value());
  const BlobSum& sum = *cloud.blobs;
  ASSERT_GT(sum.size(), BlobSum::kListed);
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<BlobSum::Term> listed(sum.max_terms()), single(sum.max_terms()), inline_one(3);
  int compared = 0, clear = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<int32_t> ids;
    for (int32_t id = 0; id < sum.size(); ++id)
      if (unit(rng) > -0.5) ids.push_back(id);
    // From inside the cloud, from near it and from far off (a camera's eye 1e3 away).
    const double far = trial % 3 == 0 ? 1e3 : trial % 3 == 1 ? 20 : 6;
    const Vec3 o = normalize({unit(rng), unit(rng), unit(rng)}) * far;
    const Vec3 d = normalize(Vec3{6 * unit(rng), 6 * unit(rng), 6 * unit(rng)} - o);
    const double len = far + 12 * (1 + unit(rng)), dd = dot(d, d);
    const int n = sum.terms_of(ids.data(), static_cast<int>(ids.size()), o, d, len, listed.data());
    int m = 0;
    for (const int32_t id : ids) {
      const int k = sum.terms_of_one(id, o, d, dd, len, single.data() + m);
      ASSERT_EQ(blob_frame::terms_of_one(sum, id, o, d, dd, len, inline_one.data()), k)
          << "blob " << id << ", trial " << trial;
      for (int i = 0; i < k; ++i)
        ASSERT_EQ(std::memcmp(&inline_one[i], &single[m + i], sizeof(BlobSum::Term)), 0)
            << "blob " << id << "'s inline term " << i << ", trial " << trial;
      Vec3 centre;
      const double reach2 = sum.bounding_sphere(id, &centre);
      const Vec3 oc = o - centre;
      const Vec3 nearest = oc + d * std::clamp(-dot(oc, d), 0.0, len);
      if (sum.is_framed(id) && dot(nearest, nearest) > reach2 * (1 + 1e-9)) {
        ++clear;
        EXPECT_EQ(k, 0) << "blob " << id << " passed clear of, trial " << trial;
      }
      m += k;
    }
    ASSERT_EQ(n, m) << "trial " << trial;
    for (int i = 0; i < n; ++i)
      ASSERT_EQ(std::memcmp(&listed[i], &single[i], sizeof(BlobSum::Term)), 0)
          << "term " << i << ", trial " << trial;
    compared += n;
  }
  EXPECT_GT(compared, 10000);
  EXPECT_GT(clear, 10000);
}

// A frame whose L has zeros off its diagonal (a segment's or an ellipsoid's that no rotation or
// matrix placed) takes L x and L^T w from the diagonal alone (BlobSum::Frame::diagonal): the rows'
// values, for every such frame of a capsule cloud, and no frame a rotation or matrix placed is
// taken so.
TEST(BlobSum, DiagonalFramesTakeTheRowsValues) {
  Cloud cloud(capsule_cloud(40, 12));
  ASSERT_TRUE(cloud.blobs.has_value());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-10, 10);
  int diagonal = 0, framed = 0;
  for (int32_t id = 0; id < cloud.blobs->size(); ++id) {
    if (!cloud.blobs->is_framed(id)) continue;
    ++framed;
    const BlobSum::Frame& f = cloud.blobs->frames()[size_t(id)];
    BlobSum::Frame rows = f;
    rows.diagonal = false;
    diagonal += f.diagonal;
    for (int trial = 0; trial < 50; ++trial) {
      const Vec3 x{unit(rng), unit(rng), unit(rng)};
      const Vec3 a = f.times(x), b = rows.times(x);
      const Vec3 at = f.transposed_times(x), bt = rows.transposed_times(x);
      const Vec3 aq = f.q(x), bq = rows.q(x);
      for (int i = 0; i < 3; ++i) {
        ASSERT_EQ(a[i], b[i]) << "blob " << id << ", L x";
        ASSERT_EQ(at[i], bt[i]) << "blob " << id << ", L^T w";
        ASSERT_EQ(aq[i], bq[i]) << "blob " << id << ", q";
      }
    }
  }
  // Of the 40 blobs, every fourth is matrix-placed and every third of the rest rotated; of the 20
  // others, two segments of zero length are balls (no frame taken), and the 18 segments and
  // ellipsoids left have diagonal frames.
  EXPECT_EQ(framed, 38);
  EXPECT_EQ(diagonal, 18);
}

// Rays exactly along a capsule's axis (its middle part is then constant along the ray: no term of
// alpha > 0), exactly across it (the ray stays in one part), through its end caps, and through a
// zero-length segment, near and from 1e8 away.
TEST(BlobSum, CapsulesAlongAndAcrossTheirAxis) {
  Cloud cloud(R"({"type":"soft_blend","children":[
      {"type":"soft_object","potential":{"type":"murakami"},
       "distance":{"type":"segment","p0":[-3,0,0],"p1":[3,0,0],"radius":2}},
      {"type":"soft_object","potential":{"type":"wyvill"},"strength":-0.8,
       "distance":{"type":"segment","p0":[2,0.5,0],"p1":[2,0.5,4],"radius":1}},
      {"type":"soft_object","potential":{"type":"cubic"},"strength":1.5,
       "distance":{"type":"segment","p0":[0,3,1],"p1":[0,3,1],"radius":1.5}}]})");
  ASSERT_TRUE(cloud.blobs.has_value());
  EXPECT_EQ(cloud.blobs->max_terms(), 3 + 2 * 2);
  std::mt19937_64 rng(8);
  int pieces = 0, outside = 0;
  const struct {
    Vec3 o, d;
  } rays[] = {
      {{-10, 0.7, -0.4}, {1, 0, 0}},  // along the first capsule's axis, inside its radius
      {{10, 1.9, 0.3}, {-1, 0, 0}},   // the same way back, grazing its surface
      {{2, 0.2, -6}, {0, 0, 1}},      // along the second's axis
      {{-1.5, -6, 0.5}, {0, 1, 0}},   // across the first's axis, between its end planes
      {{-3.5, -6, 0}, {0, 1, 0}},     // across, beyond one end plane
      {{0, 3, -6}, {0, 0, 1}},        // through the zero-length segment's point
      {{-8, -5, 0.2}, {0.8, 0.6, 0}},
  };
  for (const auto& ray : rays)
    for (const double far : {0.0, 1e8}) {
      SCOPED_TRACE("ray from " + std::to_string(ray.o.x) + (far > 0 ? ", far" : ""));
      const Vec3 d = normalize(ray.d);
      expect_stretch_is_polynomials_of_the_field(cloud, ray.o - d * far, d, 20 + 2 * far, 10, rng,
                                                 &pieces, &outside);
      if (testing::Test::HasFatalFailure()) return;
    }
  EXPECT_GT(pieces, 100);
  EXPECT_GT(outside, 20);
}

// The normals of blob sums come from BlobSum::gradient: the compiled gradient's value and
// direction, to rounding, inside and between supports, and 0 outside all of them.
// `min_inside`: of the 2000 points, how many at least fall inside a support (fewer blobs, fewer).
void expect_gradient_is_the_compiled_one(Cloud& cloud, double tol, int min_inside = 300) {
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
  EXPECT_GT(inside, min_inside);
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

TEST(BlobSum, CapsulesGradientIsTheCompiledOne) {
  Cloud cloud(capsule_cloud(40, 7));
  ASSERT_TRUE(cloud.blobs.has_value());
  expect_gradient_is_the_compiled_one(cloud, 1e-13);
}

// BlobSum::support_extent, the support function a beam's side planes test blobs that are no balls
// with (tracer_blob_beam.cpp): at a point x of a support's boundary whose outward normal is n (the
// gradient of |q|^2 there; the support is convex), the support function at n is n.x. So the
// extent must be at least n.x (else a beam could drop a blob it meets) and at most n.x plus a
// small slack (else it is not the support's). Boundary points are found by bisection of |q| from
// the blob's centre along random directions, by the frame's own q; capsules, ellipsoids, sheared
// and matrix-placed blobs of both signs, and a thin sheared capsule and a flat ellipsoid.
void expect_extents_touch_the_supports(const std::string& json, int min_framed) {
  Cloud cloud(json);
  ASSERT_TRUE(cloud.blobs.has_value());
  const BlobSum& blobs = *cloud.blobs;
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  int framed = 0;
  for (int id = 0; id < blobs.size(); ++id) {
    if (!blobs.is_framed(id)) continue;
    ++framed;
    const BlobSum::Frame& f = blobs.frames()[size_t(id)];
    Vec3 c;
    const double R = std::sqrt(blobs.bounding_sphere(id, &c));
    ASSERT_TRUE(std::isfinite(R)) << "blob " << id;
    ASSERT_LT(dot(f.q(c), f.q(c)), 1e-20) << "blob " << id;  // the centre is inside
    for (int k = 0; k < 200; ++k) {
      const Vec3 dir = normalize({u(rng), u(rng), u(rng)});
      double lo = 0, hi = R;
      for (int i = 0; i < 200 && hi - lo > 0; ++i) {
        const double m = 0.5 * (lo + hi);
        const Vec3 q = f.q(c + dir * m);
        (dot(q, q) <= 1 ? lo : hi) = m;
      }
      const Vec3 x = c + dir * lo, q = f.q(x);
      const Vec3 n = normalize(f.L.transposed_times(q));
      const double extent = blobs.support_extent(id, n);
      const double reach = dot(n, x);
      ASSERT_GE(extent, reach) << "blob " << id << ", direction " << k;
      ASSERT_LE(extent, reach + 1e-9 * (R + length(c))) << "blob " << id << ", direction " << k;
    }
  }
  EXPECT_GE(framed, min_framed);
}
TEST(BlobSum, SupportExtentsTouchTheSupports) {
  expect_extents_touch_the_supports(capsule_cloud(40, 21), 30);
  expect_extents_touch_the_supports(affine_cloud(20, 22), 15);
  // A thin sheared capsule (a matrix with a 50:1 aspect), a flat ellipsoid and a long capsule
  // rotated and scaled after the rotation, one of them of negative strength.
  expect_extents_touch_the_supports(R"({"type":"soft_blend","children":[
      {"type":"soft_object","potential":{"type":"murakami"},"strength":-0.7,
       "distance":{"type":"segment","p0":[-3,0,0],"p1":[4,1,0],"radius":0.5},
       "matrix":[[1,0.8,0,2],[0,0.02,0,1],[0,0.3,1,-5]]},
      {"type":"soft_object","potential":{"type":"wyvill"},
       "distance":{"type":"lp_metric","n":2,"radii":[3,3,3]},"scale":[1,0.01,2],
       "translate":[100,-40,7]},
      {"type":"soft_object","potential":{"type":"cubic"},
       "distance":{"type":"segment","p0":[-7,0,0],"p1":[7,0,0],"radius":0.8},
       "rotate":{"axis":[1,2,3],"deg":35},"scale":[1,1.5,0.4]}]})",
                                    3);
}

TEST(BlobSum, ListedBlobsGradientIsTheCompiledOne) {
  Cloud cloud(capsule_cloud(BlobSum::kListed, 9));
  ASSERT_TRUE(cloud.blobs.has_value());
  expect_gradient_is_the_compiled_one(cloud, 1e-13, 150);
}

// A camera ray's normal takes its beam's list instead of the point query (gradient_among): any
// superset of the blobs whose supports hold x, in any order, gives the query's f, ∇f and terms to
// the bit (the same blobs, summed in the same increasing order).
// `min_points`: of the 2000 points, how many at least fall inside a support and in several blobs'
// spheres (fewer blobs, fewer).
void expect_gradient_among_is_the_querys(Cloud& cloud, int min_points = 300) {
  ASSERT_TRUE(cloud.blobs.has_value());
  const BlobSum& blobs = *cloud.blobs;
  const Program& prog = cloud.prog;
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> u(-12, 12);
  std::vector<int32_t> among(blobs.size());
  std::vector<double> terms_query(prog.terms), terms_among(prog.terms);
  int inside = 0, several = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 x{u(rng), u(rng), u(rng)};
    Vec3 g_query, g_among;
    const double f_query = blobs.gradient(prog, x, &g_query, cloud.ids.data(), terms_query.data());
    // The blobs whose bounding spheres hold x (a beam's list keeps those), shuffled.
    int n = 0;
    for (int id = 0; id < blobs.size(); ++id) {
      Vec3 c;
      const double r2 = blobs.bounding_sphere(id, &c);
      if (dot(x - c, x - c) <= r2) among[n++] = id;
    }
    several += n > 1;
    std::shuffle(among.begin(), among.begin() + n, rng);
    const double f_among =
        blobs.gradient_among(prog, x, among.data(), n, &g_among, terms_among.data());
    ASSERT_EQ(f_among, f_query) << "at point " << i;
    ASSERT_EQ(g_among.x, g_query.x) << "at point " << i;
    ASSERT_EQ(g_among.y, g_query.y) << "at point " << i;
    ASSERT_EQ(g_among.z, g_query.z) << "at point " << i;
    ASSERT_EQ(terms_among, terms_query) << "at point " << i;
    inside += f_query != 0;
  }
  EXPECT_GT(inside, min_points);
  EXPECT_GT(several, min_points);
}
TEST(BlobSum, GradientAmongAListIsTheQuerysToTheBit) {
  Cloud cloud(3);
  expect_gradient_among_is_the_querys(cloud);
}
// A ball's q and L^T q are taken without L's zeros (sum_gradient) and its list's prefilter from
// its centre (gradient_among): the sums must be the frames' own arithmetic to the bit, at random
// points and at points within rounding of a ball's boundary, where the prefilter's slack decides.
TEST(BlobSum, ABallsGradientIsItsFramesArithmeticToTheBit) {
  Cloud cloud(3);
  ASSERT_TRUE(cloud.blobs.has_value());
  const BlobSum& blobs = *cloud.blobs;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-8, 8), side(-1, 1);
  std::vector<int32_t> balls, all(blobs.size());
  for (int id = 0; id < blobs.size(); ++id)
    if (blobs.blobs()[id].inv_r2 > 0) balls.push_back(id);
  ASSERT_GE(balls.size(), 5u);
  int near_boundary_inside = 0;
  for (int i = 0; i < 4000; ++i) {
    Vec3 x{u(rng), u(rng), u(rng)};
    if (i % 2) {  // within a few ulps of a ball's boundary, inside or out
      const BlobSum::Blob& b = blobs.blobs()[balls[i % balls.size()]];
      Vec3 dir{side(rng), side(rng), side(rng)};
      dir = dir / length(dir);
      x = b.centre + dir * (std::sqrt(1 / b.inv_r2) * (1 + 4e-16 * side(rng)));
    }
    // The frames' own arithmetic over every blob in increasing order.
    double f = 0;
    Vec3 g;
    for (int id = 0; id < blobs.size(); ++id) {
      const BlobSum::Frame& frame = blobs.frames()[id];
      const BlobSum::Blob& b = blobs.blobs()[id];
      const Vec3 w = frame.q(x);
      const double r = 1 - dot(w, w);
      if (!(r > 0)) continue;
      near_boundary_inside += i % 2 && r < 1e-12;
      f += polynomial_potential(r, b.c2, b.c3);
      g += frame.L.transposed_times(w) * (-2 * polynomial_potential_slope(r, b.c2, b.c3));
    }
    Vec3 g_query, g_among;
    ASSERT_EQ(blobs.gradient(cloud.prog, x, &g_query, cloud.ids.data()), f) << "point " << i;
    for (int id = 0; id < blobs.size(); ++id) all[id] = id;
    std::shuffle(all.begin(), all.end(), rng);
    ASSERT_EQ(blobs.gradient_among(cloud.prog, x, all.data(), blobs.size(), &g_among), f)
        << "point " << i;
    for (const Vec3& got : {g_query, g_among}) {
      ASSERT_EQ(got.x, g.x) << "point " << i;
      ASSERT_EQ(got.y, g.y) << "point " << i;
      ASSERT_EQ(got.z, g.z) << "point " << i;
    }
  }
  EXPECT_GT(near_boundary_inside, 100);  // the boundary points do test the prefilter
}
// gradient_among sorts the blobs that hold x by insertion up to 32 of them and by std::sort past
// that: 60 blobs around the origin, where x lies in all of them or in a few, give the query's
// f, ∇f and terms to the bit on both sides of the switch.
TEST(BlobSum, GradientAmongManyHeldBlobsIsTheQuerysToTheBit) {
  Cloud cloud(blob_cloud(60, 12, 1));
  ASSERT_TRUE(cloud.blobs.has_value());
  const BlobSum& blobs = *cloud.blobs;
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-5, 5);
  std::vector<int32_t> all(blobs.size());
  std::vector<double> terms_query(cloud.prog.terms), terms_among(cloud.prog.terms);
  int many = 0, few = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 x{u(rng), u(rng), u(rng)};
    Vec3 g_query, g_among;
    const double f_query =
        blobs.gradient(cloud.prog, x, &g_query, cloud.ids.data(), terms_query.data());
    int held = 0;  // the blobs whose supports hold x
    for (const BlobSum::Frame& frame : blobs.frames()) {
      const Vec3 w = frame.q(x);
      held += 1 - dot(w, w) > 0;
    }
    many += held > 32;
    few += held > 1 && held <= 32;
    for (int id = 0; id < blobs.size(); ++id) all[id] = id;
    std::shuffle(all.begin(), all.end(), rng);
    const double f_among =
        blobs.gradient_among(cloud.prog, x, all.data(), blobs.size(), &g_among, terms_among.data());
    ASSERT_EQ(f_among, f_query) << "at point " << i;
    ASSERT_EQ(g_among.x, g_query.x) << "at point " << i;
    ASSERT_EQ(g_among.y, g_query.y) << "at point " << i;
    ASSERT_EQ(g_among.z, g_query.z) << "at point " << i;
    ASSERT_EQ(terms_among, terms_query) << "at point " << i;
  }
  EXPECT_GT(many, 100);
  EXPECT_GT(few, 100);
}
TEST(BlobSum, AffineBlobsGradientAmongAListIsTheQuerysToTheBit) {
  Cloud cloud(affine_cloud(40, 5));
  expect_gradient_among_is_the_querys(cloud);
}
TEST(BlobSum, CapsulesGradientAmongAListIsTheQuerysToTheBit) {
  Cloud cloud(capsule_cloud(40, 7));
  expect_gradient_among_is_the_querys(cloud);
}
// A sum of at most kListed blobs: its query is the listed blobs in increasing order, and a short
// list is summed after a sort alone (no test of each blob's q first).
TEST(BlobSum, ListedCapsulesGradientAmongAListIsTheQuerysToTheBit) {
  Cloud cloud(capsule_cloud(BlobSum::kListed, 11));
  ASSERT_LE(cloud.blobs->size(), BlobSum::kListed);
  expect_gradient_among_is_the_querys(cloud, 150);
}

// A ray leaving a strong ball (strength 2, so its peak over its whole range is far above iso)
// through a dimple (a small negative ball): past the point where the ball has fallen below iso,
// its own largest value over a piece is below iso, though the sum of the terms' peaks is not;
// and the dimple, at its least depth over the piece, lowers the bound further.
TEST(BlobSum, PiecePeakIsEachTermsLargestOverThePiece) {
  Cloud cloud(R"({"type":"soft_blend","children":[
      {"type":"soft_object","potential":{"type":"murakami"},"strength":2,
       "distance":{"type":"lp_metric","n":2,"radii":[2,2,2]}},
      {"type":"soft_object","potential":{"type":"murakami"},"strength":-0.4,
       "distance":{"type":"lp_metric","n":2,"radii":[0.3,0.3,0.3]},"translate":[1.8,0.1,0]}]})");
  ASSERT_TRUE(cloud.blobs.has_value());
  std::vector<BlobSum::Term> terms(cloud.blobs->max_terms());
  const Vec3 o{0.5, 0.1, 0}, d{1, 0, 0};
  ASSERT_EQ(cloud.blobs->terms(cloud.prog, o, d, 3, 1e-12, terms.data(), cloud.ids.data()), 2);
  const int ball = terms[0].c2 > 0 ? 0 : 1, dimple = 1 - ball;
  // The ball from u = 0 (at x = 0.5) to sqrt(3.99) - 0.5, the dimple from 1.0 to 1.6.
  EXPECT_NEAR(terms[ball].exit, std::sqrt(3.99) - 0.5, 1e-9);
  EXPECT_NEAR(terms[dimple].enter, 1.0, 1e-9);
  const int both[2] = {ball, dimple};
  const double u0 = terms[dimple].enter, u1 = terms[ball].exit;
  EXPECT_GT(terms[ball].peak + terms[dimple].peak, 1.7);  // 2 (1 - 0.26 / 4)^2
  // The ball at u0 (x = 1.5 off its centre by 0.1 in y): 2 (1 - 2.26 / 4)^2.
  const double ball_at_u0 = 2 * (1 - 2.26 / 4) * (1 - 2.26 / 4);
  EXPECT_NEAR(piece_peak(terms.data(), &both[0], 1, u0, u1), ball_at_u0, 1e-9);
  // The dimple's least depth over [1.0, 1.5], at 1.0 (its centre at 1.3), is 0 at its edge, so
  // the bound is the ball's; over [1.2, 1.5] it is at 1.5, -0.4 (1 - 0.04 / 0.09)^2.
  EXPECT_NEAR(piece_peak(terms.data(), both, 2, u0, u1), ball_at_u0, 1e-9);
  const double ball_at = 2 * (1 - (1.7 * 1.7 + 0.01) / 4) * (1 - (1.7 * 1.7 + 0.01) / 4);
  const double dimple_least = -0.4 * (1 - 0.04 / 0.09) * (1 - 0.04 / 0.09);
  EXPECT_NEAR(piece_peak(terms.data(), both, 2, 1.2, 1.5), ball_at + dimple_least, 1e-9);
  EXPECT_LT(piece_peak(terms.data(), both, 2, 1.2, 1.5), 0.5);
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
