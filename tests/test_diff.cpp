// `softtrace diff`: it fails perturbed images, reports bad input, writes difference images
// safely, and agrees with OpenImageIO's own idiff on verdicts and counts.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "cli_util.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;
using OIIO::TypeDesc;

// A float image as the tests make it; written to disk as float or half EXR, or 8-bit PNG.
struct Image {
  int w = 0, h = 0;
  std::vector<std::string> channels;
  std::vector<float> px;

  Image(int w_, int h_, std::vector<std::string> names)
      : w(w_), h(h_), channels(std::move(names)), px(size_t(w_) * h_ * channels.size()) {}
  float& at(int x, int y, int c) { return px[(size_t(y) * w + x) * channels.size() + c]; }
  float at(int x, int y, int c) const { return px[(size_t(y) * w + x) * channels.size() + c]; }
  int nc() const { return int(channels.size()); }
};

void write(const Image& img, const std::string& path, TypeDesc format) {
  OIIO::ImageSpec spec(img.w, img.h, img.nc(), TypeDesc::FLOAT);
  spec.channelnames = img.channels;
  OIIO::ImageBuf buf(spec);
  ASSERT_TRUE(buf.set_pixels(buf.roi(), TypeDesc::FLOAT, img.px.data()));
  ASSERT_TRUE(buf.write(path, format)) << buf.geterror();
}

Image read(const std::string& path) {
  OIIO::ImageBuf buf(path);
  EXPECT_TRUE(buf.read(0, 0, true, TypeDesc::FLOAT)) << path << ": " << buf.geterror();
  Image img(buf.spec().width, buf.spec().height, buf.spec().channelnames);
  buf.get_pixels(buf.roi(), TypeDesc::FLOAT, img.px.data());
  return img;
}

// Smooth colours with a little noise, values in [0, 1], fixed seed.
Image test_image(int w, int h, std::vector<std::string> names, unsigned seed) {
  Image img(w, h, std::move(names));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(0, 0.1f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < img.nc(); ++c)
        img.at(x, y, c) = 0.8f * (x + c * y) / float(w + img.nc() * h) + noise(rng);
  return img;
}

// Pixels where some channel differs by more than t (float arithmetic, as OIIO's compare).
int count_over(const Image& a, const Image& b, float t) {
  int n = 0;
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x) {
      bool over = false;
      for (int c = 0; c < a.nc(); ++c) over |= std::abs(a.at(x, y, c) - b.at(x, y, c)) > t;
      n += over;
    }
  return n;
}

float max_difference(const Image& a, const Image& b) {
  float m = 0;
  for (size_t i = 0; i < a.px.size(); ++i) m = std::max(m, std::abs(a.px[i] - b.px[i]));
  return m;
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

// The lines of idiff's report that both tools print: worst pixel, warning and failure counts,
// and the last line (PASS, WARNING or FAILURE).
struct Report {
  std::string max_line, warn_line, fail_line, verdict;
};
Report report(const std::string& out) {
  Report r;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("  Max error", 0) == 0) r.max_line = line;
    if (line.find(" pixels (") != std::string::npos)
      (r.warn_line.empty() ? r.warn_line : r.fail_line) = line;
    if (!line.empty()) r.verdict = line;
  }
  return r;
}

