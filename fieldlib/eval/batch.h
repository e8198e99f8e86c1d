// Values and gradients at many points (a numpy array, a point cloud): the points are put in a
// spatial order first, so that each run of kBatch neighbours is evaluated on the program pruned
// to their box (eval.h's `prune`) by the batched values evaluator. A field of a thousand blobs
// then costs each point the few blobs near it, not all of them.
//
// Points are x,y,z triples (`xyz[3 * i + axis]`), values go to f[i] and, when `grad` is not
// null, gradients to grad[3 * i + axis]. The results are those of `evaluate` (eval.h) at each
// point, up to the rounding of sums whose zero terms were pruned.
#pragma once

#include <cstddef>
#include <vector>

#include "eval/eval.h"

namespace softtrace {

// The points' indices in spatial order (cells of a grid over their bounding box, in Morton
// order). Throws std::invalid_argument naming the first point with a coordinate that is not finite.
std::vector<size_t> spatial_order(const double* xyz, size_t n);

// Evaluates the points order[begin..end) (from spatial_order). Distinct ranges may run on
// distinct threads, each with its own Workspace.
void eval_ordered(const Program& p, const double* xyz, const std::vector<size_t>& order,
                  size_t begin, size_t end, double* f, double* grad, Workspace& ws);

// Both, on one thread.
void eval_points(const Program& p, const double* xyz, size_t n, double* f, double* grad,
                 Workspace& ws);

}  // namespace softtrace
