// One walk over a box: the value interval and Lipschitz bound of every instruction, and the
// program pruned to the box (libfive's intervalAndPush). Each op's bounds, over a box and along a
// segment, are its kernel struct's (program/ops/ops.h); the walk chooses the children of groups
// and prunes.
//
// Rounding. Instead of rounding every interval operation outward (nextafter), each instruction's
// result is widened once, by a bound on the rounding error of the few operations that made it
// (translation, rotation, potentials and sums say how in their op structs). Oracles and their
// children keep the model nodes' own outward-rounded bounds.
#include <algorithm>
#include <cmath>
#include <limits>

#include "eval/eval.h"
#include "program/ops/ops.h"

namespace softtrace {

namespace {

class Walker {
 public:
  Walker(const Program& p, Workspace& ws, bool with_bounds, const Segment* seg)
      : p_(p),
        ws_(ws),
        io_{&p,
            p.consts.data(),
            ws.boxes.data(),
            ws.ivals.data(),
            ws.lips.data(),
            ws.slopes.data(),
            ws.quiet.data(),
            ws.segs.data(),
            ws.seg_pads.data(),
            ws.ends.data(),
            with_bounds,
            seg != nullptr,
            seg && seg->slopes,
            seg ? length(ws.segs[1] - ws.segs[0]) : 0} {}

  // Walks code[begin, end) of the base program, appending what is kept to ws.view.
  void walk(int begin, int end) {
    for (int k = begin; k < end;) {
      const Instr& in = p_.code[k];
      if (in.op == Op::Group) {
        k = group(p_.groups[in.a]);
        continue;
      }
      step(in);
      ws_.view.code.push_back(in);
      ++k;
    }
  }

