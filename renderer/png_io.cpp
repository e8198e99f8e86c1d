// 8-bit PNG through libpng's simplified API (png_image).
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "image_io.h"

namespace softtrace {

namespace {

struct PngImage {
  png_image image{};
  PngImage() { image.version = PNG_IMAGE_VERSION; }
  ~PngImage() { png_image_free(&image); }
};

}  // namespace

ImageFile read_png(const std::string& path) {
  PngImage p;
  if (!png_image_begin_read_from_file(&p.image, path.c_str()))
    throw std::runtime_error(p.image.message);
  // Keep the stored channels (grey or colour, with or without alpha) but expand palettes and
  // bring 16-bit samples to 8 bits.
  p.image.format &= PNG_FORMAT_FLAG_COLOR | PNG_FORMAT_FLAG_ALPHA;
  ImageFile img;
  img.full_width = img.width = int(p.image.width);
  img.full_height = img.height = int(p.image.height);
  if (size_t(img.width) * img.height > (size_t(1) << 28))
    throw std::runtime_error("image too large");
  std::vector<png_byte> bytes(PNG_IMAGE_SIZE(p.image));
  if (!png_image_finish_read(&p.image, nullptr, bytes.data(), 0, nullptr))
    throw std::runtime_error(p.image.message);
  const bool colour = p.image.format & PNG_FORMAT_FLAG_COLOR;
  img.channels = colour ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"Y"};
  if (p.image.format & PNG_FORMAT_FLAG_ALPHA) img.channels.push_back("A");
  img.pixels.resize(bytes.size());
  // Times the float reciprocal, as OpenImageIO converts, so idiff and diff see the same values.
  constexpr float kScale = 1.0f / 255.0f;
  for (size_t i = 0; i < bytes.size(); ++i) img.pixels[i] = bytes[i] * kScale;
  return img;
}

uint8_t png_sample(float v) {
  v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
  return uint8_t(std::lround(v * 255.0f));
}

void write_png(const std::string& path, const ImageFile& img, bool srgb) {
  PngPixels png{img.width, img.height, int(img.channels.size()), {}};
  png.bytes.resize(img.pixels.size());
  for (size_t i = 0; i < png.bytes.size(); ++i) png.bytes[i] = png_sample(img.pixels[i]);
  write_png(path, png, srgb);
}

void write_png(const std::string& path, const PngPixels& img, bool srgb) {
  const int nc = img.channels;
  if (nc < 1 || nc > 4) throw std::runtime_error("a PNG holds 1 to 4 channels");
  PngImage p;
  p.image.width = png_uint_32(img.width);
  p.image.height = png_uint_32(img.height);
  p.image.format =
      (nc >= 3 ? PNG_FORMAT_FLAG_COLOR : 0) | (nc == 2 || nc == 4 ? PNG_FORMAT_FLAG_ALPHA : 0);
  // Without this flag libpng writes the sRGB chunk for 8-bit data (png_image_write_main).
  if (!srgb) p.image.flags |= PNG_IMAGE_FLAG_COLORSPACE_NOT_sRGB;
  // Speed over size (libpng then filters less and deflates faster): a render writes its image
  // after the frame, on one thread.
  p.image.flags |= PNG_IMAGE_FLAG_FAST;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot open the file for writing");
  const bool written = png_image_write_to_stdio(&p.image, f, 0, img.bytes.data(), 0, nullptr);
  // A full disk may show only when the buffer is flushed, or when the data reaches the disk.
  const bool flushed = written && std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written) throw std::runtime_error(p.image.message);
  if (!flushed || !closed)
    throw std::runtime_error(std::string("cannot write the file: ") +
                             std::strerror(flushed ? errno : flush_errno));
}

}  // namespace softtrace
