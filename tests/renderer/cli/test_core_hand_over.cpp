// The static softtrace renders a PNG of a scene the direct paths trace in its own process, and
// hands EXR and Embree to softtrace-core beside it (cli/core_hand_over.h): without softtrace-core
// in its folder the first still works, and the others fail in one line naming the missing
// program; with it they give what softtrace-core gives, and what the load printed before the
// hand-over is printed once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_util.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

// A field whose radius modulation fails its side condition near the skeleton: the load warns
// (fieldlib/model/modulation_check.cpp). With `second`, a ball beside it: two objects, which
// Embree traces.
std::string write_warning_scene(const std::string& dir, bool second) {
  const std::string path = dir + (second ? "/warns_two.json" : "/warns_one.json");
  std::ofstream(path)
      << R"({"camera":{"eye":[0,-20,5],"target":[0,0,0]},"objects":[{"field":)"
      << R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[4,4,4],"n":2},)"
      << R"("radii":{"type":"T_an","modulation":{"type":"lp_metric","radii":[8,8,8],"n":2,)"
      << R"("translate":[0.5,0,0]}}}})"
      << (second ? R"(,{"field":{"type":"soft_object","distance":{"type":"lp_metric",)"
                   R"("radii":[1,1,1],"n":2,"translate":[6,0,0]}}})"
                 : "")
      << "]}";
  return path;
}

// A folder holding a copy of softtrace alone.
std::string softtrace_alone(const std::string& name) {
  const std::string dir = temp_dir(name);
  fs::copy_file(SOFTTRACE_BIN, dir + "/softtrace");
  return dir;
}

// The program is static (not the launcher of a sanitizer build): only then does it render on its
// own. A dynamic program names its loader in a program header of type PT_INTERP.
bool static_program() {
  std::ifstream elf(SOFTTRACE_BIN, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(elf)), std::istreambuf_iterator<char>());
  if (bytes.size() < 64) return false;
  std::uint64_t offset = 0;
  std::uint16_t size = 0, count = 0;
  std::memcpy(&offset, bytes.data() + 32, sizeof offset);  // ELF64's e_phoff, e_phentsize, e_phnum
  std::memcpy(&size, bytes.data() + 54, sizeof size);
  std::memcpy(&count, bytes.data() + 56, sizeof count);
  constexpr std::uint32_t kInterpreter = 3;  // PT_INTERP
  for (std::uint16_t i = 0; i < count && offset + (i + 1) * size <= bytes.size(); ++i) {
    std::uint32_t type = 0;
    std::memcpy(&type, bytes.data() + offset + i * size, sizeof type);
    if (type == kInterpreter) return false;
  }
  return true;
}

TEST(CoreHandOver, APngOfOneFieldRendersWithoutSofttraceCore) {
  if (!static_program()) GTEST_SKIP() << "softtrace is the launcher in this build";
  const std::string dir = softtrace_alone("hand_over_png");
  const std::string args = " render " + source_path(kDefaultScene) + " --width 40 --height 30 -q";
  const RunResult alone = run_command(dir + "/softtrace" + args + " -o " + dir + "/alone.png");
  ASSERT_EQ(alone.status, 0) << alone.err;
  EXPECT_EQ(alone.err, "");
  const RunResult core =
      run_command(std::string(SOFTTRACE_CORE_BIN) + args + " -o " + dir + "/core.png");
  ASSERT_EQ(core.status, 0) << core.err;
  EXPECT_EQ(read_file(dir + "/alone.png"), read_file(dir + "/core.png"));
}

TEST(CoreHandOver, AnExrWithoutSofttraceCoreFailsInOneLine) {
  if (!static_program()) GTEST_SKIP() << "softtrace is the launcher in this build";
  const std::string dir = softtrace_alone("hand_over_exr");
  const RunResult r = run_command(dir + "/softtrace render " + source_path(kDefaultScene) +
                                  " --width 40 --height 30 -q -o " + dir + "/image.exr");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "softtrace: EXR and Embree need " + dir +
                       "/softtrace-core: cannot run it: No such file or directory\n");
  EXPECT_FALSE(fs::exists(dir + "/image.exr"));
}

// The load's warning was held, and is printed with the line that ends the run.
TEST(CoreHandOver, AnEmbreeSceneWithoutSofttraceCorePrintsTheLoadsWarningAndOneLine) {
  if (!static_program()) GTEST_SKIP() << "softtrace is the launcher in this build";
  const std::string dir = softtrace_alone("hand_over_embree");
  const std::string scene = write_warning_scene(dir, true);
  const RunResult r = run_command(dir + "/softtrace render " + scene +
                                  " --width 40 --height 30 -q -o " + dir + "/image.png");
  EXPECT_EQ(r.status, 2);
  const std::string warning = "softtrace: warning: " + scene + ": /objects/0/field/radii/";
  EXPECT_EQ(r.err.rfind(warning, 0), 0u) << r.err;
  const std::string last = "softtrace: EXR and Embree need " + dir +
                           "/softtrace-core: cannot run it: No such file or directory\n";
  ASSERT_GE(r.err.size(), last.size()) << r.err;
  EXPECT_EQ(r.err.substr(r.err.size() - last.size()), last) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/image.png"));
}

