// The one list of kinds (fieldlib/kinds.h) against what depends on it: the sweep has a case for
// every kind, docs/scene-format.md documents every kind with exactly the table's parameters (and
// an example that builds), and the loader's checks generated from the table (misspelled keys,
// typed slots) say what they should.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "json_types.h"
#include "sweep.h"

namespace softtrace::test {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Kinds, TableIsWellFormed) {
  std::set<std::string> names;
  for (const auto& k : kinds()) {
    EXPECT_TRUE(names.insert(k.name).second) << "duplicate kind " << k.name;
    EXPECT_EQ(k.create_node != nullptr, k.group == KindGroup::Node) << k.name;
    EXPECT_EQ(k.create_potential != nullptr, k.group == KindGroup::Potential) << k.name;
    EXPECT_EQ(k.create_radius != nullptr, k.group == KindGroup::RadiusTransform) << k.name;
    const std::string summary = k.summary;
    EXPECT_TRUE(summary.find("Eq") != std::string::npos || summary.find("§") != std::string::npos ||
                summary.find("sharp") != std::string::npos)
        << k.name << ": the summary names no paper or equation";
    std::set<std::string> params;
    for (const auto& p : k.params) {
      EXPECT_TRUE(params.insert(p.name).second) << k.name << "." << p.name;
      if (p.type == ParamType::Node || p.type == ParamType::Nodes) {
        EXPECT_NE(p.slot, Family::Any) << k.name << "." << p.name << " takes no family";
      }
    }
  }
}

// find_kind answers from an index of the table: each kind under its own name and group, nothing
// under another group, a near name or a name with more bytes after a NUL.
TEST(Kinds, FindKindIsTheTablesOwnEntryInItsGroupOnly) {
  const KindGroup groups[] = {KindGroup::Node, KindGroup::Potential, KindGroup::RadiusTransform};
  for (const auto& k : kinds())
    for (const KindGroup g : groups)
      EXPECT_EQ(find_kind(k.name, g), g == k.group ? &k : nullptr) << k.name << " " << int(g);
  EXPECT_EQ(find_kind("soft_objec", KindGroup::Node), nullptr);
  EXPECT_EQ(find_kind("", KindGroup::Node), nullptr);
  EXPECT_EQ(find_kind(std::string("murakami\0x", 10), KindGroup::Potential), nullptr);
  ASSERT_NE(find_kind("murakami", KindGroup::Potential), nullptr);
}

// libfive's habit: a kind without a sweep case is a kind whose bounds nobody checks.
TEST(Kinds, SweepHasACaseForEveryKind) {
  std::set<std::string> roots, anywhere;
  for (const ListedCase& listed : sweep_cases()) {
    const nlohmann::json j = nlohmann::json::parse(listed.c->json, nullptr, true, true);
    roots.insert(j.at("type").get<std::string>());
    collect_types(j, anywhere);
  }
  ASSERT_GT(sweep_cases().size(), 50u) << "the sweep files did not register their cases";
  for (const auto& k : kinds()) {
    if (k.group == KindGroup::Node)
      EXPECT_TRUE(roots.count(k.name)) << "no sweep case has a '" << k.name << "' at its root";
    else
      EXPECT_TRUE(anywhere.count(k.name)) << "no sweep case uses '" << k.name << "'";
  }
}

struct DocSection {
  std::vector<std::string> rows;  // "| `name` | type | range | default | notes |", trimmed
  std::string example;
};

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// "| a |  | c |" -> "|a||c|": cell text without the padding.
std::string normalise_row(const std::string& row) {
  std::string out;
  std::stringstream s(row);
  std::string cell;
  bool first = true;
  while (std::getline(s, cell, '|')) {
    if (first) {
      first = false;
      continue;
    }
    out += "|" + trim(cell);
  }
  return out;
}

// The "### `name`" sections of docs/scene-format.md: their parameter rows and ```json example.
std::map<std::string, DocSection> parse_doc(const std::string& text) {
  std::map<std::string, DocSection> doc;
  std::stringstream in(text);
  std::string line;
  DocSection* current = nullptr;
  bool in_example = false;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) {
      current = nullptr;
      if (line.rfind("### `", 0) == 0) {
        const std::string name = line.substr(5, line.find('`', 5) - 5);
        EXPECT_FALSE(doc.count(name)) << "documented twice: " << name;
        current = &doc[name];
      }
      continue;
    }
    if (!current) continue;
    if (in_example) {
      if (line.rfind("```", 0) == 0)
        in_example = false;
      else
        current->example += line + "\n";
    } else if (line.rfind("```json", 0) == 0) {
      in_example = true;
    } else if (line.rfind("| `", 0) == 0) {
      current->rows.push_back(normalise_row(line));
    }
  }
  return doc;
}

Convention convention_for(const KindInfo& k) {
  if (k.group != KindGroup::Node) return Convention::Soft;
  switch (k.family) {
    case Family::ZeroSurface:
      return Convention::Zero;
    case Family::Distance:
      return Convention::Constructive;
    default:
      return Convention::Soft;
  }
}

