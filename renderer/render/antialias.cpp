#include "render/antialias.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

AdaptivePixels::AdaptivePixels(const Antialias& a, const PixelRect& window, int full_width,
                               int full_height)
    : threshold_(a.threshold),
      inverse_gamma_(float(1 / a.gamma)),
      window_(window),
      apron_{std::max(window.x0 - 1, 0), std::max(window.y0 - 1, 0),
             std::min(window.x1 + 1, full_width), std::min(window.y1 + 1, full_height)} {
  const size_t n = size_t(apron_.x1 - apron_.x0) * (apron_.y1 - apron_.y0);
  first_.assign(n * 4, 0.0f);
  refine_.assign(n, 0);
}

void AdaptivePixels::set_first(int x, int y, const float rgba[4]) {
  // POV-Ray 3.7 compares the colours gamma-encoded by its Antialias_Gamma, 2.5 by default
  // (backend/render/tracetask.cpp, NonAdaptiveSupersamplingForOnePixel): c^(1/gamma) of the
  // linear R, G and B (negatives as 0), A as it is. A dark edge then differs as much as a bright
  // one that looks as different.
  float* first = &first_[index(x, y) * 4];
  for (int k = 0; k < 3; ++k) first[k] = std::pow(std::max(rgba[k], 0.0f), inverse_gamma_);
  first[3] = rgba[3];
}

void AdaptivePixels::decide() {
  // POV-Ray's colour distance: the sum of the channels' absolute differences.
  const auto differ = [&](size_t i, size_t j) {
    double d = 0;
    for (int k = 0; k < 4; ++k) d += std::fabs(double(first_[i * 4 + k]) - first_[j * 4 + k]);
    return d > threshold_;
  };
  refined_ = 0;
  for (int y = window_.y0; y < window_.y1; ++y)
    for (int x = window_.x0; x < window_.x1; ++x) {
      const size_t i = index(x, y);
      const bool r = (x > apron_.x0 && differ(i, index(x - 1, y))) ||
                     (x + 1 < apron_.x1 && differ(i, index(x + 1, y))) ||
                     (y > apron_.y0 && differ(i, index(x, y - 1))) ||
                     (y + 1 < apron_.y1 && differ(i, index(x, y + 1)));
      refine_[i] = r;
      refined_ += r;
    }
}

bool AdaptivePixels::any(const PixelRect& r) const {
  for (int y = std::max(r.y0, window_.y0); y < std::min(r.y1, window_.y1); ++y)
    for (int x = std::max(r.x0, window_.x0); x < std::min(r.x1, window_.x1); ++x)
      if (refine_[index(x, y)]) return true;
  return false;
}

long long AdaptivePixels::count(const PixelRect& r) const {
  long long n = 0;
  for (int y = std::max(r.y0, window_.y0); y < std::min(r.y1, window_.y1); ++y)
    for (int x = std::max(r.x0, window_.x0); x < std::min(r.x1, window_.x1); ++x)
      n += refine_[index(x, y)];
  return n;
}

}  // namespace softtrace
