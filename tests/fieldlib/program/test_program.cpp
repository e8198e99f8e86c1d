// Compiled programs (fieldlib/program.h): what compile emits and what pruning keeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "compiled_case.h"
#include "eval/eval.h"
#include "kernels/transformed_potential.h"
#include "model/program_builder.h"
#include "sweep.h"

namespace softtrace::test {

namespace {

// N murakami blobs of radius r at fixed-seed centres in [-20, 20]^3 (tools/blob_scene.py's model).
std::string blobs_json(int n, double r, std::vector<Vec3>* centres) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-20, 20);
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < n; ++i) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    centres->push_back(c);
    s += (i ? "," : "") + std::string(R"({"type":"soft_object","potential":{"type":"murakami"},)") +
         R"("distance":{"type":"lp_metric","radii":[)" + std::to_string(r) + "," +
         std::to_string(r) + "," + std::to_string(r) + R"(],"n":2},"translate":[)" +
         std::to_string(c.x) + "," + std::to_string(c.y) + "," + std::to_string(c.z) + "]}";
  }
  return s + "]}";
}

// n blobs of radius r (blobs_json), compiled, with a workspace fitted to the program.
struct Blobs {
  std::vector<Vec3> centres;
  NodePtr node;
  Program prog;
  Workspace ws;
  Blobs(int n, double r) : node(build_from_json(blobs_json(n, r, &centres))), prog(compile(*node)) {
    ws.fit(prog);
  }
};

template <class Code>
int count_ops(const Code& code, Op op) {
  int n = 0;
  for (const Instr& i : code) n += i.op == op;
  return n;
}

}  // namespace

TEST(Program, PlacementCompilesToTranslationOrRotation) {
  const NodePtr t =
      build_from_json(R"({"type":"lp_metric","radii":[1,2,3],"n":2,"translate":[1,2,3]})");
  const Program pt = compile(*t);
  EXPECT_EQ(count_ops(pt.code, Op::Translate), 1);
  EXPECT_EQ(count_ops(pt.code, Op::Place), 0);
  const NodePtr r = build_from_json(
      R"({"type":"lp_metric","radii":[1,2,3],"n":2,"rotate":{"axis":[0,0,1],"deg":30}})");
  const Program pr = compile(*r);
  EXPECT_EQ(count_ops(pr.code, Op::Translate), 0);
  EXPECT_EQ(count_ops(pr.code, Op::Place), 1);
}

TEST(Program, SoftObjectIsDistanceThenPotential) {
  const NodePtr n = build_from_json(
      R"({"type":"soft_object","potential":{"type":"wyvill"},"distance":{"type":"segment","p0":[0,0,0],"p1":[1,0,0],"radius":1}})");
  const Program p = compile(*n);
  ASSERT_EQ(p.code.size(), 2u);
  EXPECT_EQ(p.code[0].op, Op::LineSegment);
  EXPECT_EQ(p.code[1].op, Op::Wyvill);
}

// The superquadric and the super-elliptic cylinder compile to one native instruction whose batch
// values are the model's bits lane by lane (odd lane counts included), where the one-sided terms
// take each branch: random points, the axes and the origin (terms 0), the cylinder's dead zone and
// its ends (|z| <= L), and a NaN coordinate (whose term the model takes as 0).
TEST(Program, SphericalProductIsOneInstructionWithTheModelsBits) {
  const char* const kJson[] = {
      R"({"type":"superquadric","radii":[1,0.8,1.2],"n1":0.6,"n2":3,"t":[1.5,0.7,2,1,1.2,0.6]})",
      R"({"type":"superelliptic_cylinder","radii":[0.5,0.7,0.4],"n":2.5,"half_length":0.6,
          "t":[1.2,2,1,1.5,1.3,0.7]})"};
  constexpr double kHalfLength = 0.6;
  constexpr int kLanes = 13;
  for (const char* json : kJson) {
    const NodePtr node = build_from_json(json);
    const Program prog = compile(*node);
    ASSERT_EQ(prog.code.size(), 1u) << json;
    EXPECT_EQ(prog.code[0].op, Op::SphericalProduct) << json;
    Workspace ws;
    ws.fit(prog);
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> u(-2, 2), dead(-kHalfLength, kHalfLength);
    for (int i = 0; i < 200; ++i) {
      double x[kLanes], y[kLanes], z[kLanes], f[kLanes];
      for (int l = 0; l < kLanes; ++l) {
        Vec3 p{u(rng), u(rng), u(rng)};
        // 0: anywhere; 1-3: on the x, y or z axis; 4: the origin; 5: in the dead zone; 6: at
        // its ends; 7: a NaN coordinate.
        const int kind = (i + l) % 8;
        if (kind >= 1 && kind <= 4)
          for (int a = 0; a < 3; ++a) p[a] = a + 1 == kind ? p[a] : 0;
        if (kind == 5) p.z = dead(rng);
        if (kind == 6) p.z = l % 2 ? kHalfLength : -kHalfLength;
        if (kind == 7) p[l % 3] = std::nan("");
        x[l] = p.x, y[l] = p.y, z[l] = p.z;
      }
      values(prog, x, y, z, kLanes, f, ws);
      for (int l = 0; l < kLanes; ++l) {
        const double v = node->value({x[l], y[l], z[l]});
        ASSERT_EQ(std::memcmp(&f[l], &v, sizeof v), 0)
            << json << ": lane " << l << " at (" << x[l] << ", " << y[l] << ", " << z[l]
            << "): " << f[l] << " vs the model's " << v;
      }
    }
  }
}

// Equal bits, NaN payloads and the sign of zero included.
bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same_bits(const Vec3& a, const Vec3& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

// p with coordinate k % 3 NaN, or infinite (+ for odd k): special points every kernel must pass
// through as its model node does.
Vec3 with_nan(Vec3 p, int k) {
  p[k % 3] = std::nan("");
  return p;
}
Vec3 with_infinity(Vec3 p, int k) {
  p[k % 3] = k % 2 ? HUGE_VAL : -HUGE_VAL;
  return p;
}

// A native instruction's program against the model node it was compiled from: 13-lane batches, the
// single-point value and the gradient at points that `special` may move (to the kernels' branch
// points), the model's bits every one; and over random boxes, the node's interval(b) and
// lipschitz(b) to the bit, which contain sampled values and gradient lengths.
// With `bound_bits` false the bounds are only checked to hold the samples (a placed node's box goes
// through the model's placement, the program's through its own, rounded otherwise).
template <class Special>
void expect_models_bits(const std::string& json, Convention convention, const Special& special,
                        bool bound_bits = true) {
  constexpr int kLanes = 13;
  CompiledCase cc(json, convention);
  const NodePtr& node = cc.node;
  const Program& prog = cc.prog;
  Workspace& ws = cc.ws;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 200; ++i) {
    double x[kLanes], y[kLanes], z[kLanes], f[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const Vec3 p = special(Vec3{u(rng), u(rng), u(rng)}, i + l);
      x[l] = p.x, y[l] = p.y, z[l] = p.z;
    }
    values(prog, x, y, z, kLanes, f, ws);
    for (int l = 0; l < kLanes; ++l) {
      const Vec3 p{x[l], y[l], z[l]};
      Vec3 gm, gp;
      const double v = node->eval(p, &gm);
      ASSERT_TRUE(same_bits(f[l], v)) << json << ": lane " << l << " at (" << p.x << ", " << p.y
                                      << ", " << p.z << "): " << f[l] << " vs the model's " << v;
      ASSERT_TRUE(same_bits(value(prog, p, ws), v)) << json << ": one point";
      ASSERT_TRUE(same_bits(gradient(prog, p, &gp, ws), v)) << json << ": gradient's value";
      ASSERT_TRUE(same_bits(gp, gm))
          << json << " at (" << p.x << ", " << p.y << ", " << p.z << "): (" << gp.x << ", " << gp.y
          << ", " << gp.z << ") vs the model's (" << gm.x << ", " << gm.y << ", " << gm.z << ")";
    }
  }
  const Box domain({-2, -2, -2}, {2, 2, 2});
  for (int i = 0; i < 300; ++i) {
    const Box b = random_box(rng, domain);
    const BoxBounds bb = bounds(prog, b, ws);
    const Interval I = node->interval(b);
    const double L = node->lipschitz(b);
    ASSERT_TRUE(!bound_bits || (same_bits(bb.value.lo, I.lo) && same_bits(bb.value.hi, I.hi)))
        << json << ": [" << bb.value.lo << ", " << bb.value.hi << "] vs the model's [" << I.lo
        << ", " << I.hi << "]";
    ASSERT_TRUE(!bound_bits || same_bits(bb.lipschitz, L))
        << json << ": " << bb.lipschitz << " vs " << L;
    for (int j = 0; j < 20; ++j) {
      const Vec3 p = uniform_in(rng, b);
      Vec3 g;
      const double v = node->eval(p, &g);
      ASSERT_TRUE(bb.value.contains(v)) << json << ": " << v;
      ASSERT_LE(length(g), bb.lipschitz * (1 + 1e-12)) << json;
    }
  }
}

// The plane distances compile to one native instruction with the model's bits: at random points,
// on the plane (p·n = 0 exactly for an axis normal, about 0 for the others), at the origin with
// signed zeros, and with a NaN or an infinite coordinate. One-branch boxes wholly where p·n <= 0
// have Lipschitz bound 0, as the model's.
TEST(Program, PlanesAreOneInstructionWithTheModelsBits) {
  const struct {
    const char* json;
    Op op;
    Vec3 normal;
  } kCases[] = {
      {R"({"type":"parallel_planes","normal":[1,2,-0.5],"a":0.7})",
       Op::ParallelPlanes,
       {1, 2, -0.5}},
      {R"({"type":"parallel_planes","normal":[0,0,3],"a":0.4})", Op::ParallelPlanes, {0, 0, 1}},
      {R"({"type":"one_branch_plane","normal":[0.3,-1,0.4],"a":0.5})",
       Op::OneBranchPlane,
       {0.3, -1, 0.4}},
      {R"({"type":"one_branch_plane","normal":[0,-2,0],"a":1.5})", Op::OneBranchPlane, {0, -1, 0}}};
  for (const auto& c : kCases) {
    const NodePtr node = build_from_json(c.json);
    const Program prog = compile(*node);
    ASSERT_EQ(prog.code.size(), 1u) << c.json;
    EXPECT_EQ(prog.code[0].op, c.op) << c.json;
    const Vec3 n = c.normal / length(c.normal);
    expect_models_bits(c.json, Convention::Soft, [&](Vec3 p, int k) {
      // 0: anywhere; 1: on the plane; 2: the origin with signed zeros; 3: a NaN coordinate; 4: an
      // infinite one.
      switch (k % 5) {
        case 1:
          return p - n * dot(p, n);
        case 2:
          return Vec3{k % 2 ? -0.0 : 0.0, -0.0, k % 3 ? 0.0 : -0.0};
        case 3:
          return with_nan(p, k);
        case 4:
          return with_infinity(p, k);
      }
      return p;
    });
  }
}

