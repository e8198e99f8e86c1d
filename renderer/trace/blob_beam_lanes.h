// ObjectTracer::blob_beam's test of a ball against a block's frustum, one ball at a time or four
// at once with AVX2 (blob_beam_lanes.cpp): the same IEEE operations in the same order in every
// lane, so the same lists to the bit.
#pragma once

#include "eval/blob_ray.h"
#include "math/vec.h"

namespace softtrace {

// A block's frustum as blob_beam tests it: the eye, the side planes' inward unit normals through
// it (a zero normal cuts nothing), and max_abs(eye), the scale of its rounding.
struct BeamSides {
  Vec3 eye;
  Vec3 normals[4];
  double eye_scale;
};

// Whether the ball's sphere reaches inside every side plane (with a slack of 1e-9 of the
// magnitudes involved, tracer_blob_beam.cpp says why); if so, [*near, *far] holds the distances
// from the eye of its points, with that slack. `ball` must be one (inv_r2 > 0) whose radius is
// finite (1 / inv_r2 < inf).
bool ball_in_beam(const BlobSum::Blob& ball, const BeamSides& sides, double* near, double* far);

// ball_in_beam for four balls: bit i of the result set where balls[i] is in the beam, with
// near[i], far[i]; bit 4 + i set (and the others meaningless) where balls[i]'s radius is not
// finite, which ball_in_beam's caller takes another way. Chosen once for this CPU: AVX2 where it
// has it, else ball_in_beam lane by lane.
using BallsInBeam = unsigned (*)(const BlobSum::Blob* const (&balls)[4], const BeamSides& sides,
                                 double (&near)[4], double (&far)[4]);
BallsInBeam balls_in_beam();
unsigned balls_in_beam_scalar(const BlobSum::Blob* const (&balls)[4], const BeamSides& sides,
                              double (&near)[4], double (&far)[4]);
// Only where BlobSum::has_avx2().
unsigned balls_in_beam_avx2(const BlobSum::Blob* const (&balls)[4], const BeamSides& sides,
                            double (&near)[4], double (&far)[4]);

}  // namespace softtrace
