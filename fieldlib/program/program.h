// A field compiled to a flat program (the libfive/fidget design): the node tree the scene builds
// is the *model*; `compile` (model/program_builder.h) turns it once into a post-order array of
// instructions over a file of value slots and point registers, which the evaluators (eval.h) walk
// without a virtual call per node. Kinds without an instruction of their own are *oracles*: one
// instruction that calls the model node's own kernels for its whole subtree (the root-defined
// blends, whose bounds are derived next to their code, stay so by design).
//
// Layout rules the evaluators rely on:
// - Point register 0 is the evaluation point; placement writes a new register, so a subtree reads
//   the register its parent hands it.
// - Each child subtree of an n-ary instruction is a contiguous range of instructions, announced by
//   a `Group` instruction before the first child. Pruning is choosing ranges: the bounds pass skips
//   the ranges of children that cannot matter in a box and emits the rest (eval_bounds.cpp).
// - Constants live in one pool (`consts`), each op's in the layout its kernel struct defines
//   (ops/ops.h); n-ary instructions read their argument slots from `args`.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "math/box.h"
#include "math/bvh.h"
#include "math/own_lines.h"
#include "program/oracle.h"

namespace softtrace {

// The one list of instructions. Each entry `name` has its kernel struct `name##Op` (ops/ops.h:
// its constant layout, operands, lanes, point value and gradient, box and segment bounds), from
// which every evaluator's cases and the storage pass are generated.
#define SOFTTRACE_OPS(X)                                                                       \
  X(Translate)        /* reg out = reg in - t                          (placement_ops.h) */    \
  X(Place)            /* reg out = Rt (reg in - t)                     (placement_ops.h) */    \
  X(Oracle)           /* slot out = node(reg in): a model node's subtree   (oracle_op.h) */    \
  X(LpMetric)         /* slot out = lp_metric(reg in), 000 Eq. 3           (gauge_ops.h) */    \
  X(SphericalProduct) /* slot out = spherical_product(reg in), 000 Eq. 8   (gauge_ops.h) */    \
  X(ParallelPlanes)   /* slot out = |reg in · n|/a, 000 Eq. 2              (plane_ops.h) */   \
  X(OneBranchPlane)   /* slot out = [reg in · n]_+/a, 002 f_o              (plane_ops.h) */   \
  X(LineSegment)      /* slot out = |reg in - nearest|/r, 000 Eq. 5     (skeletal_ops.h) */    \
  X(Torus)            /* slot out = torus(reg in)                       (skeletal_ops.h) */    \
  X(GenDistance)      /* slot out = (Σ u_i^n)^(1/n) over n planes, 000 Eq. 4 (plane_ops.h) */ \
  X(PolarPrism)       /* slot out = polar prism, docs/math.md §10.1     (skeletal_ops.h) */   \
  X(Blanc)            /* slot out = P_blanc(slot in), 002 Eq. 2        (potential_ops.h) */    \
  X(Wyvill)           /* slot out = Wyvill's P(slot in)                (potential_ops.h) */    \
  X(Murakami)         /* slot out = (1 - d^2)^2, POV-Ray's blob        (potential_ops.h) */    \
  X(Cubic)            /* slot out = (1 - d^2)^3, Galin et al. 2020     (potential_ops.h) */    \
  X(Strength)         /* slot out = s · slot in                        (potential_ops.h) */   \
  X(Offset)           /* slot out = s (slot in - c), 003 §2.1          (potential_ops.h) */   \
  X(Complement)       /* slot out = 1 - f, -f or 1/f of slot in        (potential_ops.h) */    \
  X(RadiusTransform)  /* slot out = P(T(d, w)), d = slot in, f = slot n (potential_ops.h) */   \
  X(Group)            /* announces the children of groups[a]               (nary_ops.h) */     \
  X(Sum)              /* slot out = Σ args[a..a+n), soft_blend 000 Eq. 12  (nary_ops.h) */    \
  X(Min)              /* slot out = min of args[a..a+n)                    (nary_ops.h) */     \
  X(Max)              /* slot out = max of args[a..a+n)                    (nary_ops.h) */     \
  X(SuperUnion)       /* slot out = (Σ args^-n)^(-1/n), 000 Eq. 6          (nary_ops.h) */    \
  X(SuperIntersect)   /* slot out = (Σ [args]_+^n)^(1/n), B_RI^cg          (nary_ops.h) */    \
  X(Perlin)           /* slot out = Perlin blend, 002 Eqs. 4-6             (nary_ops.h) */     \
  X(Ricci)            /* slot out = (Σ g_i^q)^(1/q), 002 Eq. 7             (nary_ops.h) */    \
  X(Scale)            /* slot out = BSA2/BSS2 of args[a], args[a+1], 000 Eq. 8 (nary_ops.h) */ \
  X(Bt)               /* slot out = τ BT_k(σ_i args), 003 Eqs. 2-5, §3.3     (bt_ops.h) */

enum class Op : uint8_t {
#define SOFTTRACE_OP_ENUM(name) name,
  SOFTTRACE_OPS(SOFTTRACE_OP_ENUM)
#undef SOFTTRACE_OP_ENUM
};

const char* op_name(Op op);

struct Instr {
  Op op;
  int32_t out = 0;  // value slot, or point register for Translate/Place
  int32_t in = 0;   // point register (Translate, Place, distances, Oracle), value slot
                    // (potentials, Offset, Complement, RadiusTransform: the distance) or offset
                    // into consts (SuperUnion, SuperIntersect, Perlin, Ricci, Scale, Bt)
  int32_t a = 0;    // offset into consts (Translate, Place, distances, Blanc, Offset,
                    // RadiusTransform), args (n-ary instructions) or groups
  int32_t n = 0;    // argument count (n-ary instructions), number of normals (GenDistance) or
                    // value slot (RadiusTransform: the modulation)
  int32_t reg = 0;  // point register whose box an instruction over slots reads (RadiusTransform)
  const Oracle* node = nullptr;  // Oracle: the model node behind it
};

// The children of one n-ary instruction: where each child's instructions are and which slot holds
// its result, plus what lets the bounds pass prune them.
struct Group {
  int32_t op_index = 0;  // the n-ary instruction that combines the children
  int32_t reg = 0;       // the point register the children read
  struct Child {
    int32_t begin, end;  // instruction range [begin, end)
    int32_t slot;        // the child's result
  };
  std::vector<Child> children;
  // Sum only: children whose value is exactly 0 outside their support box (soft fields) may be
  // dropped where the box misses it. `prunable[i]` says whether child i is one; the BVH indexes
  // their supports (in the frame of `reg`).
  std::vector<uint8_t> prunable;
  std::vector<int32_t> always;  // children that are never dropped, in order
  BoxBvh bvh;                   // over the prunable children's support boxes
  // Sum only: child i is the program's term terms[i] (compile's `terms`), or -1; empty when no
  // child is one.
  std::vector<int32_t> terms;

