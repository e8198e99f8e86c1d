#include "io/image_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softtrace {

namespace {

struct Window {
  int x0, y0, x1, y1;  // [x0, x1) x [y0, y1) in display coordinates
};

Window union_window(const ImageFile& A, const ImageFile& B) {
  return {std::min(A.x0, B.x0), std::min(A.y0, B.y0), std::max(A.x0 + A.width, B.x0 + B.width),
          std::max(A.y0 + A.height, B.y0 + B.height)};
}

float value(const ImageFile& img, int x, int y, int c) {
  x -= img.x0;
  y -= img.y0;
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return 0.0f;
  return img.at(x, y, c);
}

bool same_non_finite(float a, float b) {
  return std::isnan(a) == std::isnan(b) && std::isinf(a) == std::isinf(b);
}

}  // namespace

long long union_pixels(const ImageFile& A, const ImageFile& B) {
  // In 64 bits: read_image bounds each window's corners by 2^30, not their distance.
  using L = long long;
  const L w = std::max(L(A.x0) + A.width, L(B.x0) + B.width) - std::min(L(A.x0), L(B.x0));
  const L h = std::max(L(A.y0) + A.height, L(B.y0) + B.height) - std::min(L(A.y0), L(B.y0));
  return w * h;
}

CompareResults compare_images(const ImageFile& A, const ImageFile& B, const ChannelPairs& pairs,
                              const CompareThresholds& t) {
  CompareResults r;
  const Window w = union_window(A, B);
  const int nc = int(pairs.a.size());
  const long long npels = (long long)(w.x1 - w.x0) * (w.y1 - w.y0);
  float maxval = 1.0f;  // PSNR's peak: 1, or the largest magnitude in either image
  double total = 0, total_sq = 0;
  // Sums per batch of pixels, as OpenImageIO does, so that the means round the same way.
  constexpr int kBatch = 4096;
  double batch = 0, batch_sq = 0;
  long long in_batch = 0;
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x) {
      bool warned = false, failed = false, nonfinite = false;
      for (int c = 0; c < nc; ++c) {
        const float a = value(A, x, y, pairs.a[c]), b = value(B, x, y, pairs.b[c]);
        if (!std::isfinite(a) || !std::isfinite(b)) {
          if (!nonfinite && !(a == b)) {  // NaN anywhere, or not the same infinity
            ++r.nonfinite;
            nonfinite = true;
          }
          if (same_non_finite(a, b)) continue;
          if (std::isfinite(r.maxerror)) {  // non-finite errors trump finite ones
            r.maxerror = std::numeric_limits<float>::infinity();
            r.maxx = x, r.maxy = y, r.maxc = c;
            continue;
          }
        }
        const float aabs = std::abs(a), babs = std::abs(b);
        const double meanabs = aabs * (1 - 0.5) + babs * 0.5;
        maxval = std::max(maxval, std::max(aabs, babs));
        const double f = std::abs(a - b);  // the float difference, as there
        const double rel = meanabs > 0.0 ? f / meanabs : 0.0;
        batch += f;
        batch_sq += f * f;
        // !(f <= t) so that a NaN difference counts.
        if (!(f <= r.maxerror)) {
          r.maxerror = f;
          r.maxx = x, r.maxy = y, r.maxc = c;
        }
        if (!warned && !(f <= t.warn) && !(rel <= t.warnrelative)) {
          ++r.nwarn;
          warned = true;
        }
        if (!failed && !(f <= t.fail) && !(rel <= t.failrelative)) {
          ++r.nfail;
          failed = true;
        }
      }
      if (++in_batch == kBatch) {
        total += batch;
        total_sq += batch_sq;
        batch = batch_sq = 0;
        in_batch = 0;
      }
    }
  total += batch;
  total_sq += batch_sq;
  const double nvals = double(npels) * nc;
  r.meanerror = total / nvals;
  r.rms_error = std::sqrt(total_sq / nvals);
  r.PSNR = 20.0 * std::log10(maxval / r.rms_error);
  return r;
}

ImageFile difference_image(const ImageFile& A, const ImageFile& B, const ChannelPairs& pairs,
                           bool absolute, float scale) {
  const Window w = union_window(A, B);
  ImageFile d;
  d.full_width = std::max(A.full_width, B.full_width);
  d.full_height = std::max(A.full_height, B.full_height);
  d.x0 = w.x0;
  d.y0 = w.y0;
  d.width = w.x1 - w.x0;
  d.height = w.y1 - w.y0;
  for (int c : pairs.a) d.channels.push_back(A.channels[c]);
  const size_t nc = pairs.a.size();
  d.pixels.resize(size_t(d.width) * d.height * nc);
  size_t i = 0;
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x)
      for (size_t c = 0; c < nc; ++c, ++i) {
        const float a = value(A, x, y, pairs.a[c]), b = value(B, x, y, pairs.b[c]);
        const bool same =
            a == b || ((!std::isfinite(a) || !std::isfinite(b)) && same_non_finite(a, b));
        const float v = same ? 0.0f : (absolute ? std::abs(a - b) : a - b);
        d.pixels[i] = v * scale;
      }
  return d;
}

}  // namespace softtrace
