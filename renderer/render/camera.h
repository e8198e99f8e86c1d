// Pinhole camera from eye/target/up and a vertical field of view (docs/scene-format.md "camera").
#pragma once

#include <cmath>

#include "scene/scene.h"
#include "trace/tracer.h"

namespace softtrace {

class PinholeCamera {
 public:
  PinholeCamera(const Camera& c, int width, int height)
      : eye_(c.eye), width_(width), height_(height) {
    forward_ = normalize(c.target - c.eye);
    right_ = normalize(cross(forward_, c.up));
    up_ = cross(right_, forward_);
    tan_half_ = std::tan(0.5 * c.fov * M_PI / 180.0);
    // Half a pixel's height on the image plane at distance 1: the footprint's radius grows by
    // that per unit of distance (off-axis pixels are a little smaller seen along their rays).
    cone_ = tan_half_ / height;
  }

  // (px, py) in pixel units: x to the right, y down from the top-left corner.
  Ray generate(double px, double py) const {
    return {eye_, normalize(direction(px, py)), 0, cone_};
  }

  // The rays through the pixels [x0, x1) x [y0, y1), wherever in them their samples fall.
  Frustum frustum(int x0, int y0, int x1, int y1) const {
    return {eye_,
            forward_,
            {direction(x0, y0), direction(x1, y0), direction(x0, y1), direction(x1, y1)}};
  }

 private:
  // Through (px, py), with forward component 1.
  Vec3 direction(double px, double py) const {
    const double aspect = static_cast<double>(width_) / height_;
    const double sx = (2 * px / width_ - 1) * tan_half_ * aspect;
    const double sy = (1 - 2 * py / height_) * tan_half_;
    return forward_ + right_ * sx + up_ * sy;
  }

  Vec3 eye_, forward_, right_, up_;
  int width_, height_;
  double tan_half_, cone_;
};

}  // namespace softtrace
