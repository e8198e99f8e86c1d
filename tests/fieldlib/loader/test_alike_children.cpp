// A blend's children that differ only in their placement (registry.cpp's build_children): the
// first is built in full and the rest are copies of its node, each placed by its own keys. The
// copies must be the nodes the full build makes, and every error and warning the full build
// gives must still come, from the child that has it.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "describe/building.h"
#include "describe/params.h"
#include "model/node.h"
#include "model/potential.h"

namespace softtrace {
namespace {

using json = nlohmann::json;

NodePtr build_json(const json& j, const BuildContext& ctx = BuildContext()) {
  return build_field(Params(j, "", std::make_shared<const std::string>("<test>")), ctx);
}

std::string build_error(const json& j) {
  try {
    build_json(j);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

json ball(double radius, const char* potential) {
  return {{"type", "soft_object"},
          {"potential", {{"type", potential}}},
          {"distance", {{"type", "lp_metric"}, {"radii", {radius, radius, radius}}, {"n", 2}}}};
}

json blend(const std::vector<json>& children) {
  return {{"type", "soft_blend"}, {"children", children}};
}

// Twelve children: runs of alike ones (translated, rotated, a strength, Blanc's potential with a
// parameter), each run broken by one that differs in a parameter.
std::vector<json> cloud() {
  std::vector<json> c;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(-3, 3);
  for (int i = 0; i < 12; ++i) {
    json child = ball(i == 5 ? 1.25 : 1.5, i < 8 ? "murakami" : "cubic");
    if (i >= 3) child["strength"] = 1.5;
    if (i >= 9) child["potential"] = {{"type", "blanc"}, {"s", 0.25}};
    if (i != 4) child["translate"] = {at(rng), at(rng), at(rng)};
    if (i == 6 || i == 7) child["rotate"] = {{"axis", {0, 0, 1}}, {"deg", 30.0 * i}};
    c.push_back(child);
  }
  return c;
}

TEST(AlikeChildren, TheCopiesAreTheFullBuildsNodes) {
  // The same children, every other one with a key that changes nothing ("strength" 1 where it is
  // absent): no two neighbours are alike there, so each is built in full.
  std::vector<json> alike = cloud(), apart = alike;
  for (size_t i = 0; i < apart.size(); i += 2)
    if (!apart[i].contains("strength")) apart[i]["strength"] = 1.0;
  apart[4]["strength"] = 1.5;  // a strength of its own, still not its neighbours' keys
  apart[4]["translate"] = {0, 0, 0};
  const NodePtr a = build_json(blend(alike)), b = build_json(blend(apart));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> at(-6, 6);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p{at(rng), at(rng), at(rng)};
    Vec3 ga, gb;
    const double va = a->eval(p, &ga), vb = b->eval(p, &gb);
    ASSERT_EQ(va, vb) << k;
    ASSERT_EQ(ga.x, gb.x) << k;
    ASSERT_EQ(ga.y, gb.y) << k;
    ASSERT_EQ(ga.z, gb.z) << k;
    const Box box(p, p + Vec3{0.5, 0.25, 1});
    ASSERT_EQ(a->interval(box).lo, b->interval(box).lo) << k;
    ASSERT_EQ(a->interval(box).hi, b->interval(box).hi) << k;
    ASSERT_EQ(a->lipschitz(box), b->lipschitz(box)) << k;
  }
  EXPECT_EQ(a->lipschitz(), b->lipschitz());
  const Box ra = a->region(0.5, Side::Above), rb = b->region(0.5, Side::Above);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(ra.lo[i], rb.lo[i]);
    EXPECT_EQ(ra.hi[i], rb.hi[i]);
  }
}

// The copies' placement is read from `translate` alone only where that is their one placement
// key: a scale or a rotation they share goes through the full placement, copy by copy.
TEST(AlikeChildren, ASharedScaleOrRotationPlacesEveryCopy) {
  for (const char* key : {"scale", "rotate"}) {
    std::vector<json> alike(6, ball(1.5, "murakami"));
    for (int i = 0; i < 6; ++i) {
      alike[i]["translate"] = {2.5 * i, 0.5 * i, -i};
      if (std::string(key) == "scale")
        alike[i]["scale"] = {2, 1, 0.5};
      else
        alike[i]["rotate"] = {{"axis", {1, 2, 3}}, {"deg", 40}};
    }
    std::vector<json> apart = alike;
    for (size_t i = 0; i < apart.size(); i += 2) apart[i]["strength"] = 1.0;
    const NodePtr a = build_json(blend(alike)), b = build_json(blend(apart));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> at(-4, 16);
    for (int k = 0; k < 2000; ++k) {
      const Vec3 p{at(rng), at(rng) / 2, -at(rng) / 2};
      Vec3 ga, gb;
      ASSERT_EQ(a->eval(p, &ga), b->eval(p, &gb)) << key << " " << k;
      ASSERT_EQ(ga.x, gb.x) << key << " " << k;
      ASSERT_EQ(ga.y, gb.y) << key << " " << k;
      ASSERT_EQ(ga.z, gb.z) << key << " " << k;
    }
    const Box ra = a->region(0.5, Side::Above), rb = b->region(0.5, Side::Above);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(ra.lo[i], rb.lo[i]) << key;
      EXPECT_EQ(ra.hi[i], rb.hi[i]) << key;
    }
  }
}

TEST(AlikeChildren, AChildsPlacementErrorIsItsOwn) {
  std::vector<json> c(4, ball(1, "murakami"));
  for (int i = 0; i < 4; ++i) c[i]["translate"] = {i, 0, 0};
  const auto with = [&](int i, const char* key, const json& value) {
    std::vector<json> children = c;
    children[i][key] = value;
    return build_error(blend(children));
  };
  EXPECT_EQ(with(2, "translate", {1e200, 0, 0}),
            "<test>: /children/2/translate/0: expected a number of magnitude at most 1e150 "
            "(docs/scene-format.md)");
  EXPECT_EQ(with(3, "translate", "x"),
            "<test>: /children/3/translate: expected [x, y, z], got \"x\"");
  EXPECT_EQ(with(1, "translate", {1, true, 0}),
            "<test>: /children/1/translate/1: expected a number, got true");
  std::vector<json> rotated = c;
  for (json& child : rotated) child["rotate"] = {{"axis", {0, 0, 1}}, {"deg", 10}};
  rotated[2]["rotate"] = {{"axis", {0, 0, 0}}, {"deg", 10}};
  EXPECT_EQ(build_error(blend(rotated)),
            "<test>: /children/2/rotate/axis: expected a non-zero axis");
  rotated[2]["rotate"] = {{"axis", {0, 0, 1}}, {"degs", 10}};
  EXPECT_EQ(build_error(blend(rotated)),
            "<test>: /children/2/rotate/degs: unknown key 'degs' (did you mean 'deg'?)");
  std::vector<json> matrix = c;
  matrix[3]["matrix"] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
  EXPECT_EQ(build_error(blend(matrix)),
            "<test>: /children/3/matrix: 'matrix' cannot be combined with 'translate' (fold it "
            "into the matrix; docs/scene-format.md \"Placement\")");
  // Alike is to the bit: nlohmann's == takes 3.0 for 3, which an integer parameter refuses.
  const json prism = json::parse(
      R"({"type":"soft_object","distance":{"type":"polar_prism","radius":1,"lobes":3,
          "amplitude":0.2,"profile":"cosine","half_height":1}})");
  std::vector<json> typed(4, prism);
  for (int i = 0; i < 4; ++i) typed[i]["translate"] = {i, 0, 0};
  typed[2]["distance"]["lobes"] = 3.0;
  EXPECT_EQ(build_error(blend(typed)),
            "<test>: /children/2/distance/lobes: expected an integer in [1, 1000], got 3.0");
}

