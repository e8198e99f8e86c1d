// `n` murakami balls of radius 0.7 at random in a 40-unit cube (seeded by `seed`), blended at iso
// 0.5 and lit by one directional light with shadows, seen through `camera` (a scene's camera
// object, as JSON): most of such a frame's pixels are background, as tools/blob_scene.py
// --meets 1 writes it. The unmet and background beam tests trace it.
#pragma once

#include <random>
#include <string>

namespace softtrace {

inline std::string sparse_ball_cloud(int n, unsigned seed, const std::string& camera) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-20, 20);
  std::string children;
  for (int i = 0; i < n; ++i) {
    children += std::string(i ? "," : "") +
                R"({"type": "soft_object", "potential": {"type": "murakami"},
        "distance": {"type": "lp_metric", "radii": [0.7, 0.7, 0.7], "n": 2}, "translate": [)" +
                std::to_string(u(rng)) + "," + std::to_string(u(rng)) + "," +
                std::to_string(u(rng)) + "]}";
  }
  return R"({"camera": )" + camera + R"(, "image": {"spp": 1},
    "lights": [{"type": "directional", "direction": [1, 0.35, -1], "shadows": true}],
    "objects": [{"iso": 0.5, "field": {"type": "soft_blend", "children": [)" +
         children + "]}}]}";
}

}  // namespace softtrace
