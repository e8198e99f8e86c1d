// POV-Ray's adaptive anti-aliasing (+A, method 1; docs/scene-format.md "antialias"): every pixel
// is first traced with its usual samples; a pixel whose colour then differs from one of its four
// neighbours' by more than the threshold is traced again with depth^2 times as many. The
// decision reads the first pass of the data window grown by one pixel (the apron): a pixel at a
// tile's edge is compared with the same neighbours, traced the same way, as in the whole frame,
// so the picture is the same bits for any thread count and any split of the frame.
#pragma once

#include <vector>

#include "scene/scene.h"

namespace softtrace {

// The full-frame pixels [x0, x1) x [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  bool empty() const { return x0 >= x1 || y0 >= y1; }
};

class AdaptivePixels {
 public:
  // The data window `window` of a full_width x full_height frame.
  AdaptivePixels(const Antialias& a, const PixelRect& window, int full_width, int full_height);

  // The window and its apron, within the frame: the first pass's pixels.
  const PixelRect& apron() const { return apron_; }
  // The first pass's colour of pixel (x, y) of the apron: R, G, B over the background, and A
  // (kept gamma-encoded, as POV-Ray compares them).
  void set_first(int x, int y, const float rgba[4]);
  // After the first pass: marks the window's pixels to trace again.
  void decide();
  bool refine(int x, int y) const { return refine_[index(x, y)] != 0; }
  // Whether any pixel of `r` (inside the window) is to be traced again.
  bool any(const PixelRect& r) const;
  // How many pixels of `r` (inside the window) are to be traced again.
  long long count(const PixelRect& r) const;
  long long refined() const { return refined_; }

 private:
  size_t index(int x, int y) const {
    return size_t(y - apron_.y0) * (apron_.x1 - apron_.x0) + (x - apron_.x0);
  }

  double threshold_;
  float inverse_gamma_;  // 1 / Antialias_Gamma
  PixelRect window_, apron_;
  std::vector<float> first_;  // 4 per apron pixel
  std::vector<char> refine_;  // 1 per apron pixel; only the window's are set
  long long refined_ = 0;
};

}  // namespace softtrace
