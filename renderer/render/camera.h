// The camera's rays (docs/scene-format.md "camera"): perspective or orthographic, through a
// pinhole or a thin lens.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scene/scene.h"
#include "trace/tracer.h"

namespace softtrace {

// A pixel's samples: the image's `spp`, at least the camera's blur_samples behind a lens.
inline int samples_per_pixel(const Camera& c, int spp) {
  return c.aperture > 0 ? std::max(spp, c.blur_samples) : spp;
}

// Where sample s of n of pixel (x, y) passes through the lens, on the unit disc: Vogel's spiral
// (radius sqrt(s / n), s golden angles round), so sample 0 is the lens's centre and the n points
// cover the disc evenly, turned by an angle hashed from the full-frame pixel, so that
// neighbouring pixels' patterns differ (noise, not bands). It depends on nothing but (x, y, s, n):
// the same bits for any thread count and any split of the frame.
inline void lens_sample(int x, int y, int s, int n, double& lx, double& ly) {
  uint32_t h = static_cast<uint32_t>(x) * 0x9E3779B1u ^ static_cast<uint32_t>(y) * 0x85EBCA77u;
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  const double turn = h * (1.0 / 4294967296.0);
  const double r = std::sqrt(static_cast<double>(s) / n);
  const double angle = 2 * M_PI * (turn + s * 0.3819660112501051);  // the golden angle, in turns
  lx = r * std::cos(angle);
  ly = r * std::sin(angle);
}

class ViewCamera {
 public:
  ViewCamera(const Camera& c, int width, int height)
      : eye_(c.eye),
        orthographic_(c.projection == Camera::Projection::Orthographic),
        width_(width),
        height_(height),
        aspect_(c.aspect > 0 ? c.aspect : static_cast<double>(width) / height),
        aperture_(c.aperture) {
    forward_ = normalize(c.target - c.eye);
    right_ = normalize(cross(forward_, c.up));
    up_ = cross(right_, forward_);
    tan_half_ = std::tan(0.5 * c.fov * M_PI / 180.0);
    const double distance = length(c.target - c.eye);
    focus_ = c.focal_distance > 0 ? c.focal_distance : distance;
    // Orthographic: the perspective view's half height at the target, the same at every depth.
    half_height_ = tan_half_ * distance;
    // Half a pixel's height: on the image plane at distance 1 (the footprint's radius grows by
    // that per unit of distance; off-axis pixels are a little smaller seen along their rays), or
    // in scene units for parallel rays.
    cone_ = orthographic_ ? 0 : tan_half_ / height;
    cone0_ = orthographic_ ? half_height_ / height : 0;
    // A stretched view's pixels are not square: half the narrower side.
    if (c.aspect > 0 && aspect_ / width < 1.0 / height) {
      cone_ *= aspect_ * height / width;
      cone0_ *= aspect_ * height / width;
    }
  }

  // Whether every ray leaves the eye (a pinhole perspective camera): then frustum() holds them.
  bool single_eye() const { return !orthographic_ && aperture_ == 0; }
  // The rays' origin, where single_eye().
  const Vec3& eye() const { return eye_; }
  // Whether the rays pass through a lens: only then does generate() read its (lx, ly).
  bool lens() const { return aperture_ > 0; }

  // (px, py) in pixel units: x to the right, y down from the top-left corner. (lx, ly): a point
  // of the unit disc, where on the lens the ray passes (ignored for a pinhole).
  Ray generate(double px, double py, double lx = 0, double ly = 0) const {
    Vec3 o = eye_, d;
    if (orthographic_) {
      const double sx = (2 * px / width_ - 1) * aspect_, sy = 1 - 2 * py / height_;
      o += right_ * (sx * half_height_) + up_ * (sy * half_height_);
      d = forward_;
    } else {
      d = direction(px, py);
    }
    if (aperture_ > 0) {
      // The pinhole ray meets the plane in focus at `focus` (d's forward component is 1).
      const Vec3 focus = o + d * focus_;
      o += right_ * (0.5 * aperture_ * lx) + up_ * (0.5 * aperture_ * ly);
      d = focus - o;
    }
    return {o, normalize(d), cone0_, cone_};
  }

  // A pinhole perspective camera's ray (single_eye()) through the image-plane point of
  // column(px) and row(py): generate(px, py) to the bit, the two divisions taken once per column
  // and row by a caller that keeps them (FrameTracer's tables).
  double column(double px) const { return (2 * px / width_ - 1) * tan_half_ * aspect_; }
  double row(double py) const { return (1 - 2 * py / height_) * tan_half_; }
  Ray pinhole(double column, double row) const {
    return {eye_, normalize(forward_ + right_ * column + up_ * row), cone0_, cone_};
  }
  // pinhole(column, row) from its two parts, kept per column and per row by the caller: the
  // direction before it is normalised is column_part(column) + row_part(row), pinhole's very sums
  // in its order (forward + right * column first), without the six products and three sums a ray.
  Vec3 column_part(double column) const { return forward_ + right_ * column; }
  Vec3 row_part(double row) const { return up_ * row; }
  Ray pinhole(const Vec3& column_part, const Vec3& row_part) const {
    return {eye_, normalize(column_part + row_part), cone0_, cone_};
  }

  // Where the point p is seen in the frame (single_eye() only), in pixel units as generate()
  // takes them: false for a point not in front of the eye. Approximate (rounding): for estimates
  // only, never for a certificate.
  bool pixel_of(const Vec3& p, double& px, double& py) const {
    const Vec3 v = p - eye_;
    const double z = dot(v, forward_);
    if (!(z > 0)) return false;
    px = (dot(v, right_) / (z * tan_half_ * aspect_) + 1) * 0.5 * width_;
    py = (1 - dot(v, up_) / (z * tan_half_)) * 0.5 * height_;
    return std::isfinite(px) && std::isfinite(py);
  }

  // The rays through the pixels [x0, x1) x [y0, y1), wherever in them their samples fall (valid
  // only where single_eye()).
  Frustum frustum(int x0, int y0, int x1, int y1) const {
    return {eye_,
            forward_,
            {direction(x0, y0), direction(x1, y0), direction(x0, y1), direction(x1, y1)}};
  }

 private:
  // Through (px, py) from the eye, with forward component 1.
  Vec3 direction(double px, double py) const {
    return forward_ + right_ * column(px) + up_ * row(py);
  }

  Vec3 eye_, forward_, right_, up_;
  bool orthographic_;
  int width_, height_;
  double aspect_;  // the view's width / height, once (a division a camera ray)
  double aperture_, focus_ = 0, tan_half_ = 0, half_height_ = 0, cone_ = 0, cone0_ = 0;
};

}  // namespace softtrace
