// Reading a gradient background from the scene file (scene/sky.h).
#include "scene/ranges.h"
#include "scene/scene_keys.h"
#include "scene/sky.h"

namespace softtrace {

SkyGradient load_sky_gradient(const Params& p) {
  p.check_keys(scene_keys("background"));
  const nlohmann::json& g = p.get("gradient");
  p.check(g.is_array() && g.size() == 2, "gradient",
          "expected two colours, [[r, g, b] bottom, [r, g, b] top]");
  const std::vector<Vec3> ends = p.vec3s("gradient");
  for (size_t i = 0; i < 2; ++i)
    for (int k = 0; k < 3; ++k)
      p.check(ends[i][k] >= 0, "gradient/" + std::to_string(i) + "/" + std::to_string(k),
              "expected a colour component >= 0");
  SkyGradient sky;
  sky.bottom = ends[0];
  sky.top = ends[1];
  sky.up = p.vec3("up", sky.up);
  p.check(max_abs(sky.up) > 0, "up", "expected a non-zero direction");
  sky.up = unit(sky.up);
  p.finish();
  return sky;
}

}  // namespace softtrace
