// The mesher's closed forms for sums of blobs: a leaf's blob list (mesh/leaf_blobs.h) gives the
// compiled program's values, its grid the same bits as its values, its gradient BlobSum's bits;
// and a block's interval (mesh/blob_bounds.h) holds the field over the block.
#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <string>
#include <vector>

#include "eval/blob_ray.h"
#include "eval/eval.h"
#include "mesh/blob_bounds.h"
#include "mesh/leaf_blobs.h"
#include "model/program_builder.h"
#include "sweep.h"

namespace softtrace::test {
namespace {

// n blobs in [-6, 6]^3: balls (every other one) and ellipsoids, every third rotated, Murakami's,
// Wyvill's and the cubic potential, every fourth with a negative strength.
std::string leaf_cloud(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-6, 6), r(1.5, 4), a(-1, 1);
  const auto num = [](double v) { return std::to_string(v); };
  const char* const potentials[] = {"murakami", "wyvill", "cubic"};
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < n; ++i) {
    const double r0 = r(rng), r1 = i % 2 ? r(rng) : r0, r2 = i % 2 ? r(rng) : r0;
    std::string distance =
        R"({"type":"lp_metric","n":2,"radii":[)" + num(r0) + "," + num(r1) + "," + num(r2) + "]";
    if (i % 3 == 0 && i % 2)
      distance += R"(,"rotate":{"axis":[)" + num(a(rng)) + "," + num(a(rng)) +
                  ",1],\"deg\":" + num(90 * a(rng)) + "}";
    distance += "}";
    s += (i ? "," : "") + std::string(R"({"type":"soft_object","potential":{"type":")") +
         potentials[i % 3] + R"("},"strength":)" + num(i % 4 == 3 ? -0.7 : 1.2) +
         R"(,"distance":)" + distance + R"(,"translate":[)" + num(c(rng)) + "," + num(c(rng)) +
         "," + num(c(rng)) + "]}";
  }
  return s + "]}";
}

struct LeafCloud {
  NodePtr node;
  Program prog;
  std::optional<BlobSum> blobs;
  explicit LeafCloud(unsigned seed)
      : node(build_from_json(leaf_cloud(40, seed))),
        prog(compile(*node)),
        blobs(BlobSum::of(prog)) {}
};

Box leaf_test_box(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> c(-8, 8), side(0.05, 3);
  const Vec3 lo{c(rng), c(rng), c(rng)};
  return {lo, lo + Vec3{side(rng), side(rng), side(rng)}};
}

TEST(LeafBlobs, ValuesGridAndGradientAreTheSumsOfTheBlobs) {
  LeafCloud cl(7);
  ASSERT_TRUE(cl.blobs) << "the cloud is a sum of blobs";
  std::mt19937_64 rng(11);
  Workspace ws;
  ws.fit(cl.prog);
  std::vector<int32_t> ids(size_t(cl.blobs->size()));
  LeafBlobs leaf;
  long nonzero = 0;
  for (int b = 0; b < 200; ++b) {
    const Box box = leaf_test_box(rng);
    leaf.select(*cl.blobs, cl.prog, box);
    // A 5 x 4 x 3 grid over the box: grid() and values() give the same bits, and the program's
    // value to rounding.
    const int m[3] = {5, 4, 3};
    std::vector<double> axis[3];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < m[a]; ++i)
        axis[a].push_back(box.lo[a] + (box.hi[a] - box.lo[a]) * i / (m[a] - 1));
    std::vector<double> f(60), x, y, z;
    leaf.grid(axis[0].data(), axis[1].data(), axis[2].data(), m, f.data());
    for (int k = 0; k < m[2]; ++k)
      for (int j = 0; j < m[1]; ++j)
        for (int i = 0; i < m[0]; ++i) {
          x.push_back(axis[0][size_t(i)]);
          y.push_back(axis[1][size_t(j)]);
          z.push_back(axis[2][size_t(k)]);
        }
    std::vector<double> g(60);
    leaf.values(x.data(), y.data(), z.data(), 60, g.data());
    for (size_t p = 0; p < 60; ++p) {
      const Vec3 at{x[p], y[p], z[p]};
      ASSERT_EQ(f[p], g[p]) << "grid and values differ at point " << p << " of box " << b;
      const double want = evaluate(cl.prog, at, nullptr, ws);
      EXPECT_NEAR(g[p], want, 1e-12 * (1 + std::abs(want))) << "box " << b << " point " << p;
      Vec3 grad, want_grad;
      const double fg = leaf.gradient(at, &grad);
      const double fw = cl.blobs->gradient(cl.prog, at, &want_grad, ids.data());
      EXPECT_EQ(fg, fw);
      EXPECT_EQ(grad.x, want_grad.x);
      EXPECT_EQ(grad.y, want_grad.y);
      EXPECT_EQ(grad.z, want_grad.z);
      nonzero += want != 0;
    }
  }
  EXPECT_GT(nonzero, 5000) << "too few points inside any blob to compare";
}

