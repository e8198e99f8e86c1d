// Per-pixel comparison of two images, with OpenImageIO's arithmetic (ImageBufAlgo::compare as
// idiff 2.4 uses it), so that `softtrace diff` reports the same numbers as idiff.
#pragma once

#include <vector>

#include "io/image_file.h"

namespace softtrace {

struct CompareThresholds {
  float fail = 1e-6f, warn = 1e-6f, failrelative = 0, warnrelative = 0;
};

struct CompareResults {
  double meanerror = 0, rms_error = 0, PSNR = 0, maxerror = 0;
  int maxx = 0, maxy = 0, maxc = 0;  // maxc indexes the compared channels
  long long nwarn = 0, nfail = 0;
  // Pixels with a NaN in either image, or an infinity against anything but the same infinity
  // (a depth of +inf where nothing was hit matches +inf). Not in idiff: a failure whatever the
  // thresholds (idiff passes NaN against NaN with a Max error of 0).
  long long nonfinite = 0;
};

// The channels compared: index pairs into A's and B's channels.
struct ChannelPairs {
  std::vector<int> a, b;
};

// The pixels of the union of both data windows (what compare_images visits).
long long union_pixels(const ImageFile& A, const ImageFile& B);

// Compares the channels `pairs` over the union of both data windows (a pixel outside one image's
// window is black there). A pixel warns (fails) when some channel differs by more than the
// threshold and, if a relative threshold is set, by more than that fraction of the channel's
// mean magnitude. The same infinity in both is equal; otherwise the first non-finite mismatch
// only makes the largest error infinite (as OpenImageIO does, which also calls NaN against NaN
// equal), and every pixel with one counts in `nonfinite`.
CompareResults compare_images(const ImageFile& A, const ImageFile& B, const ChannelPairs& pairs,
                              const CompareThresholds& t);

// A - B (|A - B| with `absolute`) times `scale` over the union of the data windows, with A's
// names for the compared channels. Where compare_images calls two values equal, 0.
ImageFile difference_image(const ImageFile& A, const ImageFile& B, const ChannelPairs& pairs,
                           bool absolute, float scale);

}  // namespace softtrace
