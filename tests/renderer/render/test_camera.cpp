// Cameras (render/camera.h, scene/scene_camera.cpp): orthographic rays, the thin lens, the camera
// a scene without one gets, and the command line's --eye/--target/--fov.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/camera.h"
#include "render/frame_metadata.h"
#include "scene/scene.h"

namespace softtrace::test {
namespace {

Camera view(Camera::Projection projection) {
  Camera c;
  c.projection = projection;
  c.eye = {10, -20, 5};
  c.target = {1, 2, 3};
  c.fov = 40;
  return c;
}

TEST(Camera, OrthographicRaysAreParallelAndLeaveTheViewPlane) {
  const Camera c = view(Camera::Projection::Orthographic);
  const ViewCamera camera(c, 64, 48);
  const Vec3 forward = normalize(c.target - c.eye);
  const double half = length(c.target - c.eye) * std::tan(20 * M_PI / 180);
  const Ray centre = camera.generate(32, 24);
  EXPECT_LT(length(centre.o - c.eye), 1e-12);
  int checked = 0;
  for (const auto& [px, py] : std::vector<std::pair<double, double>>{{0, 0}, {64, 48}, {5, 40}}) {
    const Ray r = camera.generate(px, py);
    EXPECT_LT(length(r.d - forward), 1e-15);
    EXPECT_LT(std::abs(dot(r.o - c.eye, forward)), 1e-12);  // on the plane through the eye
    ++checked;
  }
  EXPECT_EQ(checked, 3);
  // The top-left corner is half the view's height up and half its width to the left.
  const Vec3 offset = camera.generate(0, 0).o - c.eye;
  EXPECT_NEAR(length(offset), half * std::sqrt(1 + (64.0 / 48) * (64.0 / 48)), 1e-9);
  EXPECT_FALSE(camera.single_eye());
  EXPECT_GT(centre.cone0, 0);
  EXPECT_EQ(centre.cone, 0);
}

// FrameTracer traces a pinhole camera's pixel-centre rays from per-column and per-row tables of
// ViewCamera::column and row, and of their column_part and row_part: pinhole() of either must be
// generate()'s ray to the bit, at every pixel of frames of even and odd sizes.
TEST(Camera, PinholeFromColumnAndRowIsGeneratesRayToTheBit) {
  const auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  const auto same_ray = [&](const Ray& a, const Ray& b) {
    return same(a.o.x, b.o.x) && same(a.o.y, b.o.y) && same(a.o.z, b.o.z) && same(a.d.x, b.d.x) &&
           same(a.d.y, b.d.y) && same(a.d.z, b.d.z) && same(a.cone0, b.cone0) &&
           same(a.cone, b.cone);
  };
  int checked = 0;
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{320, 240}, {641, 479}, {80, 60}}) {
    const ViewCamera camera(view(Camera::Projection::Perspective), w, h);
    ASSERT_TRUE(camera.single_eye());
    int differ = 0, parts_differ = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double column = camera.column(x + 0.5), row = camera.row(y + 0.5);
        const Ray b = camera.generate(x + 0.5, y + 0.5);
        differ += !same_ray(camera.pinhole(column, row), b);
        parts_differ +=
            !same_ray(camera.pinhole(camera.column_part(column), camera.row_part(row)), b);
        ++checked;
      }
    EXPECT_EQ(differ, 0) << w << "x" << h;
    EXPECT_EQ(parts_differ, 0) << w << "x" << h;
  }
  EXPECT_EQ(checked, 320 * 240 + 641 * 479 + 80 * 60);
}

