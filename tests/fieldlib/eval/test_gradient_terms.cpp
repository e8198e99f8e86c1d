// A program's terms (Program::terms, eval.h gradient_terms): children of sums whose values one
// gradient walk reports beside f and ∇f, found by the loader's BuildObserver. The walk must give
// the same f and ∇f bits as the plain one, and each term the value of its node alone, 0 where
// its sum skips it; BlobSum's gradient reports the same terms.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "describe/building.h"
#include "eval/blob_ray.h"
#include "eval/eval.h"
#include "model/program_builder.h"

namespace softtrace::test {

namespace {

using json = nlohmann::json;

std::string ball(double x, double y, double r, double strength) {
  return R"({"type":"soft_object","potential":{"type":"murakami"},"strength":)" +
         std::to_string(strength) + R"(,"distance":{"type":"lp_metric","n":2,"radii":[)" +
         std::to_string(r) + "," + std::to_string(r) + "," + std::to_string(r) +
         R"(]},"translate":[)" + std::to_string(x) + "," + std::to_string(y) + ",0]}";
}

// Records the node built from each JSON object of interest.
class Finder final : public BuildObserver {
 public:
  std::unordered_map<const json*, const FieldNode*> nodes;
  void built(const Params& p, const FieldNode& node) override {
    if (nodes.count(&p.raw())) nodes[&p.raw()] = &node;
  }
};

// `text` built with its sums' children `paths` (child indices from the root) as the terms.
struct Built {
  json doc;
  NodePtr root;
  std::vector<const FieldNode*> terms;
  Program program;

  Built(const std::string& text, const std::vector<std::vector<int>>& paths)
      : doc(json::parse(text)) {
    Finder finder;
    std::vector<const json*> objects;
    for (const std::vector<int>& path : paths) {
      const json* at = &doc;
      for (int i : path) at = &(*at)["children"][size_t(i)];
      objects.push_back(at);
      finder.nodes[at] = nullptr;
    }
    BuildContext ctx;
    ctx.observer = &finder;
    root = build_field(Params(doc, "", std::make_shared<const std::string>("<test>")), ctx);
    for (const json* o : objects) terms.push_back(finder.nodes.at(o));
    program = compile(*root, terms);
  }
};

// 40 balls (a sum compiled in spatial order, pruned by its BVH), the last of them inside a
// nested soft_blend moved by (10, 0, 0), one of negative strength.
std::string cloud() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> c(-5, 5), r(1, 2.5);
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < 39; ++i)
    s += (i ? "," : "") + ball(c(rng), c(rng), r(rng), i == 5 ? -0.5 : 1);
  s += R"(,{"type":"soft_blend","translate":[10,0,0],"children":[)" + ball(0, 0, 2, 1) + "," +
       ball(1, 0, 2, 1) + "]}]}";
  return s;
}

std::vector<std::vector<int>> cloud_paths() {
  std::vector<std::vector<int>> paths;
  for (int i = 0; i < 39; ++i) paths.push_back({i});
  paths.push_back({39, 0});
  paths.push_back({39, 1});
  return paths;
}

TEST(GradientTerms, SameFieldAndGradientBitsAndEachTermItsNodeAlone) {
  const Built b(cloud(), cloud_paths());
  ASSERT_EQ(b.program.terms, 41);
  ASSERT_TRUE(b.program.has_pruning);
  Workspace ws, plain;
  std::vector<double> terms(41, -1);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(-8, 14), y(-8, 8), z(-3, 3);
  int nonzero = 0, several = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p{x(rng), y(rng), z(rng)};
    Vec3 g, g_plain;
    const double f = gradient_terms(b.program, p, &g, terms.data(), ws);
    const double f_plain = evaluate(b.program, p, &g_plain, plain);
    ASSERT_EQ(f, f_plain) << p.x << " " << p.y << " " << p.z;
    ASSERT_EQ(g.x, g_plain.x);
    ASSERT_EQ(g.y, g_plain.y);
    ASSERT_EQ(g.z, g_plain.z);
    int here = 0;
    for (int i = 0; i < 41; ++i) {
      // The nested blend's balls read the point in its frame, moved by (10, 0, 0).
      const Vec3 local = i < 39 ? p : p - Vec3{10, 0, 0};
      ASSERT_DOUBLE_EQ(terms[i], b.terms[i]->value(local)) << "term " << i;
      here += terms[i] != 0;
    }
    nonzero += here > 0;
    several += here > 1;
  }
  EXPECT_GT(nonzero, 200);
  EXPECT_GT(several, 50);
}

TEST(GradientTerms, OnlyTheTermsAreReportedAndOneOutsideItsSupportIsZero) {
  // Three balls, the second and the far third the terms: the first still adds to f.
  const Built b(R"({"type":"soft_blend","children":[)" + ball(0, 0, 2, 1) + "," + ball(1, 0, 2, 2) +
                    "," + ball(30, 0, 2, 1) + "]}",
                {{1}, {2}});
  ASSERT_EQ(b.program.terms, 2);
  Workspace ws;
  double terms[2] = {-1, -1};
  Vec3 g;
  const double f = gradient_terms(b.program, {0.5, 0.2, 0}, &g, terms, ws);
  EXPECT_DOUBLE_EQ(terms[0], b.terms[0]->value({0.5, 0.2, 0}));
  EXPECT_GT(terms[0], 0);
  EXPECT_LT(terms[0], f);  // the first ball, not a term, adds the rest
  EXPECT_EQ(terms[1], 0);
}

TEST(GradientTerms, BlobSumReportsTheSameTerms) {
  std::string s = R"({"type":"soft_blend","children":[)";
  std::vector<std::vector<int>> paths;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> c(-4, 4), r(1, 2.5);
  for (int i = 0; i < 36; ++i) {
    s += (i ? "," : "") + ball(c(rng), c(rng), r(rng), i % 7 == 0 ? -0.3 : 1);
    paths.push_back({i});
  }
  const Built b(s + "]}", paths);
  const std::optional<BlobSum> blobs = BlobSum::of(b.program);
  ASSERT_TRUE(blobs.has_value());
  Workspace ws;
  std::vector<double> terms(36), blob_terms(36, -1);
  std::vector<int32_t> ids(size_t(blobs->size()));
  std::uniform_real_distribution<double> x(-6, 6), z(-2, 2);
  int checked = 0;
  for (int k = 0; k < 1000; ++k) {
    const Vec3 p{x(rng), x(rng), z(rng)};
    Vec3 g, gb;
    gradient_terms(b.program, p, &g, terms.data(), ws);
    blobs->gradient(b.program, p, &gb, ids.data(), blob_terms.data());
    for (int i = 0; i < 36; ++i) {
      ASSERT_NEAR(blob_terms[i], terms[i], 1e-13) << "term " << i;
      checked += terms[i] != 0;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(GradientTerms, ANodeThatIsNoSumsChildIsRefused) {
  const Built b(R"({"type":"soft_blend","children":[)" + ball(0, 0, 2, 1) + "]}", {{0}});
  EXPECT_EQ(b.program.terms, 1);
  EXPECT_THROW(compile(*b.root, {b.root.get()}), std::logic_error);
}

}  // namespace
}  // namespace softtrace::test
