// The true gradient under bulge elimination (docs/math.md §7.6, blends_bt.h): the children's exact
// Hessians (FieldNode::hessian) against differenced gradients, and the rendered field's gradient
// against central differences of its value on every scene in scenes/ that eliminates bulges, with
// the paper's partial gradient shown to fail the same check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "kernels/bt_base.h"
#include "scene_files.h"
#include "sweep.h"

// A namespace of its own: the unity build joins this file with test_bt_nodes.cpp.
namespace softtrace::test::bulge_gradient {
namespace {

using Rng = std::mt19937_64;

double degrees_between(const Vec3& a, const Vec3& b) {
  const double c = dot(a, b) / (length(a) * length(b));
  return std::acos(std::min(1.0, std::max(-1.0, c))) * 180 / M_PI;
}

// Central differences of f's value with step h.
template <class F>
Vec3 differenced(const F& f, const Vec3& X, double h) {
  Vec3 d;
  for (int i = 0; i < 3; ++i) {
    Vec3 a = X, c = X;
    a[i] += h;
    c[i] -= h;
    d[i] = (f(a) - f(c)) / (a[i] - c[i]);
  }
  return d;
}

// ---- The children's exact Hessians

struct HessianCase {
  const char* json;
  Box domain;
  // Points closer than this to a kink of the Hessian (a segment's end planes, its axis, a
  // coordinate plane of an Lp metric with n < 2) are skipped.
  double margin;
};

// Offsets of segments as in 003 Fig. 9, Lp metrics with n = 2, 3 and 1.5, rigid and affine
// placements: each case's Hessian against central differences of its gradient.
TEST(ExactHessian, MatchesDifferencedGradients) {
  const HessianCase cases[] = {
      {R"({"type":"segment","p0":[-1,0.2,0],"p1":[1,-0.3,0.4],"radius":0.16})",
       Box({-1.5, -1, -1}, {1.5, 1, 1}), 1e-3},
      {R"({"type":"offset","scale":-2,"level":0.5,"children":[{"type":"segment","p0":[0,-1,0],"p1":[0,1,0],"radius":0.3}]})",
       Box({-1, -1.5, -1}, {1, 1.5, 1}), 1e-3},
      {R"({"type":"lp_metric","radii":[0.5,0.7,0.4],"n":2})", Box({-1, -1, -1}, {1, 1, 1}), 1e-3},
      {R"({"type":"lp_metric","radii":[0.5,0.7,0.4],"n":3})", Box({-1, -1, -1}, {1, 1, 1}), 1e-3},
      {R"({"type":"lp_metric","radii":[0.5,0.7,0.4],"n":1.5})", Box({-1, -1, -1}, {1, 1, 1}), 0.05},
      {R"({"type":"offset","translate":[0.3,-0.2,0.1],"rotate":{"axis":[1,2,3],"deg":40},"children":[{"type":"lp_metric","radii":[0.5,0.7,0.4],"n":3}]})",
       Box({-1, -1, -1}, {1, 1, 1}), 1e-3},
      {R"({"type":"offset","matrix":[[1,0.3,0,0.1],[0,0.8,0.2,0],[0.1,0,1.3,-0.2]],"children":[{"type":"segment","p0":[-1,0,0],"p1":[1,0,0],"radius":0.2}]})",
       Box({-1.5, -1, -1}, {1.5, 1, 1}), 1e-3},
  };
  Rng g(3601);
  for (const HessianCase& c : cases) {
    SCOPED_TRACE(c.json);
    const NodePtr n = build_from_json(c.json, Convention::Zero);
    int checked = 0;
    for (int s = 0; s < 2000; ++s) {
      const Vec3 X = uniform_in(g, c.domain);
      Mat3 H;
      if (!n->hessian(X, &H)) continue;
      // The kinks: differenced gradients across them disagree at two steps, which skips them.
      const double h = 1e-6;
      Mat3 D[2];
      for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 3; ++j) {
          Vec3 a = X, b = X;
          a[j] += h * (k + 1);
          b[j] -= h * (k + 1);
          D[k].r[j] = (n->gradient(a) - n->gradient(b)) / (a[j] - b[j]);
        }
      double scale = 1, jump = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          scale = std::max(scale, std::abs(D[0].r[i][j]));
          jump = std::max(jump, std::abs(D[0].r[i][j] - D[1].r[i][j]));
        }
      if (jump > 1e-4 * scale) continue;
      bool near_kink = false;
      for (int j = 0; j < 3; ++j) {
        Vec3 a = X;
        a[j] += c.margin;
        Vec3 b = X;
        b[j] -= c.margin;
        Mat3 Ha, Hb;
        near_kink = near_kink || !n->hessian(a, &Ha) || !n->hessian(b, &Hb);
      }
      if (near_kink) continue;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          ASSERT_NEAR(H.r[i][j], H.r[j][i], 1e-12 * scale);
          ASSERT_NEAR(H.r[i][j], D[0].r[j][i], 1e-5 * scale)
              << "at " << X.x << " " << X.y << " " << X.z;
        }
      ++checked;
    }
    EXPECT_GT(checked, 1500);
  }
}

