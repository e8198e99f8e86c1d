// Image files without OpenImageIO: EXR through OpenEXR, PNG through libpng. The one reader
// (`softtrace diff`, tests) and the two writers (film.cpp, diff's difference image).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace softtrace {

struct ImageFile {
  int full_width = 0, full_height = 0;        // display window
  int x0 = 0, y0 = 0, width = 0, height = 0;  // data window (origin in display coordinates)
  // EXR: in OpenImageIO's canonical order (per layer R,G,B,A,Z first; X,Y,Z first where a layer
  // has X), so reports list channels as idiff does. PNG: R,G,B(,A) or Y(,A).
  std::vector<std::string> channels;
  std::vector<float> pixels;                      // interleaved, width * height * channels.size()
  std::map<std::string, std::string> attributes;  // the EXR header's string attributes

  int channel(const std::string& name) const;  // index, or -1
  float at(int x, int y, int c) const {        // data-window coordinates
    return pixels[(size_t(y) * width + x) * channels.size() + c];
  }
};

// Reads an EXR (first part; scanline or tiled, any pixel type, read as float) or a PNG of 8 or 16
// bits (values / 255 or / 65535, as stored: sRGB-encoded, straight alpha), told apart by their
// first bytes.
// Throws std::runtime_error naming the file and the reason.
ImageFile read_image(const std::string& path);

// What an EXR header carries besides channels and string attributes.
struct ExrExtras {
  std::vector<bool> half;  // per channel: stored as half float (default: float)
  std::map<std::string, std::array<float, 16>> matrices;  // M44f, row-major (row vectors)
  std::map<std::string, float> floats;
  std::map<std::string, int> ints;
};

// Writes `image` (its windows, channels and string attributes) to `path` as a zip-compressed
// EXR. Throws std::runtime_error.
void write_exr(const std::string& path, const ImageFile& image, const ExrExtras& extras = {});

// Writes the data window as an 8-bit PNG: channels R,G,B(,A) or Y(,A), values in [0,1] already
// encoded as they should be stored (sRGB for colour). With `srgb` the file says so (sRGB chunk).
void write_png(const std::string& path, const ImageFile& image, bool srgb);

// An 8-bit PNG's samples as stored, interleaved: width * height * channels bytes, channels
// R,G,B(,A) or Y(,A). A render's film goes straight to these, with no float image between.
struct PngPixels {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> bytes;
};
// The byte that stores v (clamped to [0,1], NaN as 0), as write_png stores every value. Inline:
// a render's PNG with alpha takes one a pixel (0.3 ms of a 320x240 frame's write as a call).
inline uint8_t png_sample(float v) {
  v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
  // std::lround(v * 255.0f) without the library call: the float product plus 0.5 is exact in a
  // double, and the floor of a non-negative x + 0.5 rounds halves away from zero as lround does.
  return uint8_t(std::floor(double(v * 255.0f) + 0.5));
}
void write_png(const std::string& path, const PngPixels& image, bool srgb);

// Calls body(i) for every i in [0, count), in any order, perhaps on several threads at once (the
// command line passes its frame's worker threads, render/threads.h); empty: one after another on
// the calling thread. What is computed must not depend on which.
using EachIndex = std::function<void(size_t count, const std::function<void(size_t)>& body)>;

// Row y of an 8-bit PNG's samples, as stored (width * channels bytes, interleaved), into `row`.
using PngRow = std::function<void(int y, uint8_t* row)>;

// Writes a width x height PNG of `channels` (1 to 4: Y, YA, RGB, RGBA) whose rows `row` gives.
// The rows are made and deflated in bands of a fixed number of rows (set by the image's size
// alone, so the file is the same bytes whatever `each` runs on), each band a run of the zlib stream
// ended by a sync flush; `each` runs the bands. Throws std::runtime_error.
void write_png(const std::string& path, int width, int height, int channels, bool srgb,
               const PngRow& row, const EachIndex& each = {});

}  // namespace softtrace
