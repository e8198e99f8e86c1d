// The frame loop's worker threads (TBB's, frame.cpp): how many there are by default, a cap on
// them for a command's run, a run of its own on a given number of them, and a parallel loop over
// ranges for the Python module's batches. TBB stays behind this header, so neither the command
// line nor the Python module includes it.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

namespace softtrace {

// Caps the worker threads of every parallel loop for as long as it lives (tbb::global_control).
class ThreadLimit {
 public:
  ThreadLimit();  // no cap
  ThreadLimit(ThreadLimit&&) noexcept;
  ThreadLimit& operator=(ThreadLimit&&) noexcept;
  ~ThreadLimit();

  // Keeps the cap until the process ends, for a command that exits after its work: releasing
  // TBB's global_control raises the scheduler's limit again, and under a cap of one thread that
  // started a worker thread just before the exit. Caps kept from several threads all hold; the
  // smallest is TBB's limit.
  void keep_until_exit();

 private:
  friend ThreadLimit limit_threads(int threads);
  struct Control;
  std::unique_ptr<Control> control_;
};

// At most `threads` worker threads (0: no cap, all cores) while the result lives.
ThreadLimit limit_threads(int threads);

// Starts TBB on the calling thread, if nothing has, with a worker thread where the cap allows
// one, as Embree's scene build started it: the worker then starts beside what the caller does
// before its frame (EmbreeScene::built false: no Embree build does it), not at the first tile.
void start_threads();

// A floating-point mode (x86's MXCSR; elsewhere none) on the calling thread while it lives, the
// mode before it restored after, also when the body throws.
class FloatingPointMode {
 public:
  // The calling thread's mode.
  static unsigned current();
  // The frames' mode: the calling thread's with flush-to-zero and denormals-are-zero. Every task
  // of a frame runs in it (frame.cpp): it is the mode the frames have always had where Embree's
  // scene build started TBB (TBB's arena keeps the mode of the thread that started it, and
  // Embree's build sets these), and a denormal flushed or not changes a march's steps. Set per
  // task, it no longer depends on who started TBB, so the Python module's frames, in an arena of
  // their own, are the command line's bits.
  static unsigned frames();
  explicit FloatingPointMode(unsigned mode);
  ~FloatingPointMode();
  FloatingPointMode(const FloatingPointMode&) = delete;
  FloatingPointMode& operator=(const FloatingPointMode&) = delete;

 private:
  unsigned saved_ = 0;
};

// The worker threads a parallel loop uses when nothing caps them (TBB's default concurrency: the
// cores this process may run on).
int default_threads();

// Runs `work` on the calling thread with at most `threads` worker threads (0: all cores) for the
// parallel loops it starts (frame.cpp's, parallel_ranges), apart from other callers: unlike
// limit_threads, which caps the whole process, two such runs at different counts (two Python
// threads rendering) do not change each other's (a tbb::task_arena of its own). Exceptions of
// `work` reach the caller.
void run_on_threads(int threads, const std::function<void()>& work);

// Calls body(begin, end) over [0, count) split into ranges of at least about `grain` (TBB's
// blocked_range and automatic partitioning), in parallel on the worker threads; each range runs
// whole on one thread, so a thread_local workspace in `body` is its own for the range, and in the
// caller's floating-point mode, as parallel_each's tasks (a batch of the Python module's points
// then gives what the caller's own loop would, whoever started TBB's arena). Returns when every
// range is done; the first exception of `body` reaches the caller.
void parallel_ranges(size_t count, size_t grain,
                     const std::function<void(size_t begin, size_t end)>& body);

// Calls body(i) for every i in [0, count), one index per task, on the worker threads, each task in
// the caller's floating-point mode (a worker otherwise runs in the mode of the thread that started
// TBB's arena), so that what each computes is what a loop on the caller would give: an image's
// bands (io/image_file.h's EachIndex). The first exception of `body` reaches the caller.
void parallel_each(size_t count, const std::function<void(size_t)>& body);

}  // namespace softtrace