// The segment and the torus compile to one native instruction with the model's bits: at random
// points, on the skeleton (f = 0: the segment's points and ends, the torus's circle), beyond the
// segment's ends, on the torus's axis (ρ = 0) and plane (z = 0), and with a NaN coordinate; a
// degenerate segment (p0 = p1) and torus exponents other than 2 included.
TEST(Program, SkeletalDistancesAreOneInstructionWithTheModelsBits) {
  const struct {
    const char* json;
    Op op;
  } kCases[] = {
      {R"({"type":"segment","p0":[-0.5,0,0],"p1":[0.5,0.3,0.2],"radius":0.7})", Op::LineSegment},
      {R"({"type":"segment","p0":[0.2,-0.1,0.3],"p1":[0.2,-0.1,0.3],"radius":1.3})",
       Op::LineSegment},
      {R"({"type":"torus","major_radius":0.8,"radii":[0.3,0.4]})", Op::Torus},
      {R"({"type":"torus","major_radius":1,"radii":[0.5,0.3],"n":1.5})", Op::Torus},
      {R"({"type":"torus","major_radius":0.7,"radii":[0.4,0.4],"n":5})", Op::Torus}};
  const Vec3 p0{-0.5, 0, 0}, p1{0.5, 0.3, 0.2};
  for (const auto& c : kCases) {
    const NodePtr node = build_from_json(c.json);
    const Program prog = compile(*node);
    ASSERT_EQ(prog.code.size(), 1u) << c.json;
    EXPECT_EQ(prog.code[0].op, c.op) << c.json;
    const bool torus = c.op == Op::Torus;
    expect_models_bits(c.json, Convention::Soft, [&](Vec3 p, int k) {
      const double t = (p.x + 2) / 4;  // in [0, 1]
      // 0: anywhere; 1: on the skeleton; 2: beyond the segment's ends / on the torus's axis;
      // 3: the segment's ends / the torus's plane; 4: a NaN coordinate.
      switch (k % 5) {
        case 1:
          if (torus) return Vec3{std::cos(7 * t) * 0.8, std::sin(7 * t) * 0.8, 0};
          return p0 + (p1 - p0) * t;
        case 2:
          if (torus) return Vec3{0, 0, p.z};
          return k % 2 ? p0 - (p1 - p0) * t : p1 + (p1 - p0) * t;
        case 3:
          if (torus) return Vec3{p.x, p.y, 0};
          return k % 2 ? p0 : p1;
        case 4:
          return with_nan(p, k);
      }
      return p;
    });
  }
}

// 17 unit-ish normals round the z axis: more than Scratch keeps on the stack (its heap fallback).
std::string many_normals() {
  std::string s;
  for (int i = 0; i < 17; ++i)
    s += (i ? ",[" : "[") + std::to_string(std::cos(0.37 * i)) + "," +
         std::to_string(std::sin(0.37 * i)) + "," + std::to_string(0.3 * (i % 3) - 0.3) + "]";
  return "[" + s + "]";
}

// The generalized distance compiles to one native instruction with the model's bits: at random
// points, at the origin with signed zeros (f = 0, every u_i = 0), on the axes, on the first plane
// (X·n_0 = 0, a kink of u_0), with a NaN or an infinite coordinate; exponents 2, 3, 20 (by
// squaring), 2.5 (pow), 1 and 0.7 (no global bound), sides t_pos/t_neg, and 17 normals.
TEST(Program, GeneralizedDistanceIsOneInstructionWithTheModelsBits) {
  const std::string kCases[] = {
      R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[1,0.7,1.2],
          "n":2})",
      R"({"type":"generalized_distance","normals":[[1,1,1],[1,-1,1],[-1,1,1],[1,1,-1]],"a":0.8,
          "n":3,"t_pos":[1,1.5,2,1],"t_neg":[1.2,1,1,0.7]})",
      R"({"type":"generalized_distance","normals":[[1,0.2,0],[0,1,0.3],[0.1,0,1]],
          "a":[1,0.8,0.6],"n":20,"t_pos":[1,1,2],"t_neg":[1.1,1,1]})",
      R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1],[1,1,0],[0,1,1]],
          "a":[1,1,1,1.2,1.2],"n":2.5})",
      R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,1]],"a":[0.5,0.8],"n":1})",
      R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1],[1,1,1]],"a":1,
          "n":0.7})",
      R"({"type":"generalized_distance","a":0.9,"n":4,"normals":)" + many_normals() + "}"};
  for (const std::string& json : kCases) {
    const NodePtr node = build_from_json(json);
    const Program prog = compile(*node);
    ASSERT_EQ(prog.code.size(), 1u) << json;
    EXPECT_EQ(prog.code[0].op, Op::GenDistance) << json;
    const Vec3 n0 = [&] {
      const size_t at = json.find("[[") + 2;
      Vec3 v;
      std::sscanf(json.c_str() + at, "%lf,%lf,%lf", &v.x, &v.y, &v.z);
      return v / length(v);
    }();
    expect_models_bits(json, Convention::Soft, [&](Vec3 p, int k) {
      // 0: anywhere; 1: the origin with signed zeros; 2: on an axis; 3: on the first plane; 4: a
      // NaN coordinate; 5: an infinite one.
      switch (k % 6) {
        case 1:
          return Vec3{k % 2 ? -0.0 : 0.0, -0.0, k % 3 ? 0.0 : -0.0};
        case 2: {
          Vec3 q;
          q[k % 3] = p[k % 3];
          return q;
        }
        case 3:
          return p - n0 * dot(p, n0);
        case 4:
          return with_nan(p, k);
        case 5:
          return with_infinity(p, k);
      }
      return p;
    });
  }
}

// Along a segment every X·n_i is affine: the generalized distance's slope interval holds the
// directional derivatives at the ends and the difference quotients between points of the segment,
// and the value interval the values. On segments leaving the origin along a ray (f is positively
// homogeneous, so it grows along them) every term's rate has f's sign: the slope is one-signed
// there, never the symmetric [-L, L].
TEST(Program, GeneralizedDistanceSlopeAlongASegmentFollowsTheRates) {
  const char* const kJson[] = {
      R"({"type":"generalized_distance","normals":[[1,1,1],[1,-1,1],[-1,1,1],[1,1,-1]],"a":0.8,
          "n":3,"t_pos":[1,1.5,2,1],"t_neg":[1.2,1,1,0.7]})",
      R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[0.5,0.7,0.6],
          "n":6,"rotate":{"axis":[0,1,1],"deg":25},"translate":[0.3,0,-0.2]})",
      R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1],[1,1,0],[0,1,1]],
          "a":[1,1,1,1.2,1.2],"n":1})"};
  for (const char* json : kJson) {
    const NodePtr node = build_from_json(json, Convention::Zero);
    const Program prog = compile(*node);
    EXPECT_EQ(prog.code.back().op, Op::GenDistance) << json;
    Workspace ws;
    ws.fit(prog);
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(-2, 2);
    const bool placed = std::strstr(json, "translate") != nullptr;
    const Vec3 centre = placed ? Vec3{0.3, 0, -0.2} : Vec3{};
    for (int i = 0; i < 300; ++i) {
      const Vec3 a{u(rng), u(rng), u(rng)};
      const bool radial = i % 2 == 0;
      const Segment seg{a, radial ? centre + (a - centre) * 2.5 : Vec3{u(rng), u(rng), u(rng)}};
      const double len = length(seg.b - seg.a);
      const Vec3 dir = (seg.b - seg.a) / len;
      const BoxBounds bb = bounds(prog, seg, ws);
      const Interval D = bb.slope;
      const double slack = 1e-9 * (std::abs(D.lo) + std::abs(D.hi)) + 1e-12;
      double prev = node->value(seg.a);
      for (int j = 0; j <= 20; ++j) {
        const double v = node->value(seg.a + (seg.b - seg.a) * (j / 20.0));
        ASSERT_TRUE(bb.value.contains(v))
            << json << ": " << v << " outside [" << bb.value.lo << ", " << bb.value.hi << "]";
        if (j > 0) {
          const double q = (v - prev) / (len / 20);
          ASSERT_TRUE(D.lo - slack <= q && q <= D.hi + slack)
              << json << ": quotient " << q << " outside [" << D.lo << ", " << D.hi << "]";
        }
        prev = v;
      }
      const Vec3 ga = node->gradient(seg.a), gb = node->gradient(seg.b);
      const double ra = dot(ga, dir), rb = dot(gb, dir), tol = 1e-12 * length(ga);
      ASSERT_TRUE(D.lo <= ra + tol && ra - tol <= D.hi && D.lo <= rb + tol && rb - tol <= D.hi)
          << json << ": " << ra << ", " << rb << " outside [" << D.lo << ", " << D.hi << "]";
      ASSERT_LE(D.hi, bb.lipschitz) << json;
      ASSERT_GE(D.lo, -bb.lipschitz) << json;
      if (radial) {
        EXPECT_GE(D.lo, -1e-9 * bb.lipschitz)
            << json << ": [" << D.lo << ", " << D.hi << "] along a ray from the centre";
      }
    }
  }
}

// The polar prism compiles to one native instruction with the model's bits: at random points, at
// the origin with signed zeros, on the z axis (ρ = 0, where ∇h is 0), on the plane z = 0, on the
// negative x axis with y = ±0 (atan2's ±π), at the lobes' tips and valleys (the star's kinks),
// with a NaN or an infinite coordinate; rose and star, A = 0, one lobe, exponents 20, 2 and 1.5.
TEST(Program, PolarPrismIsOneInstructionWithTheModelsBits) {
  const struct {
    const char* json;
    int lobes;
  } kCases[] = {
      {R"({"type":"polar_prism","radius":0.8,"lobes":5,"amplitude":0.3,"profile":"cosine",
          "half_height":1.2})",
       5},
      {R"({"type":"polar_prism","radius":1.3,"lobes":5,"amplitude":0.35,"profile":"triangle",
          "half_height":0.7,"n":2})",
       5},
      {R"({"type":"polar_prism","radius":0.8,"lobes":3,"amplitude":0.6,"profile":"cosine",
          "half_height":0.5,"n":1.5})",
       3},
      {R"({"type":"polar_prism","radius":0.9,"lobes":1,"amplitude":0.5,"profile":"triangle",
          "half_height":1})",
       1},
      {R"({"type":"polar_prism","radius":0.7,"lobes":4,"amplitude":0,"profile":"cosine",
          "half_height":0.9,"n":3})",
       4}};
  for (const auto& c : kCases) {
    const NodePtr node = build_from_json(c.json);
    const Program prog = compile(*node);
    ASSERT_EQ(prog.code.size(), 1u) << c.json;
    EXPECT_EQ(prog.code[0].op, Op::PolarPrism) << c.json;
    expect_models_bits(c.json, Convention::Soft, [&](Vec3 p, int k) {
      // 0: anywhere; 1: the origin with signed zeros; 2: the z axis; 3: the plane z = 0; 4: the
      // negative x axis, y = ±0; 5: a tip or a valley; 6: a NaN coordinate; 7: an infinite one.
      switch (k % 8) {
        case 1:
          return Vec3{k % 2 ? -0.0 : 0.0, k % 3 ? -0.0 : 0.0, k % 5 ? 0.0 : -0.0};
        case 2:
          return Vec3{0, 0, p.z};
        case 3:
          return Vec3{p.x, p.y, 0};
        case 4:
          return Vec3{-std::abs(p.x), k % 2 ? -0.0 : 0.0, p.z};
        case 5: {
          const double phi = M_PI * (k % (2 * c.lobes)) / c.lobes, r = std::abs(p.x);
          return Vec3{r * std::cos(phi), r * std::sin(phi), p.z};
        }
        case 6:
          return with_nan(p, k);
        case 7:
          return with_infinity(p, k);
      }
      return p;
    });
  }
}

