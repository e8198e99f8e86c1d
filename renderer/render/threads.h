// The frame loop's worker threads (frame.cpp): how many there are by default, a cap on them for a
// command's run, a run of its own on a given number of them, and parallel loops over indices and
// ranges (the frame's tiles, an image's bands, the Python module's batches).
//
// A small pool of std::threads of our own, not TBB: every process that renders pays for its
// threads' start, and TBB's cost 2.7 ms of wall time a process on the 2-core KVM guest (a parallel
// sum of 64 numbers on 2 threads: 7.10 ms wall, 6.73 ms CPU with tbb::parallel_for under a
// global_control, 4.41 ms and 3.66 ms with two std::threads and an atomic counter, perf stat -r
// 100), where a frame at 320x240 takes 10-30 ms. Its workers also spin on sched_yield between
// loops, which costs the other core; ours sleep on a condition variable. Without TBB the program
// may also carry its own C++ runtime (Debian's libtbb needs the shared one). A frame's tiles are
// many small tasks handed out from one counter in runs of consecutive indices (each thread keeps
// to its own part of the image, as TBB's range splitting kept it); only once the counter has none
// left does a thread take the back half of another's run, so that a thread held up in a task
// (another process on its vCPU) strands none of the frame's tiles.
#pragma once

#include <cstddef>
#include <functional>

namespace softtrace {

// Caps the threads of every parallel loop in the process for as long as it lives; with a cap a
// loop runs on that many threads (the command line's --threads, more than the cores included).
// Caps held at once, from any threads, all hold: the smallest is the cap.
class ThreadLimit {
 public:
  ThreadLimit() = default;  // no cap
  ThreadLimit(ThreadLimit&& other) noexcept;
  ThreadLimit& operator=(ThreadLimit&& other) noexcept;
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

  // Keeps the cap until the process ends, for a command that exits after its work.
  void keep_until_exit();

 private:
  friend ThreadLimit limit_threads(int threads);
  int threads_ = 0;  // 0: no cap (or kept: the pool holds it)
};

// At most `threads` threads (0: no cap, all cores) while the result lives.
ThreadLimit limit_threads(int threads);

// Starts the worker threads the loops will want (the cap's or the cores' count less the caller),
// without waiting for them: they start beside what the caller does before its first loop (the
// scene's load, the tracers' build), not at the frame's first tile. Started threads are kept.
// `on_start`, where given, runs first on each worker started from then on (the command line's:
// the worker's heap filled while the caller loads the scene).
void start_threads(void (*on_start)() = nullptr);

// Ends the started workers once `loops` more loops that workers may join have opened (0: now):
// from then on a worker that finds no open loop it may join ends (after its tasks in the last of
// them, if it joined it; one asleep is woken), by the thread's exit alone, without the C library's
// teardown of the thread; later loops run on their callers alone. For a process whose next `loops`
// loops are its last with workers before it exits: its exit then ends one thread, not a sleeping
// one it must wake first.
void end_threads_after_loops(int loops);

// A floating-point mode (x86's MXCSR; elsewhere none) on the calling thread while it lives, the
// mode before it restored after, also when the body throws.
class FloatingPointMode {
 public:
  // The calling thread's mode.
  static unsigned current();
  // The frames' mode: the calling thread's with flush-to-zero and denormals-are-zero. Every task
  // of a frame runs in it (frame.cpp): it is the mode the frames have always had (TBB's arena,
  // which ran them before this pool, kept the mode of the thread that started it, and Embree's
  // scene build, which started it then, sets these), and a denormal flushed or not changes a
  // march's steps. Set per task, it depends on nobody's start, so the Python module's frames are
  // the command line's bits.
  static unsigned frames();
  explicit FloatingPointMode(unsigned mode);
  ~FloatingPointMode();
  FloatingPointMode(const FloatingPointMode&) = delete;
  FloatingPointMode& operator=(const FloatingPointMode&) = delete;

 private:
  unsigned saved_ = 0;
};

// The cores this process may run on (sched_getaffinity, as TBB's default concurrency): the
// threads of a parallel loop when nothing caps them.
int default_threads();

// Runs `work` on the calling thread with `threads` threads (0: all cores) for the parallel loops
// it starts (frame.cpp's, parallel_ranges), apart from other callers: unlike limit_threads, which
// caps the whole process (and still caps these), two such runs at different counts (two Python
// threads rendering) do not change each other's. Exceptions of `work` reach the caller.
void run_on_threads(int threads, const std::function<void()>& work);

// The threads a parallel loop started now on the calling thread would run on: the count of its
// run_on_threads, or the cores, under the smallest cap; 1 inside a loop's task.
int loop_threads();

// Calls body(i) for every i in [0, count), one index per task, handed out to the calling thread
// and up to loop_threads() - 1 workers in runs of consecutive indices, each run a share of what
// is left (1 / (2 * threads) of it, down to one index), and once none is left, a thread done
// with its run takes the back half of the longest run still waiting (a thread held up in a task
// holds up no other index); each task in the caller's floating-point mode (so that what each
// computes is what a loop on the caller would give: an image's bands, io/image_file.h's
// EachIndex). Returns when every task is done. The first exception of `body`
// reaches the caller once every running task has finished; no task starts after it. A loop
// started inside a task runs on that task's thread alone, in order (no worker waits on another).
void parallel_each(size_t count, const std::function<void(size_t)>& body);

// parallel_each, with body(i, thread) also told which of the loop's threads runs the task:
// `thread` in [0, min(threads, loop_threads())), each running one task at a time, so a total per
// thread (frame.cpp's Work) needs no lock. `threads` is loop_threads() read before the loop, the
// size of such totals.
void parallel_each_thread(size_t count, int threads,
                          const std::function<void(size_t i, int thread)>& body);

// Calls body(begin, end) over [0, count) split into ranges of `grain` indices (the last one
// shorter), each range one task of parallel_each: whole on one thread, so a thread_local
// workspace in `body` is its own for the range, in the caller's floating-point mode (a batch of
// the Python module's points gives what the caller's own loop would).
void parallel_ranges(size_t count, size_t grain,
                     const std::function<void(size_t begin, size_t end)>& body);

}  // namespace softtrace
