#include "render/tiles.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <vector>

namespace softtrace {

namespace {

// Four comma-separated numbers; `what` names the option in errors.
std::vector<double> four_numbers(const std::string& spec, const std::string& what) {
  std::vector<double> v;
  const char* p = spec.c_str();
  for (int i = 0; i < 4; ++i) {
    char* end = nullptr;
    v.push_back(std::strtod(p, &end));
    const char expected = i < 3 ? ',' : '\0';
    if (end == p || *end != expected || !std::isfinite(v.back()))
      throw std::invalid_argument(what + " '" + spec + "': expected X0,X1,Y0,Y1");
    p = end + 1;
  }
  return v;
}

}  // namespace

PixelBounds crop_window(const std::string& spec, int width, int height) {
  const std::vector<double> v = four_numbers(spec, "--crop");
  if (!(0 <= v[0] && v[0] < v[1] && v[1] <= 1 && 0 <= v[2] && v[2] < v[3] && v[3] <= 1))
    throw std::invalid_argument("--crop '" + spec +
                                "': expected 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1");
  const auto edge = [](int size, double f) {
    return static_cast<int>(std::ceil(static_cast<float>(size) * static_cast<float>(f)));
  };
  const PixelBounds b{edge(width, v[0]), edge(width, v[1]), edge(height, v[2]), edge(height, v[3])};
  if (b.width() <= 0 || b.height() <= 0)
    throw std::invalid_argument("--crop '" + spec + "': no pixel of the " + std::to_string(width) +
                                "x" + std::to_string(height) + " image is inside");
  return b;
}

PixelBounds pixel_bounds(const std::string& spec, int width, int height) {
  const std::vector<double> v = four_numbers(spec, "--pixel-bounds");
  for (double x : v)
    if (x != std::floor(x))
      throw std::invalid_argument("--pixel-bounds '" + spec + "': expected whole pixels");
  if (!(0 <= v[0] && v[0] < v[1] && v[1] <= width && 0 <= v[2] && v[2] < v[3] && v[3] <= height))
    throw std::invalid_argument("--pixel-bounds '" + spec +
                                "': expected 0 <= X0 < X1 <= " + std::to_string(width) +
                                " and 0 <= Y0 < Y1 <= " + std::to_string(height));
  return {int(v[0]), int(v[1]), int(v[2]), int(v[3])};
}

TileIndex parse_tile(const std::string& spec) {
  // Digits only, each number checked against int's range: sscanf's %d once wrapped
  // 0/4294967297 to 0/1, the whole frame.
  const auto whole = [&](size_t begin, size_t end, int& out) {
    if (begin == end || end - begin > 10) return false;
    long long v = 0;
    for (size_t i = begin; i < end; ++i) {
      if (spec[i] < '0' || spec[i] > '9') return false;
      v = v * 10 + (spec[i] - '0');
    }
    if (v > std::numeric_limits<int>::max()) return false;
    out = static_cast<int>(v);
    return true;
  };
  TileIndex t;
  const size_t slash = spec.find('/');
  if (slash == std::string::npos || !whole(0, slash, t.index) ||
      !whole(slash + 1, spec.size(), t.count) || t.count < 1 || t.index >= t.count)
    throw std::invalid_argument("--tile '" + spec +
                                "': expected I/N, whole numbers with 0 <= I < N <= 2^31 - 1 "
                                "(tiles are numbered from 0)");
  return t;
}

PixelBounds tile_bounds(TileIndex t, int width, int height) {
  const long long n = t.count;
  const auto too_many = [&] {
    return std::invalid_argument("--tile " + std::to_string(t.index) + "/" + std::to_string(n) +
                                 ": a " + std::to_string(width) + "x" + std::to_string(height) +
                                 " image has too few pixels for " + std::to_string(n) + " tiles");
  };
  // Square tiles of area W H / n have side sqrt(W H / n): that makes H / side rows.
  long long rows = std::llround(std::sqrt(double(n) * height / width));
  rows = std::max(1LL, std::min({rows, n, static_cast<long long>(height)}));
  // The first n % rows rows hold one tile more; a row's height is proportional to its tiles.
  // Every tile of the split is checked, not only the one asked for, so that all tasks of a split
  // agree on whether it is possible.
  const long long base = n / rows, extra = n % rows;
  if (base + (extra ? 1 : 0) > width) throw too_many();
  PixelBounds found;
  long long first = 0;  // index of the row's first tile
  for (long long r = 0; r < rows; ++r) {
    const long long count = base + (r < extra ? 1 : 0);
    const int y0 = static_cast<int>(height * first / n);
    const int y1 = static_cast<int>(height * (first + count) / n);
    if (y1 <= y0) throw too_many();
    if (t.index >= first && t.index < first + count) {
      const long long j = t.index - first;
      found = {static_cast<int>(width * j / count), static_cast<int>(width * (j + 1) / count), y0,
               y1};
    }
    first += count;
  }
  return found;
}

std::string render_settings(const Scene& scene, const std::string& lipschitz, int frame) {
  std::string s = std::to_string(scene.image.width) + "x" + std::to_string(scene.image.height) +
                  " spp=" + std::to_string(scene.image.spp) + " lipschitz=" + lipschitz;
  if (frame >= 0) s += " frame=" + std::to_string(frame);
  // The scene file's bytes hold the rest; only --antialias can change this without them.
  const Antialias& aa = scene.image.antialias;
  if (aa.on()) s += " antialias=" + std::to_string(aa.threshold) + "/" + std::to_string(aa.depth);
  return s;
}

std::string render_hash(uint64_t file_hash, const std::string& settings) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(fnv1a(settings, file_hash)));
  return hex;
}

}  // namespace softtrace