TEST(Diff, PerturbedImageFailsIdenticalPasses) {
  const std::string dir = temp_dir("diff_perturbed");
  const Image a = test_image(32, 24, {"R", "G", "B", "A"}, 1);
  Image b = a;
  b.at(5, 7, 1) += 0.05f;
  write(a, dir + "/a.exr", TypeDesc::FLOAT);
  write(b, dir + "/b.exr", TypeDesc::FLOAT);

  const RunResult same = run_softtrace("diff " + dir + "/a.exr " + dir + "/a.exr");
  EXPECT_EQ(same.status, 0) << same.out << same.err;
  EXPECT_EQ(report(same.out).verdict, "PASS");
  EXPECT_NE(same.out.find("  0 pixels (0%) over 1e-06"), std::string::npos) << same.out;

  const RunResult strict = run_softtrace("diff " + dir + "/a.exr " + dir + "/b.exr --fail 0.02");
  EXPECT_EQ(strict.status, 1) << strict.out << strict.err;
  const Report r = report(strict.out);
  EXPECT_EQ(r.verdict, "FAILURE");
  EXPECT_EQ(r.fail_line, "  1 pixels (0.13%) over 0.02");
  EXPECT_EQ(r.max_line.find("  Max error  = 0.05"), 0u) << r.max_line;
  EXPECT_NE(r.max_line.find("@ (5, 7, G)"), std::string::npos) << r.max_line;

  EXPECT_EQ(run_softtrace("diff " + dir + "/a.exr " + dir + "/b.exr --fail 0.06").status, 0);
  // One failing pixel of 768 is 0.13 %: allowed by 0.2 %, not by 0.1 % or a hard limit.
  const std::string b_args = "diff " + dir + "/a.exr " + dir + "/b.exr --fail 0.02 ";
  EXPECT_EQ(run_softtrace(b_args + "--failpercent 0.2").status, 0);
  EXPECT_EQ(run_softtrace(b_args + "--failpercent 0.1").status, 1);
  EXPECT_EQ(run_softtrace(b_args + "--failpercent 0.2 --hardfail 0.04").status, 1);
}

