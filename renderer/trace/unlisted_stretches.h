// The stretches of a camera ray's way through a sum of polynomial blobs where its list holds no
// blob (ObjectTracer::unlisted_stretches, and the block's rays answered together, unmet_rays.h):
// first_hit_blobs' loop with nothing to read, its stretches counted as the steps AOV counts them.
// One loop for both, so that their counters cannot part.
#pragma once

#include <algorithm>

#include "trace/tracer.h"
#include "trace/tracer_limits.h"

namespace softtrace {

// The way from t to t1 as one stretch and, where rounding leaves t short of t1, another twice as
// long (first_hit_blobs' next stretch after one of fewer than kFewTerms terms), each added to
// work.box_evals. False, with t where it stopped, where work reaches the ray limit
// (tracer_limits::kMaxSteps evaluations) first: the search gives up there.
inline bool count_unlisted_stretches(double& t, double t1, TraceCounters& work) {
  double s = t1 - t;
  while (t < t1) {
    if (work.evaluations() >= tracer_limits::kMaxSteps) return false;
    const double len = std::min(t + s, t1) - t;
    ++work.box_evals;
    t += len;
    s = 2 * len;
  }
  return true;
}

}  // namespace softtrace
