// Parameter readers shared by the distance-function creators (validation of docs/math.md §2's
// ranges).
#pragma once

#include <string>
#include <vector>

#include "describe/params.h"

namespace softtrace {

// `count` side lengths (each > 0 by the table); all 1 when the key is absent (the unmodulated
// primitive, [DF-1]). The count depends on other parameters (one per normal), so it is checked
// here.
inline std::vector<double> side_lengths(const Params& p, const std::string& key, size_t count) {
  if (!p.has(key)) return std::vector<double>(count, 1.0);
  const std::vector<double> t = p.numbers(key);
  p.check(t.size() == count, key,
          "expected " + std::to_string(count) + " side lengths, got " + std::to_string(t.size()));
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
