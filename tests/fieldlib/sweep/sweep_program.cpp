// The all-kinds sweep for the compiled program's evaluators (fieldlib/eval.h): each one against
// the model it was compiled from, and the fused box pass's bounds and pruned program against
// samples.
#include <cmath>
#include <random>

#include "compiled_case.h"
#include "eval/eval.h"
#include "sweep.h"

namespace softtrace::test {

namespace {

// Equal, or within 1e-12 relative (the gradient through nested rotations is summed in another
// order), or both NaN.
bool near(double a, double b) {
  if (a == b || (std::isnan(a) && std::isnan(b))) return true;
  return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b));
}

}  // namespace

TEST_P(NodeSweep, ProgramValuesAndGradientsMatchTheModel) {
  const SweepCase& c = GetParam();
  CompiledCase cc(c.json, c.convention);
  const NodePtr& n = cc.node;
  const Program& prog = cc.prog;
  Workspace& ws = cc.ws;
  std::mt19937_64 rng(6);
  for (int i = 0; i < 200; ++i) {
    double x[kBatch], y[kBatch], z[kBatch], f[kBatch];
    for (int l = 0; l < kBatch; ++l) {
      const Vec3 p = uniform_in(rng, c.domain);
      x[l] = p.x, y[l] = p.y, z[l] = p.z;
    }
    values(prog, x, y, z, kBatch, f, ws);
    for (int l = 0; l < kBatch; ++l) {
      const Vec3 p{x[l], y[l], z[l]};
      Vec3 gm, gp, ge;
      const double vm = n->eval(p, &gm);
      ASSERT_EQ(f[l], vm) << c.name << ": batch lane " << l;
      ASSERT_EQ(gradient(prog, p, &gp, ws), vm) << c.name;
      ASSERT_TRUE(near(gp.x, gm.x) && near(gp.y, gm.y) && near(gp.z, gm.z))
          << c.name << ": (" << gp.x << ", " << gp.y << ", " << gp.z << ") vs model (" << gm.x
          << ", " << gm.y << ", " << gm.z << ")";
      ASSERT_EQ(evaluate(prog, p, &ge, ws), vm) << c.name << ": pruned to the point";
      ASSERT_TRUE(near(ge.x, gm.x) && near(ge.y, gm.y) && near(ge.z, gm.z)) << c.name;
    }
  }
}

TEST_P(NodeSweep, ProgramBoxPassEnclosesSamplesAndPrunesExactly) {
  const SweepCase& c = GetParam();
  CompiledCase cc(c.json, c.convention);
  const NodePtr& n = cc.node;
  const Program& prog = cc.prog;
  Workspace& ws = cc.ws;
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200; ++i) {
    const Box b = random_box(rng, c.domain);
    const BoxBounds bb = bounds(prog, b, ws);
    ASSERT_FALSE(std::isnan(bb.lipschitz) || std::isnan(bb.value.lo) || std::isnan(bb.value.hi))
        << c.name;
    ASSERT_LE(ws.view.code.size(), prog.code.size());
    const ProgramView view = ws.view;  // the next calls overwrite ws.view
    for (int j = 0; j < 20; ++j) {
      const Vec3 p = uniform_in(rng, b), q = uniform_in(rng, b);
      const double v = n->value(p);
      ASSERT_EQ(value(view, p, ws), v) << c.name << ": the pruned program differs inside its box";
      ASSERT_TRUE(bb.value.contains(v))
          << c.name << ": " << v << " outside [" << bb.value.lo << ", " << bb.value.hi << "]";
      ASSERT_LE(length(n->gradient(p)), bb.lipschitz * (1 + 1e-9) + 1e-12) << c.name;
      ASSERT_LE(std::abs(v - n->value(q)), bb.lipschitz * length(p - q) * (1 + 1e-9) + 1e-12)
          << c.name;
    }
  }
}

