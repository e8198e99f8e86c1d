// The affine map that places a shape, a mesh or a CSG (placement.h reads it from the scene file):
// plain data, which the tracers take with the objects (trace_target.h).
#pragma once

#include "math/affine.h"
#include "math/vec.h"

namespace softtrace {

// p_world = linear * p_object + offset: scale, then rotate, then translate, then `matrix`.
struct Affine {
  Mat3 linear;
  Vec3 offset{0, 0, 0};
  Vec3 apply(const Vec3& p) const { return linear * p + offset; }
};

// `outer` after `inner`.
inline Affine compose(const Affine& outer, const Affine& inner) {
  return {times(outer.linear, inner.linear), outer.linear * inner.offset + outer.offset};
}

}  // namespace softtrace
