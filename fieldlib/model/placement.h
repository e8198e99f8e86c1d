// Placement of any node (docs/scene-format.md "Placement"): p_local = R^T (p - translate). A rigid
// motion keeps gradient norms, so Lipschitz bounds pass through unchanged. An affine placement
// (scale, matrix; docs/math.md §2.15) evaluates the node at p_local = A^-1 (p - t): gradients go
// through A^-T and Lipschitz bounds are multiplied by a bound on |A^-1|_2 (math/affine.h).
#pragma once

#include "model/node.h"

namespace softtrace {

NodePtr place(NodePtr child, const Mat3& rotation, const Vec3& translate);
// x -> A x + t, object to world; A invertible (the loader refuses a numerically singular one).
// Compiled as one oracle instruction: the program's own placement instructions are rigid.
NodePtr place_affine(NodePtr child, const Mat3& A, const Vec3& t);

// The axis-aligned box around the image of `b` under p -> R p + t (its 8 corners).
Box transform_box(const Box& b, const Mat3& R, const Vec3& t);
// transform_box(b, I, t) for an I whose entries equal the identity's (a zero may be -0), bit for
// bit, in a few additions where that takes 8 corners through the matrix: a 1000-component
// scene's placed children asked it 2000 times, 0.98 M instructions. There, corner coordinate i
// is ((1 x_i + 0 y) + 0 z) + t_i: every product is exact and adding a zero leaves x_i as it is
// unless x_i is itself a zero (the zeros' signs then decide its sign); where t_i is not zero the
// last sum is t_i whatever that sign. So only an axis with t_i = 0 and a zero bound takes
// transform_box. For a box that is bounded (finite, not empty), as transform_box's callers pass.
Box translate_box(const Box& b, const Mat3& I, const Vec3& t);

}  // namespace softtrace
