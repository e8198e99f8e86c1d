// Reading the image's sampling settings from the scene file (scene.h: Antialias,
// AmbientOcclusion). Both throw SceneError naming the key.
#pragma once

#include "scene/scene.h"

namespace softtrace {

Antialias load_antialias(const Params& p);
AmbientOcclusion load_occlusion(const Params& p);

}  // namespace softtrace
