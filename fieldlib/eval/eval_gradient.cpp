// f and ∇f at one point, forward mode: every slot carries its value and its gradient with respect
// to the world point, and every point register carries its Jacobian with respect to the world
// point, so an oracle's local gradient g becomes Jᵀg.
#include <algorithm>

#include "eval/eval.h"
#include "program/ops/ops.h"

namespace softtrace {

namespace {
// f and ∇f over c.code[begin, end). With `kept` (c a whole program), a sum skips the children
// whose support boxes miss the point, as value_pruned does (eval_values.cpp): the value and
// gradient of the program pruned to the point, without building that view. With `terms`, each
// term's value goes to terms[its number] as its sum adds it.
void gradient_range(const Code& c, int begin, int end, Workspace::Dual* S, Workspace::Frame* R,
                    int32_t* kept, double* terms);

// The group of sum `g` so: its kept children (all of them without `kept` or a BVH), then their
// sum in the view's order. Returns the index after the sum.
int gradient_sum(const Code& c, const Group& g, Workspace::Dual* S, Workspace::Frame* R,
                 int32_t* kept, double* terms) {
  const bool pruned = kept && !g.bvh.empty();
  const int n = pruned ? g.kept_at(R[g.reg].p, kept) : static_cast<int>(g.children.size());
  const bool reports = terms && !g.terms.empty();
  Workspace::Dual s{0, {}};
  for (int j = 0; j < n; ++j) {
    const int k = pruned ? kept[j] : j;
    const Group::Child& child = g.children[k];
    gradient_range(c, child.begin, child.end, S, R, kept ? kept + n : nullptr, terms);
    s.v += S[child.slot].v;
    s.g += S[child.slot].g;
    // The child's slot may be shared by later values (share_storage): read it now.
    if (reports && g.terms[k] >= 0) terms[g.terms[k]] = S[child.slot].v;
  }
  S[c.code[g.op_index].out] = s;
  return g.op_index + 1;
}

void gradient_range(const Code& c, int begin, int end, Workspace::Dual* S, Workspace::Frame* R,
                    int32_t* kept, double* terms) {
  const GradIO io{S, R, c.base->consts.data(), c.args};
  for (int k = begin; k < end; ++k) {
    const Instr& in = c.code[k];
    if (in.op == Op::Group && (kept || terms)) {
      const Group& g = c.base->groups[in.a];
      if ((kept && !g.bvh.empty()) || (terms && !g.terms.empty())) {
        k = gradient_sum(c, g, S, R, kept, terms) - 1;
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
  gradient_range(c, 0, c.size, ws.duals.data(), ws.frames.data(), nullptr, nullptr);
  if (grad) *grad = ws.duals[c.result].g;
  return ws.duals[c.result].v;
}

double gradient_pruned(const Program& p, const Vec3& point, Vec3* grad, Workspace& ws) {
  ws.frames[0] = {point, Mat3{}, true};
  gradient_range(p, 0, static_cast<int>(p.code.size()), ws.duals.data(), ws.frames.data(),
                 ws.kept.data(), nullptr);
  if (grad) *grad = ws.duals[p.result].g;
  return ws.duals[p.result].v;
}

double gradient_terms(const Program& p, const Vec3& point, Vec3* grad, double* terms,
                      Workspace& ws) {
  ws.fit(p);
  std::fill(terms, terms + p.terms, 0.0);  // a term its sum skips is 0 there
  ws.frames[0] = {point, Mat3{}, true};
  gradient_range(p, 0, static_cast<int>(p.code.size()), ws.duals.data(), ws.frames.data(),
                 ws.kept.data(), terms);
  if (grad) *grad = ws.duals[p.result].g;
  return ws.duals[p.result].v;
}

}  // namespace softtrace
