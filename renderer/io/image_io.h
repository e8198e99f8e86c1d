// The per-format halves of image_file.h's reader.
#pragma once

#include "io/image_file.h"

namespace softtrace {

ImageFile read_exr(const std::string& path);
ImageFile read_png(const std::string& path);

}  // namespace softtrace
