// The libraries softtrace-core opens only when a run needs them (cli/embree_on_demand.cpp,
// cli/exr_on_demand.cpp): a PNG of a scene that the direct paths trace loads neither Embree nor
// OpenEXR (nor TBB, which only Embree uses: the frame's threads are the program's own,
// render/threads.h), and a scene of several objects, or an EXR output, loads what it needs. The
// dynamic loader's own trace (LD_DEBUG=files) names every library it opens, the C library always.
#include <gtest/gtest.h>

#include <string>

#include "cli_util.h"

namespace softtrace::test {
namespace {

// The libraries a render opened, as the loader names them, and its exit status.
RunResult render_tracing_libraries(const std::string& scene, const std::string& output) {
  const std::string dir = temp_dir("on_demand");
  return run_command("LD_DEBUG=files " + std::string(SOFTTRACE_BIN) + " render " +
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

}  // namespace
}  // namespace softtrace::test
