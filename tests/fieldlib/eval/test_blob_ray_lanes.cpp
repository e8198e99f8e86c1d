// BlobSum::ball_terms4's kernels (fieldlib/eval/blob_ray_lanes.cpp): the AVX2 kernel gives the
// scalar ball_term's bits in every lane, and terms_of's runs of four balls the terms one at a
// time would, in the same order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "eval/blob_ray.h"
#include "model/program_builder.h"
#include "sweep.h"

namespace softtrace::test {

namespace {

// Balls placed about a stretch o + u d, u in [0, len], so that it misses, grazes, enters, leaves
// and passes through them, some beyond either end, some exactly tangent; strengths of both signs.
struct LaneCase {
  Vec3 o, d;
  double len;
  BlobSum::Blob balls[4];
};

LaneCase random_lane_case(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1, 1), pos(0, 1);
  LaneCase c;
  c.o = {20 * unit(rng), 20 * unit(rng), 20 * unit(rng)};
  Vec3 d{unit(rng), unit(rng), unit(rng)};
  while (!(length(d) > 0.1)) d = {unit(rng), unit(rng), unit(rng)};
  // Mostly unit, as the tracers' rays are to rounding; some not (dd != 1).
  c.d = pos(rng) < 0.8 ? d / length(d) : d * (0.5 + 2 * pos(rng));
  c.len = pos(rng) < 0.1 ? 0.0 : 30 * pos(rng);
  const Vec3 side = normalize(cross(d, Vec3{0.3, 1, -0.2}));
  for (BlobSum::Blob& b : c.balls) {
    const double radius = 0.1 + 3 * pos(rng);
    // How far from the line: inside, near the surface, exactly on it (a tangent), outside.
    const double k = pos(rng);
    const double off = k < 0.15  ? radius
                       : k < 0.3 ? radius * (1 + 1e-12 * unit(rng))
                                 : 1.3 * radius * pos(rng);
    const double along = c.len * (1.6 * pos(rng) - 0.3) + radius * unit(rng);
    b.centre = c.o + c.d * (along / length(c.d)) + side * off;
    b.inv_r2 = 1 / (radius * radius);
    const double strength = pos(rng) < 0.3 ? -0.5 - pos(rng) : 0.2 + 2 * pos(rng);
    b.c2 = strength * (pos(rng) < 0.5 ? 1.0 : 5.0 / 9);
    b.c3 = strength * (pos(rng) < 0.5 ? 0.0 : 4.0 / 9);
  }
  return c;
}

// Both kernels on one case: the same lanes found, and each found lane's term the same bits.
void expect_lanes_same_bits(const LaneCase& c, int* found) {
  const BlobSum::Blob* const balls[4] = {&c.balls[0], &c.balls[1], &c.balls[2], &c.balls[3]};
  const double dd = dot(c.d, c.d);
  BlobSum::Term scalar[4], avx2[4];
  const unsigned s = BlobSum::ball_lanes_scalar(balls, c.o, c.d, dd, c.len, scalar);
  const unsigned v = BlobSum::ball_lanes_avx2(balls, c.o, c.d, dd, c.len, avx2);
  ASSERT_EQ(s, v);
  for (int i = 0; i < 4; ++i) {
    if (!(s >> i & 1)) continue;
    ++*found;
    EXPECT_EQ(std::memcmp(&scalar[i], &avx2[i], sizeof(BlobSum::Term)), 0)
        << "lane " << i << ": enter " << scalar[i].enter << " / " << avx2[i].enter << ", exit "
        << scalar[i].exit << " / " << avx2[i].exit << ", peak " << scalar[i].peak << " / "
        << avx2[i].peak;
  }
}

// One random ray along x through a row of blobs: terms_of over `ids` against terms_of_one blob
// by blob, every term to the bit; adds the terms compared to `compared`.
void expect_terms_one_at_a_time(const BlobSum& sum, const std::vector<int32_t>& ids,
                                std::mt19937_64& rng, int& compared) {
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<BlobSum::Term> batched(sum.max_terms()), single(sum.max_terms());
  const Vec3 o{-16 + 4 * unit(rng), 1.4 * unit(rng), 1.4 * unit(rng)};
  const Vec3 d = normalize(Vec3{1, 0.05 * unit(rng), 0.05 * unit(rng)});
  const double len = 34 * (0.5 + 0.5 * unit(rng)), dd = dot(d, d);
  const int n = sum.terms_of(ids.data(), static_cast<int>(ids.size()), o, d, len, batched.data());
  int m = 0;
  for (const int32_t id : ids) m += sum.terms_of_one(id, o, d, dd, len, single.data() + m);
  ASSERT_EQ(n, m);
  for (int i = 0; i < n; ++i)
    ASSERT_EQ(std::memcmp(&batched[i], &single[i], sizeof(BlobSum::Term)), 0) << "term " << i;
  compared += n;
}

}  // namespace