// An offset compiles to its child's code (native where the child is) and one instruction, with the
// model's bits: values, gradients, and over boxes the interval and Lipschitz bound (the children's
// bounds are the model's own kernels here), negative scales included.
TEST(Program, OffsetIsOneInstructionAfterItsChildsCode) {
  const struct {
    const char* json;
    Op child;
  } kCases[] = {{R"({"type":"offset","children":[{"type":"lp_metric","radii":[1,0.8,1.2],"n":3}]})",
                 Op::LpMetric},
                {R"({"type":"offset","scale":0.5,"level":2,"children":[
          {"type":"lp_metric","radii":[0.6,0.8,1.2],"n":2}]})",
                 Op::LpMetric},
                {R"({"type":"offset","scale":-2,"level":0.5,"children":[
          {"type":"parallel_planes","normal":[1,2,-0.5],"a":0.7}]})",
                 Op::ParallelPlanes},
                {R"({"type":"offset","scale":0.7,"children":[
          {"type":"one_branch_plane","normal":[0.3,-1,0.4],"a":0.5}]})",
                 Op::OneBranchPlane},
                {R"({"type":"offset","scale":0.7,"children":[
          {"type":"superquadric","radii":[0.4,0.5,1.2],"n1":2,"n2":6}]})",
                 Op::SphericalProduct},
                {R"({"type":"offset","scale":-3,"level":1.5,"children":[
          {"type":"segment","p0":[0,0,-0.5],"p1":[0,0,0.5],"radius":0.6}]})",
                 Op::LineSegment},
                {R"({"type":"offset","level":0.8,"children":[{"type":"torus","major_radius":0.8,
          "radii":[0.3,0.4],"n":3}]})",
                 Op::Torus},
                {R"({"type":"offset","scale":2,"children":[{"type":"generalized_distance",
          "normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[1,0.7,1.2],"n":2}]})",
                 Op::GenDistance},
                {R"({"type":"offset","scale":-0.5,"level":0.3,"children":[{"type":"polar_prism",
          "radius":0.8,"lobes":5,"amplitude":0.3,"profile":"cosine","half_height":1.2}]})",
                 Op::PolarPrism}};
  for (const auto& c : kCases) {
    const NodePtr node = build_from_json(c.json, Convention::Zero);
    const Program prog = compile(*node);
    ASSERT_EQ(prog.code.size(), 2u) << c.json;
    EXPECT_EQ(prog.code[0].op, c.child) << c.json;
    EXPECT_EQ(prog.code[1].op, Op::Offset) << c.json;
    expect_models_bits(c.json, Convention::Zero, [](Vec3 p, int k) {
      // 0: anywhere; 1: the origin; 2: a NaN coordinate.
      if (k % 3 == 1) return Vec3{};
      if (k % 3 == 2) return with_nan(p, k);
      return p;
    });
  }
}

// Soft objects with a radius transform, one per profile and source of w, on the sweeps' distances
// and modulations; the segments' modulations reach past the distance's segment, where f = 0 < d
// (w takes its cap, T_an, or w_min, T_sn) and, near it, d/f reaches w's clamps.
#define TSO_SPHERE R"({"type":"lp_metric","radii":[1,0.8,1.2],"n":2})"
#define TSO_BAR R"({"type":"superquadric","radii":[1,1,1.3],"n1":2,"n2":6})"
const struct TransformCase {
  const char* name;
  const char* json;
  Op distance, modulation;  // modulation Op::RadiusTransform: w is constant
} kTransformCases[] = {
    {"T_n",
     R"({"type":"soft_object","distance":)" TSO_SPHERE
     R"(,"radii":{"type":"T_n","w1":1.6,"w2":0.7}})",
     Op::LpMetric, Op::RadiusTransform},
    {"T_n_wyvill",
     R"({"type":"soft_object","potential":{"type":"wyvill"},"distance":)" TSO_BAR
     R"(,"radii":{"type":"T_n","w1":0.4,"w2":0.8}})",
     Op::SphericalProduct, Op::RadiusTransform},
    {"T_l",
     R"({"type":"soft_object","distance":)" TSO_SPHERE R"(,"radii":{"type":"T_l","w1":0.6}})",
     Op::LpMetric, Op::RadiusTransform},
    {"T_l_wide",
     R"({"type":"soft_object","potential":{"type":"murakami"},"distance":)" TSO_BAR
     R"(,"radii":{"type":"T_l","w1":2}})",
     Op::SphericalProduct, Op::RadiusTransform},
    {"T_r",
     R"({"type":"soft_object","potential":{"type":"blanc","s":0.3},"distance":)" TSO_SPHERE
     R"(,"radii":{"type":"T_r","w2":0.4}})",
     Op::LpMetric, Op::RadiusTransform},
    {"T_an", R"({"type":"soft_object","distance":)" TSO_SPHERE R"(,"radii":{"type":"T_an",
     "modulation":{"type":"superquadric","radii":[2.2,1.8,1.6],"n1":1,"n2":3}}})",
     Op::LpMetric, Op::SphericalProduct},
    {"T_an_segment", R"({"type":"soft_object","distance":{"type":"segment","p0":[0,0,-0.5],
     "p1":[0,0,0.5],"radius":0.6},"radii":{"type":"T_an","modulation":{"type":"segment",
     "p0":[0,0,-0.8],"p1":[0,0,0.8],"radius":1.5}}})",
     Op::LineSegment, Op::LineSegment},
    {"T_al", R"({"type":"soft_object","distance":)" TSO_SPHERE R"(,"radii":{"type":"T_al",
     "modulation":{"type":"lp_metric","radii":[1.8,1.2,2.4],"n":3}}})",
     Op::LpMetric, Op::LpMetric},
    {"T_sn", R"({"type":"soft_object","distance":)" TSO_BAR R"(,"radii":{"type":"T_sn",
     "modulation":{"type":"lp_metric","radii":[0.7,0.8,0.6],"n":3}}})",
     Op::SphericalProduct, Op::LpMetric},
    {"T_sn_segment", R"({"type":"soft_object","distance":{"type":"segment","p0":[0,0,-0.5],
     "p1":[0,0,0.5],"radius":1},"radii":{"type":"T_sn","w_min":0.05,"modulation":{
     "type":"segment","p0":[0,0,-0.52],"p1":[0,0,0.52],"radius":0.6}}})",
     Op::LineSegment, Op::LineSegment},
    {"T_sr", R"({"type":"soft_object","distance":)" TSO_SPHERE R"(,"radii":{"type":"T_sr",
     "modulation":{"type":"superquadric","radii":[0.6,0.5,0.9],"n1":1.5,"n2":2}}})",
     Op::LpMetric, Op::SphericalProduct},
    {"contour", R"({"type":"soft_object","distance":)" TSO_SPHERE R"(,"radii":{"type":"contour",
     "contour":{"type":"lp_metric","radii":[1.4,1.1,2],"n":4}}})",
     Op::LpMetric, Op::LpMetric},
    {"T_sr_placed",
     R"({"type":"soft_object","translate":[1.1,-0.5,0.8],"distance":)" TSO_SPHERE
     R"(,"radii":{"type":"T_sr","modulation":{"type":"superquadric","radii":[0.6,0.5,0.9],
     "n1":1.5,"n2":2}}})",
     Op::LpMetric, Op::SphericalProduct},
    {"contour_pinched", R"({"type":"soft_object","distance":)" TSO_BAR R"(,"radii":{
     "type":"contour","w_min":0.01,"contour":{"type":"superquadric","radii":[2,2,2.6],"n1":0.6,
     "n2":4}}})",
     Op::SphericalProduct, Op::SphericalProduct},
};

// Each case's support box (the field is 0 outside it).
Box transform_support(const char* json) {
  return build_from_json(json)->region(std::numeric_limits<double>::min(), Side::Above);
}

// A radius-transformed soft object compiles to its distance's code, its modulation's (where w is
// not constant) and one RadiusTransform instruction, no oracle, with the model's bits: values in
// 13-lane batches, single points and gradients at random points, on the skeleton (the centre: d =
// 0, and f = 0), near it, on the z axis (the segments' ends, where f = 0 < d and w clamps), on the
// support box's faces and with a NaN coordinate (unplaced); over random boxes bounds that hold
// sampled values and gradient lengths (RadiusTransformBoundsAreTheModelsUnrefined compares them
// with the model's).
TEST(Program, RadiusTransformIsOneInstructionAfterItsChildrensCode) {
  for (const TransformCase& c : kTransformCases) {
    SCOPED_TRACE(c.name);
    const Program prog = compile(*build_from_json(c.json));
    const bool modulated = c.modulation != Op::RadiusTransform;
    const bool placed = prog.code[0].op == Op::Translate || prog.code[0].op == Op::Place;
    ASSERT_EQ(prog.code.size(), (modulated ? 3u : 2u) + placed);
    EXPECT_EQ(prog.code[placed].op, c.distance);
    if (modulated) {
      EXPECT_EQ(prog.code[placed + 1].op, c.modulation);
    }
    EXPECT_EQ(prog.code.back().op, Op::RadiusTransform);
    EXPECT_EQ(count_ops(prog.code, Op::Oracle), 0);
    const Box support = transform_support(c.json);
    ASSERT_TRUE(support.bounded());
    expect_models_bits(
        c.json, Convention::Soft,
        [&](Vec3 p, int k) {
          // The model's placement multiplies by its matrix, identity or not: a NaN coordinate makes
          // the others NaN, and exact zeros come back +0 from it where the program's translation
          // keeps -0. Those differences are the placement's, not this instruction's.
          if (placed && (k % 6 == 2 || k % 6 == 4)) return p;
          switch (k % 6) {
            case 1:
              return Vec3{};
            case 2:
              return with_nan(p, k);
            case 3:
              return p * 0.01;
            case 4:
              return Vec3{0, 0, p.z * 0.4};
            case 5:  // a face of the support box
              p[k % 3] = (k / 6) % 2 ? support.lo[k % 3] : support.hi[k % 3];
              return p;
            default:
              return p;
          }
        },
        false);
  }
}

