// The frame loop's worker threads (TBB's, frame.cpp): how many there are by default, and a cap on
// them for a command's run. TBB stays behind this header, so the command line never includes it.
#pragma once

#include <memory>

namespace softtrace {

// Caps the worker threads of every parallel loop for as long as it lives (tbb::global_control).
class ThreadLimit {
 public:
  ThreadLimit();  // no cap
  ThreadLimit(ThreadLimit&&) noexcept;
  ThreadLimit& operator=(ThreadLimit&&) noexcept;
  ~ThreadLimit();

 private:
  friend ThreadLimit limit_threads(int threads);
  struct Control;
  std::unique_ptr<Control> control_;
};

// At most `threads` worker threads (0: no cap, all cores) while the result lives.
ThreadLimit limit_threads(int threads);

// The worker threads a parallel loop uses when nothing caps them (TBB's default concurrency: the
// cores this process may run on).
int default_threads();

}  // namespace softtrace
