// `softtrace diff`: OpenImageIO's comparison (ImageBufAlgo::compare) with the verdict and report
// of OIIO 2.4's idiff (src/idiff/idiff.cpp), mapped onto softtrace's exit codes: idiff's 0 (pass)
// and 1 (warning) are our 0, its 2 (failure) our 1, its errors our 2. Deliberate differences:
// images of different sizes always fail (idiff pads the smaller with black and may pass), images
// with different channel sets are bad input (idiff compares channels by index), and WARNING is
// printed whenever more than --warnpercent % of pixels exceed --warn (idiff 2.4 only reaches its
// warning branch when some pixel also fails).
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "commands.h"
#include "film.h"

namespace softtrace {

namespace {

namespace fs = std::filesystem;
using OIIO::ImageBuf;

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

bool read(ImageBuf& buf, const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    report_error(path + ": no such file");
    return false;
  }
  buf.reset(path);
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    report_error(path + ": cannot read the image: " + one_line(buf.geterror()));
    return false;
  }
  return true;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

// Brings B's channels into A's order when both have the same set (EXR files may store them in
// another order); returns false when the sets differ.
bool match_channels(const ImageBuf& A, ImageBuf& B) {
  const auto &na = A.spec().channelnames, &nb = B.spec().channelnames;
  if (na == nb) return true;
  if (na.size() != nb.size()) return false;
  std::vector<int> order;
  for (const auto& name : na) {
    const auto it = std::find(nb.begin(), nb.end(), name);
    if (it == nb.end()) return false;
    order.push_back(int(it - nb.begin()));
  }
  B = OIIO::ImageBufAlgo::channels(B, int(order.size()), order, {}, na);
  return !B.has_error();
}

// Shortest text that reads back as the same float, as idiff prints pixel values and thresholds.
std::string shortest(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string pixel_values(const ImageBuf& img, int x, int y) {
  std::string s;
  for (int c = 0; c < img.nchannels(); ++c)
    s += (c ? ", " : "") + shortest(img.getchannel(x, y, 0, c));
  return s;
}

void print_report(const OIIO::ImageBufAlgo::CompareResults& cr, const ImageBuf& A,
                  const ImageBuf& B, long npels, const DiffArgs& a) {
  std::printf("  Mean error = %g\n  RMS error = %g\n  Peak SNR = %g\n  Max error  = %g",
              cr.meanerror, cr.rms_error, cr.PSNR, cr.maxerror);
  if (cr.maxerror != 0) {
    const auto& names = A.spec().channelnames;
    const std::string channel = cr.maxc >= 0 && cr.maxc < int(names.size())
                                    ? names[cr.maxc]
                                    : "channel " + std::to_string(cr.maxc);
    std::printf(" @ (%d, %d, %s)  values are %s vs %s", cr.maxx, cr.maxy, channel.c_str(),
                pixel_values(A, cr.maxx, cr.maxy).c_str(),
                pixel_values(B, cr.maxx, cr.maxy).c_str());
  }
  std::printf("\n  %llu pixels (%.3g%%) over %s\n  %llu pixels (%.3g%%) over %s\n",
              (unsigned long long)cr.nwarn, 100.0 * cr.nwarn / npels, shortest(a.warn).c_str(),
              (unsigned long long)cr.nfail, 100.0 * cr.nfail / npels, shortest(a.fail).c_str());
}

// |A - B| per channel over both images' area (black outside either); 0 where compare() calls the
// values equal, which includes inf against inf (a background depth) and NaN against NaN. A PNG
// holds R,G,B (or the first channel as grey) in 8 bits; an EXR all channels as float.
ImageBuf difference_image(const ImageBuf& A, const ImageBuf& B, bool png) {
  using namespace OIIO;
  const ROI roi = roi_union(A.roi(), B.roi());
  const size_t n = roi.npixels() * size_t(roi.nchannels());
  std::vector<float> pa(n), pb(n);
  A.get_pixels(roi, TypeDesc::FLOAT, pa.data());
  B.get_pixels(roi, TypeDesc::FLOAT, pb.data());
  for (size_t i = 0; i < n; ++i) {
    const float x = pa[i], y = pb[i];
    const bool same =
        x == y || (std::isinf(x) && std::isinf(y)) || (std::isnan(x) && std::isnan(y));
    pa[i] = same ? 0.0f : std::abs(x - y);
  }
  ImageSpec spec(roi, TypeDesc::FLOAT);
  spec.channelnames = A.spec().channelnames;
  ImageBuf D(spec);
  D.set_pixels(roi, TypeDesc::FLOAT, pa.data());
  if (!png) return D;
  const ImageSpec& s = D.spec();
  const int r = s.channelindex("R"), g = s.channelindex("G"), b = s.channelindex("B");
  if (r >= 0 && g >= 0 && b >= 0) return ImageBufAlgo::channels(D, 3, {r, g, b});
  return ImageBufAlgo::channels(D, 1, {0});
}

// Writes to a temporary file beside `path` and renames it over `path` only when complete.
void write_atomically(const ImageBuf& D, const std::string& path, bool png) {
  const fs::path target(path);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::string tmp = (dir / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw std::runtime_error(path + ": cannot create a file in '" + dir.string() + "'");
  ::close(fd);
  ImageBuf out = D;
  if (!png) out.specmod().attribute("compression", "zip");
  const auto format = png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
  if (!out.write(tmp, format, png ? "png" : "openexr")) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path +
                             ": cannot write the difference image: " + one_line(out.geterror()));
  }
  // mkstemp makes the file private; give it the usual permissions of a new file.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  std::error_code ec;
  fs::permissions(tmp, static_cast<fs::perms>(0666 & ~mask), ec);
  fs::rename(tmp, target, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": cannot replace the file: " + ec.message());
  }
}

}  // namespace