// The program's bounds over a box are the model's kernels (transformed_potential.h) on the model's
// distance and modulation bounds there, to the bit, without the octants the model refines small
// boxes over (eval_bounds.cpp says why): so they hold the node's bounds, equal them wherever the
// node does not refine (never for a constant w), and hold sampled values and gradients. Random
// boxes, and boxes of 1/100 of the support about points in it and near its centre, where [d]/[f]
// is widest and the modulated objects refine (some of them must, or this tests nothing).
TEST(Program, RadiusTransformBoundsAreTheModelsUnrefined) {
  int modulated_refined = 0;
  for (const TransformCase& c : kTransformCases) {
    SCOPED_TRACE(c.name);
    const NodePtr node = build_from_json(c.json);
    const Program prog = compile(*node);
    if (prog.code[0].op == Op::Translate || prog.code[0].op == Op::Place) continue;  // (frames)
    const nlohmann::json j = nlohmann::json::parse(c.json);
    const NodePtr d = build_from_json(j["distance"].dump());
    const nlohmann::json& r = j["radii"];
    const NodePtr f = r.contains("modulation") ? build_from_json(r["modulation"].dump())
                      : r.contains("contour")  ? build_from_json(r["contour"].dump())
                                               : nullptr;
    const TransformedPotential t =
        TransformedPotential::load(prog.consts.data() + prog.code.back().a);
    Workspace ws;
    ws.fit(prog);
    const Box support = transform_support(c.json);
    const Vec3 h = support.extent() * 0.005;
    std::mt19937_64 rng(23);
    int refined = 0;
    const Box core(support.center() - h * 12, support.center() + h * 12);
    for (int i = 0; i < 900; ++i) {
      const Vec3 p = uniform_in(rng, i < 600 ? support : core);
      const Box b = i < 300 ? random_box(rng, Box({-2, -2, -2}, {2, 2, 2})) : Box(p - h, p + h);
      const BoxBounds bb = bounds(prog, b, ws);
      Interval I(0);
      double L = 0;
      if (!t.outside_support(b)) {
        const NodeBounds D = d->bounds(b);
        const NodeBounds F = f ? f->bounds(b) : NodeBounds{};
        const TransformedPotential::Bounds B = t.bounds(D.value, D.lipschitz, F.value, F.lipschitz);
        I = t.interval(B);
        L = t.slope_bound(B);
      }
      ASSERT_TRUE(same_bits(bb.value.lo, I.lo) && same_bits(bb.value.hi, I.hi))
          << "box " << i << ": [" << bb.value.lo << ", " << bb.value.hi << "] vs [" << I.lo << ", "
          << I.hi << "]";
      ASSERT_TRUE(same_bits(bb.lipschitz, L)) << "box " << i << ": " << bb.lipschitz << " vs " << L;
      const NodeBounds N = node->bounds(b);
      const Interval In = N.value;
      const double Ln = N.lipschitz;
      ASSERT_LE(bb.value.lo, In.lo) << "box " << i;
      ASSERT_GE(bb.value.hi, In.hi) << "box " << i;
      ASSERT_GE(bb.lipschitz, Ln) << "box " << i;
      refined += !(same_bits(bb.value.lo, In.lo) && same_bits(bb.value.hi, In.hi) &&
                   same_bits(bb.lipschitz, Ln));
      for (int k = 0; k < 10; ++k) {
        const Vec3 q = uniform_in(rng, b);
        Vec3 g;
        const double v = node->eval(q, &g);
        ASSERT_TRUE(bb.value.contains(v)) << v;
        ASSERT_LE(length(g), bb.lipschitz * (1 + 1e-12));
      }
    }
    if (!f) {
      EXPECT_EQ(refined, 0);
    }
    modulated_refined += refined;
  }
  EXPECT_GT(modulated_refined, 100);
}

// Along segments through and around each object: the bounds hold the values sampled on the
// segment, their difference quotients lie in the slope, and the field is exactly 0 over the
// quiet start, which for segments starting outside the support box is often positive.
TEST(Program, RadiusTransformSegmentBoundsAndQuietStart) {
  for (const TransformCase& c : kTransformCases) {
    SCOPED_TRACE(c.name);
    const NodePtr node = build_from_json(c.json);
    const Program prog = compile(*node);
    Workspace ws;
    ws.fit(prog);
    const Box support = transform_support(c.json);
    const Box around(support.lo - support.extent(), support.hi + support.extent());
    std::mt19937_64 rng(29);
    int quiet = 0;
    for (int i = 0; i < 300; ++i) {
      const Segment seg{uniform_in(rng, around), uniform_in(rng, around)};
      const BoxBounds bb = bounds(prog, seg, ws);
      ASSERT_GE(bb.quiet, 0);
      ASSERT_LE(bb.quiet, 1);
      quiet += bb.quiet > 0;
      const double len = length(seg.b - seg.a);
      double prev = 0;
      for (int j = 0; j <= 40; ++j) {
        const double s = j / 40.0;
        const double v = node->value(seg.a + (seg.b - seg.a) * s);
        ASSERT_TRUE(bb.value.contains(v)) << "segment " << i << " at " << s << ": " << v;
        if (bb.quiet > 0 && s <= bb.quiet) {
          ASSERT_EQ(v, 0) << "segment " << i << " at " << s << " of " << bb.quiet;
        }
        if (j > 0) {
          const double q = (v - prev) / (len / 40);
          ASSERT_LE(q, bb.slope.hi * (1 + 1e-9) + 1e-12) << "segment " << i;
          ASSERT_GE(q, bb.slope.lo * (1 + 1e-9) - 1e-12) << "segment " << i;
        }
        prev = v;
      }
    }
    EXPECT_GT(quiet, 30);
  }
}

// A complement compiles to its child's code (native where the child is) and one instruction, with
// the model's bits in each convention: values, gradients, and over boxes the interval and Lipschitz
// bound. Points at the centre reach the constructive guard (f <= kCgFloor), others a NaN value.
// The soft child is a Ricci union (native) of scale unions of soft objects (native since issue 36,
// so its bounds are only checked to hold the samples: a plain soft_object's program bounds are its
// potential instruction's, not the node's).
TEST(Program, ComplementIsOneInstructionAfterItsChildsCode) {
  const struct {
    const char* json;
    Convention convention;
    Op child;
  } kCases[] = {
      {R"({"type":"complement","children":[{"type":"ricci_union","n":2,"children":[
          {"type":"scale_union","r1":0.6,"r2":0.4,"p":0.1,"children":[
            {"type":"soft_object","distance":{"type":"lp_metric","radii":[1,0.8,1.2],"n":2}},
            {"type":"soft_object","distance":{"type":"torus","major_radius":0.8,"radii":[0.3,0.4]}}]},
          {"type":"scale_union","r1":0.5,"r2":0.7,"p":0.2,"children":[
            {"type":"soft_object","distance":{"type":"lp_metric","radii":[0.5,0.5,0.5],"n":2}},
            {"type":"soft_object","potential":{"type":"wyvill"},
             "distance":{"type":"segment","p0":[0,0,-0.5],"p1":[0,0,0.5],"radius":0.6}}]}]}]})",
       Convention::Soft, Op::Ricci},
      {R"({"type":"complement","children":[{"type":"offset","scale":-2,"level":0.5,"children":[
          {"type":"parallel_planes","normal":[1,2,-0.5],"a":0.7}]}]})",
       Convention::Zero, Op::Offset},
      {R"({"type":"complement","children":[{"type":"lp_metric","radii":[0.6,0.8,1.2],"n":3}]})",
       Convention::Constructive, Op::LpMetric},
      {R"({"type":"complement","children":[{"type":"segment","p0":[0,0,-0.5],"p1":[0,0,0.5],
          "radius":0.6}]})",
       Convention::Constructive, Op::LineSegment},
      {R"({"type":"complement","children":[{"type":"generalized_distance",
          "normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[1,0.7,1.2],"n":2}]})",
       Convention::Constructive, Op::GenDistance}};
  for (const auto& c : kCases) {
    const NodePtr node = build_from_json(c.json, c.convention);
    const Program prog = compile(*node);
    ASSERT_GE(prog.code.size(), 2u) << c.json;
    EXPECT_EQ(prog.code[prog.code.size() - 2].op, c.child) << c.json;
    EXPECT_EQ(prog.code.back().op, Op::Complement) << c.json;
    // The soft case's scale unions compile (issue 36): its bounds only hold the samples.
    const bool bound_bits = std::string(c.json).find("scale_union") == std::string::npos;
    expect_models_bits(
        c.json, c.convention,
        [](Vec3 p, int k) {
          // 0: anywhere; 1: the origin (the skeleton: f = 0); 2: a NaN coordinate; 3: on the z
          // axis.
          switch (k % 4) {
            case 1:
              return Vec3{};
            case 2:
              return with_nan(p, k);
            case 3:
              return Vec3{0, 0, p.z};
          }
          return p;
        },
        bound_bits);
  }
}

