#include "film/srgb_bytes.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

float srgb_encode(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

}  // namespace softtrace
