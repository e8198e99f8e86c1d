// Parts of a frame: crop windows (pbrt's --cropwindow and --pixelbounds), the split of a frame
// into N balanced tiles, and the identity that the tiles of one frame share.
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace softtrace {

// The pixels [x0, x1) x [y0, y1) of a frame, (0, 0) at the top left.
struct PixelBounds {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

// "X0,X1,Y0,Y1", fractions with 0 <= X0 < X1 <= 1: pixels [ceil(W X0), ceil(W X1)) and the same
// in y, in single precision as pbrt-v4 computes them. Throws std::invalid_argument.
PixelBounds crop_window(const std::string& spec, int width, int height);

// "X0,X1,Y0,Y1", pixels with 0 <= X0 < X1 <= width (pbrt's --pixelbounds, half-open).
PixelBounds pixel_bounds(const std::string& spec, int width, int height);

struct TileIndex {
  int index = 0, count = 1;  // 0 <= index < count
};
// "I/N"; throws std::invalid_argument.
TileIndex parse_tile(const std::string& spec);

// Tile `t.index` of a split of the frame into `t.count` tiles: about sqrt(count * height / width)
// rows of near-square tiles, the rows' tile counts differing by at most one and their heights
// proportional to them, so tiles have nearly equal areas. Row-major from the top left. Throws
// std::invalid_argument when the frame has too few pixels for that many tiles.
PixelBounds tile_bounds(TileIndex t, int width, int height);

// What the pixels of a frame depend on besides their place: the scene file's bytes, the frame
// size, the samples per pixel, the Lipschitz mode and the frame number (-1: none). The tiles of
// one frame must agree on it.
std::string render_settings(const Scene& scene, const std::string& lipschitz, int frame);
std::string render_hash(uint64_t file_hash, const std::string& settings);  // 16 hex digits

}  // namespace softtrace
