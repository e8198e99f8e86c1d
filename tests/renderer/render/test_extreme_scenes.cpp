// Valid scenes at the edges of the documented ranges (issue 35) render safely and as they say:
// huge bounds around a small object, a turntable of 1e308 degrees, an axis whose squares
// underflow, an animation whose eye leaves the tracer's range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_util.h"
#include "io/image_file.h"
#include "same_bits.h"
#include "scene/scene.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

// [000] Fig. 12(b)'s bar and cube (about 60 units across), 48x36, `extra` inserted into the
// object and `animation` (a JSON member or empty) into the scene.
std::string bar_and_cube(const std::string& extra, const std::string& animation = "") {
  return R"({"camera": {"eye": [62, -82, 56], "target": [0, 0, -2], "up": [0, 0, 1], "fov": 24},
    "image": {"width": 48, "height": 36, "spp": 2}, )" +
         animation + R"("objects": [{)" + extra + R"("field": {"type": "soft_blend", "children": [
      {"type": "soft_object", "distance": {"type": "superquadric", "radii": [8, 8, 24], "n1": 1, "n2": 20}},
      {"type": "soft_object", "distance": {"type": "lp_metric", "radii": [30, 30, 12], "n": 20}}]}}]})";
}

// Renders `scene_text` (written to DIR/NAME.json) to DIR/NAME.exr; returns the image path.
std::string render(const std::string& dir, const std::string& name, const std::string& scene_text,
                   const std::string& options = "") {
  std::ofstream(dir + "/" + name + ".json") << scene_text;
  const std::string out = dir + "/" + name + ".exr";
  const RunResult r =
      run_softtrace("render " + dir + "/" + name + ".json --quiet " + options + " -o " + out);
  EXPECT_EQ(r.status, 0) << name << ": " << r.err;
  return out;
}

// Bounds far larger than the field's own region once changed the picture: +-1e9 moved pixels,
// +-1e12 filled the frame, +-1e20 emptied it. The box is clipped to the region.
TEST(ExtremeScenes, HugeBoundsDoNotChangeThePicture) {
  const std::string dir = temp_dir("extreme_bounds");
  const std::string plain = render(dir, "plain", bar_and_cube(""));
  for (const char* v : {"1e9", "1e12", "1e20"}) {
    const std::string bounds = std::string(R"("bounds": [[-)") + v + ",-" + v + ",-" + v + "],[" +
                               v + "," + v + "," + v + "]], ";
    expect_same_bits(plain, render(dir, std::string("bounds_") + v, bar_and_cube(bounds)));
  }
  // A box that cuts the object still cuts it.
  const std::string cut =
      render(dir, "cut", bar_and_cube(R"("bounds": [[-100,-100,-100],[100,100,0]], )"));
  const ImageFile a = read_image(plain), b = read_image(cut);
  EXPECT_NE(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
}

// degrees * frame once overflowed (1e308 * 2) and made the camera NaN, which Embree aborted on.
// The angle is reduced modulo 360 N before the multiplication: the same frame as the reduced
// angle's.
TEST(ExtremeScenes, TurntableOfHugeDegreesRendersEveryFrame) {
  const std::string dir = temp_dir("extreme_turntable");
  const auto turntable = [](const std::string& degrees) {
    return R"("animation": {"frames": 3, "turntable": {"axis": [0, 0, 1], "degrees": )" + degrees +
           "}}, ";
  };
  char reduced[64];
  std::snprintf(reduced, sizeof reduced, "%.17g", std::fmod(1e308, 360.0 * 3));
  for (const char* frame : {"1", "2"})
    expect_same_bits(render(dir, std::string("huge_") + frame, bar_and_cube("", turntable("1e308")),
                            std::string("--frame ") + frame),
                     render(dir, std::string("reduced_") + frame,
                            bar_and_cube("", turntable(reduced)), std::string("--frame ") + frame));
}

// An axis whose squares underflow is still the direction it says, scaled before normalising.
TEST(ExtremeScenes, TinyTurntableAxisIsNormalisedExactly) {
  const auto scene = [](const std::string& axis) {
    return parse_scene(
        bar_and_cube("", R"("animation": {"frames": 4, "turntable": {"axis": )" + axis + "}}, "),
        "axis.json");
  };
  Scene tiny = scene("[3e-162, 4e-162, 0]"), plain = scene("[3, 4, 0]");
  EXPECT_EQ(tiny.animation.axis.x, 0.6);
  EXPECT_EQ(tiny.animation.axis.y, 0.8);
  EXPECT_EQ(tiny.animation.axis.z, 0.0);
  set_frame(tiny, 1);
  set_frame(plain, 1);
  EXPECT_EQ(tiny.camera.eye.x, plain.camera.eye.x);
  EXPECT_EQ(tiny.camera.eye.y, plain.camera.eye.y);
  EXPECT_EQ(tiny.camera.eye.z, plain.camera.eye.z);
}

// Frame 0's eye is in range, frame 2's (half a turn about the target) is not: refused at the
// animation, not traced.
TEST(ExtremeScenes, FrameWhoseEyeLeavesTheRangeIsRefused) {
  const std::string dir = temp_dir("extreme_frame_eye");
  const std::string scene = dir + "/far.json";
  std::ofstream(scene)
      << R"({"camera": {"eye": [0, 0, 9e11], "target": [0, 0, -9e11], "up": [0, 1, 0]},
    "animation": {"frames": 4, "turntable": {"axis": [1, 0, 0]}},
    "objects": [{"field": {"type": "soft_object", "distance": {"type": "lp_metric", "radii": [30, 30, 30], "n": 2}}}]})";
  fs::create_directories(dir + "/out");
  EXPECT_EQ(run_softtrace("render " + scene + " --frame 0 --width 8 --height 6 --quiet -o " + dir +
                          "/out/f0.exr")
                .status,
            0);
  const RunResult r = run_softtrace("render " + scene + " --frame 2 --width 8 --height 6 -o " +
                                    dir + "/out/f2.exr");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("far.json: /animation/turntable: frame 2 puts the eye beyond 1e12 of the "
                       "origin"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out/f2.exr"));
}

}  // namespace
}  // namespace softtrace::test
