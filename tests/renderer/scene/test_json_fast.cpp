// The fast JSON parser against the located one: wherever the fast one answers, the two documents
// are the same value for value and type for type; where the located one refuses, the fast one
// gives up; and every committed scene takes the fast path.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "describe/params.h"
#include "scene/json_fast.h"
#include "scene/json_nesting.h"
#include "scene/json_text.h"

namespace softtrace {
namespace {

using json = nlohmann::json;

// nlohmann's == calls 1, 1u and 1.0 equal; the scene's readers do not all (integers are checked
// as integers), so the type counts here, and a float's bits (-0.0 is not 0).
bool same(const json& a, const json& b) {
  if (a.type() != b.type()) return false;
  switch (a.type()) {
    case json::value_t::object: {
      if (a.size() != b.size()) return false;
      for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j)
        if (i.key() != j.key() || !same(*i, *j)) return false;
      return true;
    }
    case json::value_t::array: {
      if (a.size() != b.size()) return false;
      for (size_t i = 0; i < a.size(); ++i)
        if (!same(a[i], b[i])) return false;
      return true;
    }
    case json::value_t::number_float: {
      const double x = a.get<double>(), y = b.get<double>();
      return std::memcmp(&x, &y, sizeof x) == 0;
    }
    case json::value_t::null:
    case json::value_t::string:
    case json::value_t::boolean:
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::binary:
    case json::value_t::discarded:
      return a == b;
  }
  return false;
}

enum class Outcome { Fast, LeftToLocated, Refused };

// Checks the contract on one text and says which way it went.
Outcome check(const std::string& text) {
  json fast;
  const bool took = parse_json_fast(text, fast);
  json located;
  try {
    located = parse_json_located(text, "t.json");
  } catch (const SceneError& e) {
    EXPECT_FALSE(took) << "the fast parser took what the located one refuses (" << e.what()
                       << "): " << text;
    return Outcome::Refused;
  }
  if (!took) return Outcome::LeftToLocated;
  EXPECT_TRUE(same(fast, located))
      << text << "\n fast:    " << fast.dump() << "\n located: " << located.dump();
  return Outcome::Fast;
}

TEST(JsonFast, EveryCommittedSceneTakesTheFastPathToTheSameDocument) {
  int count = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(SOFTTRACE_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(check(text.str()), Outcome::Fast) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 30);
}

TEST(JsonFast, NumbersAreTypedAndRoundedAsTheLocatedParserDoes) {
  const char* numbers[] = {"0",
                           "-0",
                           "7",
                           "-7",
                           "0.0",
                           "-0.0",
                           "1e2",
                           "1E2",
                           "1e+2",
                           "-1e-2",
                           "0.1",
                           "0.30000000000000004",
                           "2.2250738585072014e-308",
                           "1.7976931348623157e308",
                           "9007199254740993",
                           "18446744073709551615",
                           "-9223372036854775808",
                           "9223372036854775807",
                           "9223372036854775808",
                           "123456789012345678901234567890e-10",
                           "4.9406564584124654e-324",
                           "1e-400",
                           "-1e-400",
                           "2.4703282292062327e-324",
                           "1e308",
                           "0.5e-1",
                           "3.14159265358979323846264338327950288"};
  for (const char* n : numbers) {
    const Outcome o = check(std::string("[") + n + "]");
    EXPECT_NE(o, Outcome::Refused) << n;
  }
  EXPECT_EQ(check("[18446744073709551615]"), Outcome::Fast);
  EXPECT_EQ(check("[-0]"), Outcome::Fast);
  EXPECT_EQ(check("[0.30000000000000004]"), Outcome::Fast);
}

TEST(JsonFast, WhatItTakesAndWhatItLeaves) {
  const char* fast[] = {"{}",
                        "[]",
                        " [ 1 , 2 ] ",
                        "{\"a\":[true,false,null],\"b\":{\"c\":\"d e\"}}",
                        "// a comment\n{\"a\": 1 /* inside */, \"b\" : 2} // end",
                        "/**/[/***/1/* * / */]\r\n",
                        "[\"\x7f\", \"\"]",
                        "{\"\": 0}\n// no line break at the end"};
  for (const char* t : fast) EXPECT_EQ(check(t), Outcome::Fast) << t;
  // Valid, but the located parser's to read: escapes, UTF-8, a byte order mark, a NUL ending a
  // line comment, integers beyond 64 bits, subnormal numbers.
  const std::string left[] = {"[\"a\\nb\"]",
                              "[\"f\\u006fv\"]",
                              "[\"caf\xc3\xa9\"]",
                              "\xef\xbb\xbf[1]",
                              std::string("[1]// a\0\n", 9),
                              "[-9223372036854775809]",
                              "[18446744073709551616]",
                              "[4.9406564584124654e-324]"};
  for (const std::string& t : left) EXPECT_EQ(check(t), Outcome::LeftToLocated) << t;
  // Refused: every one must be left to the located parser for its message.
  const std::string refused[] = {"",
                                 "[1,]",
                                 "{\"a\":1,}",
                                 "{\"a\":1,\"a\":2}",
                                 "[01]",
                                 "[1.]",
                                 "[.5]",
                                 "[+1]",
                                 "[1e]",
                                 "[-]",
                                 "[1e400]",
                                 "[tru]",
                                 "[nul]",
                                 "[\"a\tb\"]",
                                 "[\"abc]",
                                 "[1] [2]",
                                 "[1] /",
                                 "[1] /* open",
                                 "/* a */* b */ [1]",
                                 std::string("[1, /* \0 */ 2]", 14),
                                 std::string("[\0]", 3),
                                 "{\"a\" 1}",
                                 "{1:2}",
                                 "[1 2]",
                                 "\xef\xbb[1]",
                                 std::string(1001, '[') + std::string(1001, ']')};
  for (const std::string& t : refused) EXPECT_EQ(check(t), Outcome::Refused) << t;
  EXPECT_EQ(check(std::string(1000, '[') + std::string(1000, ']')), Outcome::Fast);
}

// Single-byte edits of a scene (fixed seed): the contract holds on each, and the edits reach all
// three outcomes, so the check above is exercised on texts nobody wrote by hand.
TEST(JsonFast, RandomEditsOfASceneKeepTheContract) {
  const std::string base = R"(// a scene
{"camera": {"eye": [10, -2.5e0, 0.125], "target": [0, 0, 0], "fov": 30},
 /* objects */ "objects": [{"name": "ball", "iso": 0.5, "flags": [true, false, null],
   "field": {"type": "soft_object", "radius": 1.0E-1, "n": -3}}]})";
  const char alphabet[] = "{}[],:\"0123456789.eE+-/*\\ \n\ttfn\x80";
  std::mt19937 rng(1);
  int counts[3] = {0, 0, 0};
  for (int trial = 0; trial < 4000; ++trial) {
    std::string t = base;
    for (int edits = 1 + int(rng() % 3); edits > 0; --edits) {
      const size_t at = rng() % t.size();
      const char c = alphabet[rng() % (sizeof alphabet - 1)];
      switch (rng() % 3) {
        case 0:
          t[at] = c;
          break;
        case 1:
          t.insert(t.begin() + at, c);
          break;
        default:
          t.erase(at, 1);
      }
    }
    ++counts[int(check(t))];
  }
  EXPECT_GT(counts[int(Outcome::Fast)], 100);
  EXPECT_GT(counts[int(Outcome::LeftToLocated)], 0);
  EXPECT_GT(counts[int(Outcome::Refused)], 1000);
}

