#include "cli/cmd_common.h"

namespace softtrace {

void apply_image_size(Scene& scene, const std::string& scene_path, int width, int height) {
  if (width) scene.image.width = width;
  if (height) scene.image.height = height;
  check_pixel_count(scene.image, scene_path);
}

std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (!threads) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               threads);
}

}  // namespace softtrace
