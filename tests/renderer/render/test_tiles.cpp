// Parts of a frame: the tile split and crop windows, `merge` putting tiles back together with the
// bits of a single-process render, its refusals, and animation frames.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/tiles.h"
#include "same_bits.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

const char* kTurntable = "tests/scenes/turntable.json";  // 48x36, 2 spp

std::string render(const std::string& args, const std::string& out) {
  const RunResult r =
      run_softtrace("render " + source_path(kTurntable) + " -q " + args + " -o " + out);
  EXPECT_EQ(r.status, 0) << args << ": " << r.err;
  return out;
}

// Every pixel in exactly one tile; areas within 2x of each other; no tile more than 3:1 unless
// it spans a thin frame.
TEST(TileSplit, CoversTheFrameOnceBalancedAndSquareish) {
  const std::vector<std::array<int, 3>> cases = {{48, 36, 1},    {48, 36, 4},     {48, 36, 7},
                                                 {640, 480, 16}, {640, 480, 13},  {1920, 200, 5},
                                                 {100, 3000, 9}, {16384, 16, 31}, {7, 5, 35}};
  for (const auto& [w, h, n] : cases) {
    std::vector<int> owner(size_t(w) * h, 0);
    long long min_area = 1LL << 62, max_area = 0;
    for (int i = 0; i < n; ++i) {
      const PixelBounds b = tile_bounds({i, n}, w, h);
      ASSERT_GT(b.width(), 0);
      ASSERT_GT(b.height(), 0);
      for (int y = b.y0; y < b.y1; ++y)
        for (int x = b.x0; x < b.x1; ++x) ++owner[size_t(y) * w + x];
      const long long area = static_cast<long long>(b.width()) * b.height();
      min_area = std::min(min_area, area);
      max_area = std::max(max_area, area);
      // Near-square unless the frame is too thin for it: then tiles span it.
      if (area >= 64 && b.width() < w && b.height() < h) {
        const double aspect =
            double(std::max(b.width(), b.height())) / std::min(b.width(), b.height());
        EXPECT_LE(aspect, 3.0) << w << "x" << h << " tile " << i << "/" << n;
      }
    }
    EXPECT_TRUE(std::all_of(owner.begin(), owner.end(), [](int c) { return c == 1; }))
        << w << "x" << h << " in " << n;
    EXPECT_LE(max_area, 2 * min_area) << w << "x" << h << " in " << n;
  }
  EXPECT_THROW(tile_bounds({0, 36}, 5, 7), std::invalid_argument);  // 36 tiles of 35 pixels
  EXPECT_THROW(tile_bounds({0, 9}, 8, 1), std::invalid_argument);
}

TEST(TileSplit, ParsesIOfNFromZero) {
  EXPECT_EQ(parse_tile("0/4").index, 0);
  EXPECT_EQ(parse_tile("3/4").index, 3);
  EXPECT_EQ(parse_tile("3/4").count, 4);
  for (const char* bad : {"4/4", "-1/4", "1/0", "1", "1/4x", "a/b", "1/ 4", "+1/4", ""})
    EXPECT_THROW(parse_tile(bad), std::invalid_argument) << bad;
}

// pbrt-v4: pixels [ceil(W x0), ceil(W x1)) x [ceil(H y0), ceil(H y1)).
TEST(CropWindow, PbrtConvention) {
  const PixelBounds b = crop_window("0.25,0.5,0.1,1", 100, 50);
  EXPECT_EQ(b.x0, 25);
  EXPECT_EQ(b.x1, 50);
  EXPECT_EQ(b.y0, 5);
  EXPECT_EQ(b.y1, 50);
  const PixelBounds c = crop_window("0.333,0.667,0,0.5", 10, 3);
  EXPECT_EQ(c.x0, 4);  // ceil(3.33)
  EXPECT_EQ(c.x1, 7);  // ceil(6.67)
  EXPECT_EQ(c.y1, 2);  // ceil(1.5)
  for (const char* bad : {"0.5,0.25,0,1", "0,1,0", "0,1,0,1.5", "-0.1,1,0,1", "0,1,0,1,", "x",
                          "0.001,0.002,0,1", "0,nan,0,1"})
    EXPECT_THROW(crop_window(bad, 100, 50), std::invalid_argument) << bad;
  const PixelBounds p = pixel_bounds("3,10,0,2", 10, 5);
  EXPECT_EQ(p.x0, 3);
  EXPECT_EQ(p.x1, 10);
  EXPECT_EQ(p.y1, 2);
  for (const char* bad : {"3,11,0,2", "3,3,0,2", "0,1.5,0,2", "0,1,0,6", "-1,1,0,1"})
    EXPECT_THROW(pixel_bounds(bad, 10, 5), std::invalid_argument) << bad;
}

