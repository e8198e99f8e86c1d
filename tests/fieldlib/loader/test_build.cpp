// The C++ builders (build.h) and batched evaluation (batch.h).
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "describe/building.h"
#include "describe/params.h"
#include "eval/batch.h"
#include "loader/build.h"
#include "model/program_builder.h"

namespace softtrace {
namespace {

Spec two_blobs() {
  return soft_blend({soft_object(lp_metric({30, 30, 12}, 20), wyvill()),
                     translate(soft_object(lp_metric({10, 10, 10}, 2), murakami()), {25, 0, 0})});
}

TEST(Build, SameFieldAsTheSceneFormat) {
  const auto j = nlohmann::json::parse(R"({"type": "soft_blend", "children": [
    {"type": "soft_object", "distance": {"type": "lp_metric", "radii": [30, 30, 12], "n": 20},
     "potential": {"type": "wyvill"}},
    {"type": "soft_object", "distance": {"type": "lp_metric", "radii": [10, 10, 10], "n": 2},
     "potential": {"type": "murakami"}, "translate": [25, 0, 0]}]})");
  EXPECT_EQ(two_blobs().json(), j);
  const NodePtr a = build(two_blobs());
  BuildContext ctx;
  const NodePtr b = build_field(Params(j, "", std::make_shared<const std::string>("t")), ctx);
  for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{20, 1, 2}, Vec3{-5, 3, 11}, Vec3{31, 2, 0}})
    EXPECT_EQ(a->value(p), b->value(p));
}

TEST(Build, ErrorsAreTheLoadersLocatedOnes) {
  try {
    build(soft_blend({soft_object(lp_metric({1, 1, -1}, 2), wyvill()),
                      soft_object(lp_metric({1, 1, 1}, 2), wyvill())}));
    FAIL() << "a negative radius was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("<built field>: /children/0/distance/radii/2: ", 0), 0u)
        << e.what();
  }
  EXPECT_THROW(build(kind("no_such_kind")), SceneError);
  // A distance is not a soft object's field.
  EXPECT_THROW(build(lp_metric({1, 1, 1}, 2)), SceneError);
}

// Params::finish names a key nobody read and suggests the nearest key that was asked for, present
// (read or only tested with `has`) or absent, but never the unread key itself.
TEST(Params, FinishSuggestsTheKeysAskedFor) {
  const auto file = std::make_shared<const std::string>("t.json");
  const auto message = [&](const nlohmann::json& j,
                           const std::function<void(const Params&)>& read) {
    const Params p(j, "/o", file);
    read(p);
    try {
      p.finish();
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const nlohmann::json j = {{"radius", 1}, {"radus", 2}, {"size", 3}};
  // Absent keys asked for: the nearest of them.
  EXPECT_EQ(message(j,
                    [](const Params& p) {
                      p.number("radius");
                      p.number("size");
                      p.has("sizes");
                    }),
            "t.json: /o/radus: unknown key 'radus' (did you mean 'radius'?)");
  // Only tested with `has`: still unread, and not its own suggestion.
  EXPECT_EQ(message(j,
                    [](const Params& p) {
                      p.has("radus");
                      p.number("size");
                    }),
            "t.json: /o/radius: unknown key 'radius' (did you mean 'radus'?)");
  EXPECT_EQ(message(j,
                    [](const Params& p) {
                      p.has("radius");
                      p.has("radius");
                      p.number("radus");
                      p.number("radus");
                    }),
            "t.json: /o/radius: unknown key 'radius' (did you mean 'radus'?)");
  EXPECT_EQ(message({{"a", 1}}, [](const Params& p) { p.number("a"); }), "no error");
  // Equally near keys: the first in sorted order, whatever the order they were asked in.
  EXPECT_EQ(message({{"ab", 1}},
                    [](const Params& p) {
                      p.has("xb");
                      p.has("ax");
                    }),
            "t.json: /o/ab: unknown key 'ab' (did you mean 'ax'?)");
}

// A node's keys match the kinds' names whole: a prefix, an extension or a NUL inside a key is an
// unknown key, located at that key.
TEST(Params, KindKeysMatchWholeNamesOnly) {
  const auto file = std::make_shared<const std::string>("t");
  for (const std::string& key : {std::string("distanc"), std::string("distances"),
                                 std::string("distance\0", 9), std::string("typ")}) {
    nlohmann::json j = nlohmann::json::parse(R"({"type": "soft_object",
      "distance": {"type": "lp_metric", "radii": [1, 1, 1], "n": 2},
      "potential": {"type": "murakami"}})");
    j[key] = 1;
    BuildContext ctx;
    try {
      build_field(Params(j, "", file), ctx);
      ADD_FAILURE() << "key '" << key << "' (" << key.size() << " bytes) was accepted";
    } catch (const SceneError& e) {
      // A NUL is shown escaped, so the whole message survives what()'s C string.
      std::string shown = key;
      if (const size_t nul = shown.find('\0'); nul != std::string::npos)
        shown.replace(nul, 1, "\\u0000");
      EXPECT_EQ(std::string(e.what()).rfind("t: /" + shown + ": unknown key '" + shown + "'", 0),
                0u)
          << e.what();
    }
  }
}

// A message quotes the input; its control characters are written as JSON escapes, so that it
// stays one printable line: a NUL would end what() early, a newline or an escape sequence would
// break the line or drive the terminal.
TEST(Params, ControlCharactersInAMessageAreEscaped) {
  const std::string raw = std::string("key 'a\0b' \x1b[2J\n\t\x7f \xc3\xa9", 20);
  EXPECT_EQ(std::string(SceneError(raw).what()),
            "key 'a\\u0000b' \\u001b[2J\\u000a\\u0009\\u007f \xc3\xa9");
  EXPECT_EQ(printable("plain text, no escapes"), "plain text, no escapes");
}

// Members are found by their whole key in small objects (scanned) and large ones (the map).
TEST(Params, MembersFoundByTheirWholeKey) {
  const auto file = std::make_shared<const std::string>("t");
  for (const int extra : {0, 12}) {
    nlohmann::json j = {{"a", 1}, {std::string("a\0b", 3), 2}, {"ab", 3}};
    for (int i = 0; i < extra; ++i) j["k" + std::to_string(i)] = 10 + i;
    const Params p(j, "", file);
    EXPECT_EQ(p.number("a"), 1);
    EXPECT_EQ(p.number(std::string("a\0b", 3)), 2);
    EXPECT_EQ(p.number("ab"), 3);
    EXPECT_FALSE(p.has(std::string("a\0", 2)));
    EXPECT_FALSE(p.has("b"));
    if (extra) {
      EXPECT_EQ(p.number("k11"), 21);
    }
  }
}

// Which error a file with several gets must not depend on the order the children are built in:
// an element that is no object is named before any child is read.
TEST(Params, ChildrenThatAreNoObjectsFailBeforeAnyChildIsBuilt) {
  const auto file = std::make_shared<const std::string>("t");
  const auto j = nlohmann::json::parse(R"({"type": "soft_blend", "children": [
    {"type": "soft_object", "distance": {"type": "lp_metric", "radii": [1, 1, 1], "n": 2},
     "potential": {"type": "murakami"}, "translte": [1, 0, 0]}, 7]})");
  BuildContext ctx;
  try {
    build_field(Params(j, "/field", file), ctx);
    ADD_FAILURE() << "built";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "t: /field/children/1: expected an object, got 7");
  }
  // Each element's pointer, its key escaped as objects() escapes it.
  const nlohmann::json k = {{"a/b", {nlohmann::json::object(), {{"x", 1}}}}};
  const Params p(k, "/o", file);
  const std::vector<Params> items = p.objects("a/b");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[1].where(""), "t: /o/a~1b/1");
  EXPECT_EQ(items[1].number("x"), 1);
  EXPECT_EQ(items[1].where("x"), "t: /o/a~1b/1/x");
}

