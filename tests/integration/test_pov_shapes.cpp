// Each plain primitive against POV-Ray 3.7's own object of the same name: the silhouettes
// (pixel-centre coverage) of the same scene agree to IoU >= 0.999. POV-Ray is left-handed with y
// up, softtrace right-handed with z up: swapping y and z turns one frame into the other without
// mirroring the picture (tools/pov_scene.py). Each shape's placement goes to POV as a `matrix`.
// Skipped where `povray` is not installed (tools/dev.sh installs it).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/camera.h"
#include "render/frame.h"
#include "scene/scene.h"

namespace softtrace::test {
namespace {

constexpr int kW = 160, kH = 120;

std::string pov(const Vec3& v) {  // softtrace (x, y, z) as POV's <x, z, y>
  char b[128];
  std::snprintf(b, sizeof b, "<%.17g, %.17g, %.17g>", v.x, v.z, v.y);
  return b;
}

std::string number(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// The shape in POV's syntax, in its own space, then placed by S M S (S swaps y and z). POV's
// matrix <a00 .. a32> maps x' = a00 x + a10 y + a20 z + a30: the columns of our rows.
std::string pov_object(const Primitive& s) {
  std::string o;
  switch (s.shape) {
    case Primitive::Shape::Plane:
      o = "plane { " + pov(s.normal) + ", " + number(s.distance);
      break;
    case Primitive::Shape::Box:
      o = "box { " + pov(s.a) + ", " + pov(s.b);
      break;
    case Primitive::Shape::Sphere:
      o = "sphere { " + pov(s.a) + ", " + number(s.r0);
      break;
    case Primitive::Shape::Cylinder:
      o = "cylinder { " + pov(s.a) + ", " + pov(s.b) + ", " + number(s.r0);
      break;
    case Primitive::Shape::Cone:
      o = "cone { " + pov(s.a) + ", " + number(s.r0) + ", " + pov(s.b) + ", " + number(s.r1);
      break;
    case Primitive::Shape::Disc:
      o = "disc { " + pov(s.a) + ", " + pov(s.normal) + ", " + number(s.r0) + ", " + number(s.hole);
      break;
  }
  const int swap[3] = {0, 2, 1};
  double m[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = s.to_world.linear.r[swap[i]][swap[j]];
  const Vec3 t{s.to_world.offset[swap[0]], s.to_world.offset[swap[1]], s.to_world.offset[swap[2]]};
  o += " matrix <";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) o += number(m[i][j]) + ", ";
  o += number(t.x) + ", " + number(t.y) + ", " + number(t.z) + ">";
  return o + " pigment { rgb 1 } }\n";
}

std::string pov_scene(const Scene& scene) {
  const Camera& c = scene.camera;
  const double vfov = c.fov * M_PI / 180;
  const double hfov = 2 * std::atan(std::tan(vfov / 2) * kW / kH) * 180 / M_PI;
  std::string s = "#version 3.7;\nbackground { rgbt <0, 0, 0, 1> }\n";
  s += "camera { perspective location " + pov(c.eye) + " look_at " + pov(c.target) + " sky " +
       pov(c.up) + " right x*" + std::to_string(kW) + "/" + std::to_string(kH) + " up y angle " +
       number(hfov) + " }\n";
  s += "light_source { <0, 1000, 0> rgb 1 }\n";
  for (const SceneObject& o : scene.objects) s += pov_object(*o.shape);
  return s;
}

bool have_povray() {
  return run_command("command -v povray >/dev/null").status == 0;
}

struct Case {
  const char* name;
  const char* shape;
};

const Case kCases[] = {
    {"plane", R"({"type": "plane", "normal": [0.1, 0.2, 1], "distance": -1})"},
    {"box", R"({"type": "box", "corner1": [-3, -2, -1], "corner2": [3, 2, 2.5],
               "rotate": {"axis": [1, 1, 2], "deg": 30}, "translate": [1, 0, 0]})"},
    {"sphere", R"({"type": "sphere", "center": [1, 0, 0], "radius": 3, "scale": [1.5, 1, 0.6]})"},
    {"cylinder", R"({"type": "cylinder", "base": [-2, 0, -2], "cap": [2, 1, 3], "radius": 1.5,
                    "rotate": {"axis": [0, 0, 1], "deg": 50}})"},
    {"cone", R"({"type": "cone", "base": [0, 0, -3], "base_radius": 3, "cap": [0, 0, 3],
                "cap_radius": 0.8, "matrix": [[1, 0.3, 0, 0], [0, 1, 0, 0.5], [0.2, 0, 1, 0]]})"},
    {"disc", R"({"type": "disc", "center": [0, 0, 0], "normal": [0.3, -1, 0.5], "radius": 4,
                "hole_radius": 1.5})"},
};

TEST(PovShapes, SilhouettesMatchPovRay) {
  if (!have_povray()) GTEST_SKIP() << "povray is not installed (tools/dev.sh installs it)";
  const std::string dir = temp_dir("pov_shapes");
  int compared = 0;
  for (const Case& c : kCases) {
    const Scene scene = parse_scene(
        std::string(R"({"camera": {"eye": [14, -20, 11], "target": [0, 0, 0], "fov": 35},
                        "image": {"width": 160, "height": 120}, "objects": [{"shape": )") +
            c.shape + "}]}",
        std::string(c.name) + ".json");
    const std::string pov_path = dir + "/" + c.name + ".pov", png = dir + "/" + c.name + ".png";
    std::ofstream(pov_path) << pov_scene(scene);
    const RunResult r =
        run_command("cd " + dir + " && povray -D +UA +FN -GA +W" + std::to_string(kW) + " +H" +
                    std::to_string(kH) + " +I" + c.name + ".pov +O" + c.name + ".png");
    ASSERT_EQ(r.status, 0) << c.name << ": " << r.err;
    const ImageFile theirs = read_image(png);
    const int alpha = theirs.channel("A");
    ASSERT_GE(alpha, 0);
    ASSERT_EQ(theirs.width, kW);
    const TracedScene rt(scene, LipschitzMode::Local);
    const ViewCamera camera(scene.camera, kW, kH);
    long both = 0, either = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const bool ours = rt.embree
                              .intersect(camera.generate(x + 0.5, y + 0.5), 0,
                                         std::numeric_limits<double>::infinity())
                              .hit;
        const bool pov_hit = theirs.at(x, y, alpha) >= 0.5f;
        both += ours && pov_hit;
        either += ours || pov_hit;
      }
    ASSERT_GT(both, 1000) << c.name << ": the shape should fill part of the frame";
    std::printf("%s: IoU %.6f (%ld pixels differ of %ld covered)\n", c.name, double(both) / either,
                either - both, either);
    EXPECT_GE(double(both) / either, 0.999) << c.name << ": " << either - both << " pixels differ";
    ++compared;
  }
  EXPECT_EQ(compared, 6);
}

}  // namespace
}  // namespace softtrace::test
