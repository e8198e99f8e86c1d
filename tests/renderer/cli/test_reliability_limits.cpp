// Hostile scenes too big to commit, generated here: 10,000-deep nesting, 100,000 children,
// 100,000 nested brackets under an unknown key. Each must give exit status 2, one located line
// and no output, without overflowing the stack; trees just inside the limits must load, render
// and evaluate (deep recursion on the frame's worker threads included).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_util.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

const char* kLeaf =
    R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[1,1,1],"n":2}})";

std::string scene_with(const std::string& field) {
  return R"({"camera":{"eye":[40,-55,32],"target":[0,0,0]},"image":{"width":24,"height":16},)"
         R"("objects":[{"field":)" +
         field + "}]}";
}

// soft_blend(soft_blend(... soft_blend(leaf, leaf) ..., leaf), leaf): `depth` blends deep.
std::string nested_blends(int depth) {
  std::string open, close;  // built flat: wrapping one string 10,000 times is quadratic
  for (int i = 0; i < depth; ++i) {
    open += R"({"type":"soft_blend","children":[)";
    close += "," + std::string(kLeaf) + "]}";
  }
  return open + kLeaf + close;
}

std::string wide_blend(int children) {
  std::string s = R"({"type":"soft_blend","children":[)";
  for (int i = 0; i < children; ++i) s += (i ? "," : "") + std::string(kLeaf);
  return s + "]}";
}

std::string write_scene(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// Exit status 2, exactly one "softtrace: ..." line containing `expect`, nothing written.
void expect_refused(const std::string& scene, const std::string& expect) {
  const std::string out = temp_dir("limits_out");
  const RunResult r = run_softtrace("render " + scene + " -o " + out + "/out.exr --quiet");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err.substr(0, 300);
  EXPECT_EQ(r.err.rfind("softtrace: ", 0), 0u) << r.err.substr(0, 300);
  EXPECT_NE(r.err.find(expect), std::string::npos)
      << "expected: " << expect << "\n  got: " << r.err.substr(0, 300);
  EXPECT_TRUE(fs::is_empty(out));
}

TEST(Limits, TenThousandDeepNestingIsRefusedAtItsPlace) {
  const std::string dir = temp_dir("limits_deep");
  const std::string text = scene_with(nested_blends(10000));
  // The bracket that opens level 1001: the file is one line, so its column is its offset + 1.
  size_t at = 0;
  for (int depth = 0; depth <= 1000; ++at) {
    if (text[at] == '{' || text[at] == '[') ++depth;
    if (text[at] == '}' || text[at] == ']') --depth;
  }
  expect_refused(write_scene(dir, "deep.json", text),
                 "deep.json:1:" + std::to_string(at) + ": nesting deeper than 1000 levels");
}

TEST(Limits, DeepBracketsUnderAnUnknownKeyAreRefused) {
  const std::string dir = temp_dir("limits_brackets");
  const std::string text = "{\n\"junk\": " + std::string(100000, '[') + std::string(100000, ']') +
                           ",\n" + scene_with(kLeaf).substr(1);
  expect_refused(write_scene(dir, "brackets.json", text),
                 // 8 columns of "junk": , the scene's own '{' is level 1
                 "brackets.json:2:1008: nesting deeper than 1000 levels");
}

TEST(Limits, FieldTreesDeeperThan256AreRefused) {
  const std::string dir = temp_dir("limits_field_depth");
  std::string pointer = "/objects/0/field";
  for (int i = 0; i < 256; ++i) pointer += "/children/0";
  expect_refused(write_scene(dir, "d300.json", scene_with(nested_blends(300))),
                 "d300.json: " + pointer + ": field nodes nested deeper than 256 levels");
}

TEST(Limits, AHundredThousandChildrenAreRefused) {
  const std::string dir = temp_dir("limits_wide");
  expect_refused(write_scene(dir, "wide.json", scene_with(wide_blend(100000))),
                 "wide.json: /objects/0/field/children: expected at most 10000 children, got "
                 "100000");
}

// Depths count from 0 at the object's field. 254 blends put the innermost soft_object at depth
// 254 and its distance at 255, the deepest allowed; 255 blends push the distance to 256.
TEST(Limits, TheDeepestAllowedTreeRendersAndEvaluates) {
  const std::string dir = temp_dir("limits_deepest");
  const std::string scene = write_scene(dir, "d254.json", scene_with(nested_blends(254)));
  const RunResult r =
      run_softtrace("render " + scene + " -o " + dir + "/out.exr --threads 2 --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/out.exr"));
  std::ofstream(dir + "/points.txt") << "0 0 0\n0.5 0 0\n";
  const RunResult e = run_softtrace("eval " + scene + " --points " + dir + "/points.txt");
  ASSERT_EQ(e.status, 0) << e.err;
  std::istringstream out(e.out);
  double v = 0, gx, gy, gz;
  out >> v >> gx >> gy >> gz;
  EXPECT_DOUBLE_EQ(v, 255.0) << "255 unit blobs, each 1 at its centre";
  expect_refused(write_scene(dir, "d255.json", scene_with(nested_blends(255))),
                 "field nodes nested deeper than 256 levels");
}

TEST(Limits, TenThousandChildrenLoadAndEvaluate) {
  const std::string dir = temp_dir("limits_10k");
  const std::string scene = write_scene(dir, "w.json", scene_with(wide_blend(10000)));
  std::ofstream(dir + "/points.txt") << "0 0 0\n";
  const RunResult e = run_softtrace("eval " + scene + " --points " + dir + "/points.txt");
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_EQ(e.out.substr(0, e.out.find(' ')), "10000");
}

}  // namespace
}  // namespace softtrace::test