// Decimals at and around the limits of the reading by one product or quotient (2^53 in the
// digits, 10^22 either way), and random ones of up to 19 digits with a point anywhere and an
// exponent or none: the same bits as the located parser's, whichever way each was read.
TEST(JsonFast, DecimalsHaveTheLocatedParsersBits) {
  const char* limits[] = {"9007199254740992.0",
                          "9007199254740993.0",
                          "9007199254740992e22",
                          "9007199254740992e23",
                          "1e22",
                          "1e23",
                          "1e-22",
                          "1e-23",
                          "0.9007199254740993",
                          "0.1e-21",
                          "0.1e-22",
                          "-0.0e5",
                          "0.0000e-30",
                          "12345678901234567.8",
                          "1e00000000000000000000022",
                          "5e-0",
                          "0.7136496464611085",
                          "-14.62543",
                          "1.7976931348623157e308"};
  for (const char* n : limits) EXPECT_EQ(check(std::string("[") + n + "]"), Outcome::Fast) << n;
  std::mt19937_64 rng(7);
  std::string text = "[";
  for (int i = 0; i < 20000; ++i) {
    const int length = 1 + int(rng() % 19);
    std::string digits;
    for (int d = 0; d < length; ++d) digits += char('0' + rng() % 10);
    const size_t zeros = digits.find_first_not_of('0');
    digits.erase(0, std::min(zeros, digits.size() - 1));  // no leading zeros
    std::string n = rng() % 2 ? "-" : "";
    const size_t point = 1 + rng() % digits.size();
    n += digits.substr(0, point) + "." + (point < digits.size() ? digits.substr(point) : "0");
    if (rng() % 2) n += "e" + std::to_string(int(rng() % 61) - 30);
    text += (i ? "," : "") + n;
  }
  text += "]";
  EXPECT_EQ(check(text), Outcome::Fast);
}

