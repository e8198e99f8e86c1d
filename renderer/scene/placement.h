// Placement of the scene's own objects (docs/scene-format.md "Placement of shapes, meshes and
// CSGs"): the keys scale, rotate, translate and matrix read into one affine map, as the soft
// objects' placement keys read (fieldlib's are of nodes; these are of a shape, a mesh or a CSG).
// The map itself is affine.h.
#pragma once

#include "describe/params.h"
#include "math/vec.h"
#include "scene/affine.h"

namespace softtrace {

// Whether `p` has any of the placement keys.
bool has_placement(const Params& p);

// Reads `p`'s placement keys (the identity where it has none). Throws SceneError at the pointer
// of a bad value.
Affine load_placement(const Params& p);

// The inverse of an invertible linear map, or false for one that is numerically singular (its
// inverse would not be finite and within 1e30).
bool invert(const Mat3& m, Mat3& inverse);

}  // namespace softtrace
