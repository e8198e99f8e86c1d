// A cloud of 160 polynomial blobs of every placement the blob path takes, some 40 of each: balls,
// rotated ellipsoids (one in two of negative strength), capsules and sheared capsules, centred in
// [-20, 20]^3, drawn from `rng`: the children of a soft_blend, as scene text. The beam and shadow
// list tests trace it.
#pragma once

#include <random>
#include <string>

namespace softtrace {

inline std::string mixed_blob_cloud(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> c(-20, 20), u(0, 1);
  std::string children;
  for (int i = 0; i < 160; ++i) {
    const auto v = [&] {
      return "[" + std::to_string(c(rng)) + "," + std::to_string(c(rng)) + "," +
             std::to_string(c(rng)) + "]";
    };
    const std::string r = std::to_string(1.5 + 3 * u(rng));
    std::string child = R"({"type":"soft_object","potential":{"type":"murakami"},)";
    switch (i % 4) {
      case 0:  // a ball
        child += R"("translate":)" + v() + R"(,"distance":{"type":"lp_metric","radii":[)" + r +
                 "," + r + "," + r + R"(],"n":2}})";
        break;
      case 1:  // a rotated ellipsoid, some of negative strength
        child += R"("strength":)" + std::string(i % 8 == 1 ? "-0.5" : "1") +
                 R"(,"rotate":{"axis":[1,2,3],"deg":)" + std::to_string(90 * u(rng)) +
                 R"(},"translate":)" + v() + R"(,"distance":{"type":"lp_metric","radii":[)" + r +
                 ",2,1],\"n\":2}}";
        break;
      case 2:  // a capsule
        child += R"("distance":{"type":"segment","p0":)" + v() + R"(,"p1":)" + v() +
                 R"(,"radius":)" + r + "}}";
        break;
      case 3:  // a sheared capsule
        child += R"("matrix":[[1,0.9,0,)" + std::to_string(c(rng)) + R"(],[0,0.5,0,)" +
                 std::to_string(c(rng)) + R"(],[0.3,0,1,)" + std::to_string(c(rng)) +
                 R"(]],"distance":{"type":"segment","p0":[-3,0,0],"p1":[3,0,0],"radius":)" + r +
                 "}}";
        break;
    }
    children += (i ? "," : "") + child;
  }
  return children;
}

}  // namespace softtrace
