// Linear values to 8-bit sRGB samples, as a PNG stores them: png_sample(srgb_encode(v)), the
// sRGB transfer function (IEC 61966-2-1) then rounding to 0..255, without a pow per sample.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

namespace softtrace {

// The sRGB encoding of a linear value clamped to [0, 1] (NaN stays NaN).
float srgb_encode(float v);

// Exactly png_sample(srgb_encode(v)) for every float v, NaN included (0), found among 255
// thresholds: threshold k is the smallest float whose sample is k. Non-negative floats order as
// their bit patterns do, so each threshold is a binary search over the patterns of [0, 1]; the
// encoding and the rounding never decrease, so the sample is the number of thresholds at or below
// v (checked against the two functions for every float of [0, 1]). A bucket is the floats
// sharing their top 16 bits: `start` holds the sample of a bucket's first float, at or below that
// of any float in it, and the lookup steps up from there (a bucket spans under two samples).
class SrgbBytes {
 public:
  uint8_t operator()(float v) const {
    if (!(v > 0.0f)) return 0;  // 0, negatives and NaN
    if (v >= 1.0f) return 255;
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    int k = start_[bits >> kShift];
    while (v >= threshold_[k + 1]) ++k;
    return uint8_t(k);
  }

  // The table, built once from srgb_encode and png_sample on first use (thread-safe).
  static const SrgbBytes& get();

 private:
  SrgbBytes();
  static constexpr uint32_t kOne = 0x3F800000;  // the bits of 1.0f
  static constexpr int kShift = 16;
  std::array<float, 257> threshold_;  // [k]: the smallest float whose sample is k; [256] = +inf
  std::array<uint8_t, (kOne >> kShift) + 1> start_;
};

inline uint8_t srgb_byte(float v) {
  return SrgbBytes::get()(v);
}

}  // namespace softtrace