// A scene whose tracers would ask for Embree, or one field beside a ball that is not: written to
// `name`, with a transparent material on the field where `transparent` (its rays may then start
// inside it, which only Embree takes).
std::string write_field_scene(const std::string& dir, const std::string& name, bool two_fields,
                              bool transparent) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << R"({"camera":{"eye":[0,-20,5],"target":[0,0,0]},"objects":[)"
                      << R"({"field":{"type":"soft_object","distance":{"type":"lp_metric",)"
                      << R"("radii":[4,4,4],"n":2}})"
                      << (transparent ? R"(,"material":{"transmit":0.5})" : "") << "},"
                      << (two_fields ? R"({"field":{"type":"soft_object","distance":)"
                                       R"({"type":"lp_metric","radii":[1,1,1],"n":2,)"
                                       R"("translate":[6,0,0]}}})"
                                     : R"({"shape":{"type":"sphere","radius":1,)"
                                       R"("center":[6,0,0]}})")
                      << "]}";
  return path;
}

// The static program hands a scene its tracers would send to Embree to softtrace-core right after
// the load (trace/direct_paths.h), before the output's checks and the tracers: without
// softtrace-core, an output in a missing folder gives the hand-over's line, where a scene the
// direct paths trace gives the output's. (Handed over at rtcNewDevice, after the tracers, the
// first would have named the folder too.)
TEST(CoreHandOver, AnEmbreeSceneIsHandedOverBeforeTheOutputsChecks) {
  if (!static_program()) GTEST_SKIP() << "softtrace is the launcher in this build";
  const std::string dir = softtrace_alone("hand_over_early");
  const std::string core_missing = "softtrace: EXR and Embree need " + dir +
                                   "/softtrace-core: cannot run it: No such file or directory\n";
  const std::string output = dir + "/missing/image.png";
  const std::string folder_missing =
      "softtrace: " + output + ": the folder '" + dir + "/missing' does not exist\n";
  const auto run = [&](const std::string& scene) {
    return run_command(dir + "/softtrace render " + scene + " --width 40 --height 30 -q -o " +
                       output);
  };
  const RunResult two_fields = run(write_field_scene(dir, "two_fields.json", true, false));
  EXPECT_EQ(two_fields.status, 2);
  EXPECT_EQ(two_fields.err, core_missing);
  const RunResult transparent = run(write_field_scene(dir, "transparent.json", false, true));
  EXPECT_EQ(transparent.status, 2);
  EXPECT_EQ(transparent.err, core_missing);
  const RunResult direct = run(write_field_scene(dir, "direct.json", false, false));
  EXPECT_EQ(direct.status, 2);
  EXPECT_EQ(direct.err, folder_missing);
}

// Through softtrace-core, the same image and the same standard error as softtrace-core's own:
// the warning the static program's load printed before it handed over is not repeated.
TEST(CoreHandOver, AnEmbreeSceneRendersThroughSofttraceCoreWithItsBytesAndOneWarning) {
  const std::string dir = temp_dir("hand_over_embree_core");
  const std::string scene = write_warning_scene(dir, true);
  const std::string args = " render " + scene + " --width 40 --height 30 -q -o ";
  const RunResult r = run_softtrace(args + dir + "/softtrace.png");
  const RunResult core = run_command(std::string(SOFTTRACE_CORE_BIN) + args + dir + "/core.png");
  ASSERT_EQ(core.status, 0) << core.err;
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(std::count(core.err.begin(), core.err.end(), '\n'), 1) << core.err;
  EXPECT_EQ(r.err, core.err);
  EXPECT_EQ(read_file(dir + "/softtrace.png"), read_file(dir + "/core.png"));
}

// An EXR output (with AOVs) is written by softtrace-core, to its pixels.
TEST(CoreHandOver, AnExrRendersThroughSofttraceCoreWithItsPixels) {
  const std::string dir = temp_dir("hand_over_exr_core");
  const std::string args =
      " render " + source_path(kDefaultScene) + " --width 40 --height 30 --aov depth,normal -q -o ";
  const RunResult r = run_softtrace(args + dir + "/softtrace.exr");
  const RunResult core = run_command(std::string(SOFTTRACE_CORE_BIN) + args + dir + "/core.exr");
  ASSERT_EQ(core.status, 0) << core.err;
  ASSERT_EQ(r.status, 0) << r.err;
  const RunResult same =
      run_softtrace("diff " + dir + "/softtrace.exr " + dir + "/core.exr --fail 0 -q");
  EXPECT_EQ(same.status, 0) << same.out << same.err;
}

}  // namespace
}  // namespace softtrace::test
