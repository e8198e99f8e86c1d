#include "render/shadow_beams.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softtrace {

ShadowBeams::ShadowBeams(const Scene& scene, const SceneTracers& tracers)
    : tracers_(tracers), objects_(tracers.size()), slot_(scene.lights.size(), -1) {
  for (int o = 0; o < objects_; ++o)
    if (const ObjectTracer* t = tracers.tracer(o); t && t->blob_sum()) blob_objects_.push_back(o);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (l.type != Light::Type::Directional || !l.shadows || l.has_area) continue;
    Axes a;
    a.along = -l.direction;  // light_arrival's to_light
    // u across the axis least aligned with `along`, v completing the frame.
    const Vec3 e =
        std::abs(a.along.x) <= std::abs(a.along.y) && std::abs(a.along.x) <= std::abs(a.along.z)
            ? Vec3{1, 0, 0}
        : std::abs(a.along.y) <= std::abs(a.along.z) ? Vec3{0, 1, 0}
                                                     : Vec3{0, 0, 1};
    a.u = cross(a.along, e);
    a.u = a.u / length(a.u);
    a.v = cross(a.along, a.u);
    a.v = a.v / length(a.v);
    slot_[i] = static_cast<int>(lights_.size());
    lights_.push_back(a);
  }
}

void ShadowBeams::build(int level, const Point* points, int n, Lists& lists) const {
  std::vector<BlobBeam>& out = lists.level[level];
  out.resize(lights_.size() * size_t(objects_));
  if (level == 0 && n > 0) lists.origin = points[0].p;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < lights_.size(); ++k) {
    const Axes& a = lights_[k];
    ShadowPrism prism{lists.origin, a.along, a.u, a.v, kInf, -kInf, kInf, -kInf, kInf};
    for (int i = 0; i < n; ++i) {
      // The origin lies within the margin of p (grown by 1e-9: the lift's rounding).
      const Vec3 q = points[i].p - lists.origin;
      const double m = points[i].margin * (1 + 1e-9);
      const double x = dot(q, a.u), y = dot(q, a.v), z = dot(q, a.along);
      prism.x0 = std::min(prism.x0, x - m);
      prism.x1 = std::max(prism.x1, x + m);
      prism.y0 = std::min(prism.y0, y - m);
      prism.y1 = std::max(prism.y1, y + m);
      prism.z0 = std::min(prism.z0, z - m);
    }
    for (const int o : blob_objects_) {
      BlobBeam& list = out[k * objects_ + o];
      list.valid = false;
      if (n == 0) continue;
      // A prism that misses the object's box sends it no ray: no list, and no walk to build one.
      const Box& box = tracers_.object(o).bounds;
      double x0 = kInf, x1 = -kInf, y0 = kInf, y1 = -kInf, z1 = -kInf;
      for (int c = 0; c < 8; ++c) {
        const Vec3 corner{c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y,
                          c & 4 ? box.hi.z : box.lo.z};
        const Vec3 q = corner - lists.origin;
        const double x = dot(q, a.u), y = dot(q, a.v), z = dot(q, a.along);
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
        z1 = std::max(z1, z);
      }
      const double slack = 1e-9 * (max_abs(box.lo) + max_abs(box.hi) + max_abs(lists.origin));
      if (x0 > prism.x1 + slack || x1 < prism.x0 - slack || y0 > prism.y1 + slack ||
          y1 < prism.y0 - slack || z1 < prism.z0 - slack)
        continue;
      const BlobBeam* parent = level > 0 ? &lists.level[level - 1][k * objects_ + o] : nullptr;
      tracers_[o].shadow_beam(prism, parent, &list);
      // The blocks' lists, which their rays take, pick the blobs that may decide them alone.
      if (level == kLevels - 1) tracers_[o].shadow_blockers(&list);
    }
  }
}

}  // namespace softtrace