// `aspect` (POV-Ray's right/up ratio) sets the view's width whatever the image's: a 320x240
// image of aspect 1.33 spans tan(fov/2) * 1.33 to each side, not * 4/3, and the rows are as
// without it. Its pixels are narrower than high, so the cone is half a pixel's width.
TEST(Camera, AspectStretchesTheViewAcross) {
  for (const auto projection :
       {Camera::Projection::Perspective, Camera::Projection::Orthographic}) {
    Camera c = view(projection);
    const ViewCamera square(c, 320, 240);
    c.aspect = 1.33;
    const ViewCamera stretched(c, 320, 240);
    const Vec3 forward = normalize(c.target - c.eye);
    const Vec3 right = normalize(cross(forward, c.up)), up = cross(right, forward);
    const double t = std::tan(20 * M_PI / 180);
    const double half = projection == Camera::Projection::Orthographic
                            ? t * length(c.target - c.eye)
                            : t;  // the half height on the plane at distance 1
    const auto across = [&](const Ray& r) {
      return projection == Camera::Projection::Orthographic ? dot(r.o - c.eye, right)
                                                            : dot(r.d, right) / dot(r.d, forward);
    };
    const auto along_up = [&](const Ray& r) {
      return projection == Camera::Projection::Orthographic ? dot(r.o - c.eye, up)
                                                            : dot(r.d, up) / dot(r.d, forward);
    };
    EXPECT_NEAR(across(stretched.generate(320, 100)), half * 1.33, 1e-12);
    EXPECT_NEAR(across(square.generate(320, 100)), half * 4 / 3, 1e-12);
    EXPECT_NEAR(along_up(stretched.generate(17, 0)), half, 1e-12);
    EXPECT_NEAR(along_up(stretched.generate(17, 0)), along_up(square.generate(17, 0)), 1e-12);
    const Ray centre = stretched.generate(160, 120), plain = square.generate(160, 120);
    EXPECT_NEAR(centre.cone0 + centre.cone, (plain.cone0 + plain.cone) * 1.33 / (4.0 / 3), 1e-15);
  }
  Camera c = view(Camera::Projection::Perspective);
  c.aspect = 1.33;
  const ViewCamera stretched(c, 320, 240);
  double px = 0, py = 0;
  ASSERT_TRUE(stretched.pixel_of(stretched.generate(31.5, 200.25).d * 7 + c.eye, px, py));
  EXPECT_NEAR(px, 31.5, 1e-9);
  EXPECT_NEAR(py, 200.25, 1e-9);
  // The EXR's world_to_ndc (row vectors) puts that point at the same place in the frame.
  Scene scene;
  scene.camera = c;
  const auto m = frame_info(scene, 320, 240, false).world_to_ndc;
  const Vec3 p = stretched.generate(31.5, 200.25).d * 7 + c.eye;
  double ndc[4];
  for (int j = 0; j < 4; ++j) ndc[j] = p.x * m[j] + p.y * m[4 + j] + p.z * m[8 + j] + m[12 + j];
  EXPECT_NEAR(ndc[0] / ndc[3], 31.5 / 320, 1e-6);
  EXPECT_NEAR(ndc[1] / ndc[3], 200.25 / 240, 1e-6);
}

TEST(Camera, ThinLensRaysMeetInTheFocalPlane) {
  for (const auto projection :
       {Camera::Projection::Perspective, Camera::Projection::Orthographic}) {
    Camera c = view(projection);
    c.aperture = 3;
    c.focal_distance = 17;
    Camera pinhole = c;
    pinhole.aperture = 0;
    const ViewCamera lens(c, 64, 48), hole(pinhole, 64, 48);
    EXPECT_FALSE(lens.single_eye());
    const Vec3 forward = normalize(c.target - c.eye);
    int checked = 0;
    for (int s = 0; s < 16; ++s) {
      double lx, ly;
      lens_sample(7, 9, s, 16, lx, ly);
      ASSERT_LE(lx * lx + ly * ly, 1 + 1e-12);
      const Ray p = hole.generate(7.3, 9.6), r = lens.generate(7.3, 9.6, lx, ly);
      const Vec3 focus = p.o + p.d * (17 / dot(p.d, forward));
      // r passes through the pinhole ray's point in focus, from a point of the lens.
      const Vec3 to = focus - r.o;
      EXPECT_LT(length(cross(to, r.d)), 1e-9 * length(to));
      EXPECT_LE(length(r.o - p.o), 1.5 + 1e-12);
      EXPECT_GT(dot(r.d, forward), 0);
      ++checked;
    }
    EXPECT_EQ(checked, 16);
  }
  double lx, ly;
  lens_sample(3, 4, 0, 16, lx, ly);
  EXPECT_EQ(lx * lx + ly * ly, 0);  // sample 0 is the lens's centre: the pixel-centre AOVs' ray
}

