// The nodes s·g(child) whose derivative is s times the child's (offset: s·(f - c), 003 §2.1;
// strength: s·f, docs/math.md §4.10): one base for the bounds that scale by |s| alone.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/interval.h"
#include "model/node.h"

namespace softtrace {

class ScaledNode : public FieldNode {
 public:
  ScaledNode(NodePtr child, double s) : child_(std::move(child)), s_(s) {}

  // |∇(s g)| = |s| |∇g|: the child's global Lipschitz bound, gradient floor and Hessian bound
  // times |s|, rounded away from the side they bound (the box bound likewise, in each kind's
  // box_bounds through its kernel).
  double lipschitz() const override { return iv::up(std::abs(s_) * child_->lipschitz()); }
  double gradient_floor(const Box& b) const override {
    return std::max(0.0, iv::down(std::abs(s_) * child_->gradient_floor(b)));
  }
  double hessian_bound(const Box& b) const override {
    return iv::up(std::abs(s_) * child_->hessian_bound(b));
  }
  bool hessian(const Vec3& p, Mat3* H) const override {
    if (!child_->hessian(p, H)) return false;
    for (Vec3& row : H->r) row = row * s_;
    return true;
  }

 protected:
  NodePtr child_;
  double s_;
};

}  // namespace softtrace
