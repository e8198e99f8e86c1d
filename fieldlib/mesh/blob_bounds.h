// The interval of a sum of balls and ellipsoids (eval/blob_ray.h's BlobSum without capsules) over
// a block of the mesher, in closed form: each blob's potential P(r) = c2 r^2 + c3 r^3 (docs/math.md
// §3.3-§3.4) over the range of r = 1 - |q|^2 on the box, summed. |q|^2's range is exact for a
// ball (the box's nearest and farthest points from its centre) and from q's componentwise range
// for an ellipsoid (q = L x + k is affine). The blocks of the mesher's tree are nested, so each
// block reads only the blobs that can be non-zero in its parent, and hands on those that can be
// in it: a walk of the program's box evaluator over a block visits every blob whose support box
// meets it, with a slower interval kernel.
#pragma once

#include <cstdint>
#include <vector>

#include "eval/blob_ray.h"
#include "math/box.h"
#include "math/interval.h"

namespace softtrace {

// Whether blob_interval takes `sum`: every blob a ball or an ellipsoid (a capsule's |q|^2 has no
// cheap range; its sums keep the box evaluator).
bool blob_intervals_apply(const BlobSum& sum);

// Contains f over `box` (up to the rounding of a sum of n terms: the mesher widens it), from the
// blobs ids[0, n), which must hold every blob non-zero in the box. The blobs that may be non-zero
// in the box are appended to *kept, in the order of ids.
Interval blob_interval(const BlobSum& sum, const int32_t* ids, int n, const Box& box,
                       std::vector<int32_t>* kept);

}  // namespace softtrace