// A kind with no closed-form Hessian (the torus) answers false: the blend differences its
// gradient instead (blends_bt.h).
TEST(ExactHessian, KindsWithoutOneSayNo) {
  const NodePtr t =
      build_from_json(R"({"type":"torus","major_radius":1,"radii":[0.3,0.3]})", Convention::Zero);
  Mat3 H;
  EXPECT_FALSE(t->hessian({1.2, 0.1, 0.1}, &H));
}

// ---- The rendered field's gradient on the scenes that eliminate bulges

// Each object's "field" in a scene file, with the object's name: the balanced {...} after
// "field": (the scenes' strings hold no braces).
struct SceneField {
  std::string scene, name, json;
};

std::vector<SceneField> bulge_fields() {
  std::vector<SceneField> out;
  for (const auto& path : scene_files()) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    for (size_t at = text.find("\"field\""); at != std::string::npos;
         at = text.find("\"field\"", at + 1)) {
      const size_t open = text.find('{', at);
      int depth = 0;
      size_t close = open;
      for (; close < text.size(); ++close) {
        depth += text[close] == '{' ? 1 : text[close] == '}' ? -1 : 0;
        if (depth == 0) break;
      }
      const std::string json = text.substr(open, close + 1 - open);
      if (json.find("bulge_elimination") == std::string::npos) continue;
      const size_t name_key = text.rfind("\"name\"", at);
      const size_t q0 = text.find('"', text.find(':', name_key)) + 1;
      out.push_back({path.stem().string(), text.substr(q0, text.find('"', q0) - q0), json});
    }
  }
  return out;
}

// Points on and near the zero surface: random points in `domain` taken onto it by Newton steps
// along the gradient, then moved off it along the normal by up to `offset`.
std::vector<Vec3> near_surface(const FieldNode& f, const Box& domain, int count, double offset,
                               Rng& g) {
  std::vector<Vec3> out;
  for (int s = 0; s < 50 * count && static_cast<int>(out.size()) < count; ++s) {
    Vec3 X = uniform_in(g, domain), grad;
    double v = 0;
    for (int it = 0; it < 20; ++it) {
      v = f.eval(X, &grad);
      const double g2 = dot(grad, grad);
      if (!(g2 > 0) || !std::isfinite(v)) break;
      X = X - grad * (v / g2);
    }
    v = f.eval(X, &grad);
    if (!(std::abs(v) < 1e-9) || !domain.contains(X)) continue;
    out.push_back(X + normalize(grad) * std::uniform_real_distribution<double>(-offset, offset)(g));
  }
  return out;
}

// The gradient must match central differences of the field's value to 0.1 degrees. Skipped:
// points within 1e-5 of a kink (the min outside the blend, [cosθ]_+ at cosθ = 0, the switch of
// M_i's cases, a segment's end planes), detected as central differences with steps 1e-6 and
// 4e-6 disagreeing by more than 0.01 degrees; at most 1% of the points.
TEST(BulgeGradient, ScenesMatchCentralDifferencesOfTheValue) {
  const std::vector<SceneField> fields = bulge_fields();
  ASSERT_GE(fields.size(), 3u) << "fig003_9_wheel (two objects), fig003_9a_crossing_cylinders";
  Rng g(3602);
  for (const SceneField& sf : fields) {
    SCOPED_TRACE(sf.scene + " " + sf.name);
    const NodePtr n = build_from_json(sf.json, Convention::Zero);
    const auto value = [&](const Vec3& X) { return n->value(X); };
    const std::vector<Vec3> pts = near_surface(*n, Box({-6, -4, -2}, {6, 4, 2}), 3000, 0.05, g);
    ASSERT_EQ(pts.size(), 3000u);
    double worst = 0;
    int skipped = 0;
    for (const Vec3& X : pts) {
      const Vec3 fd = differenced(value, X, 1e-6);
      if (degrees_between(fd, differenced(value, X, 4e-6)) > 0.01) {
        ++skipped;
        continue;
      }
      const double a = degrees_between(n->gradient(X), fd);
      worst = std::max(worst, a);
      ASSERT_LT(a, 0.1) << "at " << X.x << " " << X.y << " " << X.z;
    }
    EXPECT_LE(skipped, 30);
    std::printf("%s %s: %zu points, %d skipped at kinks, worst %.2e degrees\n", sf.scene.c_str(),
                sf.name.c_str(), pts.size(), skipped, worst);
  }
}