TEST(Kinds, SceneFormatDocDescribesEveryKindWithTheTablesParameters) {
  const std::string path = std::string(SOFTTRACE_SOURCE_DIR) + "/docs/scene-format.md";
  const std::map<std::string, DocSection> doc = parse_doc(read_text(path));
  ASSERT_FALSE(doc.empty()) << "cannot read " << path;
  for (const auto& k : kinds()) {
    const auto it = doc.find(k.name);
    if (it == doc.end()) {
      ADD_FAILURE() << path << " has no section \"### `" << k.name << "`\"";
      continue;
    }
    std::vector<std::string> expected;
    std::string expected_text;
    for (const auto& p : k.params) {
      const std::string row = "| `" + std::string(p.name) + "` | " + type_text(p) + " | " +
                              range_text(p) + " | " + default_text(p) + " | " + p.note + " |";
      expected.push_back(normalise_row(row));
      expected_text += row + "\n";
    }
    EXPECT_EQ(it->second.rows, expected)
        << path << ": '" << k.name << "' is documented with other parameters; the table says:\n"
        << expected_text;
    // The example must be a scene field that builds and uses the kind.
    ASSERT_FALSE(it->second.example.empty()) << k.name << " has no ```json example";
    const nlohmann::json j = nlohmann::json::parse(it->second.example, nullptr, true, true);
    std::set<std::string> types;
    collect_types(j, types);
    EXPECT_TRUE(types.count(k.name)) << k.name << "'s example does not use it";
    try {
      build_from_json(it->second.example, convention_for(k));
    } catch (const SceneError& e) {
      ADD_FAILURE() << k.name << "'s example does not build: " << e.what();
    }
  }
  for (const auto& [name, section] : doc)
    EXPECT_TRUE(find_kind(name, KindGroup::Node) || find_kind(name, KindGroup::Potential) ||
                find_kind(name, KindGroup::RadiusTransform))
        << path << " documents '" << name << "', which is no kind";
}

TEST(Kinds, MisspelledKeysNameTheNearestKeyBeforeMissingOnes) {
  EXPECT_EQ(build_error(R"({"type":"segment","p0":[0,0,0],"p1":[1,0,0],"raduis":2})"),
            "<test>: /raduis: unknown key 'raduis' (did you mean 'radius'?)");
  EXPECT_EQ(build_error(R"({"type":"lp_metric","radii":[1,1,1],"N":2})"),
            "<test>: /N: unknown key 'N' (did you mean 'n'?)");
  EXPECT_EQ(build_error(R"({"type":"lp_metric","radii":[1,1,1],"n":2,"tranlsate":[1,0,0]})"),
            "<test>: /tranlsate: unknown key 'tranlsate' (did you mean 'translate'?)");
  EXPECT_EQ(build_error(R"({"type":"lp_metric","radii":[1,1,1],"n":2,"colour":1})"),
            "<test>: /colour: unknown key 'colour'");
  EXPECT_EQ(build_error(R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[1,1,1],
                            "n":2},"radii":{"type":"T_n","w1":1,"w_2":1}})"),
            "<test>: /radii/w_2: unknown key 'w_2' (did you mean 'w2'?)");
  EXPECT_EQ(build_error(R"({"type":"soft_object","potential":{"type":"blanc","ss":1},
                            "distance":{"type":"lp_metric","radii":[1,1,1],"n":2}})"),
            "<test>: /potential/ss: unknown key 'ss' (did you mean 's'?)");
}

TEST(Kinds, SlotsSayWhatTheyExpectAndWhatTheyGot) {
  const std::string ball = R"({"type":"lp_metric","radii":[1,1,1],"n":2})";
  const std::string soft = R"({"type":"soft_object","distance":)" + ball + "}";
  EXPECT_EQ(build_error(R"({"type":"soft_blend","children":[)" + soft + "," + ball + "]}"),
            "<test>: /children/1: expected a soft field, got 'lp_metric' (a distance function)");
  EXPECT_EQ(build_error(R"({"type":"super_ellipsoidal_union","n":2,"children":[)" + ball + "," +
                        soft + "]}"),
            "<test>: /children/1: expected a distance function, got 'soft_object' (a soft field)");
  EXPECT_EQ(
      build_error(R"({"type":"max","children":[)" + soft + "," + ball + "]}", Convention::Zero),
      "<test>: /children/0: expected a zero-surface function, got 'soft_object' (a soft "
      "field)");
  // A distance function is a constructive field.
  EXPECT_EQ(build_error(R"({"type":"min","children":[)" + ball + "," + ball + "]}",
                        Convention::Constructive),
            "");
}

TEST(Kinds, NearSkeletonFailuresOfTheSideConditionWarn) {
  // f_a = |X - (0.5,0,0)|/8 exceeds d = |X|/4 only where |X| < 0.5, i.e. d < 0.125.
  const nlohmann::json j = nlohmann::json::parse(
      R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[4,4,4],"n":2},
          "radii":{"type":"T_an","modulation":{"type":"lp_metric","radii":[8,8,8],"n":2,
                                               "translate":[0.5,0,0]}}})");
  static std::vector<std::string> warnings;
  warnings.clear();
  BuildContext ctx;
  ctx.warn = [](const std::string& line) { warnings.push_back(line); };
  build_field(Params(j, "", std::make_shared<const std::string>("<test>")), ctx);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("<test>: /radii/modulation: f_a <= d fails near the skeleton"),
            std::string::npos)
      << warnings[0];
}

}  // namespace
}  // namespace softtrace::test
