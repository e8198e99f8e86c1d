// libFuzzer target: arbitrary bytes through the scene loader (parse_scene), and for scenes that
// load, the first object's field evaluated — value, gradient, interval, Lipschitz bounds — at
// fixed points and boxes. Bad input must end in a SceneError, never a crash, a sanitizer report
// or (for a scene that loaded) a NaN. Built by tools/dev.sh test in build-fuzz/ and run there
// for a bounded time, seeded from scenes/ and tests/bad_scenes/.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "scene/scene.h"

using namespace softtrace;

namespace {

// NaN anywhere is a finding; infinities are legitimate for bounds (no global Lipschitz bound).
void require(bool ok) {
  if (!ok) std::abort();
}

void probe(const SceneObject& o) {
  if (!o.field) return;  // a shape object: traced in closed form, nothing to evaluate
  const Box& b = o.bounds;
  const Vec3 c = b.center(), e = b.extent() * 0.5;
  const Vec3 points[] = {c,
                         b.lo,
                         b.hi,
                         {0, 0, 0},
                         c + Vec3{e.x * 0.31, -e.y * 0.77, e.z * 0.5},
                         c + Vec3{e.x, 0, 0},
                         c + Vec3{0, 0, e.z}};
  for (const Vec3& p : points) {
    Vec3 g;
    const double v = o.field->eval(p, &g);
    require(!std::isnan(v) && !std::isnan(g.x) && !std::isnan(g.y) && !std::isnan(g.z));
  }
  const Box boxes[] = {b, Box::around(c, 1e-3 * (1 + b.diagonal())), Box({c.x, c.y, c.z}, b.hi)};
  for (const Box& box : boxes) {
    const Interval i = o.field->interval(box);
    require(!std::isnan(i.lo) && !std::isnan(i.hi) && i.lo <= i.hi);
    require(!std::isnan(o.field->lipschitz(box)));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Scene scene;
  try {
    scene = parse_scene(text, "fuzz.json");
  } catch (const SceneError&) {
    return 0;  // the expected outcome for almost every input
  }
  for (const SceneObject& o : scene.objects) probe(o);
  return 0;
}
