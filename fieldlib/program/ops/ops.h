// One kernel struct per op of the op list (program.h SOFTTRACE_OPS): `name##Op` holds everything
// about op `name` in one place:
// - constants(...) and load(c): its constant layout, written by the model's compile() and read
//   by the evaluators (ops without constants have neither);
// - operands(in, p, use, def): the values it reads and writes (program_storage.cpp);
// - values(in, LaneIO): its lane loop over a batch (eval_values.cpp);
// - value(in, PointIO) and gradient(in, GradIO): one point, its value and forward-mode gradient
//   (eval_values.cpp, eval_gradient.cpp);
// - bounds(in, BoundsIO): its value interval and Lipschitz bound over its register's box, and on
//   a segment its slope and quiet start (the support's entry) too (eval_bounds.cpp); for an n-ary
//   op, over the children the walk kept;
// - kPlaces (its box or segment is wanted by pruning even without bounds) and kZeroWhenQuiet
//   (its quiet start means it is exactly 0: a soft field's support not yet entered).
// Every function is a static inline member, so the evaluators' switches, generated from the op
// list, inline each op's code into their loops as a hand-written case would be.
#pragma once

#include <cstdlib>

#include "program/ops/bt_ops.h"
#include "program/ops/gauge_ops.h"
#include "program/ops/nary_ops.h"
#include "program/ops/op_io.h"
#include "program/ops/oracle_op.h"
#include "program/ops/placement_ops.h"
#include "program/ops/plane_ops.h"
#include "program/ops/potential_ops.h"
#include "program/ops/skeletal_ops.h"
#include "program/program.h"

namespace softtrace {

// Whether an instruction's quiet start (Workspace::quiet) means its value is 0 there: a
// potential's (transformed or not) or a sum's, not a distance's (>= 1).
inline bool zero_when_quiet(Op op) {
  switch (op) {
#define SOFTTRACE_OP_ZERO_WHEN_QUIET(name) \
  case Op::name:                           \
    return name##Op::kZeroWhenQuiet;
    SOFTTRACE_OPS(SOFTTRACE_OP_ZERO_WHEN_QUIET)
#undef SOFTTRACE_OP_ZERO_WHEN_QUIET
  }
  std::abort();  // not reached: the switch names every op, and -Werror=switch keeps it so
}

}  // namespace softtrace
