#include "render/occlusion.h"

#include <cmath>

#include "render/cancel.h"
#include "render/point_hash.h"

namespace softtrace {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Two unit vectors that make (t, b, n) an orthonormal basis, for unit n without a branch at the
// pole's singularity (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
void basis(const Vec3& n, Vec3& t, Vec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = {1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace

double open_sky(const AmbientOcclusion& ao, const Vec3& origin, const Vec3& n, double cone0,
                double cone, const EmbreeScene& rt, RayWork& shadow,
                const std::atomic<bool>* cancel) {
  Vec3 t, b;
  basis(n, t, b);
  const uint64_t seed = point_seed(origin);
  const double shift = unit_interval(seed), turn = unit_interval(splitmix(seed));
  int open = 0;
  for (int k = 0; k < ao.samples; ++k) {
    if (cancel_requested(cancel)) break;
    // Cosine-weighted: sin^2 of the angle to n uniform in [0, 1), one stratum per sample.
    const double sin2 = (k + shift) / ao.samples;
    const double r = std::sqrt(sin2), up = std::sqrt(1 - sin2);
    const double phi = 2 * kPi * (turn + k * 0.6180339887498949);  // golden ratio turns
    const Vec3 d = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * up;
    TraceCounters work;
    open += !rt.occluded({origin, d, cone0, cone}, 0, ao.distance, work);
    shadow.add(work);
  }
  return double(open) / ao.samples;
}

}  // namespace softtrace
