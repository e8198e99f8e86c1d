// f and ∇f at one point, forward mode: every slot carries its value and its gradient with respect
// to the world point, and every point register carries its Jacobian with respect to the world
// point, so an oracle's local gradient g becomes Jᵀg.
#include "eval/eval.h"
#include "program/ops/ops.h"

namespace softtrace {

namespace {
// f and ∇f over c.code[begin, end). With `kept` (c a whole program), a sum skips the children
// whose support boxes miss the point, as value_pruned does (eval_values.cpp): the value and
// gradient of the program pruned to the point, without building that view.
void gradient_range(const Code& c, int begin, int end, Workspace::Dual* S, Workspace::Frame* R,
                    int32_t* kept);

// The group of sum `g` so: its kept children, then their sum in the view's order. Returns the
// index after the sum.
int gradient_sum(const Code& c, const Group& g, Workspace::Dual* S, Workspace::Frame* R,
                 int32_t* kept) {
  const int n = g.kept_at(R[g.reg].p, kept);
  Workspace::Dual s{0, {}};
  for (int j = 0; j < n; ++j) {
    const Group::Child& child = g.children[kept[j]];
    gradient_range(c, child.begin, child.end, S, R, kept + n);
    s.v += S[child.slot].v;
    s.g += S[child.slot].g;
  }
  S[c.code[g.op_index].out] = s;
  return g.op_index + 1;
}

void gradient_range(const Code& c, int begin, int end, Workspace::Dual* S, Workspace::Frame* R,
                    int32_t* kept) {
  const GradIO io{S, R, c.base->consts.data(), c.args};
  for (int k = begin; k < end; ++k) {
    const Instr& in = c.code[k];
    if (in.op == Op::Group && kept) {
      const Group& g = c.base->groups[in.a];
      if (!g.bvh.empty()) {
        k = gradient_sum(c, g, S, R, kept) - 1;
        continue;
      }
    }
    switch (in.op) {
#define SOFTTRACE_OP_GRADIENT(name) \
  case Op::name:                    \
    name##Op::gradient(in, io);     \
    break;
      SOFTTRACE_OPS(SOFTTRACE_OP_GRADIENT)
#undef SOFTTRACE_OP_GRADIENT
    }
  }
}
}  // namespace

double gradient(Code c, const Vec3& p, Vec3* grad, Workspace& ws) {
  ws.frames[0] = {p, Mat3{}, true};
  gradient_range(c, 0, c.size, ws.duals.data(), ws.frames.data(), nullptr);
  if (grad) *grad = ws.duals[c.result].g;
  return ws.duals[c.result].v;
}

double gradient_pruned(const Program& p, const Vec3& point, Vec3* grad, Workspace& ws) {
  ws.frames[0] = {point, Mat3{}, true};
  gradient_range(p, 0, static_cast<int>(p.code.size()), ws.duals.data(), ws.frames.data(),
                 ws.kept.data());
  if (grad) *grad = ws.duals[p.result].g;
  return ws.duals[p.result].v;
}

}  // namespace softtrace
