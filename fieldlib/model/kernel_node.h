// The node of a kind that is its kernel and nothing more: a leaf whose value, gradient, bounds
// and region are the kernel's functions (kernels/) of one parameter struct, and whose code is its
// op's one instruction with those parameters inline. Such a kind writes a small struct K, not a
// FieldNode class; KernelNode<K> is its node. K names:
//   Params                        the kernel's parameter struct, which the node keeps;
//   kOp, OpKernel                 its op and the op's kernel struct (program/ops/), whose
//                                 constants(Params) is the instruction's constant layout;
//   value(m, p, grad)             f(p), and ∇f(p) into *grad when grad is non-null;
//   bounds(m, box, &value, &L)    the box question (FieldNode::box_bounds);
//   lipschitz(m)                  the global bound;
//   region(m, level, side)        FieldNode::region (Box::unbounded() where none is finite).
// KernelOf below names the first four for a kernel whose functions take the box itself. Every
// call is a static inline function of K, so the node's code is what a hand-written class
// forwarding to the kernel compiles to. A kind with more to answer (children, polynomial_blob,
// gradient_floor, hessian_bound) keeps a class of its own: model/README.md lists them.
#pragma once

#include "model/node.h"
#include "model/program_builder.h"

namespace softtrace {

// The parameters, op and kernel functions of a K whose kernel answers the box question from the
// box itself (`kernel_bounds(m, box, &value, &L)`); K derives from it and adds lipschitz and
// region.
template <class P, class OpStruct, Op op, double (&kernel)(const P&, const Vec3&, Vec3*),
          void (&kernel_bounds)(const P&, const Box&, Interval*, double*)>
struct KernelOf {
  using Params = P;
  using OpKernel = OpStruct;
  static constexpr Op kOp = op;
  static double value(const P& m, const Vec3& p, Vec3* grad) { return kernel(m, p, grad); }
  static void bounds(const P& m, const Box& b, Interval* value, double* lipschitz) {
    kernel_bounds(m, b, value, lipschitz);
  }
};

template <class K>
class KernelNode final : public FieldNode {
 public:
  explicit KernelNode(const typename K::Params& m) : m_(m) {}

  double eval(const Vec3& p, Vec3* grad) const override { return K::value(m_, p, grad); }
  double lipschitz() const override { return K::lipschitz(m_); }
  Box region(double level, Side side) const override { return K::region(m_, level, side); }
  // One instruction with the parameters inline, in the op's layout.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.single(K::kOp, reg, K::OpKernel::constants(m_));
  }

 private:
  NodeBounds box_bounds(const Box& b) const override {
    NodeBounds out;
    K::bounds(m_, b, &out.value, &out.lipschitz);
    return out;
  }

  typename K::Params m_;
};

}  // namespace softtrace