TEST(Camera, ASceneWithoutACameraFramesItsObjects) {
  const Scene s = parse_scene(R"({"image": {"width": 80, "height": 40}, "objects": [
      {"field": {"type": "soft_object", "translate": [30, 0, 5],
                 "distance": {"type": "lp_metric", "radii": [4, 4, 4], "n": 2}}},
      {"field": {"type": "soft_object", "translate": [-10, 8, -2],
                 "distance": {"type": "lp_metric", "radii": [2, 6, 2], "n": 2}}}]})",
                              "nocamera.json");
  EXPECT_TRUE(s.default_camera);
  EXPECT_TRUE(s.default_lights);
  const Box box = s.bounds();
  const ViewCamera camera(s.camera, 80, 40);
  const Vec3 forward = normalize(s.camera.target - s.camera.eye);
  const Vec3 right = normalize(cross(forward, s.camera.up)), up = cross(right, forward);
  const double t = std::tan(0.5 * s.camera.fov * M_PI / 180);
  int checked = 0;
  for (int k = 0; k < 8; ++k) {  // every corner of the objects' box is in front and in the frame
    const Vec3 v = box.corner(k) - s.camera.eye;
    const double z = dot(v, forward);
    ASSERT_GT(z, 0);
    EXPECT_LE(std::abs(dot(v, right)) / z, t * 2 + 1e-12);
    EXPECT_LE(std::abs(dot(v, up)) / z, t + 1e-12);
    ++checked;
  }
  EXPECT_EQ(checked, 8);
}