TEST_P(NodeSweep, ProgramSegmentPassEnclosesSamplesAndSlopes) {
  // The tracer's pass over a stretch of a ray: the values, the zero of the quiet start, and the
  // difference quotients along it against the slope interval, at points on the segment.
  const SweepCase& c = GetParam();
  CompiledCase cc(c.json, c.convention);
  const NodePtr& n = cc.node;
  const Program& prog = cc.prog;
  Workspace& ws = cc.ws;
  std::mt19937_64 rng(8);
  for (int i = 0; i < 200; ++i) {
    const RandomSegment s = random_segment(rng, c.domain);
    if (!(s.len > 0)) continue;
    const Segment& seg = s.seg;
    const double len = s.len;
    const Vec3 dir = s.dir;
    const BoxBounds bb = bounds(prog, seg, ws);
    const ProgramView view = ws.view;
    std::uniform_real_distribution<double> u(0, len);
    for (int j = 0; j < 20; ++j) {
      double t1 = u(rng), t2 = u(rng);
      if (t1 > t2) std::swap(t1, t2);
      const Vec3 p = seg.a + dir * t1, q = seg.a + dir * t2;
      const double v = n->value(p), w = n->value(q);
      ASSERT_EQ(value(view, p, ws), v) << c.name << ": the pruned program differs on its segment";
      ASSERT_TRUE(bb.value.contains(v))
          << c.name << ": " << v << " outside [" << bb.value.lo << ", " << bb.value.hi << "]";
      if (t1 <= bb.quiet * len) {
        ASSERT_EQ(v, 0) << c.name << ": not 0 within the quiet start " << bb.quiet;
      }
      if (!(t2 > t1) || !std::isfinite(v) || !std::isfinite(w)) continue;
      const double quotient = (w - v) / (t2 - t1);
      const double slack = 1e-9 * (std::abs(bb.slope.lo) + std::abs(bb.slope.hi)) +
                           1e-12 * (std::abs(v) + std::abs(w)) / (t2 - t1) + 1e-12;
      ASSERT_GE(quotient, bb.slope.lo - slack)
          << c.name << ": [" << bb.slope.lo << ", " << bb.slope.hi << "]";
      ASSERT_LE(quotient, bb.slope.hi + slack)
          << c.name << ": [" << bb.slope.lo << ", " << bb.slope.hi << "]";
    }
  }
}

TEST_P(NodeSweep, ProgramSegmentSlopeHoldsCentralDifferences) {
  // The slope along a segment against the derivative d f(a + t u)/dt sampled by central
  // differences at points inside it, where the step stays inside (the derivative, not a chord).
  const SweepCase& c = GetParam();
  CompiledCase cc(c.json, c.convention);
  const NodePtr& n = cc.node;
  Workspace& ws = cc.ws;
  std::mt19937_64 rng(9);
  for (int i = 0; i < 200; ++i) {
    const RandomSegment s = random_segment(rng, c.domain);
    if (!(s.len > 0)) continue;
    const Segment& seg = s.seg;
    const double len = s.len;
    const Vec3 dir = s.dir;
    const BoxBounds bb = bounds(cc.prog, seg, ws);
    const double h = 1e-6 * len;
    std::uniform_real_distribution<double> u(h, len - h);
    for (int j = 0; j < 10; ++j) {
      const double t = u(rng);
      const double fp = n->value(seg.a + dir * (t + h)), fm = n->value(seg.a + dir * (t - h));
      if (!std::isfinite(fp) || !std::isfinite(fm)) continue;
      const double derivative = (fp - fm) / (2 * h);
      // Rounding of the two values, and the second-order term of a kink or a sharp bend.
      const double slack = 1e-6 * (std::abs(bb.slope.lo) + std::abs(bb.slope.hi)) +
                           1e-12 * (std::abs(fp) + std::abs(fm)) / h + 1e-9;
      ASSERT_GE(derivative, bb.slope.lo - slack)
          << c.name << ": [" << bb.slope.lo << ", " << bb.slope.hi << "] at t = " << t;
      ASSERT_LE(derivative, bb.slope.hi + slack)
          << c.name << ": [" << bb.slope.lo << ", " << bb.slope.hi << "] at t = " << t;
    }
  }
}

