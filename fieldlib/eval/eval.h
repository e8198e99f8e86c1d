// The evaluators of compiled programs (program.h), one per numeric domain, each in its own file,
// each a loop over the instructions whose cases the op list generates (program/ops/ops.h):
// - eval_values.cpp:   f at a batch of points (structure of arrays; one instruction at a time over
//                      the batch, so the kernels vectorise);
// - eval_gradient.cpp: f and ∇f at one point (hits and normals only);
// - eval_bounds.cpp:   one walk over a box giving the value interval and the Lipschitz bound, and
//                      the program pruned to what can matter inside the box.
// None allocates once its Workspace has been fitted to the program: a thread keeps one Workspace
// and reuses it for every evaluation.
#pragma once

#include <algorithm>
#include <vector>

#include "math/own_lines.h"
#include "program/ops/op_io.h"
#include "program/program.h"

namespace softtrace {

// What an evaluator walks: a whole program or a pruned view of one.
struct Code {
  const Program* base;
  const Instr* code;
  int size;
  const int32_t* args;
  int result;

  Code(const Program& p)  // NOLINT: a program is its own whole code
      : base(&p),
        code(p.code.data()),
        size(int(p.code.size())),
        args(p.args.data()),
        result(p.result) {}
  Code(const ProgramView& v)  // NOLINT: so is a pruned view
      : base(v.base),
        code(v.code.data()),
        size(int(v.code.size())),
        args(v.args.data()),
        result(v.result) {}
};

// What fit() compares: a program's sizes, which a caller fitting the same program before every
// point it evaluates takes once (the tracer: its fit was 2.9 % of Fig. 12(b)'s instructions,
// mostly in reading the program's and the buffers' sizes again each time).
struct WorkspaceNeed {
  size_t slots = 0, regs = 0, children = 0, code = 0, args = 0;
  WorkspaceNeed() = default;
  explicit WorkspaceNeed(const Program& p)
      : slots(std::max<int32_t>(p.slots, 1)),
        regs(p.regs),
        children(size_t(p.children) + 1),
        code(p.code.size()),
        args(p.args.size()) {}
};

// Scratch memory of one thread's evaluations.
class Workspace {
 public:
  // Cache lines of their own: the main thread's buffers shared lines with the program's blocks
  // that the other threads read (math/own_lines.h).
  template <class T>
  using Lines = std::vector<T, OwnLines<T>>;

  // Grows the buffers to what `p` needs (allocating only when it needs more than before). Called
  // before every single-point evaluation: a program no larger than those fitted before costs a
  // few comparisons, inline (the tracer fits before every point it evaluates: out of line, the
  // call was 0.9 % of fig000_5b's instructions).
  void fit(const Program& p) { fit(WorkspaceNeed(p)); }
  void fit(const WorkspaceNeed& n) {
    // The buffers grow in grow_to only, which records what they hold in `held_`.
    if (n.slots <= held_.slots && n.regs <= held_.regs && n.children <= held_.children &&
        n.code <= held_.code && n.args <= held_.args)
      return;
    grow_to(n);
  }

  // values
  Lines<double> slots;  // slot s, lane l at [s * kBatch + l]
  Lines<double> regs;   // register r, axis i, lane l at [(r * 3 + i) * kBatch + l]
  Lines<Vec3> points;   // register r at [r] (one point; the slots then hold slot s at [s])
  // gradient
  using Dual = softtrace::Dual;  // a value and its gradient (program/ops/op_io.h)
  using Frame = LocalFrame;      // a point register and its Jacobian
  Lines<Dual> duals;
  Lines<Frame> frames;
  // bounds
  Lines<Interval> ivals;
  Lines<double> lips;
  Lines<Box> boxes;
  Lines<Vec3> segs;        // register r's segment ends at [2r], [2r + 1] (segment bounds)
  Lines<double> seg_pads;  // how far the computed points may stray from that segment
  Lines<Interval> slopes;  // each slot's derivative along the segment
  // On a segment, over the first fraction quiet[s] of it, slot s is a distance >= 1 or a field
  // that is exactly 0 (a potential of such a distance, a sum of such fields): no support begins.
  Lines<double> quiet;
  Lines<GaugeEnds> ends;  // the convex gauges' last segment ends (GaugeEnds::kTable)
  Lines<int32_t> kept;    // pruning's stack of chosen children
  Lines<int32_t> marks;   // where each kept child's code starts in the view
  ProgramView view;       // the last pruned program (bounds, prune)