// The committed reference with the regression test's thresholds: 1 % of pixels changed by 0.01
// fails, 0.3 % passes (regression.sh allows 0.5 %), a change below 0.005 passes.
TEST(Diff, PerturbedReferenceAtRegressionThresholds) {
  const std::string dir = temp_dir("diff_reference");
  const std::string ref = source_path("reference_images/fig12b_soft_blend.exr");
  const Image a = read(ref);
  ASSERT_GT(a.w * a.h, 1000);
  const auto perturbed = [&](double fraction, float by) {
    Image b = a;
    std::mt19937 rng(3);
    std::vector<int> order(a.w * a.h);
    for (size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::shuffle(order.begin(), order.end(), rng);
    for (int i = 0; i < int(fraction * order.size()); ++i) b.px[order[i] * b.nc() + 0] += by;
    write(b, dir + "/b.exr", TypeDesc::FLOAT);
    return run_softtrace("diff " + ref + " " + dir + "/b.exr --fail 0.005 --failpercent 0.5")
        .status;
  };
  EXPECT_EQ(perturbed(0.01, 0.01f), 1);
  EXPECT_EQ(perturbed(0.003, 0.01f), 0);
  EXPECT_EQ(perturbed(0.5, 0.004f), 0);
}

TEST(Diff, BadInputIsOneLineAndExitTwo) {
  const std::string dir = temp_dir("diff_bad");
  const Image rgba = test_image(8, 8, {"R", "G", "B", "A"}, 2);
  write(rgba, dir + "/rgba.exr", TypeDesc::HALF);
  write(test_image(8, 8, {"R", "G", "B"}, 2), dir + "/rgb.exr", TypeDesc::HALF);
  std::ofstream(dir + "/text.exr") << "not an image\n";
  const auto expect_bad = [&](const std::string& args, const std::string& message) {
    const RunResult r = run_softtrace("diff " + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("softtrace: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  };
  expect_bad(dir + "/rgba.exr " + dir + "/missing.exr", "missing.exr: no such file");
  expect_bad(dir + "/missing.exr " + dir + "/rgba.exr", "missing.exr: no such file");
  expect_bad(dir + "/rgba.exr " + dir + "/text.exr", "text.exr: cannot read the image");
  expect_bad(dir + "/rgba.exr " + dir + "/rgb.exr", "different channels (R,G,B,A vs R,G,B)");
  expect_bad(dir + "/rgba.exr " + dir + "/rgba.exr --out " + dir + "/d.tiff",
             "unsupported output format '.tiff'");
  expect_bad(dir + "/rgba.exr " + dir + "/rgba.exr --out " + dir + "/no/d.exr", "does not exist");
  expect_bad(dir + "/rgba.exr " + dir + "/rgba.exr --failpercent 101", "failpercent");
  expect_bad(dir + "/rgba.exr " + dir + "/rgba.exr --fail -1", "fail");
}

TEST(Diff, SizesDifferFailChannelOrderDoesNot) {
  const std::string dir = temp_dir("diff_size");
  const Image a = test_image(16, 12, {"R", "G", "B"}, 4);
  Image wide(20, 12, {"R", "G", "B"});  // a, then black columns
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x)
      for (int c = 0; c < 3; ++c) wide.at(x, y, c) = a.at(x, y, c);
  Image bgr(16, 12, {"B", "G", "R"});
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x)
      for (int c = 0; c < 3; ++c) bgr.at(x, y, 2 - c) = a.at(x, y, c);
  write(a, dir + "/a.exr", TypeDesc::FLOAT);
  write(wide, dir + "/wide.exr", TypeDesc::FLOAT);
  write(bgr, dir + "/bgr.exr", TypeDesc::FLOAT);

  const RunResult r = run_softtrace("diff " + dir + "/a.exr " + dir + "/wide.exr --fail 1");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("sizes differ: 16x12 vs 20x12"), std::string::npos) << r.out;
  EXPECT_EQ(report(r.out).verdict, "FAILURE");
  // Same channels in another order are matched by name.
  const RunResult same = run_softtrace("diff " + dir + "/a.exr " + dir + "/bgr.exr");
  EXPECT_EQ(same.status, 0) << same.out << same.err;
  EXPECT_NE(same.out.find("  Max error  = 0\n"), std::string::npos) << same.out;
}

TEST(Diff, DifferenceImageIsWrittenWholeAsExrOrPng) {
  const std::string dir = temp_dir("diff_out");
  Image a(6, 4, {"R", "G", "B", "A", "Z"}), b = a;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) {
      for (int c = 0; c < 4; ++c) a.at(x, y, c) = b.at(x, y, c) = 0.25f * c;
      a.at(x, y, 4) = b.at(x, y, 4) = x < 3 ? INFINITY : float(x);  // background depth
    }
  b.at(1, 2, 0) = 0.5f;  // R: 0 -> 0.5
  b.at(4, 1, 4) = 7.5f;  // Z: 4 -> 7.5
  write(a, dir + "/a.exr", TypeDesc::FLOAT);
  write(b, dir + "/b.exr", TypeDesc::FLOAT);
  std::ofstream(dir + "/d.exr") << "old";
  std::ofstream(dir + "/d.png") << "old";

  // A failed run leaves an existing output alone.
  EXPECT_EQ(
      run_softtrace("diff " + dir + "/a.exr " + dir + "/none.exr --out " + dir + "/d.exr").status,
      2);
  EXPECT_EQ(read_file(dir + "/d.exr"), "old");

  const std::string args = "diff " + dir + "/a.exr " + dir + "/b.exr --out ";
  EXPECT_EQ(run_softtrace(args + dir + "/d.exr").status, 1);
  EXPECT_EQ(run_softtrace(args + dir + "/d.png").status, 1);
  const Image d = read(dir + "/d.exr");
  ASSERT_EQ(d.channels, a.channels);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x)
      for (int c = 0; c < 5; ++c) {
        const float expected = (x == 1 && y == 2 && c == 0)   ? 0.5f
                               : (x == 4 && y == 1 && c == 4) ? 3.5f
                                                              : 0;
        EXPECT_EQ(d.at(x, y, c), expected) << x << "," << y << " channel " << c;
      }
  const Image p = read(dir + "/d.png");
  EXPECT_EQ(p.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_NEAR(p.at(1, 2, 0), 0.5f, 1.0f / 255);
  EXPECT_EQ(p.at(0, 0, 0), 0.0f);
  // Only the inputs and the two outputs: no temporary file is left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 4);
}

// `softtrace diff` against `idiff -v` on the same files and options: the same verdict (idiff's
// 0 pass and 1 warning are our 0, its 2 failure our 1) and the same report lines.
struct Case {
  std::string what, a, b, options;
};

int expected_status(int idiff_status) {
  return idiff_status <= 1 ? 0 : idiff_status == 2 ? 1 : 2;
}

