#include "render/tile_merge.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/tiles.h"

namespace softtrace {

namespace {

constexpr const char* kHash = "softtrace/renderHash";

struct Rect {
  int x0, x1, y0, y1;
};

std::string describe(const Rect& r) {
  return "x " + std::to_string(r.x0) + ".." + std::to_string(r.x1 - 1) + ", y " +
         std::to_string(r.y0) + ".." + std::to_string(r.y1 - 1);
}

// The parts of [0, width) x [0, height) that no rectangle covers, as rectangles: the frame cut
// into bands at every rectangle's top and bottom, each band's uncovered x ranges found, and a
// range that continues one in the band above extending it.
std::vector<Rect> uncovered(const std::vector<Rect>& rects, int width, int height) {
  std::vector<int> ys = {0, height};
  for (const Rect& r : rects) ys.insert(ys.end(), {r.y0, r.y1});
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::vector<Rect> done, open;
  for (size_t b = 0; b + 1 < ys.size(); ++b) {
    const int ya = ys[b], yb = ys[b + 1];
    std::vector<std::pair<int, int>> spans;
    for (const Rect& r : rects)
      if (r.y0 <= ya && r.y1 >= yb) spans.emplace_back(r.x0, r.x1);
    std::sort(spans.begin(), spans.end());
    std::vector<Rect> gaps;
    int x = 0;
    for (const auto& [s0, s1] : spans) {
      if (s0 > x) gaps.push_back({x, s0, ya, yb});
      x = std::max(x, s1);
    }
    if (x < width) gaps.push_back({x, width, ya, yb});
    std::vector<Rect> next;
    for (Rect g : gaps) {
      const auto above = std::find_if(open.begin(), open.end(), [&](const Rect& o) {
        return o.x0 == g.x0 && o.x1 == g.x1 && o.y1 == ya;
      });
      if (above != open.end()) {
        g.y0 = above->y0;
        open.erase(above);
      }
      next.push_back(g);
    }
    done.insert(done.end(), open.begin(), open.end());
    open = next;
  }
  done.insert(done.end(), open.begin(), open.end());
  return done;
}

// At most `limit` items, then how many more.
std::string list(const std::vector<std::string>& items, size_t limit = 8) {
  std::string s;
  for (size_t i = 0; i < items.size() && i < limit; ++i) s += (i ? "; " : "") + items[i];
  if (items.size() > limit) s += "; and " + std::to_string(items.size() - limit) + " more";
  return s;
}

// Tiles of a --tile split that are not among the inputs, when every input is from one split.
// The attributes were checked by tile_attribute, so `count` is at most the frame's pixels.
std::string missing_tiles(const std::vector<std::string>& tile_attrs) {
  std::vector<int> present;
  int count = -1;
  for (const std::string& t : tile_attrs) {
    if (t.empty()) return "";
    const TileIndex tile = parse_tile(t);
    if (count >= 0 && tile.count != count) return "";
    count = tile.count;
    present.push_back(tile.index);
  }
  std::sort(present.begin(), present.end());
  std::vector<std::string> missing;
  for (int i = 0; i < count && missing.size() <= 32; ++i)
    if (!std::binary_search(present.begin(), present.end(), i))
      missing.push_back(std::to_string(i));
  if (missing.empty()) return "";
  return " (missing --tile " + list(missing, 32) + " of " + std::to_string(count) + ")";
}

// A tile's `softtrace/tile` attribute, if any, must be a split render could make of its frame:
// a tampered "0/2000000000" once made merge allocate 2e9 entries.
void check_tile_attribute(const ImageFile& t, const std::string& path) {
  const auto it = t.attributes.find("softtrace/tile");
  if (it == t.attributes.end()) return;
  TileIndex tile;
  try {
    tile = parse_tile(it->second);
  } catch (const std::invalid_argument&) {
    throw std::runtime_error(path + ": softtrace/tile '" + it->second + "' is not I/N");
  }
  if (static_cast<long long>(tile.count) > static_cast<long long>(t.full_width) * t.full_height)
    throw std::runtime_error(path + ": softtrace/tile '" + it->second + "': a " +
                             std::to_string(t.full_width) + "x" + std::to_string(t.full_height) +
                             " frame has fewer pixels than tiles");
}

struct Channels {
  AovSelection aovs;
  std::vector<int> index;  // per file channel: which film value it is, in write order
};

// Maps the channel names `render` writes (film.h) to the film; anything else is refused.
Channels channels_of(const std::vector<std::string>& names, const std::string& path) {
  static const std::vector<std::string> order = {
      "R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z", "steps", "albedo.R", "albedo.G", "albedo.B"};
  Channels c;
  for (const std::string& n : names) {
    const auto it = std::find(order.begin(), order.end(), n);
    if (it == order.end())
      throw std::runtime_error(path + ": channel '" + n + "' is not one softtrace writes");
    c.index.push_back(static_cast<int>(it - order.begin()));
  }
  const auto has = [&](int k) { return std::count(c.index.begin(), c.index.end(), k) == 1; };
  const int normals = has(5) + has(6) + has(7), albedos = has(9) + has(10) + has(11);
  if (!has(0) || !has(1) || !has(2) || !has(3) || (normals != 0 && normals != 3) ||
      (albedos != 0 && albedos != 3) ||
      static_cast<size_t>(has(4) + normals + has(8) + albedos + 4) != names.size())
    throw std::runtime_error(path +
                             ": expected channels R,G,B,A and optionally Z, N.X,N.Y,N.Z, "
                             "steps, albedo.R,albedo.G,albedo.B, each once");
  c.aovs.depth = has(4);
  c.aovs.normal = normals == 3;
  c.aovs.steps = has(8);
  c.aovs.albedo = albedos == 3;
  return c;
}

void paste(const ImageFile& tile, const Channels& c, Film& film) {
  const size_t nc = tile.channels.size();
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x) {
      const float* in = &tile.pixels[(size_t(y) * tile.width + x) * nc];
      const size_t i = size_t(tile.y0 + y) * film.width + (tile.x0 + x);
      for (size_t k = 0; k < nc; ++k) {
        const int v = c.index[k];
        if (v < 4)
          film.rgba[i * 4 + v] = in[k];
        else if (v == 4)
          film.depth[i] = in[k];
        else if (v < 8)
          film.normal[i * 3 + (v - 5)] = in[k];
        else if (v == 8)
          film.steps[i] = in[k];
        else
          film.albedo[i * 3 + (v - 9)] = in[k];
      }
    }
}

}  // namespace