// A scene without a camera whose CSGs hold infinite planes frames their finite parts: a union
// with a floor frames the ball on it, an intersection with a half-space the part of the ball's
// box inside it, a difference from a plane nothing (the other object alone is framed), a placed
// CSG its ball placed.
TEST(Camera, ACsgWithAnInfinitePlaneFramesItsFiniteOperands) {
  const std::string ball = R"({"shape": {"type": "sphere", "center": [5, 0, 0], "radius": 2}})";
  const std::string floor = R"({"shape": {"type": "plane", "normal": [0, 0, 1], "distance": 0}})";
  const auto camera_of = [](const std::string& objects) {
    return parse_scene(R"({"image": {"width": 80, "height": 60}, "objects": [)" + objects + "]}",
                       "frame.json")
        .camera;
  };
  // `tol`: where a rotated or tilted plane's normal is rounded, the box's edge is too.
  const auto expect_frames = [&](const std::string& objects, const std::string& alone,
                                 double tol = 0) {
    SCOPED_TRACE(objects);
    const Camera got = camera_of(objects), want = camera_of(alone);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(got.target[i], want.target[i], tol);
      EXPECT_NEAR(got.eye[i], want.eye[i], tol);
    }
  };
  expect_frames(R"({"csg": "union", "operands": [)" + ball + ", " + floor + "]}", ball);
  expect_frames(R"({"csg": "merge", "operands": [)" + floor + ", " + ball + "]}", ball);
  const std::string lower_half =
      R"({"shape": {"type": "box", "corner1": [3, -2, -2], "corner2": [7, 2, 0]}})";
  expect_frames(R"({"csg": "intersection", "operands": [)" + ball + ", " + floor + "]}",
                lower_half);
  // Taking the floor's solid away leaves the upper half.
  expect_frames(R"({"csg": "difference", "operands": [)" + ball + ", " + floor + "]}",
                R"({"shape": {"type": "box", "corner1": [3, -2, 0], "corner2": [7, 2, 2]}})");
  // A tilted plane cuts the box to the box of what lies inside it: x + z <= 4 on
  // [3, 7] x [-2, 2] x [-2, 2] reaches x = 4 - (-2) and z = 4 - 3.
  const std::string tilted =
      R"({"shape": {"type": "plane", "normal": [1, 0, 1], "distance": 2.8284271247461903}})";
  expect_frames(R"({"csg": "intersection", "operands": [)" + tilted + ", " + ball + "]}",
                R"({"shape": {"type": "box", "corner1": [3, -2, -2], "corner2": [6, 2, 1]}})",
                1e-12);
  // A placed plane: x <= 0 turned a quarter about z is y <= 0, moved up by 1 y <= 1.
  expect_frames(R"({"csg": "intersection", "operands": [)" + ball + R"(, {"shape": {"type":
      "plane", "normal": [1, 0, 0], "rotate": {"axis": [0, 0, 1], "deg": 90},
      "translate": [0, 1, 0]}}]})",
                R"({"shape": {"type": "box", "corner1": [3, -2, -2], "corner2": [7, 1, 2]}})",
                1e-12);
  // A half-space that misses the ball leaves nothing to frame but the other object.
  expect_frames(R"({"csg": "intersection", "operands": [)" + ball + R"(, {"shape": {"type":
      "plane", "normal": [1, 0, 0], "distance": 2}}]}, )" +
                    R"({"shape": {"type": "sphere",
      "center": [0, 9, 0], "radius": 1}})",
                R"({"shape": {"type": "sphere", "center": [0, 9, 0], "radius": 1}})");
  const std::string small = R"({"shape": {"type": "sphere", "center": [0, 9, 0], "radius": 1}})";
  expect_frames(R"({"csg": "difference", "operands": [)" + floor + ", " + ball + "]}, " + small,
                small);
  expect_frames(
      R"({"csg": "union", "translate": [0, 0, 10], "operands": [)" + ball + ", " + floor + "]}",
      R"({"shape": {"type": "sphere", "center": [5, 0, 10], "radius": 2}})");
  // Before, the union's box (the plane's, the whole range) put the eye 1e12 away.
  EXPECT_LT(length(camera_of(R"({"csg": "union", "operands": [)" + ball + ", " + floor + "]}").eye),
            100);
  // A union of a plane and a CSG of planes has nothing finite: the scene needs a camera.
  try {
    camera_of(R"({"csg": "union", "operands": [)" + floor + R"(, {"csg": "intersection",
        "operands": [)" +
              floor + ", " + floor + "]}]}");
    ADD_FAILURE() << "framed nothing";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("frame.json: /camera: expected a camera"),
              std::string::npos)
        << e.what();
  }
}

