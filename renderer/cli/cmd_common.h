// What `render` and `bench` share: the command line's overrides of the scene's image and camera
// (the thread limit is render/threads.h).
#pragma once

#include <string>

#include "cli/commands.h"
#include "scene/scene.h"

namespace softtrace {

// The image size from --width, --height (0: not given) or --scale (0: not given; excludes the
// others). Both sides given are taken as they are; one alone keeps the scene's aspect, the other
// side rounded to the nearest pixel, since a camera's `fov` is vertical and a width alone would
// widen the view; --scale multiplies both sides, rounded. A derived side is at least 1. A side
// outside [1, 16384] is refused naming the option, and frames above 2^26 pixels
// with a SceneError naming /image (check_pixel_count, scene.h).
void apply_image_size(Scene& scene, const std::string& scene_path, int width, int height,
                      double scale);

// Moves the scene's camera by --eye, --target and --fov (those given; override_camera, scene.h),
// after any animation frame is set. Throws std::invalid_argument naming the option.
void apply_camera_options(Scene& scene, const CameraArgs& view);

}  // namespace softtrace
