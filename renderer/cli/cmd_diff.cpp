// `softtrace diff`: OpenImageIO 2.4's idiff without OpenImageIO: the same options (single- or
// double-dash), report lines, verdict and exit codes (0 pass, 1 warning, 2 failure, 4 a file
// that cannot be read or written). Deliberate differences: images of different sizes always fail
// (idiff pads the smaller with black and may pass); channels are matched by name and only those
// both images have are compared, with a note (idiff compares by index, a missing channel as 0);
// the report is printed on a pass too; a pixel with NaN, or an infinity against anything but the
// same infinity, fails the comparison (idiff passes NaN against NaN); bad usage exits 2 (idiff: 1,
// its warning code, which would let a mistyped command pass a script that accepts warnings).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "cli/commands.h"
#include "film/film.h"
#include "io/image_compare.h"
#include "io/image_file.h"

namespace softtrace {

namespace {

enum DiffStatus { kPass = 0, kWarn = 1, kFail = 2, kFileError = 4 };

const char* const kDiffExtensions[] = {".exr", ".png", nullptr};

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t comma; (comma = list.find(',', start)) != std::string::npos; start = comma + 1)
    out.push_back(list.substr(start, comma - start));
  out.push_back(list.substr(start));
  return out;
}

// Shortest text that reads back as the same float, as idiff prints pixel values and thresholds.
std::string shortest(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// The channels to compare: those named by --channels, or A's channels that B has too.
ChannelPairs pair_channels(const ImageFile& A, const ImageFile& B, const std::string& only) {
  ChannelPairs p;
  const std::vector<std::string> wanted = only.empty() ? A.channels : split(only);
  for (const auto& name : wanted) {
    const int ia = A.channel(name), ib = B.channel(name);
    if (!only.empty() && (ia < 0 || ib < 0))
      throw std::invalid_argument("--channels: '" + name + "' is not in both images (" +
                                  joined(A.channels) + " vs " + joined(B.channels) + ")");
    if (ia >= 0 && ib >= 0) {
      p.a.push_back(ia);
      p.b.push_back(ib);
    }
  }
  return p;
}

std::string pixel_values(const ImageFile& img, const std::vector<int>& channels, int x, int y) {
  std::string s;
  x -= img.x0;
  y -= img.y0;
  const bool inside = x >= 0 && y >= 0 && x < img.width && y < img.height;
  for (size_t c = 0; c < channels.size(); ++c)
    s += (c ? ", " : "") + shortest(inside ? img.at(x, y, channels[c]) : 0.0f);
  return s;
}

void print_report(const CompareResults& cr, const ImageFile& A, const ImageFile& B,
                  const ChannelPairs& pairs, long long npels, const DiffArgs& a) {
  std::printf("  Mean error = %g\n  RMS error = %g\n  Peak SNR = %g\n  Max error  = %g",
              cr.meanerror, cr.rms_error, cr.PSNR, cr.maxerror);
  if (cr.maxerror != 0)
    std::printf(" @ (%d, %d, %s)  values are %s vs %s", cr.maxx, cr.maxy,
                A.channels[pairs.a[cr.maxc]].c_str(),
                pixel_values(A, pairs.a, cr.maxx, cr.maxy).c_str(),
                pixel_values(B, pairs.b, cr.maxx, cr.maxy).c_str());
  std::printf("\n  %lld pixels (%.3g%%) over %s\n  %lld pixels (%.3g%%) over %s\n", cr.nwarn,
              100.0 * cr.nwarn / npels, shortest(a.warn).c_str(), cr.nfail,
              100.0 * cr.nfail / npels, shortest(a.fail).c_str());
  if (cr.nonfinite > 0)
    std::printf("  %lld pixels (%.3g%%) with NaN or infinite values (a failure)\n", cr.nonfinite,
                100.0 * cr.nonfinite / npels);
}

// idiff 2.4's verdict: up to -allowfailures failing pixels pass whatever else is true; beyond
// that, too many failing pixels or one beyond -hardfail fail, and too many warning pixels or one
// beyond -hardwarn warn. Percentages are float, as there.
DiffStatus verdict(const CompareResults& cr, long long npels, const DiffArgs& a) {
  if (cr.nonfinite > 0) return kFail;  // not idiff's: NaN or a lone infinity is never a match
  if (cr.nfail <= a.allowfailures) return kPass;
  if (cr.nfail > a.failpercent / 100.0 * npels || cr.maxerror > a.hardfail) return kFail;
  if (cr.nwarn > a.warnpercent / 100.0 * npels || cr.maxerror > a.hardwarn) return kWarn;
  return kPass;
}

void write_difference(const ImageFile& d, const std::string& path) {
  const std::string target = resolve_output_target(path);
  remove_stale_temporaries(target, process_start_time());
  const std::string tmp = create_pending_temp(target, path);
  try {
    if (is_exr_path(path)) {
      write_exr(tmp, d);
    } else {  // 8-bit: R,G,B where there are, else the first channel as grey
      const int r = d.channel("R"), g = d.channel("G"), b = d.channel("B");
      const std::vector<int> keep =
          r >= 0 && g >= 0 && b >= 0 ? std::vector<int>{r, g, b} : std::vector<int>{0};
      ImageFile png = d;
      png.channels = keep.size() == 3 ? std::vector<std::string>{"R", "G", "B"}
                                      : std::vector<std::string>{"Y"};
      png.pixels.clear();
      for (size_t i = 0; i < size_t(d.width) * d.height; ++i)
        for (int c : keep) png.pixels.push_back(d.pixels[i * d.channels.size() + c]);
      write_png(tmp, png, false);
    }
  } catch (const std::exception& e) {
    abandon_pending_writes();
    throw std::runtime_error(path + ": cannot write the difference image: " + e.what());
  }
  try {
    commit_temp(tmp, target, path);
  } catch (...) {
    abandon_pending_writes();
    throw;
  }
  forget_pending_writes();
}

}  // namespace

