// Linear values to 8-bit sRGB samples, as a PNG stores them: png_sample(srgb_encode(v)), the
// sRGB transfer function (IEC 61966-2-1) then rounding to 0..255, without a pow per sample.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <limits>

#include "film/srgb_thresholds.h"

namespace softtrace {

// The sRGB encoding of a linear value clamped to [0, 1] (NaN stays NaN).
float srgb_encode(float v);

namespace srgb_table {

constexpr uint32_t kOne = 0x3F800000;  // the bits of 1.0f
constexpr int kShift = 16;

// Whether the floats of every bucket (a run sharing their bits above kShift) reach at most one
// threshold past the bucket's first float: then a sample is its bucket's start or one more. Two
// consecutive thresholds in one bucket break it unless the first is the bucket's first float.
constexpr bool at_most_one_step() {
  for (size_t k = 0; k + 1 < 257; ++k) {
    const uint32_t t = kSrgbThresholdBits[k], next = kSrgbThresholdBits[k + 1];
    if (t >> kShift == next >> kShift && (t & ((1u << kShift) - 1)) != 0) return false;
  }
  return true;
}
static_assert(at_most_one_step(), "a bucket's lookup steps at most once (SrgbBytes)");

// The float whose bit pattern is `bits`, for the patterns of kSrgbThresholdBits: 0, +inf and
// positive normal floats, (2^23 + mantissa) 2^(exponent - 150), exact in a double and in the float
// (std::memcpy, which the lookup uses, is not constexpr).
constexpr float float_of_bits(uint32_t bits) {
  if (bits == 0) return 0.0f;
  if (bits == 0x7F800000) return std::numeric_limits<float>::infinity();
  double v = double((bits & 0x7FFFFF) | 0x800000);
  for (int e = int(bits >> 23) - 150; e < 0; ++e) v *= 0.5;
  for (int e = int(bits >> 23) - 150; e > 0; --e) v *= 2.0;
  return float(v);
}

}  // namespace srgb_table

// Exactly png_sample(srgb_encode(v)) for every float v, NaN included (0), found among 255
// thresholds (kSrgbThresholdBits): threshold k is the smallest float whose sample is k, and the
// sample is the number of thresholds at or below v. Non-negative floats order as their bit
// patterns do, so a bucket is the floats sharing their top 16 bits: its start is the sample of its
// first float, at or below that of any float in it, and the lookup steps up from there. No bucket
// holds two thresholds past its first float (at_most_one_step), so the step is one comparison
// added, not a loop, whose exit branch a frame's gradients mispredicted: pov:molecule's 320x240
// rows took 46,266 mispredicted branches (callgrind's model), now 789.
class SrgbBytes {
 public:
  uint8_t operator()(float v) const {
    if (!(v > 0.0f)) return 0;  // 0, negatives and NaN
    if (v >= 1.0f) return 255;
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    const int k = start_[bits >> srgb_table::kShift];
    return uint8_t(k + (v >= threshold_[k + 1]));
  }

  // The table, made by the compiler: no process spends its start on it.
  static const SrgbBytes& get();

 private:
  constexpr SrgbBytes() : threshold_{}, start_{} {
    for (size_t k = 0; k < threshold_.size(); ++k)
      threshold_[k] = srgb_table::float_of_bits(kSrgbThresholdBits[k]);
    // Bucket i's first float has the bits i << kShift; its sample is the number of thresholds
    // after the first at or below it.
    int k = 0;
    for (uint32_t i = 0; i < start_.size(); ++i) {
      while (kSrgbThresholdBits[k + 1] <= i << srgb_table::kShift) ++k;
      start_[i] = uint8_t(k);
    }
  }

  std::array<float, 257> threshold_;  // [k]: the smallest float whose sample is k; [256] = +inf
  std::array<uint8_t, (srgb_table::kOne >> srgb_table::kShift) + 1> start_;
};

inline const SrgbBytes& SrgbBytes::get() {
  static constexpr SrgbBytes table;
  return table;
}

inline uint8_t srgb_byte(float v) {
  return SrgbBytes::get()(v);
}

}  // namespace softtrace