TEST(Build, Placement) {
  const Spec moved =
      translate(translate(soft_object(lp_metric({1, 1, 1}, 2), wyvill()), {1, 0, 0}), {0, 2, 0});
  EXPECT_EQ(moved.json()["translate"], nlohmann::json({1, 2, 0}));
  EXPECT_THROW(rotate(moved, {0, 0, 1}, 90), std::invalid_argument);
  const NodePtr turned = build(
      translate(rotate(soft_object(lp_metric({4, 1, 1}, 2), wyvill()), {0, 0, 1}, 90), {0, 0, 5}));
  EXPECT_NEAR(turned->value({0, 3, 5}),
              build(soft_object(lp_metric({4, 1, 1}, 2), wyvill()))->value({3, 0, 0}), 1e-12);
}

TEST(Batch, MatchesEvaluateAtEveryPoint) {
  std::vector<Spec> blobs;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-20, 20);
  for (int i = 0; i < 200; ++i)
    blobs.push_back(
        translate(soft_object(lp_metric({4, 4, 4}, 2), murakami()), {u(rng), u(rng), u(rng)}));
  const NodePtr f = build(soft_blend(blobs));
  const Program p = compile(*f);
  ASSERT_TRUE(p.has_pruning);
  const size_t n = 5000;
  std::vector<double> xyz(3 * n), v(n), vg(n), g(3 * n);
  for (double& c : xyz) c = u(rng) * 1.2;
  Workspace ws;
  eval_points(p, xyz.data(), n, v.data(), nullptr, ws);
  eval_points(p, xyz.data(), n, vg.data(), g.data(), ws);
  int nonzero = 0;
  for (size_t i = 0; i < n; ++i) {
    Vec3 grad;
    const double e = evaluate(p, {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, &grad, ws);
    ASSERT_NEAR(v[i], e, 1e-12) << i;
    ASSERT_NEAR(vg[i], e, 1e-12) << i;
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(g[3 * i + k], grad[k], 1e-12) << i;
    nonzero += e > 0;
  }
  EXPECT_GT(nonzero, 100);  // the points meet the blobs
  xyz[3 * 17 + 1] = std::nan("");
  EXPECT_THROW(eval_points(p, xyz.data(), n, v.data(), nullptr, ws), std::invalid_argument);
}

}  // namespace
}  // namespace softtrace
