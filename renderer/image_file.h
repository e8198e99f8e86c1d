// Reading an image file whole: its windows, channels, float pixels and string metadata, for
// commands that take images in (merge). The implementation is the only reader of image files.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace softtrace {

// The data window [x0, x0 + width) x [y0, y0 + height) of a full_width x full_height display
// window whose origin is (0, 0); `pixels` holds width * height * channels.size() floats,
// interleaved, row by row from the top.
struct ImageFile {
  int full_width, full_height;
  int x0, y0, width, height;
  std::vector<std::string> channels;
  std::vector<float> pixels;  // interleaved
  std::map<std::string, std::string> attributes;
};

// Reads the first image (part) of an EXR file. Throws std::runtime_error naming the path.
ImageFile read_image(const std::string& path);

}  // namespace softtrace
