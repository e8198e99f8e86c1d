// A progress bar on stderr, updated from worker threads at most ten times a second:
//   rendering [=============>                          ]  34%    2.41 Mrays/s (1.2s|2.3s)
// with the primary-ray rate, the time elapsed and the estimated time left (as pbrt's bar); other
// work (meshing) names its own unit of rate.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace softtrace {

class Progress {
 public:
  // `total` units of work (pixels) of `rays_per_unit` primary rays each (samples per pixel); the
  // rate shown is millions of those per second, named `rate_unit`.
  Progress(std::string label, long total, bool enabled, double rays_per_unit = 1,
           std::string rate_unit = "Mrays/s");
  void advance(long n = 1);
  // More work found on the way (adaptive anti-aliasing's second pass, known after the first):
  // the bar and the time left count it from now on.
  void add_total(long n) { total_ += n; }
  long total() const { return total_; }
  void finish();                       // ends the bar's line
  long done() const { return done_; }  // units advanced so far, from any thread

  // "0.4s", "12.0s", "3m07s", "2h05m".
  static std::string duration(double seconds);

 private:
  void draw(long done);

  std::string label_;
  std::atomic<long> total_;
  bool enabled_;
  double rays_per_unit_;
  std::string rate_unit_;
  std::atomic<long> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_;
  size_t drawn_ = 0;  // length of the last line, so that a shorter one overwrites it all
};

}  // namespace softtrace