TEST(Camera, BadCameraKeysAreRefusedAtTheirPointers) {
  const std::string head = R"({"camera": {"eye": [0, -10, 0], "target": [0, 0, 0], )";
  const std::string tail = R"(}, "objects": [{"field": {"type": "soft_object",
      "distance": {"type": "lp_metric", "radii": [2, 2, 2], "n": 2}}}]})";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"("projection": "fisheye")", "/camera/projection: unknown projection 'fisheye'"},
      {R"("aperture": -1)", "/camera/aperture: expected an aperture >= 0"},
      {R"("focal_distance": -2)", "/camera/focal_distance: expected a focal distance >= 0"},
      {R"("blur_samples": 0)", "/camera/blur_samples"},
      {R"("aspect": 0)", "/camera/aspect"},
      {R"("aspect": 16385)", "/camera/aspect: expected a view's width / height from 1/16384"},
      {R"("projection": "orthographic", "fov": 179.9999999)",
       "/camera/fov: expected an orthographic"},
  };
  for (const auto& [keys, expected] : cases) {
    try {
      parse_scene(head + keys + tail, "bad.json");
      ADD_FAILURE() << keys << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

// The pixels (every channel's bits) of two renders.
std::vector<float> pixels(const std::string& path) {
  return read_image(path).pixels;
}

TEST(CameraCli, EyeTargetAndFovOverrideTheScenesCamera) {
  const std::string dir = temp_dir("camera_cli");
  const std::string scene = source_path("tests/scenes/turntable.json");
  const std::string moved = dir + "/moved.json";
  {
    std::string text = read_file(scene);
    const std::string from =
        R"("eye": [62, -82, 56], "target": [0, 0, -2], "up": [0, 0, 1], "fov": 24)";
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, from.size(), R"("eye": [0, -90, 30], "target": [0, 0, 4], "fov": 31.5)");
    std::ofstream(moved) << text;
  }
  const RunResult a = run_softtrace(
      "render " + scene + " -q --eye 0,-90,30 --target 0,0,4 --fov 31.5 -o " + dir + "/a.exr");
  ASSERT_EQ(a.status, 0) << a.err;
  const RunResult b = run_softtrace("render " + moved + " -q -o " + dir + "/b.exr");
  ASSERT_EQ(b.status, 0) << b.err;
  const std::vector<float> pa = pixels(dir + "/a.exr"), pb = pixels(dir + "/b.exr");
  ASSERT_EQ(pa.size(), pb.size());
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0);
  const RunResult original = run_softtrace("render " + scene + " -q -o " + dir + "/c.exr");
  ASSERT_EQ(original.status, 0);
  EXPECT_NE(pixels(dir + "/c.exr"), pa);

  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--fov 180", "softtrace: --fov: expected a vertical field of view in (0, 180) degrees\n"},
      {"--eye 0,0,-2 --target 0,0,-2",
       "softtrace: --target: expected a target different from the eye\n"},
      {"--eye 0,0,40",
       "softtrace: --eye: expected an up vector not parallel to the viewing direction\n"},
      {"--eye 1e13,0,0",
       "softtrace: --eye: expected an eye within 1e12 of the origin in every coordinate (rays "
       "start there)\n"},
  };
  for (const auto& [args, err] : bad) {
    const RunResult r =
        run_softtrace("render " + scene + " -q " + args + " -o " + dir + "/bad.exr");
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.err, err) << args;
  }
  EXPECT_NE(run_softtrace("render " + scene + " --eye 1,2 -o " + dir + "/bad.exr").status, 0);
}

// A lens and an orthographic view: the same bits for any thread count and any crop of the frame.
TEST(CameraCli, LensAndOrthographicFramesAreTheSameBitsForAnySplit) {
  const std::string dir = temp_dir("camera_bits");
  std::string text = read_file(source_path("tests/scenes/turntable.json"));
  const std::string from = R"("fov": 24 })";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  int checked = 0;
  for (const std::string& extra :
       {std::string(R"("fov": 24, "aperture": 6, "focal_distance": 90, "blur_samples": 5 })"),
        std::string(R"("fov": 24, "projection": "orthographic" })")}) {
    std::string scene_text = text;
    scene_text.replace(at, from.size(), extra);
    const std::string scene = dir + "/scene" + std::to_string(checked) + ".json";
    std::ofstream(scene) << scene_text;
    const std::string full = dir + "/full.exr", crop = dir + "/crop.exr";
    ASSERT_EQ(run_softtrace("render " + scene + " -q --threads 1 -o " + full).status, 0);
    ASSERT_EQ(
        run_softtrace("render " + scene + " -q --threads 3 --pixel-bounds 5,41,3,30 -o " + crop)
            .status,
        0);
    const ImageFile a = read_image(full), b = read_image(crop);
    const size_t nc = a.channels.size();
    ASSERT_EQ(a.channels, b.channels);
    size_t differing = 0, covered = 0;
    for (int y = 3; y < 30; ++y)
      for (int x = 5; x < 41; ++x)
        for (size_t c = 0; c < nc; ++c) {
          const float va = a.pixels[(size_t(y) * a.width + x) * nc + c];
          const float vb = b.pixels[(size_t(y - 3) * b.width + (x - 5)) * nc + c];
          differing += std::memcmp(&va, &vb, sizeof va) != 0;
          covered += a.channels[c] == "A" && va > 0;
        }
    EXPECT_EQ(differing, 0u) << extra;
    EXPECT_GT(covered, 100u) << extra;  // the object is in the crop
    ++checked;
  }
  EXPECT_EQ(checked, 2);
}

}  // namespace
}  // namespace softtrace::test
