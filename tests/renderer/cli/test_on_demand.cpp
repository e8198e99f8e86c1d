// The libraries softtrace-core opens only when a run needs them (cli/embree_on_demand.cpp,
// cli/exr_on_demand.cpp): a PNG of a scene that the direct paths trace loads neither Embree nor
// OpenEXR (nor TBB, which only Embree uses: the frame's threads are the program's own,
// render/threads.h), and a scene of several objects, or an EXR output, loads what it needs. The
// dynamic loader's own trace (LD_DEBUG=files) names every library it opens, the C library always.
// Nor does the loader relocate the program itself: softtrace-core is linked at a fixed address.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "cli_util.h"

namespace softtrace::test {
namespace {

// The libraries a render by softtrace-core opened, as the loader names them, and its exit status
// (the static softtrace has no loader, and hands EXR and Embree to softtrace-core).
RunResult render_tracing_libraries(const std::string& scene, const std::string& output) {
  const std::string dir = temp_dir("on_demand");
  return run_command("LD_DEBUG=files " + std::string(SOFTTRACE_CORE_BIN) + " render " +
                     source_path(scene) + " --width 16 --height 12 -q -o " + dir + "/" + output);
}

bool opened(const RunResult& r, const std::string& library) {
  return r.err.find("file=" + library) != std::string::npos;
}

TEST(OnDemand, APngOfOneFieldLoadsNeitherEmbreeNorOpenExrNorTbb) {
  const RunResult r = render_tracing_libraries("scenes/fig000_12b_soft_blend.json", "one.png");
  ASSERT_EQ(r.status, 0) << r.err.substr(0, 2000);
  EXPECT_TRUE(opened(r, "libc.so")) << "the loader's trace is not there to read";
  EXPECT_FALSE(opened(r, "libtbb"));
  EXPECT_FALSE(opened(r, "libembree3"));
  EXPECT_FALSE(opened(r, "libOpenEXR"));
}

TEST(OnDemand, SeveralObjectsLoadEmbreeAndAnExrLoadsOpenExr) {
  const RunResult r =
      render_tracing_libraries("scenes/fig000_1b_superquadrics.json", "several.exr");
  ASSERT_EQ(r.status, 0) << r.err.substr(0, 2000);
  EXPECT_TRUE(opened(r, "libembree3"));
  EXPECT_TRUE(opened(r, "libOpenEXR"));
}

// A position-independent program is relocated at each start (4,500 pointers, the pages that hold
// them copied): 0.5-0.7 ms more CPU a process (renderer/CMakeLists.txt). Sanitizer builds keep it.
TEST(OnDemand, TheProgramIsLoadedWhereItWasLinked) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "a sanitizer build";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  GTEST_SKIP() << "a sanitizer build";
#endif
#endif
  std::ifstream elf(SOFTTRACE_CORE_BIN, std::ios::binary);
  unsigned char header[18] = {};
  ASSERT_TRUE(elf.read(reinterpret_cast<char*>(header), sizeof header)) << SOFTTRACE_CORE_BIN;
  ASSERT_EQ(std::string(reinterpret_cast<char*>(header) + 1, 3), "ELF");
  constexpr std::uint16_t kExecutable = 2;  // ELF's ET_EXEC; a PIE is ET_DYN (3)
  const std::uint16_t type = std::uint16_t(header[16] | header[17] << 8);  // e_type, little-endian
  EXPECT_EQ(type, kExecutable);
}

}  // namespace
}  // namespace softtrace::test