std::vector<std::string> idiff_style_arguments(const std::vector<std::string>& args) {
  static const char* const kLong[] = {
      "fail",  "failpercent", "failrelative", "hardfail", "allowfailures",
      "warn",  "warnpercent", "warnrelative", "hardwarn", "abs",
      "scale", "od",          nullptr};
  std::vector<std::string> out;
  for (const auto& arg : args) {
    bool idiff_long = false;
    for (auto name = kLong; *name && !idiff_long; ++name)
      idiff_long = arg == std::string("-") + *name;
    out.push_back(idiff_long ? "-" + arg : arg);
  }
  return out;
}

int run_diff(const DiffArgs& a) {
  if (!a.out.empty()) {
    try {
      check_output_path(a.out, kDiffExtensions);
    } catch (const std::exception& e) {
      report_error(e.what());
      return output_extension(a.out) == ".exr" || output_extension(a.out) == ".png" ? kFileError
                                                                                    : kFail;
    }
  }
  ImageFile A, B;
  try {
    A = read_image(a.a);
    B = read_image(a.b);
  } catch (const std::exception& e) {
    report_error(one_line(e.what()));
    return kFileError;
  }
  ChannelPairs pairs;
  try {
    pairs = pair_channels(A, B, a.channels);
  } catch (const std::exception& e) {
    report_error(e.what());
    return kFail;
  }
  if (pairs.a.empty()) {
    report_error(a.a + " and " + a.b + " have no channel in common (" + joined(A.channels) +
                 " vs " + joined(B.channels) + ")");
    return kFail;
  }

  // Data windows far apart (a tampered header) would make the union, and the work, unbounded.
  if (union_pixels(A, B) > (1LL << 28)) {
    report_error(a.a + " and " + a.b + ": their data windows span more than 2^28 pixels together");
    return kFileError;
  }
  if (!a.quiet) std::printf("Comparing \"%s\" and \"%s\"\n", a.a.c_str(), a.b.c_str());
  std::vector<std::string> compared;
  for (int c : pairs.a) compared.push_back(A.channels[c]);
  if (!a.quiet && (compared != A.channels || compared != B.channels))
    std::printf("  note: comparing channels %s (%s has %s, %s has %s)\n", joined(compared).c_str(),
                a.a.c_str(), joined(A.channels).c_str(), a.b.c_str(), joined(B.channels).c_str());

  const CompareResults cr =
      compare_images(A, B, pairs, {a.fail, a.warn, a.failrelative, a.warnrelative});
  // idiff counts percentages against the first image's pixels.
  const long long npels = std::max(1LL, (long long)A.width * A.height);
  const bool same_size = A.width == B.width && A.height == B.height && A.x0 == B.x0 && A.y0 == B.y0;
  const DiffStatus status = same_size ? verdict(cr, npels, a) : kFail;
  if (!a.quiet) {
    print_report(cr, A, B, pairs, npels, a);
    if (!same_size)
      std::printf("  sizes differ: %dx%d vs %dx%d\n", A.width, A.height, B.width, B.height);
    std::printf("%s\n", status == kFail ? "FAILURE" : (status == kWarn ? "WARNING" : "PASS"));
  } else if (status == kFail) {
    std::fprintf(stderr, "FAILURE\n");
  }

  if (!a.out.empty() && (cr.maxerror != 0 || !a.out_only_if_different)) {
    try {
      write_difference(difference_image(A, B, pairs, a.abs, a.scale), a.out);
    } catch (const std::exception& e) {
      report_error(one_line(e.what()));
      return kFileError;
    }
  }
  return status;
}

}  // namespace softtrace
