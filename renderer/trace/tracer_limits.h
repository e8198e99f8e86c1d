// The tolerances and limits both of ObjectTracer's searches share (tracer.cpp, the segment
// tracer; tracer_blobs.cpp, the polynomial one).
#pragma once

namespace softtrace::tracer_limits {

// A ray that needs more evaluations than this gives up (reported as a hit); no test scene comes
// close.
constexpr int kMaxSteps = 200000;
// The tolerance of the march is this multiple of the footprint radius: a certified step shorter
// than that ends the approach, and probes ahead decide. It sets the cost, not what is found (a
// give-up needs the surface within kFinest of a tolerance). With tracer.cpp's kSegmentSteps, over
// the 1000 blobs and six figure scenes at 80x60: 2 and 4 take 4-13 % fewer evaluations than 1
// and 8, 0.7 more.
constexpr double kDecide = 2;
// The shortest piece the halving looks at, in tolerances, before a piece it could not decide is
// halved on to kFinestDeep (within kDeepBudget evaluations): a surface must pass within about
// that of the ray, without a sign change seen, for a piece to stay undecided.
constexpr double kFinest = 1.0 / 1024;
// A ray grazing a surface at a distance e from it needs pieces about 2e/L long where no slope
// along the segment is known (oracles: bulge-eliminated BT blends): fig003_9a's graze 3e-7 of a
// footprint from its bulge-eliminated blend took 2835 evaluations, beyond the 2000 this was.
constexpr double kFinestDeep = 1e-9;
constexpr int kDeepBudget = 20000;
// Root refinement stops when the bracket is this fraction of the footprint radius.
constexpr double kRefine = 1e-3;

}  // namespace softtrace::tracer_limits
