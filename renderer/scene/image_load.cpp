#include "scene/image_load.h"

#include "scene/ranges.h"
#include "scene/scene_keys.h"

namespace softtrace {

namespace {

// POV-Ray's +R: a refined pixel takes depth^2 times its samples; the image's spp is at most 4096.
constexpr int kMaxAntialiasDepth = 9;
// Antialias_Gamma: c^(1/gamma) must stay a finite, increasing encoding of colours up to 1e6.
constexpr double kMinAntialiasGamma = 0.01, kMaxAntialiasGamma = 100;
// Each occlusion sample is a shadow ray at every shaded point.
constexpr int kMaxOcclusionSamples = 1024;

}  // namespace

Antialias load_antialias(const Params& p) {
  p.check_keys(scene_keys("antialias"));
  Antialias a;
  a.threshold = p.number("threshold");
  p.check(a.threshold >= 0 && a.threshold <= 1e6, "threshold",
          "expected a colour difference in [0, 1e6] (POV-Ray's +A0.3 is 0.3)");
  a.depth = p.integer("depth", 1, kMaxAntialiasDepth, a.depth);
  a.gamma = p.number("gamma", a.gamma);
  p.check(a.gamma >= kMinAntialiasGamma && a.gamma <= kMaxAntialiasGamma, "gamma",
          "expected a gamma in [0.01, 100] (POV-Ray's Antialias_Gamma, 2.5 by default)");
  p.finish();
  return a;
}

AmbientOcclusion load_occlusion(const Params& p) {
  p.check_keys(scene_keys("ambient_occlusion"));
  AmbientOcclusion o;
  o.samples = p.integer("samples", 1, kMaxOcclusionSamples);
  o.distance = p.number("distance");
  p.check(o.distance > 0 && o.distance <= kMaxDistance, "distance",
          "expected a distance in (0, 1e150]");
  p.finish();
  return o;
}

}  // namespace softtrace