 private:
  void grow_to(const WorkspaceNeed& n);
  WorkspaceNeed held_;  // the most any fitted program needed (zero sizes before the first fit)
};

// f at points (x[i], y[i], z[i]), i < n <= kBatch, into f[i].
void values(Code c, const double* x, const double* y, const double* z, int n, double* f,
            Workspace& ws);
double value(Code c, const Vec3& p, Workspace& ws);
// f(p) from a whole program, skipping the children of sums whose support boxes miss p: the value
// of the program pruned to p (prune() over the point's box), without building that view. `ws`
// must fit p.
double value_pruned(const Program& p, const Vec3& point, Workspace& ws);

// f(p) and ∇f(p) into *grad (any element of the Clarke subdifferential at kinks).
double gradient(Code c, const Vec3& p, Vec3* grad, Workspace& ws);
// The same from a whole program, skipping the children of sums whose support boxes miss p, as
// value_pruned does. `ws` must fit p.
double gradient_pruned(const Program& p, const Vec3& point, Vec3* grad, Workspace& ws);

// gradient_pruned's f(p) and ∇f(p), with each of the program's terms (Program::terms: children of
// sums that compile was asked to number) at p in terms[0, p.terms): the value its sum adds, 0
// where the sum skips it (outside its support). One walk gives the normal and the values that
// weigh per-component materials. Fits ws to p.
double gradient_terms(const Program& p, const Vec3& point, Vec3* grad, double* terms,
                      Workspace& ws);

// A stretch of a ray: the points between a and b, or within `pad` of them (the caller's
// rounding of the points it will evaluate).
struct Segment {
  Vec3 a, b;
  double pad = 0;
  // Whether bounds() derives the slope along it (BoxBounds::slope) where it costs work beyond the
  // values' (gauges' and potentials' derivative ranges); without, those take [-L, L].
  bool slopes = true;
};

struct BoxBounds {
  Interval value;    // contains f over the box
  double lipschitz;  // >= |∇f| over the box (+inf where no bound exists)
  // On a segment: contains df/dt along it (t the distance from a towards b) wherever f is
  // differentiable, so f(t2) - f(t1) lies in slope (t2 - t1); off a segment, [-lipschitz,
  // lipschitz].
  Interval slope = Interval::entire();
  // On a segment: f is exactly 0 over this first fraction of it (the segment has entered no
  // child's support yet, as POV-Ray's blob finds from its list of support entries); else 0.
  double quiet = 0;
};

// One walk over the box: bounds, and in ws.view the program pruned to the box (children of sums
// whose supports miss the box, and min/max children that cannot be the extreme in it, dropped).
// The view is valid only for points inside the box.
BoxBounds bounds(const Program& p, const Box& b, Workspace& ws);
// The same for the points of a segment only (b its bounding box): the children whose supports the
// segment misses are dropped too, and ellipsoidal distances (lp_metric, n = 2), planes and
// generalized distances take their range along the segment, far tighter than over a long
// segment's box. Valid only on the segment.
BoxBounds bounds(const Program& p, const Segment& s, Workspace& ws);

// Only the pruning of `bounds`, by support boxes (no min/max pruning, no bound computed): the
// cheap way to a short program for a small region (a batch of points; one point needs no view:
// value_pruned). Result in ws.view.
void prune(const Program& p, const Box& b, Workspace& ws);
void prune(const Program& p, const Segment& s, Workspace& ws);

// f(p) (and ∇f(p) when grad is non-null) anywhere: value_pruned or gradient_pruned, after fitting
// ws to p. Leaves ws.view as it was.
double evaluate(const Program& p, const Vec3& point, Vec3* grad, Workspace& ws);

}  // namespace softtrace