// The combinations and distances whose slope along a segment is derived (docs/math.md §8, "Slopes
// along a segment") must show it one-signed where the field rises or falls through a short segment:
// a slope of [-L, L] never is. Counts such segments among 400 short ones.
TEST(ProgramSegmentSlopes, CombinationsGiveOneSignedSlopes) {
  const char* soft_a =
      R"({"type":"soft_object","translate":[-0.4,0,0],"distance":{"type":"lp_metric","radii":[1,0.8,1.1],"n":2}})";
  const char* soft_b =
      R"({"type":"soft_object","translate":[0.5,0.2,0],"distance":{"type":"lp_metric","radii":[0.9,1.2,0.8],"n":4}})";
  const char* dist_a = R"({"type":"lp_metric","translate":[-0.4,0,0],"radii":[1,0.8,1.1],"n":2})";
  const char* dist_b =
      R"({"type":"lp_metric","translate":[0.5,0.2,0],"radii":[0.9,1.2,0.8],"n":4})";
  // Zero-convention children (inside <= 0) for BT_k: d - 1.
  const char* zero_a =
      R"({"type":"offset","children":[{"type":"lp_metric","translate":[-0.4,0,0],"radii":[1,0.8,1.1],"n":2}]})";
  const char* zero_b =
      R"({"type":"offset","children":[{"type":"lp_metric","translate":[0.5,0.2,0],"radii":[0.9,1.2,0.8],"n":4}]})";
  struct Kind {
    const char* name;
    std::string json;
    Convention convention;
  };
  const auto pair = [](const std::string& head, const char* a, const char* b) {
    return head + R"(,"children":[)" + a + "," + b + "]}";
  };
  const Kind kinds[] = {
      {"scale_BSS2", pair(R"({"type":"scale_union","r1":0.6,"r2":0.4,"p":0.1)", soft_a, soft_b),
       Convention::Soft},
      {"scale_BSA2", pair(R"({"type":"scale_union","r1":0.6,"r2":0.4,"p":0.1)", dist_a, dist_b),
       Convention::Constructive},
      {"perlin_union", pair(R"({"type":"perlin_union")", soft_a, soft_b), Convention::Soft},
      {"perlin_intersection", pair(R"({"type":"perlin_intersection")", soft_a, soft_b),
       Convention::Soft},
      {"perlin_difference", pair(R"({"type":"perlin_difference")", soft_a, soft_b),
       Convention::Soft},
      {"ricci_union", pair(R"({"type":"ricci_union","n":3)", soft_a, soft_b), Convention::Soft},
      {"ricci_difference_cg", pair(R"({"type":"ricci_difference","n":4)", dist_a, dist_b),
       Convention::Constructive},
      {"super_ellipsoidal_union",
       pair(R"({"type":"super_ellipsoidal_union","n":4)", dist_a, dist_b),
       Convention::Constructive},
      {"super_ellipsoidal_intersection",
       pair(R"({"type":"super_ellipsoidal_intersection","n":4)", dist_a, dist_b),
       Convention::Constructive},
      {"bt_union_conic",
       pair(R"({"type":"bt_union","base":"conic","r1":0.3,"r2":0.5,"p":0,"m":[1,2])", zero_a,
            zero_b),
       Convention::Zero},
      {"bt_intersection_hyperellipsoid",
       pair(R"({"type":"bt_intersection","base":"hyperellipsoid","r":[0.3,0.4],"p":[2,3])", zero_a,
            zero_b),
       Convention::Zero},
      {"bt_difference_conic",
       pair(R"({"type":"bt_difference","base":"conic","r1":0.2,"r2":0.3,"p":-0.1,"m":[1,0.5])",
            zero_a, zero_b),
       Convention::Zero},
      {"displacement_union_conic",
       pair(R"({"type":"displacement_union","base":"conic","r1":0.3,"r2":0.3,"p":-0.2)", zero_a,
            zero_b),
       Convention::Zero},
      // Distances whose slope is derived from their own convexity along a line.
      {"segment", R"({"type":"segment","p0":[-0.5,0,0],"p1":[0.5,0.3,0.2],"radius":0.7})",
       Convention::Constructive},
      {"torus", R"({"type":"torus","major_radius":0.8,"radii":[0.3,0.4]})",
       Convention::Constructive},
      {"torus_n1_5", R"({"type":"torus","major_radius":1,"radii":[0.5,0.3],"n":1.5})",
       Convention::Constructive},
      {"polar_prism_rose",
       R"({"type":"polar_prism","radius":0.8,"lobes":5,"amplitude":0.3,"profile":"cosine","half_height":0.6})",
       Convention::Constructive},
      {"polar_prism_star",
       R"({"type":"polar_prism","radius":0.8,"lobes":5,"amplitude":0.35,"profile":"triangle","half_height":0.6})",
       Convention::Constructive},
  };
  const Box domain({-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5});
  for (const Kind& k : kinds) {
    const NodePtr n = build_from_json(k.json, k.convention);
    const Program prog = compile(*n);
    Workspace ws;
    ws.fit(prog);
    std::mt19937_64 rng(10);
    std::normal_distribution<double> g(0, 1);
    int one_signed = 0;
    for (int i = 0; i < 400; ++i) {
      const Vec3 a = uniform_in(rng, domain);
      const Vec3 d = normalize(Vec3{g(rng), g(rng), g(rng)});
      const BoxBounds bb = bounds(prog, Segment{a, a + d * 0.05}, ws);
      if (bb.slope.lo > 0 || bb.slope.hi < 0) ++one_signed;
    }
    EXPECT_GT(one_signed, 0) << k.name;
    RecordProperty(k.name, one_signed);
  }
}

