// Hostile and careless command lines and inputs (issue 35): every refusal is one line naming
// the value and the rule, exit 2, and nothing written; nothing read or allocated without bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_util.h"
#include "io/image_file.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

const std::string kTileScene = source_path("tests/scenes/turntable.json");  // 48x36

// `args` exits 2 with exactly one line on stderr containing `expect`, and `dir` (where outputs
// would go) stays empty.
void expect_refused(const std::string& args, const std::string& expect, const std::string& dir) {
  const RunResult r = run_softtrace(args);
  EXPECT_EQ(r.status, 2) << args;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("softtrace: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expect), std::string::npos)
      << args << "\n  expected: " << expect << "\n  got: " << r.err;
  if (!dir.empty()) {
    EXPECT_TRUE(fs::is_empty(dir)) << args << " wrote a file";
  }
}

// --tile's numbers once wrapped (0/4294967297 rendered the whole frame as 0/1), and an empty
// --tile, --crop or --pixel-bounds rendered the whole frame as if it were not given.
TEST(HostileOptions, PartsOfTheFrameAreExact) {
  const std::string dir = temp_dir("hostile_parts");
  const std::string render =
      "render " + source_path(kDefaultScene) + " --width 8 --height 6 --quiet -o " + dir + "/o.exr";
  expect_refused(render + " --tile 0/4294967297", "--tile '0/4294967297': expected I/N", dir);
  expect_refused(render + " --tile 4294967296/4294967297", "--tile '4294967296/4294967297'", dir);
  expect_refused(render + " --tile ''", "--tile '': expected I/N", dir);
  expect_refused(render + " --crop ''", "--crop '': expected X0,X1,Y0,Y1", dir);
  expect_refused(render + " --pixel-bounds ''", "--pixel-bounds '': expected X0,X1,Y0,Y1", dir);
}

// Each refusal in our words, naming the value: CLI11's own said "unknown option" for an
// out-of-range idiff-style option, printed all 309 digits of the largest double, or let NaN
// through (which turned every mismatch into a pass).
TEST(HostileOptions, RefusalsNameTheValueAndTheRule) {
  const std::string dir = temp_dir("hostile_options");
  const std::string diff = "diff " + source_path(kDefaultScene) + " " + source_path(kDefaultScene);
  expect_refused(diff + " -failpercent 101",
                 "--failpercent: expected a number from 0 to 100, got '101'", dir);
  expect_refused(diff + " -failpercent nan",
                 "--failpercent: expected a number from 0 to 100, got 'nan'", dir);
  expect_refused(diff + " -warnpercent -1",
                 "--warnpercent: expected a number from 0 to 100, got '-1'", dir);
  expect_refused(diff + " -allowfailures -1", "--allowfailures: expected an integer >= 0, got '-1'",
                 dir);
  const RunResult digits = run_softtrace(diff + " -allowfailures -1");
  EXPECT_LT(digits.err.size(), 160u) << digits.err;
  expect_refused(diff + " -fail nan", "--fail: expected a number >= 0, got 'nan'", dir);
  expect_refused("render " + source_path(kDefaultScene) + " --frame 1e3",
                 "--frame: expected an integer from 0 to 999999, got '1e3'", dir);
  expect_refused("render " + source_path(kDefaultScene) + " --frame 1000000",
                 "--frame: expected an integer from 0 to 999999, got '1000000'", dir);
}

// A folder once read as an empty scene ("1:1: invalid JSON"); /dev/zero was read until memory
// ran out; `eval --points` of a folder or /dev/zero exited 0 with no output.
TEST(HostileInputs, FoldersAndEndlessFilesAreRefused) {
  const std::string dir = temp_dir("hostile_inputs");
  const std::string out = " -o " + dir + "/o.exr";
  expect_refused("render " + dir + out, dir + ": is a folder, not a scene file", dir);
  expect_refused("render /dev/zero" + out, "/dev/zero:1:1: invalid JSON", dir);
  expect_refused("eval /dev/zero", "/dev/zero:1:1: invalid JSON", dir);
  expect_refused("eval " + source_path(kDefaultScene) + " --points " + dir,
                 dir + ": is a folder, not a points file", dir);
  expect_refused("eval " + source_path(kDefaultScene) + " --points /dev/zero",
                 "/dev/zero:1: a line longer than 4096 bytes", dir);
}

// Lines up to the limit are read whole, the last one also without a newline.
TEST(HostileInputs, EvalReadsLongAndUnterminatedLines) {
  const std::string dir = temp_dir("eval_lines");
  std::string padded = "1 2 3";
  padded.append(4096 - padded.size(), ' ');
  std::ofstream(dir + "/points") << padded << "\n\n  \n4 5 6";
  const RunResult r =
      run_softtrace("eval " + source_path(kDefaultScene) + " --points " + dir + "/points");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r.out;
  std::ofstream(dir + "/long") << padded << " \n";
  expect_refused("eval " + source_path(kDefaultScene) + " --points " + dir + "/long",
                 "/long:1: a line longer than", "");
}

// A tile whose softtrace/tile attribute was tampered with ("0/2000000000") once made merge
// allocate and list two billion missing tiles; now it is refused before anything is allocated.
TEST(HostileTiles, TamperedTileAttributeIsRefused) {
  const std::string dir = temp_dir("hostile_tile_attr");
  const std::string t0 = dir + "/t0.exr";
  ASSERT_EQ(run_softtrace("render " + kTileScene + " --quiet --tile 0/2 -o " + t0).status, 0);
  ImageFile tile = read_image(t0);
  tile.attributes["softtrace/tile"] = "0/2000000000";
  write_exr(dir + "/tampered.exr", tile);
  fs::create_directories(dir + "/out");
  expect_refused("merge " + dir + "/tampered.exr -o " + dir + "/out/m.exr",
                 "tampered.exr: softtrace/tile '0/2000000000': a 48x36 frame has fewer pixels "
                 "than tiles",
                 dir + "/out");
  tile.attributes["softtrace/tile"] = "0/-2";
  write_exr(dir + "/tampered.exr", tile);
  expect_refused("merge " + dir + "/tampered.exr -o " + dir + "/out/m.exr",
                 "softtrace/tile '0/-2' is not I/N", dir + "/out");
}

// --flatten and --half tiles hold other pixels than premultiplied float ones: merging them with
// those once gave a frame of mixed halves.
TEST(HostileTiles, FlattenedOrHalfTileAmongPremultipliedIsRefused) {
  const std::string dir = temp_dir("hostile_tile_kinds");
  const auto tile = [&](int i, const std::string& extra) {
    const std::string path =
        dir + "/t" + std::to_string(i) + (extra.empty() ? "" : extra.substr(2)) + ".exr";
    EXPECT_EQ(run_softtrace("render " + kTileScene + " --quiet --tile " + std::to_string(i) +
                            "/2 " + extra + " -o " + path)
                  .status,
              0);
    return path;
  };
  const std::string t0 = tile(0, ""), flat = tile(1, "--flatten"), half = tile(1, "--half");
  fs::create_directories(dir + "/out");
  for (const std::string& other : {flat, half})
    expect_refused("merge " + t0 + " " + other + " -o " + dir + "/out/m.exr",
                   "are from different scenes or render settings", dir + "/out");
  const RunResult same = run_softtrace("merge " + tile(0, "--half") + " " + half + " --quiet -o " +
                                       dir + "/out/m.exr");
  EXPECT_EQ(same.status, 0) << same.err;
}

// A tampered display window may not make merge allocate more than render would.
TEST(HostileTiles, HugeDisplayWindowIsRefused) {
  const std::string dir = temp_dir("hostile_display");
  ImageFile tile;
  tile.full_width = 100000;
  tile.full_height = 100000;
  tile.width = tile.height = 1;
  tile.channels = {"A", "B", "G", "R"};
  tile.pixels.assign(4, 0.0f);
  tile.attributes["softtrace/renderHash"] = "0123456789abcdef";
  write_exr(dir + "/huge.exr", tile);
  fs::create_directories(dir + "/out");
  expect_refused("merge " + dir + "/huge.exr -o " + dir + "/out/m.exr",
                 "huge.exr: a 100000x100000 frame; render makes sides of 1 to 16384", dir + "/out");
}

}  // namespace
}  // namespace softtrace::test
