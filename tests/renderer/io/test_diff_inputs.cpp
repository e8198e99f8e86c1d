// `softtrace diff` on values idiff gets wrong or lets through (issue 35): NaN and lone
// infinities fail the comparison, and a 16-bit PNG is read as stored (sRGB-encoded, as an 8-bit
// one), the way OpenImageIO reads it.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "cli_util.h"
#include "io/image_file.h"

namespace softtrace::test {
namespace {

// A w x h image of `nc` channels from `value(x, y, c)`, written by OpenImageIO as `format`.
template <class Value>
void write_image(const std::string& path, int w, int h, int nc, OIIO::TypeDesc format, Value value,
                 std::vector<std::string> names = {}) {
  OIIO::ImageSpec spec(w, h, nc, OIIO::TypeDesc::FLOAT);
  if (!names.empty()) spec.channelnames = names;
  std::vector<float> px(size_t(w) * h * nc);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < nc; ++c) px[(size_t(y) * w + x) * nc + c] = value(x, y, c);
  OIIO::ImageBuf buf(spec);
  ASSERT_TRUE(buf.set_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, px.data()));
  ASSERT_TRUE(buf.write(path, format)) << buf.geterror();
}

float ramp(int x, int y, int c) {
  return float((x * 7 + y * 13 + c * 29) % 97) / 96.0f;
}

// NaN against NaN passed with "Max error = 0" (as in idiff); now any NaN, or an infinity
// against anything but the same infinity, fails, with a line saying how many pixels.
TEST(DiffNonFinite, NaNAndLoneInfinitiesFail) {
  const std::string dir = temp_dir("diff_nonfinite");
  const auto with = [&](const std::string& name, float special, int at) {
    write_image(
        dir + "/" + name + ".exr", 8, 6, 4, OIIO::TypeDesc::FLOAT,
        [&](int x, int y, int c) { return x + 8 * y == at && c == 0 ? special : ramp(x, y, c); },
        {"R", "G", "B", "Z"});
    return dir + "/" + name + ".exr";
  };
  const std::string nan_a = with("nan_a", NAN, 5), nan_b = with("nan_b", NAN, 5),
                    inf_a = with("inf_a", INFINITY, 5), inf_b = with("inf_b", INFINITY, 5),
                    minus_inf = with("minus_inf", -INFINITY, 5), plain = with("plain", 0.5f, -1);
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {nan_a, nan_b}, {nan_a, plain}, {plain, nan_b}, {inf_a, plain}, {inf_a, minus_inf}}) {
    const RunResult r = run_softtrace("diff " + a + " " + b + " -failpercent 50 -allowfailures 3");
    EXPECT_EQ(r.status, 2) << a << " vs " << b << "\n" << r.out;
    EXPECT_NE(r.out.find("  1 pixels (2.08%) with NaN or infinite values (a failure)"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("FAILURE"), std::string::npos) << r.out;
  }
  // The same infinity in both (a depth of +inf where nothing was hit) is a match.
  const RunResult same = run_softtrace("diff " + inf_a + " " + inf_b);
  EXPECT_EQ(same.status, 0) << same.out;
  EXPECT_EQ(same.out.find("NaN or infinite"), std::string::npos) << same.out;
}

// libpng's simplified reader took a 16-bit PNG without a gAMA chunk for linear data and encoded
// it to sRGB again, so the same picture at 16 and 8 bits differed by up to 0.2 where idiff
// passes them. Now the samples are divided by 65535, as OpenImageIO does.
TEST(DiffPng16, SixteenBitPngIsReadAsStored) {
  const std::string dir = temp_dir("diff_png16");
  write_image(dir + "/p16.png", 32, 24, 3, OIIO::TypeDesc::UINT16, ramp);
  write_image(dir + "/p8.png", 32, 24, 3, OIIO::TypeDesc::UINT8, ramp);
  const ImageFile img = read_image(dir + "/p16.png");
  ASSERT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B"}));
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) {
        const float stored = std::round(ramp(x, y, c) * 65535.0f);
        ASSERT_EQ(img.at(x, y, c), stored * (1.0f / 65535.0f)) << x << "," << y << "," << c;
      }
  // Quantising to 8 bits moves a value by at most 1/510.
  const std::string files = dir + "/p16.png " + dir + "/p8.png -fail 0.002";
  const RunResult idiff = run_command(std::string(IDIFF_BIN) + " " + files);
  const RunResult ours = run_softtrace("diff " + files);
  EXPECT_EQ(idiff.status, 0) << idiff.out;
  EXPECT_EQ(ours.status, 0) << ours.out;
  // With alpha, grey, and grey with alpha, 16 bits give the 8-bit picture's channels.
  for (int nc : {1, 2, 4}) {
    const std::string p = dir + "/c" + std::to_string(nc) + ".png";
    write_image(p, 4, 3, nc, OIIO::TypeDesc::UINT16, ramp);
    EXPECT_EQ(read_image(p).channels.size(), size_t(nc));
  }
}

// OpenEXR allocates an attribute's declared size before reading it: a 1.5 KB file whose
// pixelAspectRatio claimed 1.9 GB made the diff fuzzer run out of memory. The size is now checked
// against what the file holds, and the file refused with the attribute named.
TEST(DiffTamperedExr, AnAttributeLargerThanTheFileIsRefused) {
  const std::string dir = temp_dir("diff_tampered_exr");
  const std::string good = dir + "/good.exr", bad = dir + "/bad.exr";
  write_image(good, 8, 6, 4, OIIO::TypeDesc::FLOAT, ramp, {"R", "G", "B", "A"});
  std::string bytes = read_file(good);
  const std::string key = std::string("pixelAspectRatio") + '\0' + "float" + '\0';
  const size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  const char size[4] = {0, 0, 0, 0x70};  // 1,879,048,192 bytes
  bytes.replace(at + key.size(), 4, size, 4);
  std::ofstream(bad, std::ios::binary) << bytes;
  const RunResult r = run_softtrace("diff " + bad + " " + good);
  EXPECT_EQ(r.status, 4) << r.out;
  EXPECT_NE(r.err.find("attribute 'pixelAspectRatio' declares 1879048192 bytes"), std::string::npos)
      << r.err;
  EXPECT_EQ(run_softtrace("diff " + good + " " + good).status, 0);
}

// OpenEXR reads a channel list (and a fixed-size or preview attribute) by its contents, not by
// its declared size: a channel list declared one byte short made OpenEXR read on from a place
// the size check never walked, where a string claimed 1.8 GB (the diff fuzzer's find). A value
// that does not take exactly its declared size is refused.
TEST(DiffTamperedExr, AValueThatDoesNotTakeItsDeclaredSizeIsRefused) {
  const std::string dir = temp_dir("diff_tampered_exr_size");
  const std::string good = dir + "/good.exr";
  write_image(good, 8, 6, 4, OIIO::TypeDesc::FLOAT, ramp, {"R", "G", "B", "A"});
  for (const std::string& key : {std::string("channels") + '\0' + "chlist" + '\0',
                                 std::string("pixelAspectRatio") + '\0' + "float" + '\0'}) {
    std::string bytes = read_file(good);
    const size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    --bytes[at + key.size()];  // the size's low byte: one short (the sizes here are < 256)
    const std::string bad = dir + "/bad.exr";
    std::ofstream(bad, std::ios::binary) << bytes;
    const RunResult r = run_softtrace("diff " + bad + " " + good);
    EXPECT_EQ(r.status, 4) << r.out;
    EXPECT_NE(r.err.find("value takes"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace softtrace::test
