// Placement of any node (docs/scene-format.md "Placement"): p_local = R^T (p - translate). A rigid
// motion keeps gradient norms, so Lipschitz bounds pass through unchanged.
#pragma once

#include "model/node.h"

namespace softtrace {

NodePtr place(NodePtr child, const Mat3& rotation, const Vec3& translate);

// The axis-aligned box around the image of `b` under p -> R p + t (its 8 corners).
Box transform_box(const Box& b, const Mat3& R, const Vec3& t);

}  // namespace softtrace