 private:
  // The bounds of one instruction (an n-ary one's over the children kept: io_.group, io_.kept);
  // without bounds wanted, only the placements' boxes or segments, which pruning reads.
  void step(const Instr& in) {
    switch (in.op) {
#define SOFTTRACE_OP_BOUNDS(name)                                   \
  case Op::name:                                                    \
    if (io_.bounds || name##Op::kPlaces) name##Op::bounds(in, io_); \
    break;
      SOFTTRACE_OPS(SOFTTRACE_OP_BOUNDS)
#undef SOFTTRACE_OP_BOUNDS
    }
  }

  // Chooses, walks and combines the children of a group; returns the index after it.
  int group(const Group& g) {
    const Instr& combine = p_.code[g.op_index];
    int32_t* kept = ws_.kept.data();
    const int first = top_;
    if (combine.op == Op::Sum && !g.bvh.empty()) {
      // The children that are never dropped, merged in order with those whose support meets the
      // box (both lists ascend).
      const Vec3* S = ws_.segs.data() + 2 * g.reg;
      const int mid = io_.segment ? g.bvh.query(segment_box_of(g.reg), S[0], S[1],
                                                ws_.seg_pads[g.reg], kept, first)
                                  : g.bvh.query(ws_.boxes[g.reg], kept, first);
      top_ = first + g.merge_always(kept + first, mid - first);
    } else {
      for (size_t i = 0; i < g.children.size(); ++i) kept[top_++] = static_cast<int32_t>(i);
    }
    const int last = top_;
    int32_t* marks = ws_.marks.data();
    // A sum with a BVH may be large: its children kept in a box then lie in runs far apart in a
    // program too large for the cache (10,000 blobs: 2 MB of code, constants and slots). Their
    // addresses are known from the kept list, so their loads start a few children ahead: the code
    // four ahead, the constants (found from that code; 24 doubles hold a placement's and a
    // distance's) two ahead. blob_box_pass at N = 10,000: 0.95x the time; N = 100 unchanged.
    // (Written here, not as a function: GCC drops a call whose only effect is prefetching.)
    const bool indexed = !g.bvh.empty();
    for (int j = first; j < last; ++j) {
      const Group::Child& c = g.children[kept[j]];
      if (indexed && j + 4 < last) {
        const Group::Child& ahead = g.children[kept[j + 4]];
        __builtin_prefetch(&p_.code[ahead.begin]);
        __builtin_prefetch(&p_.code[ahead.end - 1]);
      }
      // Not without constants: an offset from a null K is undefined (clang's UBSan says so).
      if (indexed && io_.K && j + 2 < last) {
        const double* k = io_.K + p_.code[g.children[kept[j + 2]].begin].a;
        for (int line = 0; line < 3; ++line) __builtin_prefetch(k + 8 * line);
      }
      marks[j] = static_cast<int32_t>(ws_.view.code.size());
      if (zero_outside_support(c)) continue;
      walk(c.begin, c.end);
    }
    // The power sums and products keep every child: each one's value moves theirs.
    const bool min_max = combine.op == Op::Min || combine.op == Op::Max;
    if (io_.bounds && min_max) drop_inactive(g, combine.op == Op::Min, first, last);
    if (io_.bounds && io_.segment && combine.op == Op::Sum) drop_quiet(g, first, last);

    Instr out = combine;
    out.n = top_ - first;
    if (io_.bounds) {
      io_.group = &g;
      io_.kept = kept + first;
      if (combine.op == Op::Scale)
        keep_sharp(out, g, first, ScaleOp::bounds_and_pick(out, io_));
      else
        step(out);
    }
    out.a = static_cast<int32_t>(ws_.view.args.size());
    for (int j = first; j < first + out.n; ++j) ws_.view.args.push_back(g.children[kept[j]].slot);
    ws_.view.code.push_back(out);
    top_ = first;
    return g.op_index + 1;
  }

  // Register r's box on a segment (io_.box). Register 0's is the pass's own box, which run() set
  // from the same ends and pad: the same bits without taking it again (a top-level sum's query
  // took it on every pass, 61 instructions of Fig. 12(b)'s 2,950 a pass).
  Box segment_box_of(int r) const {
    return r == 0 ? ws_.boxes[0] : io_.box(r);
  }

  // The scale method outside its region III all over the box or segment (`pick`, from
  // ScaleOperator::sharp_everywhere on the children's intervals, or -1): h is that child's value,
  // bit for bit, at every point there. The other child's code is removed from the view and the
  // instruction becomes the min of one argument (a copy): the points of a segment evaluate one
  // branch of a nested union (fig000_5b: 6 cylinders, 5 unions), not all of it.
  void keep_sharp(Instr& out, const Group& g, int first, int pick) {
    if (pick < 0) return;
    const int32_t other = g.children[ws_.kept[first + 1 - pick]].slot;
    drop_children(g, first, first + 2, [&](const Group::Child& c) { return c.slot == other; });
    out.op = Op::Min;
    out.n = 1;
  }

  // A child ending in a radius transform whose support the box misses is 0 there, whatever its
  // distance and modulation: its bounds are written without bounding them (RadiusTransformOp::
  // zero_outside, the same as its own bounds() writes) and its code is kept for the points. Only
  // for a child of plain instructions (no group, no placement: its register is set before it).
  bool zero_outside_support(const Group::Child& c) {
    const Instr& last = p_.code[c.end - 1];
    if (!io_.bounds || last.op != Op::RadiusTransform) return false;
    for (int k = c.begin; k < c.end; ++k) {
      const Op op = p_.code[k].op;
      if (op == Op::Group || op == Op::Translate || op == Op::Place) return false;
    }
    if (!RadiusTransformOp::zero_outside(last, io_)) return false;
    ws_.view.code.insert(ws_.view.code.end(), p_.code.begin() + c.begin, p_.code.begin() + c.end);
    return true;
  }

  // min/max: a child whose interval lies wholly beyond the extreme's is never the extreme in the
  // box; its code is removed from the view.
  void drop_inactive(const Group& g, bool is_min, int first, int last) {
    const Interval* I = ws_.ivals.data();
    const int32_t* kept = ws_.kept.data();
    double bound =
        is_min ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    for (int j = first; j < last; ++j) {
      const Interval& a = I[g.children[kept[j]].slot];
      bound = is_min ? std::min(bound, a.hi) : std::max(bound, a.lo);
    }
    // NaN bounds count as active: nothing is known of them.
    drop_children(g, first, last, [&](const Group::Child& c) {
      return is_min ? I[c.slot].lo > bound : I[c.slot].hi < bound;
    });
  }

  // A sum on a segment: a child quiet all along it (its support never entered) is exactly 0
  // there, so the points of the segment need not evaluate it.
  void drop_quiet(const Group& g, int first, int last) {
    drop_children(g, first, last,
                  [&](const Group::Child& c) { return SumOp::zero_start(io_, c) >= 1; });
  }

  // Removes the kept children [first, last) that `drop` picks, and their code from the view (the
  // others' code moves down).
  template <class Drop>
  void drop_children(const Group& g, int first, int last, const Drop& drop) {
    if (first == last) return;
    int32_t* kept = ws_.kept.data();
    const int32_t* marks = ws_.marks.data();
    auto& code = ws_.view.code;
    int w = first;
    size_t write = marks[first];
    for (int j = first; j < last; ++j) {
      const Group::Child& c = g.children[kept[j]];
      if (drop(c)) continue;
      const size_t from = marks[j], to = j + 1 < last ? marks[j + 1] : code.size();
      // Until the first child dropped the code stays where it is: a sum on a segment asks this of
      // every pass and mostly drops nothing (memmove onto itself was a call per child kept).
      if (from != write) std::copy(code.begin() + from, code.begin() + to, code.begin() + write);
      write += to - from;
      kept[w++] = kept[j];
    }
    code.resize(write);
    top_ = w;
  }

  const Program& p_;
  Workspace& ws_;
  BoundsIO io_;
  int top_ = 0;
};

void run(const Program& p, const Box& b, const Segment* seg, Workspace& ws, bool with_bounds) {
  ws.view.base = &p;
  ws.view.code.clear();
  ws.view.args.clear();
  ws.boxes[0] = b;
  if (seg) {
    ws.segs[0] = seg->a;
    ws.segs[1] = seg->b;
    ws.seg_pads[0] = seg->pad;
  }
  Walker(p, ws, with_bounds, seg).walk(0, static_cast<int>(p.code.size()));
  ws.view.result = p.result;
}

}  // namespace

BoxBounds bounds(const Program& p, const Box& b, Workspace& ws) {
  run(p, b, nullptr, ws, true);
  const double L = ws.lips[p.result];
  return {ws.ivals[p.result], L, {-L, L}};
}

BoxBounds bounds(const Program& p, const Segment& s, Workspace& ws) {
  run(p, segment_box(s.a, s.b, s.pad), &s, ws, true);
  return {ws.ivals[p.result], ws.lips[p.result], ws.slopes[p.result],
          zero_when_quiet(p.code.back().op) ? ws.quiet[p.result] : 0.0};
}

void prune(const Program& p, const Box& b, Workspace& ws) {
  run(p, b, nullptr, ws, false);
}

void prune(const Program& p, const Segment& s, Workspace& ws) {
  run(p, segment_box(s.a, s.b, s.pad), &s, ws, false);
}

}  // namespace softtrace
