// A film's PNG rows (film.cpp): every sample of the file is png_sample(srgb_encode(...)) of the
// film's value, to the byte, for straight alpha (colour over coverage) and over the background,
// at every kind of coverage a frame gives (none, whole, a part, and values no frame gives).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "film/film.h"
#include "film/srgb_bytes.h"
#include "io/image_file.h"

namespace softtrace {
namespace {

// The film's pixels: coverages 0, 1 and parts of it (a pixel some of whose samples met nothing),
// each with colours from black to beyond white (premultiplied, so at most the coverage in a
// frame; larger ones are clamped). The last row is a frame's background, which nothing covers:
// colour and coverage 0 (the rows' own way for such a pixel).
Film png_rows_film() {
  const float coverages[] = {1.0f,  0.0f, 0.5f,  0.25f, 0.75f, 1e-3f,
                             -0.0f, 1.0f, 0.25f, 1.5f,  NAN,   0.6f};
  const float colours[] = {0.0f, 0.002f, 0.04f, 0.18f, 0.5f, 0.73f, 1.0f, 1.7f, -0.2f, NAN};
  const int w = 12, h = 11;
  Film film(w, h, AovSelection{});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* px = &film.rgba[(size_t(y) * w + x) * 4];
      if (y == h - 1) {
        std::fill_n(px, 4, 0.0f);
        continue;
      }
      const float a = coverages[x];
      for (int k = 0; k < 3; ++k) {
        const float c = colours[(y + 3 * k) % 10];
        px[k] = a > 0 && a <= 1 && !std::isnan(c) ? c * a : c;
      }
      px[3] = a;
    }
  return film;
}

uint8_t png_rows_reference(float v) {
  return png_sample(srgb_encode(v));
}

// The file's samples, as bytes.
std::vector<int> png_rows_written(const Film& film, const OutputOptions& opt, const FrameInfo& info,
                                  const std::string& name) {
  const std::string dir = ::testing::TempDir() + "png_rows";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name + ".png";
  commit_image(write_image_temp(path, film, opt, info), path);
  const ImageFile img = read_image(path);
  std::vector<int> bytes;
  for (const float v : img.pixels) bytes.push_back(int(std::lround(v * 255)));
  return bytes;
}

TEST(PngRows, StraightAlphaIsTheColourOverTheCoverage) {
  const Film film = png_rows_film();
  OutputOptions opt;
  opt.png_alpha = true;
  const std::vector<int> bytes = png_rows_written(film, opt, FrameInfo{}, "straight");
  ASSERT_EQ(bytes.size(), size_t(film.width) * film.height * 4);
  for (size_t i = 0; i < size_t(film.width) * film.height; ++i) {
    const float* in = &film.rgba[i * 4];
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(bytes[i * 4 + k], png_rows_reference(in[3] > 0 ? in[k] / in[3] : 0.0f))
          << "pixel " << i << " channel " << k;
    EXPECT_EQ(bytes[i * 4 + 3], png_sample(in[3])) << "pixel " << i;
  }
}

TEST(PngRows, FlattenedOverTheBackground) {
  const Film film = png_rows_film();
  FrameInfo info;
  info.background = {0.2, 0.5, 1.0};
  for (const bool alpha : {false, true}) {
    OutputOptions opt;
    opt.png_alpha = alpha;
    opt.flatten = alpha;  // RGB is always over the background; RGBA with flatten too
    const int nc = alpha ? 4 : 3;
    const std::vector<int> bytes = png_rows_written(film, opt, info, alpha ? "flat_rgba" : "rgb");
    ASSERT_EQ(bytes.size(), size_t(film.width) * film.height * nc);
    for (size_t i = 0; i < size_t(film.width) * film.height; ++i) {
      const float* in = &film.rgba[i * 4];
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(bytes[i * nc + k],
                  png_rows_reference(in[k] + float(info.background[k]) * (1 - in[3])))
            << "pixel " << i << " channel " << k;
      if (alpha) {
        EXPECT_EQ(bytes[i * nc + 3], 255) << "pixel " << i;
      }
    }
  }
}

}  // namespace
}  // namespace softtrace