// The super-ellipsoidal union and intersection compile to their children's code as a group that is
// never pruned (nor are children dropped over boxes: every one moves the power sum) and one
// instruction, with the model's bits: values, gradients, and over boxes the interval and
// Lipschitz bound. Points at a child's skeleton reach the union's U = 0 branch and the
// intersection's clamp; NaN coordinates give NaN children. No child is placed: a translation's
// box bounds are the program's own (translate_box), not the placed node's.
TEST(Program, SuperEllipsoidalCombinationsAreOneInstructionAfterTheirChildren) {
  const struct {
    const char* json;
    Op op;
    int children;
  } kCases[] = {{R"({"type":"super_ellipsoidal_union","n":2,"children":[
          {"type":"lp_metric","radii":[1,0.8,1.2],"n":2},
          {"type":"lp_metric","radii":[0.6,0.8,1.2],"n":3}]})",
                 Op::SuperUnion, 2},
                {R"({"type":"super_ellipsoidal_union","n":7.5,"children":[
          {"type":"parallel_planes","normal":[1,2,-0.5],"a":0.7},
          {"type":"segment","p0":[0,0,-0.5],"p1":[0,0,0.5],"radius":0.6},
          {"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[1,0.7,1.2],
           "n":2}]})",
                 Op::SuperUnion, 3},
                {R"({"type":"super_ellipsoidal_intersection","n":2,"children":[
          {"type":"lp_metric","radii":[1,0.8,1.2],"n":2},
          {"type":"torus","major_radius":0.8,"radii":[0.3,0.4]}]})",
                 Op::SuperIntersect, 2},
                {R"({"type":"super_ellipsoidal_intersection","n":0.7,"children":[
          {"type":"one_branch_plane","normal":[0.3,-1,0.4],"a":0.5},
          {"type":"lp_metric","radii":[0.6,0.8,1.2],"n":3},
          {"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[1,0.7,1.2],
           "n":2}]})",
                 Op::SuperIntersect, 3},
                {R"({"type":"super_ellipsoidal_intersection","n":4,"children":[
          {"type":"super_ellipsoidal_union","n":3,"children":[
            {"type":"lp_metric","radii":[1,1,1],"n":2},
            {"type":"torus","major_radius":0.8,"radii":[0.3,0.4],"n":3}]},
          {"type":"segment","p0":[0,0,0],"p1":[1,0,0],"radius":0.6}]})",
                 Op::SuperIntersect, 2}};
  for (const auto& c : kCases) {
    const NodePtr node = build_from_json(c.json, Convention::Constructive);
    const Program prog = compile(*node);
    EXPECT_EQ(count_ops(prog.code, Op::Oracle), 0) << c.json;
    EXPECT_EQ(prog.code.back().op, c.op) << c.json;
    EXPECT_EQ(prog.code.back().n, c.children) << c.json;
    EXPECT_FALSE(prog.has_pruning) << c.json;
    for (const Group& g : prog.groups) EXPECT_TRUE(g.bvh.empty()) << c.json;
    expect_models_bits(c.json, Convention::Constructive, [](Vec3 p, int k) {
      // 0: anywhere; 1: the origin (a skeleton); 2: a NaN coordinate; 3: on the x axis.
      switch (k % 4) {
        case 1:
          return Vec3{};
        case 2:
          return with_nan(p, k);
        case 3:
          return Vec3{p.x, 0, 0};
      }
      return p;
    });
    // Over a box far from every child no child is dropped.
    Workspace ws;
    ws.fit(prog);
    bounds(prog, Box::around({1.5, 1.5, 1.5}, 0.1), ws);
    EXPECT_EQ(ws.view.code.size(), prog.code.size() - prog.groups.size()) << c.json;
    EXPECT_EQ(ws.view.code.back().n, c.children) << c.json;
  }
}

// Perlin's blends compile to their children's code as a group that is never pruned and one
// instruction, with the model's bits: values, gradients, and over boxes the interval and
// Lipschitz bound. The children are Ricci unions (native) of oracles (scale unions of soft
// objects) or nested blends of them: a plain soft_object's program bounds are its potential
// instruction's, not the node's. Points at the origin put the children at their peaks; NaN
// coordinates give NaN children.
TEST(Program, PerlinBlendsAreOneInstructionAfterTheirChildren) {
#define BALL R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[1,0.8,1.2],"n":2}})"
#define RING                                                                           \
  R"({"type":"soft_object","potential":{"type":"wyvill"},"distance":{"type":"torus",)" \
  R"("major_radius":0.8,"radii":[0.3,0.4]}})"
#define SOFT_A R"({"type":"scale_union","r1":0.6,"r2":0.4,"p":0.1,"children":[)" BALL "," RING "]}"
#define SOFT_B R"({"type":"scale_union","r1":0.5,"r2":0.7,"p":0.2,"children":[)" RING "," BALL "]}"
#define RICCI(n, a, b) R"({"type":"ricci_union","n":)" #n R"(,"children":[)" a "," b "]}"
  const std::string a = RICCI(2, SOFT_A, SOFT_B), b = RICCI(3, SOFT_B, SOFT_A),
                    c = RICCI(1.5, SOFT_A, SOFT_A);
#undef RICCI
#undef SOFT_B
#undef SOFT_A
#undef RING
#undef BALL
  const auto blend = [](const char* kind, const std::vector<std::string>& children) {
    std::string s = std::string(R"({"type":")") + kind + R"(","children":[)";
    for (size_t i = 0; i < children.size(); ++i) s += (i ? "," : "") + children[i];
    return s + "]}";
  };
  const std::string kCases[] = {blend("perlin_union", {a, b}),
                                blend("perlin_union", {a, b, c}),
                                blend("perlin_intersection", {a, b}),
                                blend("perlin_intersection", {c, a, b}),
                                blend("perlin_difference", {a, b}),
                                blend("perlin_difference", {b, c, a}),
                                blend("perlin_union", {blend("perlin_difference", {a, c}), b})};
  for (const std::string& json : kCases) {
    const NodePtr node = build_from_json(json, Convention::Soft);
    const Program prog = compile(*node);
    EXPECT_EQ(prog.code.back().op, Op::Perlin) << json;
    int blends = 0;
    for (size_t at = json.find("perlin_"); at != std::string::npos;
         at = json.find("perlin_", at + 1))
      ++blends;
    EXPECT_EQ(count_ops(prog.code, Op::Perlin), blends) << json;
    EXPECT_FALSE(prog.has_pruning) << json;
    // The values and gradients to the bit; the bounds only to hold the samples: the scale unions
    // compile (issue 36), so their soft objects are bounded by the program's kernels, whose
    // intervals round otherwise than the model's by an ulp or so.
    expect_models_bits(
        json, Convention::Soft,
        [](Vec3 p, int k) {
          // 0: anywhere; 1: the origin; 2: a NaN coordinate.
          if (k % 3 == 1) return Vec3{};
          if (k % 3 == 2) return with_nan(p, k);
          return p;
        },
        false);
    // Over a box outside every support no child is dropped; over all of space the bound is the
    // node's global one.
    Workspace ws;
    ws.fit(prog);
    bounds(prog, Box::around({5, 5, 5}, 0.1), ws);
    EXPECT_EQ(ws.view.code.size(), prog.code.size() - prog.groups.size()) << json;
    EXPECT_TRUE(same_bits(bounds(prog, Box::unbounded(), ws).lipschitz, node->lipschitz())) << json;
  }
}

// Ricci's union, intersection and difference, in both conventions, compile to their children's
// code as a group that is never pruned (nor are children dropped over boxes: every one moves the
// power mean) and one instruction per blend, with the model's bits: values, gradients, and over
// boxes the interval and Lipschitz bound. Soft leaves are oracles (scale unions of soft objects: a
// plain soft_object's program bounds are its potential instruction's, not the node's); constructive
// leaves are native distances and one oracle (a scale union). Special points
// put children at 1 (the soft peaks, the constructive unit surface) and at 0 (the constructive
// skeletons, where 1/f takes its guard, and the soft fields outside their supports, where a
// difference's 1 - f is 1), or give NaN children. Along segments the slope is [-L, L] and holds
// the field's differences.
TEST(Program, RicciBlendsAreOneInstructionAfterTheirChildren) {
#define BALL R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[1,0.8,1.2],"n":2}})"
#define RING                                                                           \
  R"({"type":"soft_object","potential":{"type":"wyvill"},"distance":{"type":"torus",)" \
  R"("major_radius":0.8,"radii":[0.3,0.4]}})"
#define BAR                                                                                   \
  R"({"type":"soft_object","distance":{"type":"segment","p0":[-0.5,0,0],"p1":[0.5,0.3,0.2],)" \
  R"("radius":0.7}})"
#define SOFT_A R"({"type":"scale_union","r1":0.6,"r2":0.4,"p":0.1,"children":[)" BALL "," RING "]}"
#define SOFT_B R"({"type":"scale_union","r1":0.5,"r2":0.7,"p":0.2,"children":[)" BAR "," BALL "]}"
#define SOFT_C R"({"type":"scale_union","r1":0.3,"r2":0.8,"p":0,"children":[)" RING "," BAR "]}"
#define LP R"({"type":"lp_metric","radii":[1,0.8,1.2],"n":2})"
#define SEG R"({"type":"segment","p0":[0,0,-0.5],"p1":[0,0,0.5],"radius":0.6})"
#define TORUS R"({"type":"torus","major_radius":0.8,"radii":[0.3,0.4]})"
#define PLANE R"({"type":"one_branch_plane","normal":[0.3,-1,0.4],"a":0.5})"
#define SCALE R"({"type":"scale_union","r1":0.5,"r2":0.8,"p":0.2,"children":[)" LP "," SEG "]}"
  const struct {
    std::string json;
    Convention convention;
    int children, scales;  // the scale unions compile to Scale instructions (issue 36)
  } kCases[] = {
      {R"({"type":"ricci_union","n":2,"children":[)" SOFT_A "," SOFT_B "]}", Convention::Soft, 2,
       2},
      {R"({"type":"ricci_union","n":0.7,"children":[)" SOFT_A "," SOFT_B "," SOFT_C "]}",
       Convention::Soft, 3, 3},
      {R"({"type":"ricci_intersection","n":4,"children":[)" SOFT_A "," SOFT_C "]}",
       Convention::Soft, 2, 2},
      {R"({"type":"ricci_difference","n":3,"children":[)" SOFT_A "," SOFT_B "," SOFT_C "]}",
       Convention::Soft, 3, 3},
      {R"({"type":"ricci_difference","n":1.5,"children":[{"type":"ricci_union","n":3,)"
       R"("children":[)" SOFT_A "," SOFT_C "]}," SOFT_B "]}",
       Convention::Soft, 2, 3},
      {R"({"type":"ricci_union","n":4,"children":[)" LP "," TORUS "]}", Convention::Constructive, 2,
       0},
      {R"({"type":"ricci_union","n":0.5,"children":[)" SEG "," PLANE "," SCALE "]}",
       Convention::Constructive, 3, 1},
      {R"({"type":"ricci_intersection","n":2.5,"children":[)" LP "," SEG "," TORUS "]}",
       Convention::Constructive, 3, 0},
      {R"({"type":"ricci_intersection","n":0.7,"children":[)" PLANE "," LP "]}",
       Convention::Constructive, 2, 0},
      {R"({"type":"ricci_difference","n":6,"children":[)" LP "," SEG "," SCALE "]}",
       Convention::Constructive, 3, 1},
      {R"({"type":"ricci_difference","n":2,"children":[{"type":"ricci_intersection","n":3,)"
       R"("children":[)" LP "," TORUS "]}," SEG "]}",
       Convention::Constructive, 2, 0}};
#undef SCALE
#undef PLANE
#undef TORUS
#undef SEG
#undef LP
#undef SOFT_C
#undef SOFT_B
#undef SOFT_A
#undef BAR
#undef RING
#undef BALL
  for (const auto& c : kCases) {
    const std::string& json = c.json;
    const NodePtr node = build_from_json(json, c.convention);
    const Program prog = compile(*node);
    EXPECT_EQ(prog.code.back().op, Op::Ricci) << json;
    EXPECT_EQ(prog.code.back().n, c.children) << json;
    int blends = 0;
    for (size_t at = json.find("ricci_"); at != std::string::npos; at = json.find("ricci_", at + 1))
      ++blends;
    EXPECT_EQ(count_ops(prog.code, Op::Ricci), blends) << json;
    EXPECT_EQ(count_ops(prog.code, Op::Scale), c.scales) << json;
    EXPECT_EQ(count_ops(prog.code, Op::Oracle), 0) << json;
    EXPECT_FALSE(prog.has_pruning) << json;
    for (const Group& g : prog.groups) EXPECT_TRUE(g.bvh.empty()) << json;
    // The bounds to the model's bits where no scale union is compiled: a compiled one's children
    // are bounded by the program's kernels, which round otherwise than the model's nodes.
    const bool bound_bits = json.find("scale_union") == std::string::npos;
    expect_models_bits(
        json, c.convention,
        [](Vec3 p, int k) {
          // 0: anywhere; 1: the origin (soft peaks, constructive skeletons); 2: a NaN coordinate;
          // 3: the lp_metric leaf's unit surface; 4: on the z axis (the segment's skeleton); 5: far
          // out (outside every support).
          switch (k % 6) {
            case 1:
              return Vec3{};
            case 2:
              return with_nan(p, k);
            case 3:
              return p / std::sqrt(p.x * p.x + p.y * p.y / 0.64 + p.z * p.z / 1.44);
            case 4:
              return Vec3{0, 0, p.z * 0.25};
            case 5:
              return p * 4;
          }
          return p;
        },
        bound_bits);
    // Over a box outside every support (every soft child 0) no child is dropped.
    Workspace ws;
    ws.fit(prog);
    bounds(prog, Box::around({5, 5, 5}, 0.1), ws);
    EXPECT_EQ(ws.view.code.size(), prog.code.size() - prog.groups.size()) << json;
    EXPECT_EQ(ws.view.code.back().n, c.children) << json;
    // Along a segment: the slope (the chain rule's, ricci_slope) lies in [-L, L] and bounds the
    // difference quotients of values along it.
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(-2, 2);
    for (int i = 0; i < 100; ++i) {
      const Segment seg{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
      const BoxBounds bb = bounds(prog, seg, ws);
      ASSERT_TRUE(bb.slope.lo >= -bb.lipschitz && bb.slope.hi <= bb.lipschitz) << json;
      EXPECT_EQ(bb.quiet, 0) << json;
      const double len = length(seg.b - seg.a);
      double prev = node->value(seg.a);
      for (int j = 0; j <= 16; ++j) {
        const double v = node->value(seg.a + (seg.b - seg.a) * (j / 16.0));
        ASSERT_TRUE(bb.value.contains(v)) << json << ": " << v;
        if (j > 0 && std::isfinite(v) && std::isfinite(prev)) {
          const double q = (v - prev) / (len / 16), slack = 1e-9 * bb.lipschitz + 1e-12;
          ASSERT_TRUE(q >= bb.slope.lo - slack && q <= bb.slope.hi + slack)
              << json << ": " << q << " outside [" << bb.slope.lo << ", " << bb.slope.hi << "]";
        }
        prev = v;
      }
    }
  }
}

// A soft object under a Ricci blend is native code, not an oracle: its distance's and potential's
// instructions, with the model's values and gradients (its bounds are the potential
// instruction's, sound but not the node's bits).
TEST(Program, SoftObjectsUnderRicciBlendsAreNative) {
  const std::string json = R"({"type":"ricci_difference","n":3,"children":[
      {"type":"ricci_union","n":2,"children":[
        {"type":"soft_object","distance":{"type":"lp_metric","radii":[1,0.8,1.2],"n":2}},
        {"type":"soft_object","potential":{"type":"wyvill"},
         "distance":{"type":"torus","major_radius":0.8,"radii":[0.3,0.4]}}]},
      {"type":"soft_object","potential":{"type":"murakami"},
       "distance":{"type":"lp_metric","radii":[0.5,0.5,0.5],"n":2},"translate":[0.6,0,0]}]})";
  const NodePtr node = build_from_json(json, Convention::Soft);
  const Program prog = compile(*node);
  EXPECT_EQ(count_ops(prog.code, Op::Oracle), 0);
  EXPECT_EQ(count_ops(prog.code, Op::Ricci), 2);
  EXPECT_EQ(count_ops(prog.code, Op::Blanc) + count_ops(prog.code, Op::Wyvill) +
                count_ops(prog.code, Op::Murakami),
            3);
  Workspace ws;
  ws.fit(prog);
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = i % 4 == 1   ? Vec3{}
                   : i % 4 == 2 ? Vec3{0.6, 0, 0}
                                : Vec3{u(rng), u(rng), u(rng)};
    Vec3 gm, gp;
    const double v = node->eval(p, &gm);
    ASSERT_TRUE(same_bits(value(prog, p, ws), v));
    ASSERT_TRUE(same_bits(gradient(prog, p, &gp, ws), v));
    ASSERT_TRUE(same_bits(gp, gm));
  }
  const Box domain({-2, -2, -2}, {2, 2, 2});
  for (int i = 0; i < 300; ++i) {
    const Box b = random_box(rng, domain);
    const BoxBounds bb = bounds(prog, b, ws);
    for (int j = 0; j < 20; ++j) {
      const Vec3 p = uniform_in(rng, b);
      Vec3 g;
      const double v = node->eval(p, &g);
      ASSERT_TRUE(bb.value.contains(v)) << v;
      ASSERT_LE(length(g), bb.lipschitz * (1 + 1e-12));
    }
  }
}

