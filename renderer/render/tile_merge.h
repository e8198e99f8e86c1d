// Tiles of one frame (render --tile/--crop/--pixel-bounds EXRs) put back together. Every pixel
// of the frame must come from exactly one tile, and all tiles from the same scene and settings
// (softtrace/renderHash, which covers --flatten and --half too), so the result has the bits of a
// single-process render.
#pragma once

#include <string>
#include <vector>

#include "film/film.h"
#include "io/image_file.h"

namespace softtrace {

// The largest frame merge puts together: what render makes (sides of 1 to 16384, at most 2^26
// pixels), so that a tampered header cannot make it allocate more.
constexpr int kMaxSide = 16384;
constexpr long long kMaxPixels = 1LL << 26;

// Checks the tiles (read from `paths`, named in errors) against each other and the frame, then
// pastes them into a film of the whole frame carrying their renderHash, render and frame
// attributes. Throws std::runtime_error saying what is wrong (which pixels no tile has, which
// tiles overlap or disagree), before allocating anything the size of the frame.
Film merge_tiles(const std::vector<ImageFile>& tiles, const std::vector<std::string>& paths);

}  // namespace softtrace
