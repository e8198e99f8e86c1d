// same_bits A B: exit 0 when two images have the same windows, channels and pixel bits (every
// channel of every pixel, NaN payloads and signed zeros included), else 1 with the first
// difference on stderr; 2 when one cannot be read. For shell tests
// (tests/integration/test_slurm.sh).
#include <cstdio>
#include <cstring>
#include <exception>

#include "io/image_file.h"

using softtrace::ImageFile;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: same_bits A B\n");
    return 2;
  }
  ImageFile a, b;
  try {
    a = softtrace::read_image(argv[1]);
    b = softtrace::read_image(argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "same_bits: %s\n", e.what());
    return 2;
  }
  if (a.full_width != b.full_width || a.full_height != b.full_height || a.x0 != b.x0 ||
      a.y0 != b.y0 || a.width != b.width || a.height != b.height) {
    std::fprintf(stderr, "same_bits: %s and %s have different windows\n", argv[1], argv[2]);
    return 1;
  }
  if (a.channels != b.channels) {
    std::fprintf(stderr, "same_bits: %s and %s have different channels\n", argv[1], argv[2]);
    return 1;
  }
  const size_t nc = a.channels.size();
  for (size_t i = 0; i < a.pixels.size(); ++i)
    if (std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0) {
      const size_t pixel = i / nc;
      std::fprintf(stderr,
                   "same_bits: %s and %s differ at x %zu, y %zu, channel %s: %.9g vs %.9g\n",
                   argv[1], argv[2], a.x0 + pixel % a.width, a.y0 + pixel / a.width,
                   a.channels[i % nc].c_str(), a.pixels[i], b.pixels[i]);
      return 1;
    }
  return 0;
}
