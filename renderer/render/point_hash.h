// Deterministic "random" numbers for a shading point: a hash of the point's coordinates' bits
// (SplitMix64's finaliser), so that jittered samples at a point are the same in any tile, thread
// or split of the frame, and need no random state.
#pragma once

#include <cstdint>
#include <cstring>

#include "math/vec.h"

namespace softtrace {

inline uint64_t splitmix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

inline uint64_t double_bits(double v) {
  uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

inline uint64_t point_seed(const Vec3& p) {
  return splitmix(splitmix(splitmix(double_bits(p.x)) ^ double_bits(p.y)) ^ double_bits(p.z));
}

// A hash's top 53 bits as a double in [0, 1).
inline double unit_interval(uint64_t h) {
  return double(h >> 11) * 0x1p-53;
}

}  // namespace softtrace
