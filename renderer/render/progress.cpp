#include "render/progress.h"

#include <cmath>
#include <cstdio>

namespace softtrace {

Progress::Progress(std::string label, long total, bool enabled, double rays_per_unit,
                   std::string rate_unit)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled),
      rays_per_unit_(rays_per_unit),
      rate_unit_(std::move(rate_unit)) {
  start_ = last_ = std::chrono::steady_clock::now();
  if (enabled_) draw(0);
}

void Progress::advance(long n) {
  const long done = done_ += n;
  if (!enabled_) return;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  draw(done);
}

std::string Progress::duration(double seconds) {
  char text[32];
  if (!(seconds < 60)) {
    const long s = std::lround(seconds);
    if (s < 3600)
      std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
    else
      std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, s / 60 % 60);
  } else {
    std::snprintf(text, sizeof text, "%.1fs", seconds);
  }
  return text;
}

void Progress::draw(long done) {
  constexpr int kWidth = 40;
  const long total = total_;
  const double frac = total > 0 ? static_cast<double>(done) / total : 1;
  const int filled = static_cast<int>(frac * kWidth);
  std::string bar(filled, '=');
  if (filled < kWidth && done > 0) bar += '>';
  bar.resize(kWidth, ' ');
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // Nothing is known of the rate before the first pixels are done.
  const bool known = done > 0 && secs > 0;
  char rate[32] = "      ?";
  if (known) std::snprintf(rate, sizeof rate, "%7.2f", done * rays_per_unit_ / secs * 1e-6);
  const std::string left = known ? duration(secs * (total - done) / done) : "?";
  char line[256];
  const int n = std::snprintf(line, sizeof line, "%s [%s] %3d%% %s %s (%s|%s)", label_.c_str(),
                              bar.c_str(), static_cast<int>(frac * 100), rate, rate_unit_.c_str(),
                              duration(secs).c_str(), left.c_str());
  const size_t len = n > 0 ? static_cast<size_t>(n) : 0;
  std::fprintf(stderr, "\r%s%*s", line, static_cast<int>(drawn_ > len ? drawn_ - len : 0), "");
  drawn_ = len;
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  draw(done_);
  std::fprintf(stderr, "\n");
}

}  // namespace softtrace
