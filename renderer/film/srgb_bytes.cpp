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

// Where sample k begins if the encoding and the rounding were exact: the decoded midpoint
// (k - 1/2) / 255, as bits. The float functions land within a few units in the last place of it.
uint32_t guess_bits(int k) {
  const double c = (k - 0.5) / 255;
  const double v = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  uint32_t b;
  const float f = float(v);
  std::memcpy(&b, &f, sizeof b);
  return b;
}

// The smallest float v (as bits) with reference_byte(v) >= k, found by stepping one unit in the
// last place at a time from `g` (both functions never decrease); 0 when it is more than 16 steps
// away (or is 0 itself), which the search then finds.
uint32_t step_to_threshold(uint32_t g, int k) {
  constexpr int kSteps = 16;
  constexpr uint32_t kOneBits = 0x3F800000;  // 1.0f
  if (g <= kSteps || g >= kOneBits - kSteps) return 0;
  if (reference_byte(float_of(g)) >= k) {
    for (int i = 0; i < kSteps; ++i, --g)
      if (reference_byte(float_of(g - 1)) < k) return g;
    return 0;
  }
  for (int i = 0; i < kSteps; ++i)
    if (reference_byte(float_of(++g)) >= k) return g;
  return 0;
}

}  // namespace

SrgbBytes::SrgbBytes() {
  threshold_[0] = 0.0f;
  for (int k = 1; k < 256; ++k) {
    // reference_byte(bits lo) < k <= reference_byte(bits hi): a bracket around the guess, widened
    // until it holds, then halved. Every process that writes a PNG builds this table; a search
    // over all of [0, 1] took 30 halvings per sample.
    const uint32_t g = guess_bits(k);
    // The guess is within a few units in the last place of the threshold: step to it, a sample
    // or two a threshold (the search below took about 15).
    if (const uint32_t t = step_to_threshold(g, k)) {
      threshold_[k] = float_of(t);
      continue;
    }
    uint32_t lo = 0, hi = kOne;
    for (uint32_t w = 64; w < kOne; w *= 8) {
      const uint32_t a = g > w ? g - w : 0, b = std::min(g + w, kOne);
      if ((a == 0 || reference_byte(float_of(a)) < k) && reference_byte(float_of(b)) >= k) {
        lo = a, hi = b;
        break;
      }
    }
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
