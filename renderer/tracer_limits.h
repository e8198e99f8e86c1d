// The tolerances and limits both of ObjectTracer's searches share (tracer.cpp, the segment
// tracer; tracer_blobs.cpp, the polynomial one).
#pragma once

namespace softtrace::tracer_limits {

// A ray that needs more evaluations than this gives up (reported as a hit); no test scene comes
// close.
constexpr int kMaxSteps = 200000;
// Sphere-tracing steps within one segment before it is cut short at the current point: the bound
// over a long segment's box can be far looser than over a short one (e.g. a modulated radius whose
// [d]/[f] decorrelates). Every step taken was certified, so stopping early skips nothing.
constexpr int kSegmentSteps = 4;
// The tolerance of the march is this multiple of the footprint radius: a certified step shorter
// than that ends the approach, and probes ahead decide. It sets the cost, not what is found (a
// give-up needs the surface within kFinest of a tolerance). With kSegmentSteps, measured over
// the 1000 blobs and six figure scenes at 80x60: 2 and 4 take 4-13 % fewer evaluations than 1
// and 8, 0.7 more.
constexpr double kDecide = 2;
// The farthest probe, in tolerances (4 footprint radii): a bracket is refined to its one crossing
// only when it is that short.
constexpr double kProbeReach = 2;
// The shortest piece the halving looks at, in tolerances: a surface must pass within about this
// of the ray for a search to give up there.
constexpr double kFinest = 1.0 / 1024;
// Root refinement stops when the bracket is this fraction of the footprint radius.
constexpr double kRefine = 1e-3;

}  // namespace softtrace::tracer_limits
