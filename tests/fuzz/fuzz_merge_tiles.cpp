// libFuzzer target: arbitrary bytes as a tile through `merge`'s reading and checks — the EXR
// header (display and data windows, channels) and softtrace's attributes (renderHash, tile) —
// alone, twice, and beside a one-pixel tile of the same frame that agrees with it. Bad input
// must end in a std::runtime_error, never a crash, a sanitizer report or an allocation the size
// of a tampered header. Built by tools/dev.sh test in build-fuzz/ and run there for a bounded
// time, seeded with tiles softtrace rendered (tools/dev.sh fuzz_seeds).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_image_input.h"
#include "io/image_file.h"
#include "render/tile_merge.h"

using namespace softtrace;

namespace {

void try_merge(const std::vector<ImageFile>& tiles) {
  const std::vector<std::string> paths(tiles.size(), "fuzz.exr");
  try {
    merge_tiles(tiles, paths);
  } catch (const std::runtime_error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const FuzzImageInput input("merge");
  ImageFile tile;
  if (!input.read(data, size, &tile)) return 0;
  try_merge({tile});
  try_merge({tile, tile});
  // One pixel at the frame's origin with the same channels and attributes: gets past the
  // agreement checks to the overlap, gap and missing-tile logic.
  ImageFile pixel;
  pixel.full_width = tile.full_width;
  pixel.full_height = tile.full_height;
  pixel.width = pixel.height = 1;
  pixel.channels = tile.channels;
  pixel.pixels.assign(tile.channels.size(), 0.5f);
  pixel.attributes = tile.attributes;
  try_merge({tile, pixel});
  try_merge({pixel, tile});
  return 0;
}
