// A progress bar on a terminal (stderr), updated from worker threads at most ten times a second.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace softtrace {

class Progress {
 public:
  Progress(std::string label, long total, bool enabled);
  void advance(long n = 1);
  void finish();  // ends the bar's line

 private:
  void draw(long done);

  std::string label_;
  long total_;
  bool enabled_;
  std::atomic<long> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace softtrace