// Along a segment X·n is affine, so a plane's slope interval is its rate (n·dir)/a to within the
// padding where the segment keeps to one side of the plane (an offset's is s times that, ends
// swapped for s < 0; under a rotation too), and holds the rate, with either sign for |X·n|, where
// it crosses; the value interval holds the values along it.
TEST(Program, PlaneSlopeAlongASegmentIsItsRate) {
  const char* const kJson[] = {R"({"type":"parallel_planes","normal":[1,2,-0.5],"a":0.7})",
                               R"({"type":"one_branch_plane","normal":[0.3,-1,0.4],"a":0.5})",
                               R"({"type":"offset","scale":-2,"level":0.5,"children":[
          {"type":"parallel_planes","normal":[1,2,-0.5],"a":0.7,
           "rotate":{"axis":[1,1,0],"deg":40}}]})"};
  for (const char* json : kJson) {
    CompiledCase cc(json, Convention::Zero);
    const NodePtr& node = cc.node;
    const Program& prog = cc.prog;
    Workspace& ws = cc.ws;
    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> u(-2, 2);
    int one_side = 0, crossing = 0;
    for (int i = 0; i < 300; ++i) {
      const Segment seg{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
      const Vec3 dir = (seg.b - seg.a) / length(seg.b - seg.a);
      const BoxBounds bb = bounds(prog, seg, ws);
      const Interval D = bb.slope;
      for (int j = 0; j <= 10; ++j) {
        const double v = node->value(seg.a + (seg.b - seg.a) * (j / 10.0));
        ASSERT_TRUE(bb.value.contains(v))
            << json << ": " << v << " outside [" << bb.value.lo << ", " << bb.value.hi << "]";
      }
      const Vec3 ga = node->gradient(seg.a), gb = node->gradient(seg.b);
      const double ra = dot(ga, dir), rb = dot(gb, dir), tol = 1e-12 * length(ga);
      ASSERT_TRUE(D.lo <= ra + tol && ra - tol <= D.hi && D.lo <= rb + tol && rb - tol <= D.hi)
          << json << ": " << ra << ", " << rb << " outside [" << D.lo << ", " << D.hi << "]";
      if (same_bits(ga, gb)) {
        ++one_side;
        EXPECT_LE(D.width(), 1e-8 * length(ga)) << json << ": [" << D.lo << ", " << D.hi << "]";
      } else {
        ++crossing;
      }
    }
    EXPECT_GT(one_side, 50) << json;
    EXPECT_GT(crossing, 50) << json;
  }
}

// The segment distance is convex along a line, so its slope along a segment is the ends'
// directional derivatives (docs/math.md §8, "Slopes along a segment"), its largest value an end's;
// segments that pass over the skeleton take the subgradient's extreme there.
TEST(Program, LineSegmentSlopeAlongASegmentIsTheEndsDerivatives) {
  const char* const kJson[] = {
      R"({"type":"segment","p0":[-0.5,0,0],"p1":[0.5,0.3,0.2],"radius":0.7})",
      R"({"type":"segment","p0":[0,-1,0],"p1":[0,1,0],"radius":0.4,
          "rotate":{"axis":[1,1,0],"deg":40},"translate":[0.2,0,-0.1]})"};
  for (const char* json : kJson) {
    const NodePtr node = build_from_json(json, Convention::Constructive);
    const Program prog = compile(*node);
    Workspace ws;
    ws.fit(prog);
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(-2, 2);
    int exact = 0, one_signed = 0;
    for (int i = 0; i < 300; ++i) {
      const Segment seg{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
      const Vec3 dir = (seg.b - seg.a) / length(seg.b - seg.a);
      const BoxBounds bb = bounds(prog, seg, ws);
      const double va = node->value(seg.a), vb = node->value(seg.b);
      for (int j = 0; j <= 10; ++j) {
        const double v = node->value(seg.a + (seg.b - seg.a) * (j / 10.0));
        ASSERT_TRUE(bb.value.contains(v))
            << json << ": " << v << " outside [" << bb.value.lo << ", " << bb.value.hi << "]";
      }
      EXPECT_LE(bb.value.hi, std::max(va, vb) * (1 + 1e-9) + 1e-12) << json;
      const double ra = dot(node->gradient(seg.a), dir), rb = dot(node->gradient(seg.b), dir);
      const double L = 1 / 0.4;
      ASSERT_TRUE(bb.slope.lo <= ra + 1e-9 * L && rb - 1e-9 * L <= bb.slope.hi)
          << json << ": " << ra << ", " << rb << " outside [" << bb.slope.lo << ", " << bb.slope.hi
          << "]";
      if (std::abs(bb.slope.lo - ra) <= 1e-8 * L && std::abs(bb.slope.hi - rb) <= 1e-8 * L) ++exact;
      if (bb.slope.lo > 0 || bb.slope.hi < 0) ++one_signed;
    }
    // Only a segment whose line passes within 1e-4 of the magnitudes of the skeleton is wider.
    EXPECT_EQ(exact, 300) << json;
    EXPECT_GT(one_signed, 50) << json;
  }
}

