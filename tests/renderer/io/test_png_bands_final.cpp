// A PNG's bands deflated as their rows become final (io/png_bands.h, PngBands::pixels_final), as a
// render's tiles finish: a band reads its rows only once every pixel of them (and of its history
// rows above) has been counted, and the file is the bytes of the whole image's encoding, whatever
// the order of the tiles and the threads that count them.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "io/png_bands.h"
#include "render/threads.h"

namespace softtrace {
namespace {

constexpr int kTile = 16;

std::string png_final_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string png_final_dir() {
  const std::string dir = ::testing::TempDir() + "png_bands_final";
  std::filesystem::create_directories(dir);
  return dir;
}

// An image of gradients and a pattern, so that deflate finds matches within and across rows.
struct FinalImage {
  int width, height, channels;
  std::vector<uint8_t> bytes;
  FinalImage(int w, int h, int c) : width(w), height(h), channels(c), bytes(size_t(w) * h * c) {
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t((i * 7 + (i / 331) * 13) & 255);
  }
  size_t row_bytes() const { return size_t(width) * channels; }
};

// The image's tiles of kTile pixels a side (the last ones cut at its edges), in a shuffled order.
struct FinalTile {
  int x0, y0, x1, y1;
};
std::vector<FinalTile> shuffled_tiles(int width, int height, unsigned seed) {
  std::vector<FinalTile> tiles;
  for (int y = 0; y < height; y += kTile)
    for (int x = 0; x < width; x += kTile)
      tiles.push_back({x, y, std::min(width, x + kTile), std::min(height, y + kTile)});
  std::shuffle(tiles.begin(), tiles.end(), std::mt19937(seed));
  return tiles;
}

// Renders `img` tile by tile in a shuffled order on `threads` threads, counting each tile's pixels
// final after it has "traced" them (copied them into the frame), and writes the PNG. Every row that
// a band reads must be final by then; and every band must be deflated before the frame ends.
std::string write_as_tiles_finish(const FinalImage& img, int threads, unsigned seed,
                                  const std::string& path) {
  std::vector<uint8_t> frame(img.bytes.size(), 0);
  std::vector<std::atomic<int>> final_pixels(size_t(img.height));
  std::atomic<int> rows_read_early{0}, rows_read{0};
  PngBands bands(img.width, img.height, img.channels, [&](int y, uint8_t* row) {
    if (final_pixels[size_t(y)].load(std::memory_order_acquire) != img.width) ++rows_read_early;
    ++rows_read;
    std::memcpy(row, frame.data() + size_t(y) * img.row_bytes(), img.row_bytes());
  });
  const std::vector<FinalTile> tiles = shuffled_tiles(img.width, img.height, seed);
  run_on_threads(threads, [&] {
    parallel_each(tiles.size(), [&](size_t i) {
      const FinalTile& t = tiles[i];
      const size_t bytes = size_t(t.x1 - t.x0) * img.channels;
      for (int y = t.y0; y < t.y1; ++y) {
        const size_t at = size_t(y) * img.row_bytes() + size_t(t.x0) * img.channels;
        std::memcpy(frame.data() + at, img.bytes.data() + at, bytes);
        final_pixels[size_t(y)].fetch_add(t.x1 - t.x0, std::memory_order_release);
      }
      bands.pixels_final(t.y0, t.y1, t.x1 - t.x0);
    });
  });
  EXPECT_EQ(rows_read_early.load(), 0) << "a band read rows not yet final";
  // Every band deflated as the tiles finished: none left for the write.
  EXPECT_GE(rows_read.load(), img.height);
  const int read_in_the_frame = rows_read.load();
  write_png(path, true, bands, parallel_each);
  EXPECT_EQ(rows_read.load(), read_in_the_frame) << "bands left for the write";
  return png_final_file(path);
}

std::string write_whole(const FinalImage& img, const std::string& path) {
  write_png(path, img.width, img.height, img.channels, true, [&](int y, uint8_t* row) {
    std::memcpy(row, img.bytes.data() + size_t(y) * img.row_bytes(), img.row_bytes());
  });
  return png_final_file(path);
}

TEST(PngBandsFinal, ABandIsDeflatedOnceItsRowsAreFinalAndTheFileIsTheWholeImages) {
  const std::string dir = png_final_dir();
  // 641x307 RGBA: 17 bands of 19 rows, the last one short, their edges inside tiles; 320x240 RGB:
  // 8 bands of 34 rows, the last one of 2; 33x5 RGB: one band, one row of tiles.
  for (const FinalImage& img :
       {FinalImage(641, 307, 4), FinalImage(320, 240, 3), FinalImage(33, 5, 3)}) {
    const std::string name = dir + "/" + std::to_string(img.width) + "x" +
                             std::to_string(img.height) + "x" + std::to_string(img.channels);
    const std::string whole = write_whole(img, name + "_whole.png");
    for (const int threads : {1, 2, 4})
      for (const unsigned seed : {1u, 2u, 3u}) {
        const std::string as_tiles = write_as_tiles_finish(
            img, threads, seed,
            name + "_t" + std::to_string(threads) + "_s" + std::to_string(seed) + ".png");
        EXPECT_EQ(as_tiles, whole) << name << ", " << threads << " threads, order " << seed;
      }
  }
}

// Bands whose rows are not all counted final stay for the write, which deflates them: a frame's
// rows counted in part (a cancelled render's) leave a file of the same bytes.
TEST(PngBandsFinal, BandsNotAllFinalAreDeflatedByTheWrite) {
  const std::string dir = png_final_dir();
  const FinalImage img(320, 240, 3);
  const std::string whole = write_whole(img, dir + "/part_whole.png");
  std::vector<int> rows_read(size_t(img.height), 0);
  PngBands bands(img.width, img.height, img.channels, [&](int y, uint8_t* row) {
    ++rows_read[size_t(y)];
    std::memcpy(row, img.bytes.data() + size_t(y) * img.row_bytes(), img.row_bytes());
  });
  ASSERT_EQ(bands.count(), 8u);
  // Rows 0-99 whole and row 100 but its last pixel: band 2 (rows 68-101, history 66-67) waits.
  bands.pixels_final(0, 100, img.width);
  bands.pixels_final(100, 101, img.width - 1);
  for (int y = 0; y < img.height; ++y)
    EXPECT_EQ(rows_read[size_t(y)] > 0, y < bands.end_row(1)) << y;
  write_png(dir + "/part.png", true, bands);
  EXPECT_EQ(png_final_file(dir + "/part.png"), whole);
  // Each row once for its band and once more as the history of the band below it.
  for (int y = 0; y < img.height; ++y) {
    int readers = 0;
    for (size_t k = 0; k < bands.count(); ++k)
      readers += y >= bands.first_row_read(k) && y < bands.end_row(k);
    EXPECT_EQ(rows_read[size_t(y)], readers) << y;
  }
}

}  // namespace
}  // namespace softtrace
