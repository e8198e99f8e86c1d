#include "render/threads.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <mutex>
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace softtrace {

struct ThreadLimit::Control {
  explicit Control(int threads)
      : control(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads)) {}
  tbb::global_control control;
  Control* kept_before = nullptr;  // the cap kept until exit before this one (keep_until_exit)
};

ThreadLimit::ThreadLimit() = default;
ThreadLimit::ThreadLimit(ThreadLimit&&) noexcept = default;
ThreadLimit& ThreadLimit::operator=(ThreadLimit&&) noexcept = default;
ThreadLimit::~ThreadLimit() = default;

void ThreadLimit::keep_until_exit() {
  // Held by plain pointers, never destroyed (a static unique_ptr's destructor would release it at
  // exit, starting the worker all the same); reachable, one from the other, so no leak checker
  // counts them. Several caps may be kept: TBB takes the smallest.
  static Control* kept = nullptr;
  static std::mutex guard;
  if (!control_) return;
  const std::lock_guard<std::mutex> lock(guard);
  control_->kept_before = kept;
  kept = control_.release();
}

ThreadLimit limit_threads(int threads) {
  ThreadLimit limit;
  if (threads) limit.control_ = std::make_unique<ThreadLimit::Control>(threads);
  return limit;
}

void start_threads() {
  // Two tasks, as Embree's build spawned them.
  tbb::parallel_for(
      tbb::blocked_range<int>(0, 2, 1), [](const tbb::blocked_range<int>&) {},
      tbb::simple_partitioner());
}

#if defined(__x86_64__) || defined(__i386__)
unsigned FloatingPointMode::current() {
  return _mm_getcsr();
}
unsigned FloatingPointMode::frames() {
  constexpr unsigned kFlushToZero = 1u << 15, kDenormalsAreZero = 1u << 6;  // MXCSR's bits
  return _mm_getcsr() | kFlushToZero | kDenormalsAreZero;
}
FloatingPointMode::FloatingPointMode(unsigned mode) : saved_(_mm_getcsr()) {
  if (saved_ != mode) _mm_setcsr(mode);
}
FloatingPointMode::~FloatingPointMode() {
  if (_mm_getcsr() != saved_) _mm_setcsr(saved_);
}
#else
unsigned FloatingPointMode::current() {
  return 0;
}
unsigned FloatingPointMode::frames() {
  return 0;
}
FloatingPointMode::FloatingPointMode(unsigned) {}
FloatingPointMode::~FloatingPointMode() = default;
#endif

int default_threads() {
  return tbb::info::default_concurrency();
}

void run_on_threads(int threads, const std::function<void()>& work) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute(work);
}

void parallel_ranges(size_t count, size_t grain,
                     const std::function<void(size_t begin, size_t end)>& body) {
  const unsigned mode = FloatingPointMode::current();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, grain),
                    [&](const tbb::blocked_range<size_t>& r) {
                      const FloatingPointMode callers(mode);
                      body(r.begin(), r.end());
                    });
}

void parallel_each(size_t count, const std::function<void(size_t)>& body) {
  const unsigned mode = FloatingPointMode::current();
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, count, 1),
      [&](const tbb::blocked_range<size_t>& r) {
        const FloatingPointMode callers(mode);
        for (size_t i = r.begin(); i < r.end(); ++i) body(i);
      },
      tbb::simple_partitioner());
}

}  // namespace softtrace