int run_diff(const DiffArgs& a) {
  using namespace OIIO;
  if (!a.out.empty()) {
    try {
      check_output_path(a.out);
    } catch (const std::exception& e) {
      report_error(e.what());
      return 2;
    }
  }
  ImageBuf A, B;
  if (!read(A, a.a) || !read(B, a.b)) return 2;
  if (!match_channels(A, B)) {
    report_error(a.a + " and " + a.b + " have different channels (" +
                 joined(A.spec().channelnames) + " vs " + joined(B.spec().channelnames) + ")");
    return 2;
  }

  std::printf("Comparing \"%s\" and \"%s\"\n", a.a.c_str(), a.b.c_str());
  const auto cr = ImageBufAlgo::compare(A, B, a.fail, a.warn, 0.0f, 0.0f);
  // cr.error is also set when any pixel fails (OIIO 2.4), so look at the images' own errors.
  if (A.has_error() || B.has_error()) {
    report_error("cannot compare the images: " + one_line(A.geterror() + B.geterror()));
    return 2;
  }
  // idiff counts percentages against the first image's pixels.
  const long npels = std::max(1L, long(A.spec().width) * A.spec().height * A.spec().depth);
  print_report(cr, A, B, npels, a);

  if (!a.out.empty()) {
    const bool png = !is_exr_path(a.out);
    try {
      write_atomically(difference_image(A, B, png), a.out, png);
    } catch (const std::exception& e) {
      report_error(e.what());
      return 2;
    }
  }

  const bool same_size = A.spec().width == B.spec().width && A.spec().height == B.spec().height &&
                         A.spec().depth == B.spec().depth;
  // idiff 2.4: no failing pixel passes (before the hard threshold is looked at); otherwise too
  // many failing pixels or one beyond the hard threshold fail. Percentages are float, as there.
  const bool fail =
      !same_size ||
      (cr.nfail > 0 && (cr.nfail > a.failpercent / 100.0 * npels || cr.maxerror > a.hardfail));
  const bool warn = cr.nwarn > a.warnpercent / 100.0 * npels;
  if (!same_size)
    std::printf("  sizes differ: %dx%d vs %dx%d\n", A.spec().width, A.spec().height, B.spec().width,
                B.spec().height);
  std::printf("%s\n", fail ? "FAILURE" : (warn ? "WARNING" : "PASS"));
  return fail ? 1 : 0;
}

}  // namespace softtrace
