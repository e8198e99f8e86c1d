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

}  // namespace softtrace