TEST(BallLanes, Avx2ChosenWhereLibgccFindsIt) {
  // has_avx2 reads glibc's record of the processor (or cpuid) instead of libgcc's constructor,
  // which would run a dozen trapping cpuid queries at every start: both must agree.
  __builtin_cpu_init();
  EXPECT_EQ(BlobSum::has_avx2(), __builtin_cpu_supports("avx2") != 0);
}

TEST(BallLanes, Avx2GivesTheScalarBitsInEveryLane) {
  if (!BlobSum::has_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937_64 rng(30);
  int found = 0;
  for (int i = 0; i < 200000; ++i) {
    expect_lanes_same_bits(random_lane_case(rng), &found);
    if (HasFailure()) return;
  }
  // Most lanes have a term, and enough miss: both kinds were compared.
  EXPECT_GT(found, 200000);
  EXPECT_LT(found, 700000);
}

TEST(BallLanes, TermsOfTakesRunsOfBallsAsOneAtATime) {
  // 40 balls of equal radius along a line (every seventh a Wyvill ball of another strength), and
  // lists of them mixing runs of four or more with shorter ones; terms_of against terms_of_one.
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < 40; ++i)
    s += std::string(i ? "," : "") + R"({"type":"soft_object","potential":{"type":")" +
         (i % 7 ? "murakami" : "wyvill") + R"("},"distance":{"type":"lp_metric","n":2,)" +
         R"("radii":[1.5,1.5,1.5]},"translate":[)" + std::to_string(0.7 * i - 14) + "," +
         std::to_string(0.3 * std::sin(i)) + ",0]}";
  s += "]}";
  const Program p = compile(*build_from_json(s));
  const std::optional<BlobSum> sum = BlobSum::of(p);
  ASSERT_TRUE(sum);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<int32_t> ids;
    for (int32_t id = 0; id < sum->size(); ++id)
      if (unit(rng) > -0.6) ids.push_back(id);
    expect_terms_one_at_a_time(*sum, ids, rng, compared);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(compared, 20000);
}

TEST(BallLanes, TermsOfTakesShortRunsOfBallsAsOneAtATime) {
  // Balls with ellipsoids among them (about one child in three), so that lists hold runs of one,
  // two, three and four or more balls between other blobs: with the AVX2 kernel a run of three
  // takes it too, its fourth lane given the third ball again and that term dropped. terms_of
  // against terms_of_one, every run length seen.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < 36; ++i) {
    const bool ball = unit(rng) > -0.35;
    s += std::string(i ? "," : "") + R"({"type":"soft_object","potential":{"type":")" +
         (i % 5 ? "murakami" : "wyvill") + R"("},"distance":{"type":"lp_metric","n":2,)" +
         (ball ? R"("radii":[1.5,1.5,1.5]},)" : R"("radii":[1.5,1.1,1.3]},)") + R"("translate":[)" +
         std::to_string(0.8 * i - 14) + "," + std::to_string(0.3 * std::sin(i)) + ",0]}";
  }
  s += "]}";
  const Program p = compile(*build_from_json(s));
  const std::optional<BlobSum> sum = BlobSum::of(p);
  ASSERT_TRUE(sum);
  const auto ball = [&](int32_t id) { return sum->blobs()[size_t(id)].inv_r2 > 0; };
  int compared = 0, runs[5] = {0, 0, 0, 0, 0};
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<int32_t> ids;
    for (int32_t id = 0; id < sum->size(); ++id)
      if (unit(rng) > -0.4) ids.push_back(id);
    for (size_t i = 0; i < ids.size();) {  // the list's runs of balls, by length (4: 4 or more)
      size_t j = i;
      while (j < ids.size() && ball(ids[j])) ++j;
      ++runs[std::min<size_t>(j - i, 4)];
      i = j + 1;
    }
    expect_terms_one_at_a_time(*sum, ids, rng, compared);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(compared, 10000);
  for (int k = 1; k <= 4; ++k) EXPECT_GT(runs[k], 500) << k;
}

}  // namespace softtrace::test