// A spherical product with n1 = 1 (Fig. 12's prism bar) is convex, and C^1 off the planes where
// its inner sum u_x + u_y kinks: along a segment its range and slope come from the ends' values
// and gradients (docs/math.md §8, "Slopes along a segment"), not from the segment's box. The
// range is then the segment's, narrower than the box pass's; both hold every point of it.
TEST(Program, PrismBarTakesItsRangeAlongASegment) {
  const char* kJson[] = {
      R"({"type":"superquadric","radii":[8,8,24],"n1":1,"n2":20})",
      R"({"type":"superquadric","radii":[0.6,0.5,0.9],"n1":1,"n2":8,"t":[2,1,1,1.5,1,1.1]})"};
  const double kSpan[] = {30, 1.5};
  for (int c = 0; c < 2; ++c) {
    CompiledCase cc(kJson[c], Convention::Constructive);
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> u(-kSpan[c], kSpan[c]);
    int narrower = 0;
    for (int i = 0; i < 300; ++i) {
      const Segment seg{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
      const double len = length(seg.b - seg.a);
      const Vec3 dir = (seg.b - seg.a) / len;
      const BoxBounds bb = bounds(cc.prog, seg, cc.ws);
      const Interval box = bounds(cc.prog, segment_box(seg.a, seg.b, seg.pad), cc.ws).value;
      double last = cc.node->value(seg.a);
      for (int j = 1; j <= 64; ++j) {
        const double t = len * j / 64, v = cc.node->value(seg.a + dir * t);
        ASSERT_TRUE(bb.value.contains(v))
            << kJson[c] << ": " << v << " outside [" << bb.value.lo << ", " << bb.value.hi << "]";
        const double quotient = (v - last) / (len / 64), slack = 1e-9 * (1 + std::abs(quotient));
        ASSERT_TRUE(bb.slope.lo - slack <= quotient && quotient <= bb.slope.hi + slack)
            << kJson[c] << ": " << quotient << " outside [" << bb.slope.lo << ", " << bb.slope.hi
            << "]";
        last = v;
      }
      if (bb.value.hi - bb.value.lo < 0.9 * (box.hi - box.lo)) ++narrower;
    }
    EXPECT_GT(narrower, 100) << kJson[c] << ": " << narrower << " of 300";
  }
}

// The points a tracer evaluates lie within the segment's pad of it; where an end is within the
// pad of a kink (here on the plane x = 0), the gradient there says nothing of the derivative on a
// parallel segment that starts across the plane, so that end takes the subgradient's extreme.
TEST(Program, PrismBarEndWithinThePadOfAKinkTakesTheExtreme) {
  CompiledCase cc(R"({"type":"superquadric","radii":[8,8,24],"n1":1,"n2":20})",
                  Convention::Constructive);
  const double pad = 0.01;
  const Segment seg{{0, 6, 0}, {-4, 6.8, 0.4}, pad};
  const Vec3 dir = (seg.b - seg.a) / length(seg.b - seg.a);
  const BoxBounds bb = bounds(cc.prog, seg, cc.ws);
  // On the parallel segment 0.9 pad away (x > 0), f falls at (dir.x + dir.y) / 8 until it
  // crosses x = 0; at the end itself (x = 0, a subgradient with df/dx = 0) it rises at dir.y / 8.
  const Vec3 start = seg.a + Vec3{0.9 * pad, 0, 0};
  const double h = 0.4 * pad;
  const double quotient = (cc.node->value(start + dir * h) - cc.node->value(start)) / h;
  EXPECT_NEAR(quotient, (dir.x + dir.y) / 8, 1e-6);
  EXPECT_LE(bb.slope.lo, quotient);
  EXPECT_TRUE(bb.value.contains(cc.node->value(start)));
}

// The issue's target: for a box the size of one blob's support the pruned program holds exactly
// the children whose supports meet it, and evaluates as the whole program does inside the box (to
// the bit: only zeros are dropped), which is the model's field up to the rounding of the sum's
// order (a large sum is compiled in the spatial order of its children).
TEST(Program, PruningKeepsExactlyTheChildrenWhoseSupportsMeetTheBox) {
  const double r = 3;
  Blobs blobs(1000, r);
  const std::vector<Vec3>& centres = blobs.centres;
  const NodePtr& n = blobs.node;
  const Program& prog = blobs.prog;
  Workspace& ws = blobs.ws;
  ASSERT_TRUE(prog.has_pruning);
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-22, 22);
  int nonempty = 0;
  for (int i = 0; i < 200; ++i) {
    const Box b = Box::around({u(rng), u(rng), u(rng)}, r);
    int expected = 0;
    for (const Vec3& c : centres) expected += !Box::around(c, r).intersected(b).empty();
    const BoxBounds bb = bounds(prog, b, ws);
    const Instr& sum = ws.view.code.back();
    ASSERT_EQ(sum.op, Op::Sum);
    EXPECT_EQ(sum.n, expected);
    EXPECT_EQ(count_ops(ws.view.code, Op::LpMetric), expected);
    nonempty += expected > 0;
    const ProgramView view = ws.view;
    for (int j = 0; j < 10; ++j) {
      const Vec3 p{b.lo.x + (b.hi.x - b.lo.x) * (j / 9.0), b.center().y, b.center().z};
      const double v = value(prog, p, ws);
      EXPECT_EQ(value(view, p, ws), v);
      EXPECT_NEAR(v, n->value(p), 1e-12 * std::abs(v));
      EXPECT_TRUE(bb.value.contains(v));
    }
  }
  EXPECT_GT(nonempty, 50) << "too few boxes met a blob to judge";
}

TEST(Program, NeverDroppedChildrenMergeInOrder) {
  Group g;
  g.always = {1, 4, 9, 12};
  std::vector<int32_t> kept = {0, 2, 3, 10, -1, -1, -1, -1};
  ASSERT_EQ(g.merge_always(kept.data(), 4), 8);
  EXPECT_EQ(kept, (std::vector<int32_t>{0, 1, 2, 3, 4, 9, 10, 12}));
  std::vector<int32_t> none(4, -1);
  ASSERT_EQ(g.merge_always(none.data(), 0), 4);
  EXPECT_EQ(none, g.always);
}

// One point's value and gradient without a view (evaluate()) are those of the program pruned to
// the point, to the bit: through a large sum, a sum nested in a placed child, and a
// term with no support box (a complement, 1 - f, never dropped) merged in among the kept ones.
TEST(Program, EvaluatingAPointIsEvaluatingTheViewPrunedToIt) {
  std::vector<Vec3> centres;
  std::string json = blobs_json(60, 3, &centres);
  const std::string nested =
      R"({"type":"soft_blend","translate":[2,-1,0.5],"children":[)"
      R"({"type":"soft_object","potential":{"type":"wyvill"},"distance":{"type":"lp_metric","radii":[4,4,4],"n":2}},)"
      R"({"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"lp_metric","radii":[3,5,2],"n":2},"translate":[1,1,1]}]},)"
      R"({"type":"complement","children":[{"type":"soft_object","potential":{"type":"murakami"},)"
      R"("distance":{"type":"lp_metric","radii":[30,30,30],"n":2}}]},)";
  json.insert(json.find("\"children\":[") + 12, nested);
  const NodePtr n = build_from_json(json);
  const Program prog = compile(*n);
  ASSERT_EQ(prog.groups.size(), 2u);
  ASSERT_FALSE(prog.groups[0].always.empty()) << "the complement is never dropped";
  Workspace ws;
  ws.fit(prog);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-24, 24);
  int inside = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    prune(prog, Box(p, p), ws);
    const double in_view = value(ws.view, p, ws);
    ASSERT_EQ(evaluate(prog, p, nullptr, ws), in_view) << i;
    ASSERT_EQ(value(prog, p, ws), in_view) << i;  // only zeros are dropped
    Vec3 g_view, g;
    const double with_gradient = gradient(ws.view, p, &g_view, ws);
    ASSERT_EQ(evaluate(prog, p, &g, ws), with_gradient) << i;
    ASSERT_TRUE(g.x == g_view.x && g.y == g_view.y && g.z == g_view.z) << i;
    inside += count_ops(ws.view.code, Op::LpMetric) > 1;
  }
  EXPECT_GT(inside, 100) << "too few points in a blob to judge";
}

// Values share storage where their lifetimes do not overlap: a sum of 1000 translated blobs keeps
// its 1000 terms, one slot for every blob's distance and then the sum, and one register for every
// blob's local point beside the evaluation point. The blobs' pruned views (every child range
// dropped or kept, around shared storage) are evaluated against the model in the test above and in
// the sweeps' ProgramBoxPassEnclosesSamplesAndPrunesExactly.
TEST(Program, ValuesShareStorageWhereTheirLifetimesDoNotOverlap) {
  const Blobs blobs(1000, 3);
  EXPECT_EQ(blobs.prog.slots, 1000 + 1);
  EXPECT_EQ(blobs.prog.regs, 2);
  const Group& g = blobs.prog.groups[0];
  for (size_t k = 0; k < g.children.size(); ++k)
    ASSERT_EQ(g.children[k].slot, g.children[0].slot + static_cast<int32_t>(k))
        << "the terms' slots lie side by side, in the children's order";
  // A modulated radius transform reads its distance, its modulation and its register at once:
  // none of them may share storage with another live value, nor with the result it writes.
  const NodePtr m = build_from_json(
      R"({"type":"soft_blend","children":[{"type":"soft_object","potential":{"type":"wyvill"},)"
      R"("distance":{"type":"lp_metric","radii":[1,1,1],"n":2},"translate":[0.5,0,0],)"
      R"("radii":{"type":"T_an","modulation":{"type":"lp_metric","radii":[2,1.5,1],"n":3}}},)"
      R"({"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"lp_metric","radii":[1,1,1],"n":2}}]})");
  const Program p = compile(*m);
  const auto rt = std::find_if(p.code.begin(), p.code.end(),
                               [](const Instr& i) { return i.op == Op::RadiusTransform; });
  ASSERT_NE(rt, p.code.end());
  EXPECT_NE(rt->in, rt->n);
  EXPECT_NE(rt->out, rt->in);
  EXPECT_NE(rt->out, rt->n);
  Workspace ws;
  ws.fit(p);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 500; ++i) {
    const Vec3 q{u(rng), u(rng), u(rng)};
    ASSERT_EQ(value(p, q, ws), m->value(q)) << i;
  }
}

// A workspace fitted to a small program grows for a larger one (fit() skips only programs within
// what it has fitted before), and then serves both.
TEST(Program, AWorkspaceGrowsForALargerProgram) {
  const Blobs small(10, 3), large(1000, 3);
  Workspace ws;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-20, 20);
  for (int i = 0; i < 200; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    ASSERT_EQ(evaluate(small.prog, p, nullptr, ws), small.node->value(p)) << i;
    ASSERT_NEAR(evaluate(large.prog, p, nullptr, ws), large.node->value(p), 1e-12) << i;
    ASSERT_EQ(evaluate(small.prog, p, nullptr, ws), small.node->value(p)) << i;
  }
  EXPECT_GE(ws.slots.size(), static_cast<size_t>(large.prog.slots) * kBatch);
  EXPECT_GE(ws.kept.size(), static_cast<size_t>(large.prog.children) + 1);
}

