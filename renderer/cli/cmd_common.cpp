#include "cli/cmd_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "cli/option_checks.h"

namespace softtrace {

namespace {

constexpr int kMaxSide = 16384;

// `side` scaled by `factor`, rounded, at least 1; an error naming `option` beyond the largest side.
int scaled_side(int side, double factor, const std::string& option, const char* which) {
  const double v = std::max(1.0, std::round(side * factor));
  if (v > kMaxSide) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "%s: keeping the scene's aspect gives an image %s of %.0f pixels (expected 1 "
                  "to %d)",
                  option.c_str(), which, v, kMaxSide);
    throw std::invalid_argument(text);
  }
  return static_cast<int>(v);
}

}  // namespace

void apply_image_size(Scene& scene, const std::string& scene_path, int width, int height,
                      double scale) {
  ImageSettings& image = scene.image;
  if (scale > 0) {
    char option[64];
    std::snprintf(option, sizeof option, "--scale %g", scale);
    const int w = scaled_side(image.width, scale, option, "width");
    image.height = scaled_side(image.height, scale, option, "height");
    image.width = w;
  } else if (width && height) {
    image.width = width;
    image.height = height;
  } else if (width) {
    image.height = scaled_side(image.height, double(width) / image.width,
                               "--width " + std::to_string(width), "height");
    image.width = width;
  } else if (height) {
    image.width = scaled_side(image.width, double(height) / image.height,
                              "--height " + std::to_string(height), "width");
    image.height = height;
  }
  check_pixel_count(image, scene_path);
}

void apply_camera_options(Scene& scene, const CameraArgs& view) {
  CameraOverride o;
  if (view.eye) o.eye = point_of(*view.eye);
  if (view.target) o.target = point_of(*view.target);
  o.fov = view.fov;
  override_camera(scene, o);
}

}  // namespace softtrace