// A child with no closed-form Hessian (a torus) is differenced (blends_bt.h): the gradient still
// matches central differences of the value to 0.1 degrees near the surface.
TEST(BulgeGradient, DifferencedHessiansOfOtherKinds) {
  const NodePtr n = build_from_json(
      R"({"type":"bt_union","base":"hyperellipsoid","r":[0.6,0.6],"p":[2,2],"m":[0.5,1],)"
      R"("bulge_elimination":{"omega":0.05},"children":[)"
      R"({"type":"offset","children":[{"type":"torus","major_radius":1.2,"radii":[0.3,0.3]}]},)"
      R"({"type":"offset","children":[{"type":"segment","p0":[-2,0,0],"p1":[2,0,0],"radius":0.25}]}]})",
      Convention::Zero);
  const auto value = [&](const Vec3& X) { return n->value(X); };
  Rng g(3604);
  const std::vector<Vec3> pts = near_surface(*n, Box({-2, -2, -1}, {2, 2, 1}), 2000, 0.05, g);
  ASSERT_EQ(pts.size(), 2000u);
  int checked = 0;
  for (const Vec3& X : pts) {
    const Vec3 fd = differenced(value, X, 1e-6);
    if (degrees_between(fd, differenced(value, X, 4e-6)) > 0.01) continue;
    ASSERT_LT(degrees_between(n->gradient(X), fd), 0.1) << X.x << " " << X.y << " " << X.z;
    ++checked;
  }
  EXPECT_GT(checked, 1980);
}

// The same check fails with the paper's partial gradient (P and M frozen at the point), which
// is what softtrace shaded with before: on 003 Fig. 9(a)'s bulge-eliminated crossing it is
// degrees off the surface's normal, while the true gradient stays within 0.1 degrees.
TEST(BulgeGradient, ThePartialGradientFailsTheCheck) {
  const char* spoke_x =
      R"({"type":"offset","children":[{"type":"segment","p0":[-2,0,0],"p1":[2,0,0],"radius":0.5}]})";
  const char* spoke_y =
      R"({"type":"offset","children":[{"type":"segment","p0":[0,-2,0],"p1":[0,2,0],"radius":0.5}]})";
  const NodePtr f1 = build_from_json(spoke_x, Convention::Zero);
  const NodePtr f2 = build_from_json(spoke_y, Convention::Zero);
  const NodePtr n = build_from_json(
      std::string(R"({"type":"bt_union","base":"hyperellipsoid","r":[0.8,0.8],"p":[2,2],)"
                  R"("bulge_elimination":{"omega":0.05},"children":[)") +
          spoke_x + "," + spoke_y + "]}",
      Convention::Zero);
  const BtOperator op = BtOperator::hyperellipsoid({0.8, 0.8}, {2, 2}, {1, 1});
  const double r[2] = {0.8, 0.8}, m[2] = {1, 1};
  const auto value = [&](const Vec3& X) { return n->value(X); };
  Rng g(3603);
  const std::vector<Vec3> pts = near_surface(*n, Box({-3, -3, -2}, {3, 3, 2}), 2000, 0.05, g);
  double worst_partial = 0, worst_true = 0;
  for (const Vec3& X : pts) {
    const Vec3 fd = differenced(value, X, 1e-6);
    if (degrees_between(fd, differenced(value, X, 4e-6)) > 0.01) continue;
    Vec3 g1, g2;
    const double x[2] = {f1->eval(X, &g1), f2->eval(X, &g2)};
    const BulgeParameters b = bulge_parameters(g1, g2, r, m, 0.05);
    double dx[2];
    op.eval(x, b.P, b.M, dx);
    const Vec3 partial = g1 * dx[0] + g2 * dx[1];
    worst_partial = std::max(worst_partial, degrees_between(partial, fd));
    worst_true = std::max(worst_true, degrees_between(n->gradient(X), fd));
  }
  std::printf("partial gradient: worst %.2f degrees; true gradient: worst %.2e degrees\n",
              worst_partial, worst_true);
  EXPECT_GT(worst_partial, 5.0);
  EXPECT_LT(worst_true, 0.1);
}

}  // namespace
}  // namespace softtrace::test::bulge_gradient