// A need taken once (the tracer's) fits as its program does, and each of its sizes alone grows
// the buffers that size sets: a need larger in one size only is not taken for one already fitted.
TEST(Program, AWorkspaceFitsANeedTakenOnce) {
  const Blobs small(10, 3), large(1000, 3);
  Workspace ws;
  ws.fit(WorkspaceNeed(small.prog));
  const WorkspaceNeed big(large.prog);
  ws.fit(big);
  EXPECT_GE(ws.slots.size(), big.slots * kBatch);
  EXPECT_GE(ws.regs.size(), big.regs * 3 * kBatch);
  EXPECT_GE(ws.kept.size(), big.children);
  EXPECT_GE(ws.view.code.capacity(), big.code);
  EXPECT_GE(ws.view.args.capacity(), big.args);
  ws.fit(WorkspaceNeed(small.prog));  // never shrinks
  EXPECT_GE(ws.slots.size(), big.slots * kBatch);
  for (int size = 0; size < 5; ++size) {
    WorkspaceNeed one = big;
    size_t* field[5] = {&one.slots, &one.regs, &one.children, &one.code, &one.args};
    *field[size] *= 2;
    ws.fit(one);
    EXPECT_GE(ws.slots.size(), one.slots * kBatch) << size;
    EXPECT_GE(ws.regs.size(), one.regs * 3 * kBatch) << size;
    EXPECT_GE(ws.points.size(), one.regs) << size;
    EXPECT_GE(ws.ivals.size(), one.slots) << size;
    EXPECT_GE(ws.marks.size(), one.children) << size;
    EXPECT_GE(ws.view.code.capacity(), one.code) << size;
    EXPECT_GE(ws.view.args.capacity(), one.args) << size;
  }
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-20, 20);
  for (int i = 0; i < 100; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    ASSERT_NEAR(value_pruned(large.prog, p, ws), large.node->value(p), 1e-12) << i;
  }
}

// A thread's workspace is written at every evaluation while the other threads read the program
// beside it on the heap: a buffer sharing a cache line with the program's children or args cost
// Fig. 12(b)'s 2-thread process 10-55 % more CPU, by how long the command line was. Each buffer
// begins on a line and fills its last one, so no other block's bytes lie on its lines.
TEST(Program, AWorkspaceSharesNoCacheLine) {
  const Blobs small(10, 3);
  constexpr uintptr_t kLine = 64;
  std::vector<std::vector<double>> around;  // small blocks the heap may place beside them
  for (int i = 0; i < 64; ++i) around.emplace_back(1 + i % 5);
  Workspace ws;
  ws.fit(small.prog);
  for (int i = 0; i < 64; ++i) around.emplace_back(1 + i % 5);
  struct Buffer {
    uintptr_t begin, end;
    const char* name;
  };
  const auto lines = [](const auto& v, const char* name) {
    const uintptr_t begin = reinterpret_cast<uintptr_t>(v.data());
    return Buffer{begin, begin + v.capacity() * sizeof(v[0]), name};
  };
  const Buffer buffers[] = {
      lines(ws.slots, "slots"),    lines(ws.regs, "regs"),     lines(ws.points, "points"),
      lines(ws.duals, "duals"),    lines(ws.frames, "frames"), lines(ws.ivals, "ivals"),
      lines(ws.lips, "lips"),      lines(ws.boxes, "boxes"),   lines(ws.segs, "segs"),
      lines(ws.seg_pads, "pads"),  lines(ws.slopes, "slopes"), lines(ws.quiet, "quiet"),
      lines(ws.ends, "ends"),      lines(ws.kept, "kept"),     lines(ws.marks, "marks"),
      lines(ws.view.code, "code"), lines(ws.view.args, "args")};
  for (const Buffer& b : buffers) {
    ASSERT_LT(b.begin, b.end) << b.name;
    EXPECT_EQ(b.begin % kLine, 0u) << b.name;
    const uintptr_t last_line = (b.end - 1) / kLine;
    for (const auto& block : around) {
      const uintptr_t q = reinterpret_cast<uintptr_t>(block.data());
      const uintptr_t q_end = q + block.size() * sizeof(double);
      EXPECT_TRUE(q / kLine > last_line || (q_end - 1) / kLine < b.begin / kLine) << b.name;
    }
  }
}

// Along a segment, the pass reports how far from its start no support has begun (POV-Ray's first
// support entry): the field is exactly 0 there, entry included (the tracer takes g there as known),
// and for spheres the bound is tight: just past it the field is positive.
TEST(Program, SegmentQuietStartEndsAtTheFirstSupportEntry) {
  Blobs blobs(1000, 3);
  const NodePtr& n = blobs.node;
  Workspace& ws = blobs.ws;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-30, 30);
  int entered = 0;
  for (int i = 0; i < 300; ++i) {
    const Segment seg{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    const BoxBounds bb = bounds(blobs.prog, seg, ws);
    ASSERT_GE(bb.quiet, 0);
    ASSERT_LE(bb.quiet, 1);
    const auto at = [&](double s) { return seg.a + (seg.b - seg.a) * s; };
    for (int j = 0; j <= 20 && bb.quiet > 0; ++j) {  // (quiet = 0 claims nothing)
      const double s = bb.quiet * j / 20;
      ASSERT_EQ(n->value(at(s)), 0) << "segment " << i << " at s = " << s << " of " << bb.quiet;
    }
    if (bb.quiet < 1) {
      ++entered;
      EXPECT_GT(n->value(at(bb.quiet + 1e-6)), 0) << "segment " << i << ": the entry is loose";
    }
  }
  EXPECT_GT(entered, 100) << "too few segments entered a support to judge";
}

TEST(Program, MinDropsChildrenThatCannotBeTheMinimum) {
  const NodePtr n = build_from_json(
      R"({"type":"min","children":[{"type":"lp_metric","radii":[1,1,1],"n":2},
          {"type":"lp_metric","radii":[1,1,1],"n":2,"translate":[100,0,0]}]})",
      Convention::Constructive);
  const Program prog = compile(*n);
  Workspace ws;
  ws.fit(prog);
  bounds(prog, Box::around({0, 0, 0}, 1), ws);
  EXPECT_EQ(ws.view.code.back().op, Op::Min);
  EXPECT_EQ(ws.view.code.back().n, 1);
  EXPECT_EQ(count_ops(ws.view.code, Op::LpMetric), 1);
  EXPECT_EQ(value(ws.view, {0.5, 0, 0}, ws), 0.5);
  bounds(prog, Box::around({50, 0, 0}, 1), ws);  // both can be the minimum here
  EXPECT_EQ(ws.view.code.back().n, 2);
}

}  // namespace softtrace::test

namespace softtrace::test {

// A scale union outside its region III all along a segment is one child's value there (the sharp
// min or max, bit for bit): the view keeps only that child's code, its instruction a copy (a min
// of one), and still evaluates to the whole program's bits at every point of the segment. The
// fig000_5b ring (BSA2 nested five deep over six cylinders) beside one cylinder's middle keeps
// that cylinder alone; near a joint, both of its cylinders.
TEST(Program, ScaleUnionKeepsOnlyTheChildItIsAlongASegment) {
  std::string ring = R"({"type":"segment","p0":[4,0,0],"p1":[2,3.4641,0],"radius":0.8})";
  const Vec3 corner[7] = {{4, 0, 0},        {2, 3.4641, 0},  {-2, 3.4641, 0}, {-4, 0, 0},
                          {-2, -3.4641, 0}, {2, -3.4641, 0}, {4, 0, 0}};
  for (int k = 1; k < 6; ++k) {
    char seg[160];
    std::snprintf(seg, sizeof seg,
                  R"({"type":"segment","p0":[%g,%g,0],"p1":[%g,%g,0],"radius":0.8})", corner[k].x,
                  corner[k].y, corner[k + 1].x, corner[k + 1].y);
    ring =
        R"({"type":"scale_union","r1":0.5,"r2":0.5,"p":0,"children":[)" + ring + "," + seg + "]}";
  }
  // The soft convention's union is BSS2 (the sharp max): two soft segments.
  const std::string soft =
      R"({"type":"scale_union","r1":0.6,"r2":0.4,"p":0.1,"children":[
          {"type":"soft_object","distance":{"type":"segment","p0":[-3,0,0],"p1":[-1,0,0],"radius":1.5}},
          {"type":"soft_object","distance":{"type":"segment","p0":[1,0,0],"p1":[3,0,0],"radius":1.5}}]})";
  const struct {
    std::string json;
    Convention convention;
    Segment beside_one, beside_joint;
    int pruned;  // fewer than this of 400 random segments prune a child: a failure
  } kCases[] = {{ring,
                 Convention::Constructive,
                 {{3, 1.9, 0.9}, {3.05, 1.7, 0.9}},
                 {{3.9, -0.3, 0.7}, {3.9, 0.3, 0.7}},
                 300},
                {soft,
                 Convention::Soft,
                 {{-2.2, 0.3, 0.2}, {-1.9, 0.3, 0.2}},
                 {{-0.3, 0.2, 0}, {0.3, 0.2, 0}},
                 30}};
  for (const auto& c : kCases) {
    const NodePtr node = build_from_json(c.json, c.convention);
    const Program prog = compile(*node);
    Workspace ws;
    ws.fit(prog);
    const int all = count_ops(prog.code, Op::LineSegment);
    const auto points_agree = [&](const Segment& seg) {
      for (int j = 0; j <= 16; ++j) {
        const Vec3 p = seg.a + (seg.b - seg.a) * (j / 16.0);
        const double in_view = value(ws.view, p, ws), whole = value(Code(prog), p, ws);
        if (std::memcmp(&in_view, &whole, sizeof whole) != 0) {
          ADD_FAILURE() << c.json << ": " << in_view << " != " << whole << " at " << p.x << ", "
                        << p.y << ", " << p.z;
          return false;
        }
      }
      return true;
    };
    bounds(prog, c.beside_one, ws);
    EXPECT_EQ(count_ops(ws.view.code, Op::LineSegment), 1) << c.json;
    EXPECT_EQ(count_ops(ws.view.code, Op::Scale), 0) << c.json;
    EXPECT_EQ(ws.view.code.back().op, Op::Min) << c.json;
    EXPECT_EQ(ws.view.code.back().n, 1) << c.json;
    points_agree(c.beside_one);
    bounds(prog, c.beside_joint, ws);
    EXPECT_EQ(count_ops(ws.view.code, Op::LineSegment), 2) << c.json;
    EXPECT_GE(count_ops(ws.view.code, Op::Scale), 1) << c.json;
    points_agree(c.beside_joint);
    // Random segments about the shapes: every view evaluates to the whole program's bits.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-5, 5);
    int pruned = 0;
    for (int i = 0; i < 400; ++i) {
      const Vec3 a{u(rng), u(rng), 0.3 * u(rng)};
      const Vec3 b = a + Vec3{u(rng), u(rng), u(rng)} * 0.2;
      bounds(prog, Segment{a, b}, ws);
      pruned += count_ops(ws.view.code, Op::LineSegment) < all;
      if (!points_agree(Segment{a, b})) break;
    }
    EXPECT_GT(pruned, c.pruned) << c.json;
  }
}

}  // namespace softtrace::test
