#include "sweep.h"

#include <cmath>
#include <random>

namespace softtrace::test {

namespace {

constexpr int kPoints = 4000;
constexpr int kBoxes = 300;

Vec3 central_difference(const FieldNode& n, const Vec3& p, double h) {
  Vec3 g;
  for (int i = 0; i < 3; ++i) {
    Vec3 a = p, b = p;
    a[i] += h;
    b[i] -= h;
    g[i] = (n.value(a) - n.value(b)) / (2 * h);
  }
  return g;
}

}  // namespace

TEST_P(NodeSweep, GradientMatchesCentralDifferences) {
  const SweepCase& c = GetParam();
  const NodePtr n = build_from_json(c.json, c.convention);
  std::mt19937_64 rng(1);
  const double h = 1e-6 * c.domain.diagonal();
  int checked = 0, smooth_nonzero = 0;
  for (int i = 0; i < kPoints; ++i) {
    const Vec3 p = uniform_in(rng, c.domain);
    const Vec3 fd = central_difference(*n, p, h), fd2 = central_difference(*n, p, 2 * h);
    const double scale = std::max(1.0, length(fd));
    // A kink within 2h makes the two quotients disagree: the point says nothing about ∇f.
    if (length(fd - fd2) > 1e-4 * scale) continue;
    ++checked;
    if (length(fd) > 0) ++smooth_nonzero;
    const Vec3 g = n->gradient(p);
    ASSERT_LE(length(g - fd), 1e-4 * scale)
        << c.name << " at (" << p.x << ", " << p.y << ", " << p.z << "): analytic (" << g.x << ", "
        << g.y << ", " << g.z << ") vs FD (" << fd.x << ", " << fd.y << ", " << fd.z << ")";
  }
  EXPECT_GE(checked, kPoints * 8 / 10) << "too few smooth points to judge";
  EXPECT_GT(smooth_nonzero, 0) << "the domain shows no variation of the field";
}

TEST_P(NodeSweep, GlobalLipschitzBoundsSampledSlopes) {
  const SweepCase& c = GetParam();
  const NodePtr n = build_from_json(c.json, c.convention);
  const double L = n->lipschitz();
  ASSERT_FALSE(std::isnan(L));
  if (!std::isfinite(L)) GTEST_SKIP() << "no global bound exists (exponent below 1)";
  std::mt19937_64 rng(2);
  for (int i = 0; i < kPoints; ++i) {
    const Vec3 p = uniform_in(rng, c.domain), q = uniform_in(rng, c.domain);
    ASSERT_LE(length(n->gradient(p)), L * (1 + 1e-9) + 1e-12) << c.name;
    ASSERT_LE(std::abs(n->value(p) - n->value(q)), L * length(p - q) * (1 + 1e-9) + 1e-12)
        << c.name;
  }
}

TEST_P(NodeSweep, BoxBoundsEncloseSamples) {
  const SweepCase& c = GetParam();
  const NodePtr n = build_from_json(c.json, c.convention);
  std::mt19937_64 rng(3);
  for (int i = 0; i < kBoxes; ++i) {
    const Box b = random_box(rng, c.domain);
    const NodeBounds nb = n->bounds(b);
    const Interval I = nb.value;
    const double L = nb.lipschitz;
    ASSERT_FALSE(std::isnan(L) || std::isnan(I.lo) || std::isnan(I.hi)) << c.name;
    ASSERT_LE(L, n->lipschitz() * (1 + 1e-12)) << "a box bound must not exceed the global one";
    for (int j = 0; j < 30; ++j) {
      const Vec3 p = uniform_in(rng, b), q = uniform_in(rng, b);
      const double v = n->value(p);
      ASSERT_TRUE(I.contains(v)) << c.name << ": " << v << " outside [" << I.lo << ", " << I.hi
                                 << "]";
      ASSERT_LE(length(n->gradient(p)), L * (1 + 1e-9) + 1e-12) << c.name;
      ASSERT_LE(std::abs(v - n->value(q)), L * length(p - q) * (1 + 1e-9) + 1e-12) << c.name;
    }
  }
}

// gradient_floor and hessian_bound (node.h) over random boxes: |∇f| never below the floor, and
// ∇f never changing faster than the Hessian bound between two points of the box.
TEST_P(NodeSweep, CurvatureBoundsHoldOnSamples) {
  const SweepCase& c = GetParam();
  const NodePtr n = build_from_json(c.json, c.convention);
  std::mt19937_64 rng(5);
  int claims = 0;
  for (int i = 0; i < kBoxes; ++i) {
    const Box b = random_box(rng, c.domain);
    const double floor = n->gradient_floor(b), H = n->hessian_bound(b);
    ASSERT_GE(floor, 0) << c.name;
    ASSERT_FALSE(std::isnan(H)) << c.name;
    if (floor == 0 && !std::isfinite(H)) continue;
    ++claims;
    for (int j = 0; j < 30; ++j) {
      const Vec3 p = uniform_in(rng, b), q = uniform_in(rng, b);
      const Vec3 gp = n->gradient(p), gq = n->gradient(q);
      ASSERT_GE(length(gp), floor * (1 - 1e-9)) << c.name;
      ASSERT_LE(length(gp - gq), H * length(p - q) * (1 + 1e-9) + 1e-12) << c.name;
    }
  }
  RecordProperty("boxes_with_claims", claims);
  if (claims == 0) GTEST_SKIP() << "the node claims no gradient floor and no Hessian bound";
}

TEST_P(NodeSweep, RegionContainsItsLevelSet) {
  const SweepCase& c = GetParam();
  if (std::isnan(c.region_level)) GTEST_SKIP() << "no finite region for this field";
  const NodePtr n = build_from_json(c.json, c.convention);
  const Box r = n->region(c.region_level, c.region_side);
  if (r.empty()) {  // a claim that no point reaches the level (min with a negative term)
    std::mt19937_64 rng(4);
    for (int i = 0; i < 20 * kPoints; ++i) {
      const Vec3 p = uniform_in(rng, c.domain);
      const double v = n->value(p);
      ASSERT_FALSE(c.region_side == Side::Above ? v >= c.region_level : v <= c.region_level)
          << c.name << ": f = " << v << " at (" << p.x << ", " << p.y << ", " << p.z
          << ") although the region is empty";
    }
    return;
  }
  ASSERT_TRUE(r.bounded()) << c.name << ": expected a finite region box";
  std::mt19937_64 rng(4);
  // Sample a domain twice the size of the region's so points outside it are tried too.
  const Box wide(r.center() - r.extent(), r.center() + r.extent());
  int inside = 0;
  for (int i = 0; i < 20 * kPoints; ++i) {
    const Vec3 p = uniform_in(rng, wide);
    const double v = n->value(p);
    const bool in = c.region_side == Side::Above ? v >= c.region_level : v <= c.region_level;
    if (!in) continue;
    ++inside;
    ASSERT_TRUE(r.contains(p)) << c.name << ": f = " << v << " at (" << p.x << ", " << p.y << ", "
                               << p.z << ") outside the region box";
  }
  EXPECT_GT(inside, 0) << "no sample reached the level: the check proved nothing";
}

}  // namespace softtrace::test
