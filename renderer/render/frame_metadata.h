// What the EXR header says about a frame: the camera as OpenEXR's standard worldToCamera and
// worldToNDC attributes, and the scene's name and content hash.
#pragma once

#include <cstdint>
#include <string>

#include "film/film.h"
#include "scene/scene.h"

namespace softtrace {

// FNV-1a (64-bit) of `bytes` as 16 lower-case hex digits: a stable name for a scene file's
// content, not a cryptographic hash.
std::string fnv1a64_hex(const std::string& bytes);

// 16 lower-case hex digits of `value`.
std::string hex64(uint64_t value);

// The frame's header data for `scene` rendered as a full_width x full_height display window. The
// scene hash (left empty without `with_hash`: a PNG has no use for it) is scene.file_hash(), of
// the bytes that were parsed: the file is never read again, so
// a scene parsed from text has one, and an edit during a render cannot change it. Matrices follow
// OpenEXR's conventions (ImfStandardAttributes.h), as row vectors (p' = p * M, as pbrt and Mitsuba
// write them): camera space is left-handed with x right, y up and z the viewing direction; NDC has
// (0,0) at the display window's top-left corner and (1,1) at its bottom-right, after dividing by w
// (= camera-space z). NDC z is 1/z. For an orthographic camera w is 1 and NDC z is z.
FrameInfo frame_info(const Scene& scene, int full_width, int full_height, bool with_hash = true);

}  // namespace softtrace
