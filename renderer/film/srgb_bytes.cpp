#include "film/srgb_bytes.h"

#include <algorithm>
#include <cmath>

#include "io/image_file.h"

namespace softtrace {

float srgb_encode(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

namespace {

float float_of(uint32_t b) {
  float v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

uint8_t reference_byte(float v) {
  return png_sample(srgb_encode(v));
}

}  // namespace

SrgbBytes::SrgbBytes() {
  threshold_[0] = 0.0f;
  for (int k = 1; k < 256; ++k) {
    uint32_t lo = 0, hi = kOne;  // reference_byte(bits lo) < k <= reference_byte(bits hi)
    while (hi - lo > 1) {
      const uint32_t mid = lo + (hi - lo) / 2;
      (reference_byte(float_of(mid)) >= k ? hi : lo) = mid;
    }
    threshold_[k] = float_of(hi);
  }
  threshold_[256] = INFINITY;
  int k = 0;
  for (uint32_t i = 0; i < start_.size(); ++i) {
    const float first = float_of(i << kShift);
    while (threshold_[k + 1] <= first) ++k;
    start_[i] = uint8_t(k);
  }
}

const SrgbBytes& SrgbBytes::get() {
  static const SrgbBytes table;
  return table;
}

}  // namespace softtrace
