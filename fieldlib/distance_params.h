// Parameter readers shared by the distance-function creators (validation of MATH.md §2's ranges).
#pragma once

#include <string>
#include <vector>

#include "params.h"

namespace softtrace {

// A [a, b, c] of radii, each > 0.
inline Vec3 positive_radii(const Params& p, const std::string& key) {
  const Vec3 r = p.vec3(key);
  for (int i = 0; i < 3; ++i) p.check_at(r[i] > 0, key, i, "expected a radius > 0");
  return r;
}

// `count` numbers, each > 0; all 1 when the key is absent (the unmodulated primitive, [DF-1]).
inline std::vector<double> side_lengths(const Params& p, const std::string& key, size_t count) {
  if (!p.has(key)) return std::vector<double>(count, 1.0);
  const std::vector<double> t = p.numbers(key);
  p.check(t.size() == count, key,
          "expected " + std::to_string(count) + " side lengths, got " + std::to_string(t.size()));
  for (size_t i = 0; i < count; ++i)
    p.check_at(t[i] > 0, key, i,
               "expected a side length t > 0 (MATH.md §2.10; t >= 1 for outer modulations)");
  return t;
}

// A unit normal from a non-zero vector.
inline Vec3 unit_normal(const Params& p, const std::string& key) {
  const Vec3 n = p.vec3(key);
  const double l = length(n);
  p.check(l > 0 && std::isfinite(l), key, "expected a non-zero normal");
  return n / l;
}

}  // namespace softtrace
