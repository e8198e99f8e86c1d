// `softtrace diff`: OpenImageIO's comparison (ImageBufAlgo::compare) with idiff's pass/fail rules.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cstdio>
#include <filesystem>

#include "commands.h"

namespace softtrace {

namespace {

bool read(OIIO::ImageBuf& buf, const std::string& path) {
  if (!std::filesystem::exists(path)) {
    report_error(path + ": no such file");
    return false;
  }
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    report_error(path + ": cannot read the image: " + buf.geterror());
    return false;
  }
  return true;
}

}  // namespace

int run_diff(const DiffArgs& a) {
  using namespace OIIO;
  ImageBuf A(a.a), B(a.b);
  if (!read(A, a.a) || !read(B, a.b)) return 2;
  if (A.spec().channelnames != B.spec().channelnames) {
    report_error(a.a + " and " + a.b + " have different channels");
    return 2;
  }
  const ROI ra = A.roi(), rb = B.roi();
  if (ra.width() != rb.width() || ra.height() != rb.height()) {
    std::printf("FAILURE: sizes differ (%dx%d vs %dx%d)\n", ra.width(), ra.height(), rb.width(),
                rb.height());
    return 1;
  }

  const auto cr = ImageBufAlgo::compare(A, B, a.fail, a.warn);
  if (cr.error) {
    report_error("cannot compare the images: " + A.geterror() + B.geterror());
    return 2;
  }
  const double npix = double(ra.width()) * ra.height();
  const std::string worst_channel =
      cr.maxc >= 0 && cr.maxc < A.nchannels() ? A.spec().channelnames[cr.maxc] : "?";
  std::printf("  Mean error = %.6g\n  RMS error = %.6g\n  Peak SNR = %.6g\n", cr.meanerror,
              cr.rms_error, cr.PSNR);
  std::printf("  Max error  = %.6g @ (%d, %d, %s)\n", cr.maxerror, cr.maxx, cr.maxy,
              worst_channel.c_str());
  std::printf("  %llu pixels (%.4g%%) over %g\n  %llu pixels (%.4g%%) over %g\n",
              (unsigned long long)cr.nwarn, 100.0 * cr.nwarn / npix, a.warn,
              (unsigned long long)cr.nfail, 100.0 * cr.nfail / npix, a.fail);

  if (!a.out.empty()) {
    ImageBuf D = ImageBufAlgo::absdiff(A, B);
    const std::filesystem::path out(a.out), tmp = out.string() + ".tmp" + out.extension().string();
    if (D.has_error() || !D.write(tmp.string())) {
      std::filesystem::remove(tmp);
      report_error(a.out + ": cannot write the difference image: " + D.geterror());
      return 2;
    }
    std::filesystem::rename(tmp, out);
  }

  const bool fail = cr.nfail > a.failpercent / 100.0 * npix || cr.maxerror > a.hardfail;
  const bool warn = cr.nwarn > a.warnpercent / 100.0 * npix;
  std::printf("%s\n", fail ? "FAILURE" : (warn ? "WARNING" : "PASS"));
  return fail ? 1 : 0;
}

}  // namespace softtrace