// The heart of it: tiles rendered apart, merged, give the single-process render's bits.
TEST(Merge, TilesGiveTheSingleProcessBitsInEveryChannel) {
  const std::string dir = temp_dir("merge_tiles");
  const std::string aov = " --aov depth,normal,steps,albedo ";
  const std::string full = render(aov, dir + "/full.exr");
  std::string tiles;
  for (int i = 0; i < 5; ++i)
    tiles += " " + render(aov + "--tile " + std::to_string(i) + "/5",
                          dir + "/t" + std::to_string(i) + ".exr");
  const ImageFile t2 = read_image(dir + "/t2.exr");
  EXPECT_EQ(t2.full_width, 48);
  EXPECT_EQ(t2.full_height, 36);
  EXPECT_LT(t2.width * t2.height, 48 * 36);
  EXPECT_EQ(t2.attributes.at("softtrace/tile"), "2/5");
  EXPECT_EQ(t2.attributes.at("softtrace/renderHash").size(), 16u);

  const RunResult m = run_softtrace("merge" + tiles + " -o " + dir + "/merged.exr");
  ASSERT_EQ(m.status, 0) << m.err;
  expect_same_bits(full, dir + "/merged.exr");
  EXPECT_EQ(read_image(dir + "/merged.exr").attributes.at("softtrace/renderHash"),
            read_image(full).attributes.at("softtrace/renderHash"));

  // Any mix of crops: a --crop half and two --pixel-bounds quarters.
  const std::string parts = render("--crop 0,0.5,0,1", dir + "/left.exr") + " " +
                            render("--pixel-bounds 24,48,0,20", dir + "/tr.exr") + " " +
                            render("--pixel-bounds 24,48,20,36", dir + "/br.exr");
  ASSERT_EQ(run_softtrace("merge " + parts + " -o " + dir + "/crops.exr").status, 0);
  expect_same_bits(render("", dir + "/plain.exr"), dir + "/crops.exr");
}

// README documents oiiotool --paste as another way to put tiles together.
TEST(Merge, OiiotoolPasteGivesTheSamePixels) {
  if (run_command("oiiotool --version").status != 0) GTEST_SKIP() << "no oiiotool";
  const std::string dir = temp_dir("merge_paste");
  const std::string full = render("--aov depth", dir + "/full.exr");
  std::string tiles, pastes;
  for (int i = 0; i < 4; ++i) {
    tiles += " " + render("--aov depth --tile " + std::to_string(i) + "/4",
                          dir + "/t" + std::to_string(i) + ".exr");
    if (i) pastes += " --paste:mergeroi=1 -";
  }
  const RunResult r = run_command("oiiotool" + tiles + pastes + " -o " + dir + "/pasted.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  expect_same_bits(full, dir + "/pasted.exr");
}

// Refusals: one line naming the tiles or pixels, exit 2, no output.
TEST(Merge, RefusesGapsOverlapsAndMismatches) {
  const std::string dir = temp_dir("merge_bad");
  std::vector<std::string> t;
  for (int i = 0; i < 4; ++i)
    t.push_back(
        render("--tile " + std::to_string(i) + "/4", dir + "/t" + std::to_string(i) + ".exr"));
  const std::string out = dir + "/out.exr";
  const auto refused = [&](const std::string& inputs, const std::string& expect) {
    const RunResult r = run_softtrace("merge " + inputs + " -o " + out);
    EXPECT_EQ(r.status, 2) << inputs;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos)
        << "expected: " << expect << "\ngot: " << r.err;
    EXPECT_FALSE(fs::exists(out));
  };
  const PixelBounds b1 = tile_bounds({1, 4}, 48, 36), b3 = tile_bounds({3, 4}, 48, 36);
  const auto range = [](const PixelBounds& b) {
    return "x " + std::to_string(b.x0) + ".." + std::to_string(b.x1 - 1) + ", y " +
           std::to_string(b.y0) + ".." + std::to_string(b.y1 - 1);
  };
  // Tiles 1 and 3 are the right column: one uncovered range.
  ASSERT_EQ(b1.x0, b3.x0);
  ASSERT_EQ(b1.y1, b3.y0);
  refused(t[0] + " " + t[2], "no tile has the pixels " + range({b1.x0, b1.x1, b1.y0, b3.y1}) +
                                 " (missing --tile 1; 3 of 4)");
  refused(t[1] + " " + t[2],
          "no tile has the pixels " + range(tile_bounds({0, 4}, 48, 36)) + "; " + range(b3));
  refused(t[0] + " " + t[1] + " " + t[2] + " " + t[3] + " " + t[1], "overlap at " + range(b1));
  refused(t[0] + " " + t[1] + " " + t[2] + " " + render("--crop 0,1,0.5,1", dir + "/bottom.exr"),
          "overlap");
  refused(t[0] + " " + t[1] + " " + t[2] + " " + render("--tile 3/4 --spp 1", dir + "/spp.exr"),
          "are from different scenes or render settings");
  refused(t[0] + " " + render("--tile 1/4 --width 50 --height 36", dir + "/w.exr"),
          "is a tile of a 50x36 image");
  refused(t[0] + " " + render("--tile 1/4 --aov depth", dir + "/z.exr"), "different channels");
  refused(t[0] + " " + render("--tile 1/4 --frame 1", dir + "/f1.exr"), "different scenes");
  refused(dir + "/absent.exr", "absent.exr");
  EXPECT_EQ(run_softtrace("merge -o " + out).status, 2);
}