  // The children that may be non-zero at p (p in the frame of `reg`: those whose supports hold
  // it, and those never dropped), ascending, into out[] (room for every child); returns their
  // number. Only for a sum with a BVH.
  int kept_at(const Vec3& p, int32_t* out) const;
  // Merges `always` into the n ascending children in kept[] (room for every child), in order;
  // returns the new count.
  int merge_always(int32_t* kept, int n) const;
};

struct Program {
  std::vector<Instr> code;
  std::vector<double> consts;
  std::vector<int32_t> args;
  std::vector<Group> groups;
  int32_t slots = 0, regs = 1;
  int32_t result = 0;        // the slot holding f
  int32_t children = 0;      // Σ children over the groups (the pruning stack's depth)
  bool has_pruning = false;  // some sum can drop children: pruning pays even for one point
  // Terms: children of sums whose own values a caller reads beside f (gradient_terms), numbered
  // as compile's `terms` lists their nodes.
  int32_t terms = 0;
};

// A program valid inside one box: the instructions the bounds pass kept, with their own argument
// lists. Its constants, groups and oracle nodes are the base program's.
struct ProgramView {
  const Program* base = nullptr;
  // Written at every bounds pass by its thread: on lines of their own (math/own_lines.h).
  std::vector<Instr, OwnLines<Instr>> code;
  std::vector<int32_t, OwnLines<int32_t>> args;
  int32_t result = 0;
};

// Renumbers p's slots and registers so that values whose lifetimes do not overlap share one
// (program_storage.cpp); compile() calls it last.
void share_storage(Program& p);

}  // namespace softtrace
