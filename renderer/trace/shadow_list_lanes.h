// A shadow ray's entries of its directional light's list (BlobBeam::parallel,
// tracer_shadow_beam.cpp) found two at a time with SSE2, or four with AVX2 where the CPU has it
// (shadow_list_lanes.cpp): the same IEEE operations as the scalar test the comment states, so the
// same entries in the same order.
#pragma once

#include "trace/tracer.h"

namespace softtrace {

// The entries of a prism's list whose bounding spheres a ray along the prism's axis from (x, y) =
// across passes within reach of (dx * dx + dy * dy <= reach * reach, dx = x - across[0], dy =
// y - across[1]), into `out` (room for the list's entries), in the list's order; their count.
// A list's `across` must be as long as its entries. Its own file keeps it out of line from
// first_hit_blobs: inline, its registers cost the camera sweep's loop. Chosen once for this CPU:
// entries_on_line_four where it has AVX2, else entries_on_line_pairs.
int entries_on_line(const BlobBeam& list, const double (&across)[2], BlobBeam::Entry* out);
int entries_on_line_pairs(const BlobBeam& list, const double (&across)[2], BlobBeam::Entry* out);
#ifdef __SSE2__
// Only where BlobSum::has_avx2().
int entries_on_line_four(const BlobBeam& list, const double (&across)[2], BlobBeam::Entry* out);
#endif

}  // namespace softtrace