TEST(Frames, FrameNumberGoesIntoTheNameAndTheCamera) {
  const std::string dir = temp_dir("frames");
  for (int f = 0; f < 3; ++f) {
    const RunResult r = run_softtrace("render " + source_path(kTurntable) + " -q --frame " +
                                      std::to_string(f) + " -o " + dir + "/turn.####.exr");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const ImageFile f0 = read_image(dir + "/turn.0000.exr"), f1 = read_image(dir + "/turn.0001.exr"),
                  f2 = read_image(dir + "/turn.0002.exr");
  EXPECT_NE(f0.pixels, f1.pixels);
  EXPECT_NE(f1.pixels, f2.pixels);
  EXPECT_EQ(f1.attributes.at("softtrace/frame"), "1");
  // The default name is the scene's, with the frame.
  const RunResult def = run_command("cd " + dir + " && " + SOFTTRACE_BIN + " render " +
                                    source_path(kTurntable) + " -q --frame 2 --width 8 --height 6");
  EXPECT_EQ(def.status, 0) << def.err;
  EXPECT_TRUE(fs::exists(dir + "/turntable.0002.exr"));

  // A list of cameras: a frame with the scene's own camera is the render without --frame.
  const std::string listed = dir + "/listed.json";
  std::string text = read_file(source_path(kTurntable));
  const std::string turntable =
      R"("frames": 3, "turntable": { "axis": [0, 0, 1], "degrees": 360 })";
  ASSERT_NE(text.find(turntable), std::string::npos);
  text.replace(text.find(turntable), turntable.size(),
               R"("cameras": [ { "eye": [0, -90, 0], "target": [0, 0, 0] },
                               { "eye": [62, -82, 56], "target": [0, 0, -2], "fov": 24 } ])");
  std::ofstream(listed) << text;
  ASSERT_EQ(run_softtrace("render " + listed + " -q --frame 1 -o " + dir + "/l1.exr").status, 0);
  ASSERT_EQ(run_softtrace("render " + listed + " -q -o " + dir + "/l.exr").status, 0);
  expect_same_bits(dir + "/l.exr", dir + "/l1.exr");
  ASSERT_EQ(run_softtrace("render " + listed + " -q --frame 0 -o " + dir + "/l0.exr").status, 0);
  EXPECT_NE(read_image(dir + "/l0.exr").pixels, read_image(dir + "/l.exr").pixels);

  const auto refused = [&](const std::string& args, const std::string& expect) {
    const RunResult r = run_softtrace("render " + args + " -o " + dir + "/bad.exr");
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/bad.exr"));
  };
  refused(source_path(kTurntable) + " --frame 3",
          "turntable.json: /animation: there is no frame 3 (frames 0 to 2)");
  refused(source_path("scenes/fig000_12b_soft_blend.json") + " --frame 0", "has no /animation");
  const RunResult hash =
      run_softtrace("render " + source_path(kTurntable) + " -o " + dir + "/x.##.exr");
  EXPECT_EQ(hash.status, 2);
  EXPECT_NE(hash.err.find("'#' stands for the frame: give --frame"), std::string::npos) << hash.err;
}

// An interrupted tile task writes no tile, so merge names the tile as missing rather than
// accepting a partial one.
TEST(Merge, InterruptedTileLeavesNothingToMerge) {
  const std::string dir = temp_dir("merge_interrupt");
  const std::string tile0 = render("--tile 0/2", dir + "/t0.exr");
  const std::string tile1 = dir + "/t1.exr";
  // Big enough to be still rendering when the signal comes.
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl(SOFTTRACE_BIN, SOFTTRACE_BIN, "render", source_path(kTurntable).c_str(), "-q",
            "--width", "4000", "--height", "3000", "--spp", "16", "--tile", "1/2", "-o",
            tile1.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Once it has a handler for SIGINT (SigCgt), it is past start-up.
  const auto catching = [pid] {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
      if (line.rfind("SigCgt:", 0) == 0)
        return ((std::stoull(line.substr(7), nullptr, 16) >> (SIGINT - 1)) & 1) != 0;
    return false;
  };
  for (int i = 0; i < 30000 && !catching(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, SIGINT);
  int raw = 0;
  ::waitpid(pid, &raw, 0);
  ASSERT_TRUE(WIFEXITED(raw)) << "killed by signal " << WTERMSIG(raw);
  EXPECT_EQ(WEXITSTATUS(raw), 130);
  EXPECT_FALSE(fs::exists(tile1));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left: " << e.path();
  const RunResult m = run_softtrace("merge " + tile0 + " -o " + dir + "/m.exr");
  EXPECT_EQ(m.status, 2);
  EXPECT_NE(m.err.find("missing --tile 1 of 2"), std::string::npos) << m.err;
}

}  // namespace
}  // namespace softtrace::test
