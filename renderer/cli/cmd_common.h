// What `render` and `bench` share: the command line's overrides of the scene's image and the
// thread limit.
#pragma once

#include <tbb/global_control.h>

#include <memory>
#include <string>

#include "scene/scene.h"

namespace softtrace {

// The image size from --width/--height (0 keeps the scene's). Frames above 2^26 pixels are
// refused (check_pixel_count, scene.h).
void apply_image_size(Scene& scene, const std::string& scene_path, int width, int height);

// Caps TBB's parallelism at `threads` (0: all cores) for as long as the result lives.
std::unique_ptr<tbb::global_control> limit_threads(int threads);

}  // namespace softtrace
