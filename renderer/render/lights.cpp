#include "render/lights.h"

#include <array>
#include <cmath>
#include <cstdint>

#include "render/cancel.h"
#include "render/point_hash.h"

namespace softtrace {

namespace {

// POV-Ray's spot falloff: 0 below `low`, 1 from `high`, a cubic with flat ends between.
double cubic_spline(double low, double high, double x) {
  if (x < low) return 0;
  if (x >= high) return 1;
  const double t = (x - low) / (high - low);
  return (3 - 2 * t) * t * t;
}

// Multiplies `light` by the spot's cone and the fading seen from a point in direction `to_light`
// (unit) at `distance` from the light; false when nothing is left.
bool spot_and_fade(const Light& l, const Vec3& to_light, double distance, Vec3& light) {
  if (l.type == Light::Type::Spot) {
    const double c = -dot(to_light, l.direction);  // cosine off the spot's axis
    if (c <= 0) return false;
    double k = std::pow(c, l.tightness);
    if (l.cos_radius > 0 && c < l.cos_radius) k *= cubic_spline(l.cos_falloff, l.cos_radius, c);
    if (k == 0) return false;
    light = light * k;
  }
  if (l.fade_power > 0)
    light = light * (2 / (1 + std::pow(distance / l.fade_distance, l.fade_power)));
  return true;
}

// An area light's samples at one point, each traced once (adaptive sampling asks for corners
// that neighbouring blocks share).
class AreaSamples {
 public:
  AreaSamples(const Light& l, const Vec3& origin, double cone0, double cone, const EmbreeScene& rt,
              RayWork& shadow, const std::atomic<bool>* cancel)
      : l_(l),
        origin_(origin),
        cone0_(cone0),
        cone_(cone),
        rt_(rt),
        shadow_(shadow),
        cancel_(cancel) {
    seed_ = point_seed(origin);
    seen_.fill(-1);
  }

  // 1 when sample (i, j) of the size1 x size2 grid sees the light, else 0.
  int visible(int i, int j) {
    signed char& v = seen_[size_t(i) * kMax + j];
    if (v < 0) v = static_cast<signed char>(trace(i, j));
    return v;
  }

  // POV-Ray's adaptive rule over the block [i0, i1] x [j0, j1] of sample indices: the mean of its
  // corners where they agree (from subdivision `level` >= adaptive on) or it is one cell;
  // otherwise the mean of its halves' (quarters') results.
  double block(int i0, int j0, int i1, int j1, int level) {
    const int a = visible(i0, j0), b = visible(i1, j0), c = visible(i0, j1), d = visible(i1, j1);
    const bool agree = a == b && a == c && a == d;
    if ((i1 - i0 <= 1 && j1 - j0 <= 1) || (agree && level >= l_.area.adaptive))
      return (a + b + c + d) / 4.0;
    const int im = (i0 + i1) / 2, jm = (j0 + j1) / 2;
    const bool split_i = i1 - i0 > 1, split_j = j1 - j0 > 1;
    if (split_i && split_j)
      return (block(i0, j0, im, jm, level + 1) + block(im, j0, i1, jm, level + 1) +
              block(i0, jm, im, j1, level + 1) + block(im, jm, i1, j1, level + 1)) /
             4;
    if (split_i) return (block(i0, j0, im, j1, level + 1) + block(im, j0, i1, j1, level + 1)) / 2;
    return (block(i0, j0, i1, jm, level + 1) + block(i0, jm, i1, j1, level + 1)) / 2;
  }

  static constexpr int kMax = 64;  // the loader's limit per axis

 private:
  // Whether the sample (placed by area_sample) is seen from the origin.
  bool trace(int i, int j) {
    if (cancel_requested(cancel_)) return true;  // up to 4096 rays per light: stop between them
    const Vec3 to = area_sample(l_, seed_, i, j) - origin_;
    const double distance = length(to);
    if (distance == 0) return true;
    TraceCounters work;
    const bool blocked = rt_.occluded({origin_, to / distance, cone0_, cone_}, 0, distance, work);
    shadow_.add(work);
    return !blocked;
  }

  const Light& l_;
  const Vec3 origin_;
  const double cone0_, cone_;
  const EmbreeScene& rt_;
  RayWork& shadow_;
  const std::atomic<bool>* cancel_;
  uint64_t seed_;
  std::array<signed char, kMax * kMax> seen_;
};

}  // namespace

Vec3 area_sample(const Light& l, uint64_t seed, int i, int j) {
  const AreaLight& a = l.area;
  double u = a.size1 > 1 ? double(i) / (a.size1 - 1) - 0.5 : 0;
  double v = a.size2 > 1 ? double(j) / (a.size2 - 1) - 0.5 : 0;
  if (a.jitter) {
    const uint64_t h = splitmix(seed ^ (uint64_t(i) << 32 | uint64_t(j)));
    const double ju = double(h >> 11) * 0x1p-53 - 0.5,
                 jv = double(splitmix(h) >> 11) * 0x1p-53 - 0.5;
    if (a.size1 > 1) u += ju / (a.size1 - 1);
    if (a.size2 > 1) v += jv / (a.size2 - 1);
  }
  return l.position + a.axis1 * u + a.axis2 * v;
}

bool spot_and_fade_at(const Light& l, const Vec3& p, LightArrival& out) {
  // The cone and the fading are the surface point's (POV-Ray's); the shadow ray's origin sits a
  // footprint above it, and the spot's edge is steep enough to show the difference.
  const Vec3 from_p = l.position - p;
  const double distance = length(from_p);
  if (distance == 0) return false;
  return spot_and_fade(l, from_p / distance, distance, out.light);
}

double area_visibility(const Light& l, const Vec3& origin, double cone0, double cone,
                       const EmbreeScene& rt, RayWork& shadow, const std::atomic<bool>* cancel) {
  AreaSamples samples(l, origin, cone0, cone, rt, shadow, cancel);
  const int n1 = l.area.size1 - 1, n2 = l.area.size2 - 1;
  if (l.area.adaptive >= 0) return samples.block(0, 0, n1, n2, 0);
  int seen = 0;
  for (int i = 0; i <= n1; ++i)
    for (int j = 0; j <= n2; ++j) seen += samples.visible(i, j);
  return double(seen) / ((n1 + 1) * (n2 + 1));
}

}  // namespace softtrace
