// `softtrace nodes` against lists made without the kinds table: every type the scenes in scenes/
// use and every kind docs/scene-format.md documents must be listed (nodes, potentials and radius
// transforms, with their parameters), and the fuzzer dictionary must hold every one of them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "cli_util.h"
#include "json_types.h"
#include "scene_files.h"

namespace softtrace::test {
namespace {

std::set<std::string> types_in_scenes() {
  std::set<std::string> types;
  for (const auto& path : scene_files()) {
    const nlohmann::json j = nlohmann::json::parse(read_file(path.string()), nullptr, true, true);
    for (const auto& o : j.at("objects"))
      if (o.contains("field")) collect_types(o.at("field"), types);  // not a shape
  }
  return types;
}

std::set<std::string> kinds_in_doc() {
  std::set<std::string> kinds;
  std::stringstream in(read_file(source_path("docs/scene-format.md")));
  std::string line;
  const std::regex heading("^### `([A-Za-z_0-9]+)`");
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, heading)) kinds.insert(m[1]);
  return kinds;
}

// The kind names `softtrace nodes` lists: the first word of every unindented line.
std::set<std::string> listed(const std::string& out) {
  std::set<std::string> names;
  std::stringstream in(out);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != ' ') names.insert(line.substr(0, line.find(' ')));
  return names;
}

TEST(Nodes, ListsEveryKindTheScenesAndTheDocsUse) {
  const RunResult r = run_softtrace("nodes");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::set<std::string> names = listed(r.out);
  const std::set<std::string> scenes = types_in_scenes(), doc = kinds_in_doc();
  ASSERT_GE(scenes.size(), 20u);
  ASSERT_GE(doc.size(), 40u);
  for (const auto& t : scenes) EXPECT_TRUE(names.count(t)) << "scenes/ use '" << t << "'";
  for (const auto& t : doc) EXPECT_TRUE(names.count(t)) << "the docs describe '" << t << "'";
  for (const auto& t : names) EXPECT_TRUE(doc.count(t)) << "'" << t << "' is not documented";
  // Potentials and radius transforms come with their parameters and defaults.
  for (const char* line : {"\nblanc  (potential)", "\n    s: number, >= 0; 0\n",
                           "\nT_an  (radius transform)", "\n    w_min: number, (0, 0.5); 1e-4\n",
                           "\n    modulation: distance function node; required",
                           "\ncontour  (radius transform)", "\nmurakami  (potential)"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line;
}

TEST(Nodes, DictionaryHoldsEveryKindName) {
  const RunResult r = run_softtrace("nodes --dict");
  ASSERT_EQ(r.status, 0) << r.err;
  std::set<std::string> all = types_in_scenes();
  for (const auto& t : kinds_in_doc()) all.insert(t);
  for (const std::string key : {"radius", "modulation", "children", "w_min", "translate"})
    all.insert(key);
  for (const auto& t : all)
    EXPECT_NE(r.out.find("\"\\\"" + t + "\\\"\"\n"), std::string::npos) << t;
}

}  // namespace
}  // namespace softtrace::test
