#include "io/image_file.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "io/image_io.h"

namespace softtrace {

int ImageFile::channel(const std::string& name) const {
  const auto it = std::find(channels.begin(), channels.end(), name);
  return it == channels.end() ? -1 : int(it - channels.begin());
}

ImageFile read_image(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": no such file or not readable");
  unsigned char magic[8] = {};
  in.read(reinterpret_cast<char*>(magic), sizeof magic);
  static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  try {
    if (in.gcount() >= 4 && std::memcmp(magic, kExr, 4) == 0) return read_exr(path);
    if (in.gcount() == 8 && std::memcmp(magic, kPng, 8) == 0) return read_png(path);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot read the image: " + e.what());
  }
  throw std::runtime_error(path + ": cannot read the image: not an EXR or PNG file");
}

}  // namespace softtrace