TEST(AlikeChildren, EachChildWarnsAtItsOwnPlace) {
  // registry's test of the side condition (test_kinds.cpp), three times over, translated.
  const json warned = json::parse(
      R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[4,4,4],"n":2},
          "radii":{"type":"T_an","modulation":{"type":"lp_metric","radii":[8,8,8],"n":2,
                                               "translate":[0.5,0,0]}}})");
  std::vector<json> c(3, warned);
  for (int i = 0; i < 3; ++i) c[i]["translate"] = {10 * i, 0, 0};
  static std::vector<std::string> warnings;
  warnings.clear();
  BuildContext ctx;
  ctx.warn = [](const std::string& line) { warnings.push_back(line); };
  build_json(blend(c), ctx);
  ASSERT_EQ(warnings.size(), 3u);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(warnings[i].rfind("<test>: /children/" + std::to_string(i) +
                                    "/radii/modulation: f_a <= d fails near the skeleton",
                                0),
              0u)
        << warnings[i];
}

// The kinds a cloud of balls is made of copy themselves; the others build each node in full.
TEST(AlikeChildren, SoftObjectsOfAGaugeCopyThemselves) {
  json strong = ball(1.5, "wyvill");
  strong["strength"] = -0.5;
  json blanc = ball(1.5, "blanc");
  blanc["potential"]["s"] = 0.5;
  for (const json& j : {ball(1.5, "murakami"), ball(2, "cubic"), strong, blanc}) {
    const NodePtr node = build_json(j);
    const NodePtr copy = node->clone();
    ASSERT_TRUE(copy) << j.dump();
    for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{0.3, -0.7, 0.2}, Vec3{1.2, 0.1, 0}}) {
      Vec3 g, h;
      EXPECT_EQ(node->eval(p, &g), copy->eval(p, &h));
      EXPECT_EQ(g.x, h.x);
      EXPECT_EQ(g.y, h.y);
      EXPECT_EQ(g.z, h.z);
    }
  }
  const json segment = json::parse(
      R"({"type":"soft_object","distance":{"type":"segment","p0":[0,0,0],"p1":[1,0,0],
          "radius":1}})");
  EXPECT_FALSE(build_json(segment)->clone());
}

}  // namespace
}  // namespace softtrace
