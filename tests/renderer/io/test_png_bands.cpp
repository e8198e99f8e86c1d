// The PNG writer's bands (io/image_file.h): rows made and deflated band by band, in any order and
// on any threads, joined into one zlib stream. The file must be the same bytes however the bands
// are run, and any PNG reader (OpenImageIO's, besides ours) must read back exactly the samples.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/threads.h"

namespace softtrace::test {
namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Smooth gradients (which deflate finds matches in, within and across rows) and, with `noise`,
// random samples (which it cannot compress).
PngPixels test_image(int width, int height, int channels, bool noise) {
  PngPixels img{width, height, channels, std::vector<uint8_t>(size_t(width) * height * channels)};
  std::mt19937 random(7);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c)
        img.bytes[(size_t(y) * width + x) * channels + c] =
            noise ? uint8_t(random()) : uint8_t((x * (c + 1) + y * 3 + (x / 17) * (y / 13)) & 255);
  return img;
}

std::string write_with(const PngPixels& img, const std::string& path, const EachIndex& each) {
  const size_t row_bytes = size_t(img.width) * img.channels;
  write_png(
      path, img.width, img.height, img.channels, true,
      [&](int y, uint8_t* row) {
        std::memcpy(row, img.bytes.data() + size_t(y) * row_bytes, row_bytes);
      },
      each);
  return file_bytes(path);
}

// The samples as OpenImageIO's PNG reader decodes them.
// Alpha as stored (OpenImageIO would otherwise premultiply the colour by it). Each file is read
// once: OpenImageIO's cache keeps a name's first image.
std::vector<uint8_t> oiio_samples(const std::string& path, int channels) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageBuf buf(path, 0, 0, nullptr, &config);
  EXPECT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::UINT8)) << buf.geterror();
  EXPECT_EQ(buf.spec().nchannels, channels);
  std::vector<uint8_t> out(size_t(buf.spec().width) * buf.spec().height * channels);
  buf.get_pixels(buf.roi(), OIIO::TypeDesc::UINT8, out.data());
  return out;
}

// The chunk types of a PNG file, in order (after the 8-byte signature).
std::vector<std::string> chunk_types(const std::string& bytes) {
  std::vector<std::string> types;
  for (size_t at = 8; at + 8 <= bytes.size();) {
    const auto b = [&](size_t i) { return uint32_t(uint8_t(bytes[at + i])); };
    const uint32_t length = b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
    types.push_back(bytes.substr(at + 4, 4));
    at += 12 + size_t(length);
  }
  return types;
}

TEST(PngBands, TheSameBytesInAnyOrderOnAnyThreads) {
  const std::string dir = temp_dir("png_bands_order");
  // 19 rows a band at this size (787 kB of rows, at most about 16 bands): 17 bands, the last one
  // short.
  const PngPixels img = test_image(641, 307, 4, false);
  const std::string serial = write_with(img, dir + "/serial.png", {});
  const std::string backwards =
      write_with(img, dir + "/backwards.png", [](size_t n, const std::function<void(size_t)>& f) {
        for (size_t i = n; i-- > 0;) f(i);
      });
  std::mutex m;
  std::set<std::thread::id> threads;
  const std::string parallel =
      write_with(img, dir + "/parallel.png", [&](size_t n, const std::function<void(size_t)>& f) {
        parallel_each(n, [&](size_t i) {
          {
            const std::lock_guard<std::mutex> lock(m);
            threads.insert(std::this_thread::get_id());
          }
          f(i);
        });
      });
  EXPECT_EQ(backwards, serial);
  EXPECT_EQ(parallel, serial);
  EXPECT_EQ(oiio_samples(dir + "/parallel.png", 4), img.bytes);
  EXPECT_EQ(read_image(dir + "/parallel.png").pixels.size(), img.bytes.size());
  std::printf("bands ran on %zu thread(s)\n", threads.size());
}

