// Values at a batch of points: each instruction runs over every lane before the next, so the
// kernels are loops over contiguous doubles that the compiler can vectorise, and an oracle pays
// its virtual call per lane only for its own subtree.
#include <algorithm>

#include "eval/eval.h"
#include "program/ops/ops.h"

namespace softtrace {

void values(Code c, const double* x, const double* y, const double* z, int n, double* f,
            Workspace& ws) {
  double* S = ws.slots.data();
  double* R = ws.regs.data();
  const double* K = c.base->consts.data();
  const LaneIO io{S, R, K, c.args, n};
  std::copy(x, x + n, io.reg(0, 0));
  std::copy(y, y + n, io.reg(0, 1));
  std::copy(z, z + n, io.reg(0, 2));

  // Each instruction over every lane before the next: its op's lane loop (ops.h).
  for (int k = 0; k < c.size; ++k) {
    const Instr& in = c.code[k];
    switch (in.op) {
#define SOFTTRACE_OP_VALUES(name) \
  case Op::name:                  \
    name##Op::values(in, io);     \
    break;
      SOFTTRACE_OPS(SOFTTRACE_OP_VALUES)
#undef SOFTTRACE_OP_VALUES
    }
  }
  std::copy(S + c.result * kBatch, S + c.result * kBatch + n, f);
}

namespace {
// One point over c.code[begin, end): the same operations as one lane of `values` (so the same
// bits), without the lane loops, whose set-up costs more than the work for a single point (the
// tracer's case). With `kept` (room for the program's children; c a whole program, not a view),
// a sum whose children have support boxes evaluates only those whose boxes hold the point, as
// the program pruned to the point would (the others are exactly 0 there) without building it.
void point_range(const Code& c, int begin, int end, double* S, Vec3* R, int32_t* kept);

// The group of sum `g` so: its kept children, then their sum in the view's order. Returns the
// index after the sum.
int point_sum(const Code& c, const Group& g, double* S, Vec3* R, int32_t* kept) {
  const int n = g.kept_at(R[g.reg], kept);
  double sum = 0;
  for (int j = 0; j < n; ++j) {
    const Group::Child& child = g.children[kept[j]];
    point_range(c, child.begin, child.end, S, R, kept + n);
    sum += S[child.slot];
  }
  S[c.code[g.op_index].out] = sum;
  return g.op_index + 1;
}

void point_range(const Code& c, int begin, int end, double* S, Vec3* R, int32_t* kept) {
  const PointIO io{S, R, c.base->consts.data(), c.args};
  for (int k = begin; k < end; ++k) {
    const Instr& in = c.code[k];
    if (in.op == Op::Group && kept) {
      const Group& g = c.base->groups[in.a];
      if (!g.bvh.empty()) {
        k = point_sum(c, g, S, R, kept) - 1;
        continue;
      }
    }
    switch (in.op) {
#define SOFTTRACE_OP_VALUE(name) \
  case Op::name:                 \
    name##Op::value(in, io);     \
    break;
      SOFTTRACE_OPS(SOFTTRACE_OP_VALUE)
#undef SOFTTRACE_OP_VALUE
    }
  }
}
}  // namespace

double value(Code c, const Vec3& p, Workspace& ws) {
  ws.points[0] = p;
  point_range(c, 0, c.size, ws.slots.data(), ws.points.data(), nullptr);
  return ws.slots[c.result];
}

double value_pruned(const Program& p, const Vec3& point, Workspace& ws) {
  ws.points[0] = point;
  point_range(p, 0, static_cast<int>(p.code.size()), ws.slots.data(), ws.points.data(),
              ws.kept.data());
  return ws.slots[p.result];
}

}  // namespace softtrace
