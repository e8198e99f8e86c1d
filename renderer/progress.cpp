#include "progress.h"

#include <cstdio>

namespace softtrace {

Progress::Progress(std::string label, long total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled) {
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

void Progress::draw(long done) {
  constexpr int kWidth = 40;
  const double frac = total_ > 0 ? static_cast<double>(done) / total_ : 1;
  const int filled = static_cast<int>(frac * kWidth);
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string bar(filled, '=');
  bar.resize(kWidth, ' ');
  std::fprintf(stderr, "\r%s [%s] %3d%% %6.1fs", label_.c_str(), bar.c_str(),
               static_cast<int>(frac * 100), secs);
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  draw(done_);
  std::fprintf(stderr, "\n");
}

}  // namespace softtrace