// A thread keeps its bands' buffers from band to band; a band that starts on a thread while one of
// its own is still being made (here a row that writes another PNG) takes buffers of its own: both
// files are the bytes they are alone.
TEST(PngBands, ABandWithinABandOnOneThreadLeavesTheOuterOnesRows) {
  const std::string dir = temp_dir("png_bands_nested");
  const PngPixels outer = test_image(300, 200, 4, false), inner = test_image(211, 97, 3, true);
  const std::string outer_alone = write_with(outer, dir + "/outer_alone.png", {});
  const std::string inner_alone = write_with(inner, dir + "/inner_alone.png", {});
  const size_t row_bytes = size_t(outer.width) * outer.channels;
  std::string inner_nested;
  write_png(dir + "/outer.png", outer.width, outer.height, outer.channels, true,
            [&](int y, uint8_t* row) {
              if (y == 30) inner_nested = write_with(inner, dir + "/inner.png", {});
              std::memcpy(row, outer.bytes.data() + size_t(y) * row_bytes, row_bytes);
            });
  EXPECT_EQ(file_bytes(dir + "/outer.png"), outer_alone);
  EXPECT_EQ(inner_nested, inner_alone);
}

// Every channel count, one pixel, and images of one column: many rows a band, and a band of one
// row where a row alone is larger than a band.
TEST(PngBands, EveryShapeReadsBackExactly) {
  const std::string dir = temp_dir("png_bands_shapes");
  struct Shape {
    int width, height, channels;
  };
  for (const Shape s : {Shape{1, 1, 1}, Shape{1, 1, 4}, Shape{3, 2, 2}, Shape{1, 40000, 1},
                        Shape{9000, 3, 4}, Shape{320, 240, 3}}) {
    const PngPixels img = test_image(s.width, s.height, s.channels, false);
    const std::string path = dir + "/" + std::to_string(s.width) + "x" + std::to_string(s.height) +
                             "x" + std::to_string(s.channels) + ".png";
    write_with(img, path, parallel_each);
    EXPECT_EQ(oiio_samples(path, s.channels), img.bytes)
        << s.width << "x" << s.height << "x" << s.channels;
  }
}

// A stream over 1 MiB (noise does not compress) goes into more than one IDAT chunk, in order,
// before IEND; the reader checks every chunk's CRC and the stream's Adler-32.
TEST(PngBands, ALongStreamSpansIdatChunks) {
  const std::string dir = temp_dir("png_bands_long");
  const PngPixels img = test_image(700, 520, 3, true);
  const std::string bytes = write_with(img, dir + "/noise.png", parallel_each);
  EXPECT_GT(bytes.size(), size_t(1) << 20);
  const std::vector<std::string> types = chunk_types(bytes);
  ASSERT_GE(types.size(), 5u);
  EXPECT_EQ(types.front(), "IHDR");
  EXPECT_EQ(types[1], "sRGB");
  EXPECT_EQ(types[2], "IDAT");
  EXPECT_EQ(types[3], "IDAT");
  EXPECT_EQ(types.back(), "IEND");
  EXPECT_EQ(oiio_samples(dir + "/noise.png", 3), img.bytes);
  const ImageFile ours = read_image(dir + "/noise.png");
  ASSERT_EQ(ours.pixels.size(), img.bytes.size());
  for (size_t i = 0; i < img.bytes.size(); ++i)
    ASSERT_EQ(ours.pixels[i], img.bytes[i] * (1.0f / 255.0f)) << i;
}

// Each band runs in the caller's floating-point mode, wherever it runs: here rounding towards zero,
// which the worker threads do not have (the arena is started first, in the usual mode, as the
// frame starts it before the image is written).
TEST(PngBands, EachTaskTakesTheCallersFloatingPointMode) {
#if defined(__x86_64__) || defined(__i386__)
  // MXCSR's control bits; the low six are the exceptions' sticky flags, which any sum may set.
  const auto control = [] { return _mm_getcsr() & ~0x3Fu; };
  parallel_each(64, [](size_t) { std::this_thread::sleep_for(std::chrono::microseconds(100)); });
  const unsigned before = _mm_getcsr();
  const unsigned mode = (before & ~0x3Fu) | 0x6000u;  // RC = 11: towards zero
  _mm_setcsr(mode);
  std::mutex m;
  std::vector<unsigned> seen;
  std::set<std::thread::id> threads;
  parallel_each(64, [&](size_t) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    const std::lock_guard<std::mutex> lock(m);
    seen.push_back(control());
    threads.insert(std::this_thread::get_id());
  });
  const unsigned after = control();
  _mm_setcsr(before);
  EXPECT_EQ(after, mode);
  ASSERT_EQ(seen.size(), 64u);
  for (const unsigned s : seen) EXPECT_EQ(s, mode);
  if (threads.size() < 2) GTEST_SKIP() << "every task ran on the calling thread (a loaded machine)";
#else
  GTEST_SKIP() << "x86 only";
#endif
}

}  // namespace
}  // namespace softtrace::test