TEST(Diff, AgreesWithIdiff) {
  const std::string idiff = IDIFF_BIN;
  ASSERT_TRUE(fs::exists(idiff)) << "idiff not found (apt-get install openimageio-tools)";
  const std::string dir = temp_dir("diff_idiff");
  const auto path = [&](const std::string& name) { return dir + "/" + name; };
  std::vector<Case> cases;

  // Float EXR, RGBA: ~8 % of pixels changed in one channel by up to 0.06.
  const Image a = test_image(64, 48, {"R", "G", "B", "A"}, 5);
  Image b = a;
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(0, 1), delta(-0.06f, 0.06f);
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x)
      if (u(rng) < 0.08f) b.at(x, y, int(4 * u(rng)) % 4) += delta(rng);
  write(a, path("a.exr"), TypeDesc::FLOAT);
  write(b, path("b.exr"), TypeDesc::FLOAT);
  const float m = max_difference(a, b);
  const int npix = a.w * a.h, n03 = count_over(a, b, 0.03f);
  ASSERT_GT(n03, 20);
  ASSERT_LT(n03, npix / 10);
  const std::string ab = path("a.exr") + " " + path("b.exr");
  cases.push_back({"exr defaults", ab, "", ""});
  cases.push_back({"exr identical", path("a.exr"), path("a.exr"), ""});
  cases.push_back({"exr fail just below max", ab, "", "-fail " + number(m * 0.999)});
  cases.push_back({"exr fail just above max", ab, "", "-fail " + number(m * 1.001)});
  for (double k : {n03 - 0.5, double(n03), n03 + 0.5})
    cases.push_back({"exr failpercent around the count", ab, "",
                     "-fail 0.03 -failpercent " + number(100.0 * k / npix)});
  cases.push_back({"exr hardfail below max", ab, "",
                   "-fail 0.03 -failpercent 50 -hardfail " + number(m * 0.99)});
  cases.push_back({"exr hardfail above max", ab, "",
                   "-fail 0.03 -failpercent 50 -hardfail " + number(m * 1.01)});
  cases.push_back({"exr hardfail with no failing pixel", ab, "",
                   "-fail " + number(m * 1.01) + " -hardfail " + number(m * 0.5)});
  cases.push_back({"exr warnings only", ab, "", "-warn 0.01 -fail 0.1"});
  cases.push_back({"exr warnings and failures", ab, "",
                   "-warn 0.01 -warnpercent 1 -fail 0.03 -failpercent 50"});

  // The same image stored as half: rounding differences only.
  write(a, path("a_half.exr"), TypeDesc::HALF);
  const std::string ah = path("a.exr") + " " + path("a_half.exr");
  cases.push_back({"half rounding, default", ah, "", ""});
  cases.push_back({"half rounding, 0.001", ah, "", "-fail 0.001"});

  // 8-bit PNG, RGB: some pixels 1 to 4 levels off.
  write(test_image(40, 30, {"R", "G", "B"}, 7), path("p.png"), TypeDesc::UINT8);
  const Image p = read(path("p.png"));  // the values as quantized
  Image q = p;
  for (int i = 0; i < 120; ++i) {
    const int x = int(u(rng) * q.w) % q.w, y = int(u(rng) * q.h) % q.h, c = i % 3;
    q.at(x, y, c) = std::min(1.0f, q.at(x, y, c) + float(1 + i % 4) / 255);
  }
  write(q, path("q.png"), TypeDesc::UINT8);
  const std::string pq = path("p.png") + " " + path("q.png");
  const int n_png3 = count_over(p, read(path("q.png")), 2.5f / 255);
  ASSERT_GT(n_png3, 10);
  cases.push_back({"png defaults", pq, "", ""});
  cases.push_back({"png fail below 3 levels", pq, "", "-fail 0.0117"});
  cases.push_back({"png fail above 3 levels", pq, "", "-fail 0.0118"});
  cases.push_back({"png fail above 4 levels", pq, "", "-fail 0.0157"});
  cases.push_back({"png failpercent just above", pq, "",
                   "-fail 0.0098 -failpercent " + number(100.0 * (n_png3 + 0.5) / (40 * 30))});
  cases.push_back({"png failpercent just below", pq, "",
                   "-fail 0.0098 -failpercent " + number(100.0 * (n_png3 - 0.5) / (40 * 30))});

  // Different sizes with different content in the extra columns: both fail.
  Image wide = test_image(72, 48, {"R", "G", "B", "A"}, 5);
  write(wide, path("wide.exr"), TypeDesc::FLOAT);
  cases.push_back({"different sizes", path("a.exr") + " " + path("wide.exr"), "", "-fail 0.05"});
  cases.push_back({"different sizes, swapped", path("wide.exr") + " " + path("a.exr"), "", ""});

  // Depth channels: inf (background) in both matches; inf against a number fails, NaN too.
  Image z1(20, 10, {"R", "G", "B", "Z"});
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x) {
      for (int c = 0; c < 3; ++c) z1.at(x, y, c) = 0.1f * c;
      z1.at(x, y, 3) = x < 8 ? INFINITY : 10.0f + x;
    }
  Image z2 = z1;
  z2.at(2, 2, 3) = 12;
  z2.at(3, 3, 3) = 13;
  z2.at(12, 5, 3) = NAN;
  z2.at(15, 6, 0) = 0.2f;
  write(z1, path("z1.exr"), TypeDesc::FLOAT);
  write(z2, path("z2.exr"), TypeDesc::FLOAT);
  cases.push_back({"depth inf", path("z1.exr") + " " + path("z1.exr"), "", ""});
  cases.push_back({"depth inf and nan", path("z1.exr") + " " + path("z2.exr"), "", "-fail 0.5"});

  for (const Case& c : cases) {
    SCOPED_TRACE(c.what + ": " + c.options);
    const std::string files = c.a + (c.b.empty() ? "" : " " + c.b);
    std::string ours_options = c.options;  // idiff's -fail is our --fail
    for (size_t i = 0; (i = ours_options.find(" -", i)) != std::string::npos; i += 2)
      ours_options.insert(i + 1, "-");
    if (ours_options.rfind("-", 0) == 0) ours_options.insert(0, "-");
    const RunResult theirs = run_command(idiff + " -v " + c.options + " " + files);
    const RunResult ours = run_softtrace("diff " + files + " " + ours_options);
    ASSERT_LE(theirs.status, 2) << theirs.out << theirs.err;
    const Report rt = report(theirs.out), ro = report(ours.out);
    const bool sizes_differ = ours.out.find("sizes differ") != std::string::npos;
    EXPECT_EQ(ours.status, expected_status(theirs.status)) << "idiff:\n"
                                                           << theirs.out << "softtrace:\n"
                                                           << ours.out << ours.err;
    EXPECT_EQ(ro.max_line, rt.max_line);
    EXPECT_EQ(ro.warn_line, rt.warn_line);
    EXPECT_EQ(ro.fail_line, rt.fail_line);
    EXPECT_FALSE(ro.fail_line.empty());
    if (theirs.status == 2) {
      EXPECT_EQ(ro.verdict, "FAILURE");
    }
    if (theirs.status == 0 && !sizes_differ) {
      EXPECT_NE(ro.verdict, "FAILURE");
    }
  }
  // Our own count of the 0.03 case matches what both print.
  const RunResult r = run_softtrace("diff " + ab + " --fail 0.03");
  EXPECT_NE(r.out.find("  " + std::to_string(n03) + " pixels ("), std::string::npos) << r.out;

  // The one deliberate difference: idiff pads a smaller image with black and can pass; a
  // different size always fails here.
  Image padded(72, 48, {"R", "G", "B", "A"});
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x)
      for (int c = 0; c < 4; ++c) padded.at(x, y, c) = a.at(x, y, c);
  write(padded, path("padded.exr"), TypeDesc::FLOAT);
  const std::string ap = path("a.exr") + " " + path("padded.exr");
  EXPECT_EQ(run_command(idiff + " " + ap).status, 0);
  EXPECT_EQ(run_softtrace("diff " + ap).status, 1);
}

}  // namespace
}  // namespace softtrace::test