TEST(BlobInterval, HoldsTheFieldOverTheBoxAndKeepsEveryBlobThere) {
  LeafCloud cl(3);
  ASSERT_TRUE(cl.blobs);
  ASSERT_TRUE(blob_intervals_apply(*cl.blobs)) << "balls and ellipsoids only";
  std::vector<int32_t> all;
  for (int32_t i = 0; i < cl.blobs->size(); ++i) all.push_back(i);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  Workspace ws;
  ws.fit(cl.prog);
  long checked = 0, narrow = 0;
  for (int b = 0; b < 300; ++b) {
    const Box box = leaf_test_box(rng);
    std::vector<int32_t> kept;
    const Interval v = blob_interval(*cl.blobs, all.data(), int(all.size()), box, &kept);
    // The kept blobs alone give the same interval (what a child block reads from its parent).
    std::vector<int32_t> again;
    const Interval w = blob_interval(*cl.blobs, kept.data(), int(kept.size()), box, &again);
    EXPECT_EQ(kept, again);
    EXPECT_EQ(v.lo, w.lo);
    EXPECT_EQ(v.hi, w.hi);
    LeafBlobs leaf;
    for (int s = 0; s < 50; ++s) {
      const Vec3 e = box.extent(), p = box.lo + Vec3{e.x * u(rng), e.y * u(rng), e.z * u(rng)};
      const double f = evaluate(cl.prog, p, nullptr, ws);
      const double slack = 1e-12 * (1 + std::abs(f));
      EXPECT_GE(f, v.lo - slack) << "box " << b;
      EXPECT_LE(f, v.hi + slack) << "box " << b;
      ++checked;
    }
    // Every blob with a support box meeting the box and not kept is 0 all over it: the list
    // from kept alone gives the field at the box's points.
    leaf.select(*cl.blobs, cl.prog, box);
    for (int s = 0; s < 10; ++s) {
      const Vec3 e = box.extent(), p = box.lo + Vec3{e.x * u(rng), e.y * u(rng), e.z * u(rng)};
      double f = 0;
      for (const int32_t id : kept) {
        const BlobSum::Frame& fr = cl.blobs->frames()[size_t(id)];
        const Vec3 q = fr.L * p + fr.k;
        const double r = 1 - dot(q, q);
        const BlobSum::Blob& bl = cl.blobs->blobs()[size_t(id)];
        f += r > 0 ? r * r * (bl.c2 + bl.c3 * r) : 0.0;
      }
      EXPECT_NEAR(f, evaluate(cl.prog, p, nullptr, ws), 1e-12 * (1 + std::abs(f)));
    }
    narrow += v.hi - v.lo < 0.5;
  }
  EXPECT_EQ(checked, 300 * 50);
  EXPECT_GT(narrow, 30) << "the intervals should be tight on small boxes";
}

}  // namespace
}  // namespace softtrace::test
