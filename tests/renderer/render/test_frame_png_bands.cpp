// The frame's final pixels (RenderOptions::pixels_final, frame.h): each tile of the frame's last
// pass tells of its pixels once it has written them, so a PNG whose bands are deflated as they are
// told (film.h's film_png_bands, as the command line writes) is the bytes of the PNG written after
// the frame, at any thread count, with adaptive anti-aliasing's two passes and in a crop.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "film/film.h"
#include "render/frame.h"
#include "render/threads.h"
#include "scene/scene.h"
#include "sparse_ball_cloud.h"

namespace softtrace {
namespace {

std::string frame_png_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The 100x70 frame's data window [x0, x0 + width) x [y0, y0 + height), at `threads` threads: the
// PNG deflated band by band as its rows are told final, and the one written after the frame.
struct FramePngs {
  std::string during, after;
  long pixels_told = 0;
  int rows_told_twice = 0;
  long covered = 0;  // pixels that show an object
};
FramePngs frame_pngs(const Scene& scene, const TracedScene& rt, int x0, int y0, int width,
                     int height, int threads, const std::string& name) {
  const std::string dir = ::testing::TempDir() + "frame_png_bands";
  std::filesystem::create_directories(dir);
  Film film(width, height, AovSelection{});
  film.full_width = scene.image.width;
  film.full_height = scene.image.height;
  film.x0 = x0;
  film.y0 = y0;
  const OutputOptions out;
  const FrameInfo info;
  const std::unique_ptr<PngBands> png = film_png_bands(film, out, info);
  std::vector<std::atomic<long>> told(static_cast<size_t>(height));
  FramePngs result;
  RenderOptions opt;
  opt.pixels_final = [&](int r0, int r1, int w) {
    for (int y = r0; y < r1; ++y) told[size_t(y)] += w;
    png->pixels_final(r0, r1, w);
  };
  run_on_threads(threads,
                 [&] { EXPECT_TRUE(render_frame(scene, rt, opt, film, nullptr, nullptr)); });
  for (size_t i = 3; i < film.rgba.size(); i += 4) result.covered += film.rgba[i] > 0;
  for (const auto& t : told) {
    result.pixels_told += t;
    result.rows_told_twice += t != width;
  }
  const std::string during = dir + "/" + name + "_during.png", after = dir + "/" + name + ".png";
  commit_image(write_image_temp(during, film, out, info, {}, png.get()), during);
  commit_image(write_image_temp(after, film, out, info), after);
  result.during = frame_png_file(during);
  result.after = frame_png_file(after);
  return result;
}

Scene frame_png_scene(bool antialias) {
  Scene scene = parse_scene(
      sparse_ball_cloud(
          900, 5, R"({"eye": [22, -33, 18], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 50})"),
      "<test>");
  scene.image.width = 100;
  scene.image.height = 70;
  if (antialias) scene.image.antialias.threshold = 0.05;
  return scene;
}

TEST(FramePngBands, TheBandsDeflatedAsTilesFinishAreTheFileWrittenAfterTheFrame) {
  for (const bool antialias : {false, true}) {
    const Scene scene = frame_png_scene(antialias);
    const TracedScene rt(scene, LipschitzMode::Local);
    std::string first;
    for (const int threads : {1, 2, 8}) {
      const std::string name =
          std::string(antialias ? "aa" : "plain") + "_t" + std::to_string(threads);
      const FramePngs whole = frame_pngs(scene, rt, 0, 0, 100, 70, threads, name);
      EXPECT_EQ(whole.during, whole.after) << name;
      EXPECT_EQ(whole.pixels_told, 100 * 70) << name;
      EXPECT_EQ(whole.rows_told_twice, 0) << name;
      EXPECT_GT(whole.covered, 100 * 70 / 10) << name;  // not a frame of background alone
      if (first.empty()) first = whole.after;
      EXPECT_EQ(whole.after, first) << name;  // the same bits at any thread count
      // A crop whose edges cut tiles.
      const FramePngs crop = frame_pngs(scene, rt, 13, 9, 61, 47, threads, name + "_crop");
      EXPECT_EQ(crop.during, crop.after) << name;
      EXPECT_EQ(crop.pixels_told, 61 * 47) << name;
      EXPECT_EQ(crop.rows_told_twice, 0) << name;
    }
  }
}

}  // namespace
}  // namespace softtrace