// An object's text met again at the same depth is read as a copy of its first value: the texts
// here repeat in turns longer than the parser keeps, at other depths, as prefixes of longer
// objects, with other number types and spacing, and nested in repeated objects.
TEST(JsonFast, RepeatedObjectsAreTheValuesTheirTextsSay) {
  const char* texts[] = {
      R"([{"a":1},{"a":1},{"a":1},{"a":1.0},{"a":1},{"a":-0.0},{"a":0.0},{"a":-0.0},{"a":0}])",
      R"([{"a":1},{"a":1},{"a":1,"b":2},{"a":1,"b":2},{"a":1},{"a":1 },{"a":1}])",
      R"([{"b":2},{"a":{"b":2}},{"b":2},[{"b":2},{"b":2}],{"a":{"b":2}},{"a":{"b":2}},{"b":2}])",
      R"({"x":{"s":"}"},"y":{"s":"}"},"z":{"s":"}","t":1},"w":{"s":"}"}})",
      R"([{"a":/* c */1},{"a":/* c */1},{"a":/* c */1},{"a":/* d */1},{"a":1}])"};
  for (const char* t : texts) EXPECT_EQ(check(t), Outcome::Fast) << t;
  // Six objects in turn, then their repeats: more than a depth's ring holds.
  std::string turns = "[";
  for (int round = 0; round < 4; ++round)
    for (int k = 0; k < 6; ++k)
      turns += "{\"k\":" + std::to_string(k) + ",\"v\":[" + std::to_string(k) + ".5]},";
  turns.back() = ']';
  EXPECT_EQ(check(turns), Outcome::Fast);
  // A cloud of balls: the potential and the distance repeat, the placement does not.
  std::string cloud = R"({"children":[)";
  for (int i = 0; i < 50; ++i)
    cloud += std::string(i ? "," : "") +
             R"({"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":)" +
             R"("lp_metric","radii":[0.7136496464611085,0.7136496464611085,0.7)" +
             (i == 30 ? "2" : "1") + R"(36496464611085],"n":2},"translate":[)" + std::to_string(i) +
             R"(.25,-1,2]})";
  cloud += "]}";
  EXPECT_EQ(check(cloud), Outcome::Fast);
  // A repeated object between distinct ones, more of them than a ring holds (it stays there).
  std::string segments = "[";
  for (int i = 0; i < 20; ++i)
    segments +=
        std::string(i ? "," : "") + R"({"p":{"t":"m"},"d":{"x":)" + std::to_string(i % 7) + R"(}})";
  segments += "]";
  EXPECT_EQ(check(segments), Outcome::Fast);
  // Repeated objects at the deepest level the parsers take, and one past it.
  for (const int depth : {kMaxJsonNesting, kMaxJsonNesting + 1}) {
    const std::string open(depth - 1, '['), close(depth - 1, ']');
    const std::string deep = open + R"({"a":1},{"a":1},{"a":1})" + close;
    EXPECT_EQ(check(deep), depth <= kMaxJsonNesting ? Outcome::Fast : Outcome::Refused) << depth;
  }
}

}  // namespace
}  // namespace softtrace