// Modulated radii (002 Fig. 6's levels, scaled: the T_an and T_sn of fig002_6d and 6f, at their
// levels 0.15 and 0.85): along a short segment that crosses the level surface steeply, P(T(d, w))
// falls one-signed with d. The w' term's interval spans 0 there, so it is T_d's lower bound
// (RadiusProfile::slope_d_min) that keeps the slope one-signed: 196, 208 and 200 of 209 segments
// here; Fig. 6's two 0 of 209 with T_d in [0, sup], T_an_close 110 without ratio_along.
TEST(ProgramSegmentSlopes, ModulatedTransformsAcrossTheSurfaceAreOneSigned) {
  struct Kind {
    const char* name;
    const char* json;
    double level;
  };
  const Kind kinds[] = {
      {"T_an_levels",
       R"({"type":"soft_object","distance":{"type":"superquadric","radii":[1,0.6,2.5],"n1":2,
           "n2":10},"radii":{"type":"T_an","modulation":{"type":"lp_metric","radii":[2.4,1.5,5],
           "n":10}}})",
       0.15},
      // 002 Fig. 3's cylinder, its modulation 1/60 of a radius outside on five sides: over a
      // segment [d]/[f] takes w down to its clamp, and only d/f from the gauges' values at the
      // ends (RadiusTransformOp::ratio_along) keeps the linear branch's T_d >= 1/w usable.
      {"T_an_close",
       R"({"type":"soft_object","distance":{"type":"superelliptic_cylinder","radii":[1,1,1],"n":8,
           "half_length":1.5},"radii":{"type":"T_an","modulation":{"type":"superelliptic_cylinder",
           "radii":[1,1,1],"n":8,"half_length":1.5,"t":[1.0166666666666667,1.0166666666666667,2,
           1.0166666666666667,1.0166666666666667,1.0166666666666667]}}})",
       0.3},
      {"T_sn_levels",
       R"({"type":"soft_object","distance":{"type":"superquadric","radii":[1,0.6,2.5],"n1":2,
           "n2":10},"radii":{"type":"T_sn","modulation":{"type":"superquadric",
           "radii":[0.4,0.4,1.25],"n1":2,"n2":10}}})",
       0.85},
  };
  for (const Kind& k : kinds) {
    const NodePtr n = build_from_json(k.json, Convention::Soft);
    const Program prog = compile(*n);
    Workspace ws;
    ws.fit(prog);
    std::mt19937_64 rng(11);
    std::normal_distribution<double> g(0, 1);
    int crossing = 0, one_signed = 0;
    for (int i = 0; i < 400; ++i) {
      // A point of the level surface on a ray from the centre (the field falls outward), and a
      // short segment through it within 60 degrees of that ray.
      const Vec3 u = normalize(Vec3{g(rng), g(rng), g(rng)});
      double lo = 0.01, hi = 6;
      if (!(n->value(u * lo) > k.level && n->value(u * hi) < k.level)) continue;
      for (int j = 0; j < 60; ++j) {
        const double m = 0.5 * (lo + hi);
        (n->value(u * m) > k.level ? lo : hi) = m;
      }
      Vec3 d = normalize(Vec3{g(rng), g(rng), g(rng)});
      if (dot(d, u) < 0) d = d * -1;
      if (dot(d, u) < 0.5) continue;
      const Vec3 p = u * lo;
      ++crossing;
      const BoxBounds bb = bounds(prog, Segment{p - d * 0.005, p + d * 0.005}, ws);
      if (bb.slope.lo >= 0 || bb.slope.hi <= 0) ++one_signed;  // as the tracer reads it
    }
    ASSERT_GT(crossing, 50) << k.name;
    EXPECT_GE(one_signed, 0.9 * crossing) << k.name << ": " << one_signed << " of " << crossing;
    RecordProperty(k.name, one_signed);
  }
}

}  // namespace softtrace::test