Film merge_tiles(const std::vector<ImageFile>& tiles, const std::vector<std::string>& paths) {
  if (tiles.empty() || tiles.size() != paths.size())
    throw std::invalid_argument("merge: expected one path per tile, at least one tile");
  // Everything that must agree, checked against the first tile.
  const ImageFile& first = tiles[0];
  const std::string& p0 = paths[0];
  const auto hash_of = [&](size_t i) {
    const auto it = tiles[i].attributes.find(kHash);
    if (it == tiles[i].attributes.end())
      throw std::runtime_error(paths[i] + ": no " + kHash +
                               " attribute: not an image from softtrace render");
    return it->second;
  };
  const auto attribute = [&](size_t i, const std::string& name) {
    const auto it = tiles[i].attributes.find(name);
    return it == tiles[i].attributes.end() ? std::string() : it->second;
  };
  hash_of(0);  // not from softtrace render: say so before anything else
  // The merged film is allocated at the frame's size: no more than render would make.
  if (first.full_width < 1 || first.full_width > kMaxSide || first.full_height < 1 ||
      first.full_height > kMaxSide ||
      static_cast<long long>(first.full_width) * first.full_height > kMaxPixels)
    throw std::runtime_error(p0 + ": a " + std::to_string(first.full_width) + "x" +
                             std::to_string(first.full_height) +
                             " frame; render makes sides of 1 to 16384 and at most 2^26 pixels");
  const Channels channels = channels_of(first.channels, p0);
  std::vector<Rect> rects;
  for (size_t i = 0; i < tiles.size(); ++i) {
    const ImageFile& t = tiles[i];
    const std::string& p = paths[i];
    check_tile_attribute(t, p);
    if (t.full_width != first.full_width || t.full_height != first.full_height)
      throw std::runtime_error(p + " is a tile of a " + std::to_string(t.full_width) + "x" +
                               std::to_string(t.full_height) + " image, " + p0 + " of a " +
                               std::to_string(first.full_width) + "x" +
                               std::to_string(first.full_height) + " one");
    if (hash_of(i) != hash_of(0))
      throw std::runtime_error(
          p + " and " + p0 + " are from different scenes or render settings (" + kHash + " " +
          hash_of(i) + " vs " + hash_of(0) + "; '" + attribute(i, "softtrace/render") + "' vs '" +
          attribute(0, "softtrace/render") + "')");
    if (t.channels != first.channels)
      throw std::runtime_error(p + " and " + p0 + " have different channels");
    const Rect r{t.x0, t.x0 + t.width, t.y0, t.y0 + t.height};
    if (r.x0 < 0 || r.y0 < 0 || r.x1 > t.full_width || r.y1 > t.full_height)
      throw std::runtime_error(p + ": its pixels (" + describe(r) + ") reach outside the image");
    for (size_t j = 0; j < rects.size(); ++j) {
      const Rect& o = rects[j];
      const Rect both{std::max(r.x0, o.x0), std::min(r.x1, o.x1), std::max(r.y0, o.y0),
                      std::min(r.y1, o.y1)};
      if (both.x0 < both.x1 && both.y0 < both.y1)
        throw std::runtime_error(p + " and " + paths[j] + " overlap at " + describe(both));
    }
    rects.push_back(r);
  }
  const std::vector<Rect> gaps = uncovered(rects, first.full_width, first.full_height);
  if (!gaps.empty()) {
    std::vector<std::string> where, tile_attrs;
    for (const Rect& g : gaps) where.push_back(describe(g));
    for (size_t i = 0; i < tiles.size(); ++i) tile_attrs.push_back(attribute(i, "softtrace/tile"));
    throw std::runtime_error("merge: no tile has the pixels " + list(where) +
                             missing_tiles(tile_attrs));
  }

  Film film(first.full_width, first.full_height, channels.aovs);
  for (const char* name : {kHash, "softtrace/render", "softtrace/frame"})
    if (first.attributes.count(name)) film.attributes[name] = first.attributes.at(name);
  for (const ImageFile& t : tiles) paste(t, channels, film);
  return film;
}

}  // namespace softtrace
