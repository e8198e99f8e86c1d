// The ranges a scene's positions and distances keep to, and length and direction of vectors
// from the scene without overflow or underflow. Shared by the scene's loader and its camera.
#pragma once

#include "math/vec.h"

namespace softtrace {

// Lengths and directions of vectors from the scene without overflow or underflow: a component
// of 1e308 squares to inf, one of 1e-200 to 0. Scaling by the largest component first keeps
// |v| and v / |v| exact to rounding for every finite v.
inline double scaled_length(const Vec3& v) {
  const double m = max_abs(v);
  return m > 0 ? m * length(v / m) : 0;
}
inline Vec3 unit(const Vec3& v) {  // v non-zero and finite
  return normalize(v / max_abs(v));
}

// Distances the renderer squares (camera to target, point light to objects) stay within this,
// and above its inverse, so that their squares are normal doubles.
constexpr double kMaxDistance = 1e150;

// Where rays start: the eye, and shading points inside the objects' boxes. Embree takes ray
// origins in float and (Debian's build) asserts |origin| <= 1.8e18; well before that, float's
// rounding of the origin (6e-8 of it) misplaces the rays it culls with, and the tracer's steps
// stop advancing along t. Fig. 12(b)'s object at 64x48, seen from 1e7 and from farther along
// the same line (the fov scaled): from 1e12, 1 pixel of 3072 differs; from 1e15, 33; from 1e17
// the render does not finish.
constexpr double kMaxPosition = 1e12;
constexpr const char* kPositionRule = "within 1e12 of the origin in every coordinate";

}  // namespace softtrace
