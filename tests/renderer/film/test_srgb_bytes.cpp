// srgb_byte against the function it replaces, png_sample(srgb_encode(v)): every float of [0, 1]
// at a stride, and every float between two strided ones where the sample changes (the only places
// a wrong threshold could show), plus the values outside [0, 1]. The thresholds are literal data
// (film/srgb_thresholds.h): this is their proof.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "film/srgb_bytes.h"
#include "io/image_file.h"

namespace softtrace {
namespace {

float srgb_test_float(uint32_t b) {
  float v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

uint8_t srgb_test_reference(float v) {
  return png_sample(srgb_encode(v));
}

TEST(SrgbByte, MatchesThePowAndRoundingAtEveryChange) {
  constexpr uint32_t kOne = 0x3F800000, kStride = 97;
  int changes = 0;
  uint8_t previous = srgb_test_reference(0.0f);
  for (uint32_t b = kStride; b <= kOne + kStride - 1; b += kStride) {
    const uint32_t end = std::min(b, kOne);
    const float v = srgb_test_float(end);
    const uint8_t now = srgb_test_reference(v);
    ASSERT_EQ(srgb_byte(v), now) << "at " << v;
    if (now != previous) {
      ++changes;
      for (uint32_t c = end - kStride + 1; c < end; ++c)
        ASSERT_EQ(srgb_byte(srgb_test_float(c)), srgb_test_reference(srgb_test_float(c)))
            << "at " << srgb_test_float(c);
    }
    previous = now;
  }
  EXPECT_EQ(changes, 255);  // every sample from 0 to 255 is met, one change each
}

TEST(SrgbByte, OutsideZeroToOne) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (float v : {nan, -nan, -inf, -1.0f, -0.0f, 0.0f, std::numeric_limits<float>::denorm_min(),
                  1.0f, std::nextafter(1.0f, 2.0f), 3.5f, inf})
    EXPECT_EQ(srgb_byte(v), srgb_test_reference(v)) << "at " << v;
  EXPECT_EQ(srgb_byte(nan), 0);
  EXPECT_EQ(srgb_byte(1.0f), 255);
}

}  // namespace
}  // namespace softtrace
