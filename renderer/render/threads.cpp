#include "render/threads.h"

#include <pthread.h>
#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace softtrace {
namespace {

// One parallel loop, on its caller's stack: the caller runs its tasks as thread 0 and up to
// `helpers` workers join it as threads 1, 2, ... Indices are handed out from `next` in runs
// (next_run), and, once it has none left, a thread whose run is done takes part of another's
// (steal).
struct Loop {
  // A thread's run of indices [begin, end) not yet started, in one word (begin in the low half):
  // its owner takes the first index and another thread the back half (steal), each by one
  // compare-and-swap, so each index is started once.
  struct alignas(64) Run {
    std::atomic<uint64_t> word{0};
  };
  static uint64_t pack(size_t begin, size_t end) { return uint64_t(end) << 32 | uint64_t(begin); }
  static size_t begin_of(uint64_t run) { return size_t(run & 0xffffffffu); }
  static size_t end_of(uint64_t run) { return size_t(run >> 32); }

  size_t count = 0;
  const std::function<void(size_t, int)>* body = nullptr;
  unsigned mode = 0;         // the caller's floating-point mode, every task's
  size_t share = 2;          // next_run's divisor: twice the loop's threads
  int helpers = 0;           // workers that may join (the pool's mutex guards this and below)
  int joined = 0;            // workers that have joined: threads 1..joined
  int running = 0;           // workers in the loop now
  bool open = true;          // false once the caller has closed it to new workers
  std::exception_ptr error;  // the first exception of `body`
  std::condition_variable finished;  // running fell to 0
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};  // an exception: no task starts after it
  // Each thread's run, threads 0..helpers (none where count does not fit a run's half word: its
  // runs are then never stolen).
  std::vector<Run> runs;
};

// Set while the thread runs a loop's tasks: a loop it starts runs inline.
thread_local bool t_in_task = false;
// run_on_threads' count on this thread (0: none).
thread_local int t_own_threads = 0;

// The next run of indices [begin, end) for a thread of `loop`, empty once none is left: a
// share of what is left, 1 / (2 * threads) of it ("guided" scheduling), so that each thread
// works through consecutive indices while the others are far away. Handed out one index at a
// time, the two threads of a frame traced neighbouring tiles at the same moment, and each took
// 7-14 % more CPU time than alone (molecule and meets1 at 640x480); the shares shrink to one
// index towards the end, so the threads still finish together.
std::pair<size_t, size_t> next_run(Loop& loop) {
  size_t begin = loop.next.load(std::memory_order_relaxed);
  for (;;) {
    if (begin >= loop.count) return {begin, begin};
    const size_t take = std::max<size_t>(1, (loop.count - begin) / loop.share);
    if (loop.next.compare_exchange_weak(begin, begin + take, std::memory_order_relaxed))
      return {begin, begin + take};
  }
}

// Another thread's run for `thread` once the counter has none left: the back half of the longest
// run still waiting (at least its last index), moved to `thread`'s own. A thread held up in a task
// (its vCPU taken by another process, a slow tile) left its whole run waiting while the others
// had finished theirs: on the loaded 2-vCPU guest a 320x240 frame's thread sat idle for up to 14
// ms of a 25-45 ms frame. False where no run has an index left.
bool steal(Loop& loop, int thread) {
  for (;;) {
    int victim = -1;
    uint64_t seen = 0;
    size_t most = 0;
    for (size_t t = 0; t < loop.runs.size(); ++t) {
      const uint64_t run = loop.runs[t].word.load(std::memory_order_relaxed);
      const size_t left = Loop::end_of(run) - std::min(Loop::end_of(run), Loop::begin_of(run));
      if (int(t) != thread && left > most) {
        victim = int(t);
        seen = run;
        most = left;
      }
    }
    if (victim < 0) return false;
    const size_t end = Loop::end_of(seen), from = end - (most + 1) / 2;
    if (loop.runs[size_t(victim)].word.compare_exchange_weak(
            seen, Loop::pack(Loop::begin_of(seen), from), std::memory_order_relaxed)) {
      loop.runs[size_t(thread)].word.store(Loop::pack(from, end), std::memory_order_relaxed);
      return true;
    }
  }
}

// The next index for `thread`: the first of its run, else the first of a new run from the
// counter or, once it has none, of one stolen; false once no index is left anywhere. `own`: the
// thread's run where the loop keeps none (a count too large for a run's word).
bool next_index(Loop& loop, int thread, std::pair<size_t, size_t>& own, size_t& index) {
  if (loop.runs.empty()) {  // runs from the counter alone, never stolen
    if (own.first >= own.second) own = next_run(loop);
    if (own.first >= own.second) return false;
    index = own.first++;
    return true;
  }
  std::atomic<uint64_t>& mine = loop.runs[size_t(thread)].word;
  for (;;) {
    uint64_t run = mine.load(std::memory_order_relaxed);
    while (Loop::begin_of(run) < Loop::end_of(run)) {
      const uint64_t rest = Loop::pack(Loop::begin_of(run) + 1, Loop::end_of(run));
      if (mine.compare_exchange_weak(run, rest, std::memory_order_relaxed)) {
        index = Loop::begin_of(run);
        return true;
      }
    }
    const auto [begin, end] = next_run(loop);
    if (begin < end)
      mine.store(Loop::pack(begin, end), std::memory_order_relaxed);
    else if (!steal(loop, thread))
      return false;
  }
}

// Runs tasks of `loop` as thread `thread` until none is left or one has thrown.
void run_tasks(Loop& loop, int thread, std::mutex& guard) {
  t_in_task = true;
  const auto stopped = [&] { return loop.stop.load(std::memory_order_acquire); };
  std::pair<size_t, size_t> own{0, 0};
  size_t i = 0;
  while (!stopped() && next_index(loop, thread, own, i)) {
    try {
      (*loop.body)(i, thread);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(guard);
      if (!loop.error) loop.error = std::current_exception();
      loop.stop.store(true, std::memory_order_release);
    }
  }
  t_in_task = false;
}

#if defined(__SANITIZE_ADDRESS__)
#define SOFTTRACE_THREADS_TEARDOWN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define SOFTTRACE_THREADS_TEARDOWN 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define SOFTTRACE_THREADS_TEARDOWN 1
#endif

// A worker's end (end_threads_after_loops): the thread's exit system call alone, none of the C
// library's teardown (its stack, its thread-local objects, its malloc cache), which the process
// that ends next takes back at once. A sanitizer build returns through the C library, so that the
// leak check knows the thread's memory.
void end_this_thread() {
#if !defined(SOFTTRACE_THREADS_TEARDOWN) && defined(__linux__)
  ::syscall(SYS_exit, 0);
#endif
}

// The worker threads and the loops that want them. Made once and never destroyed: a process
// that exits (cmd_render's _exit, or exit()) neither joins nor wakes its sleeping workers, and no
// static destructor pulls the mutex from under them.
class Pool {
 public:
  static Pool& get() {
    static Pool* const pool = make();
    return *pool;
  }

  int threads_for(int own) {
    const int wanted = own > 0 ? own : default_threads();
    const std::lock_guard<std::mutex> lock(mutex_);
    const int cap = cap_locked();
    return cap > 0 ? (own > 0 ? std::min(own, cap) : cap) : wanted;
  }

  void add_cap(int threads) {
    const std::lock_guard<std::mutex> lock(mutex_);
    caps_.push_back(threads);
  }
  void remove_cap(int threads) {
    const std::lock_guard<std::mutex> lock(mutex_);
    caps_.erase(std::find(caps_.begin(), caps_.end(), threads));
    work_.notify_all();  // a larger cap lets more workers join the open loops
  }

  void start(int workers, void (*on_start)()) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (on_start) on_start_ = on_start;
    spawn_locked(workers);
  }

  // Runs `loop` on the caller (thread 0) and `loop.helpers` workers at most.
  void run(Loop& loop) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      spawn_locked(loop.helpers);
      open_.push_back(&loop);
      if (end_after_loops_ > 0 && --end_after_loops_ == 0) ending_ = true;
    }
    // Wakes as many as may join; one more than the idle is harmless.
    for (int i = 0; i < loop.helpers; ++i) work_.notify_one();
    {
      const FloatingPointMode callers(loop.mode);
      run_tasks(loop, 0, mutex_);
    }
    std::unique_lock<std::mutex> lock(mutex_);
    close_locked(loop);
    loop.finished.wait(lock, [&] { return loop.running == 0; });
  }

  void end_after_loops(int loops) {
    const std::lock_guard<std::mutex> lock(mutex_);
    end_after_loops_ = std::max(loops, 0);
    if (loops <= 0) {
      ending_ = true;
      work_.notify_all();
    }
  }

  std::mutex& guard() { return mutex_; }

 private:
  static Pool* make() {
    Pool* pool = new Pool;
    // A forked child (Python's multiprocessing) has none of the parent's workers: it starts
    // with an empty pool of its own. The old one is held by `pool` still, never freed.
    pthread_atfork(nullptr, nullptr, [] { Pool::get().forked(); });
    return pool;
  }
  void forked() {
    new (&mutex_) std::mutex;
    new (&work_) std::condition_variable;
    workers_ = busy_ = 0;
    end_after_loops_ = 0;
    ending_ = false;
    open_.clear();
  }

  int cap_locked() const {
    return caps_.empty() ? 0 : *std::min_element(caps_.begin(), caps_.end());
  }

  void spawn_locked(int workers) {
    for (; workers_ < workers; ++workers_) start_worker();
  }

  // A worker first runs on another of the process's CPUs than its creator's, its start hook
  // included, then has them all again. This guest's scheduler packs a new thread onto its
  // creator's vCPU (18 of 20 runs, first run 1.3 ms after its creation, against 0.4 ms placed
  // apart), where the worker's start (its heap's huge page) and the scene's load then take turns:
  // placed apart, meets1's, molecule's, candle's and old_syntax's processes at 320x240 took 0.7-1.6
  // ms less of wall, meets10's at 640x480 1.1-2.2 ms less (docs/performance.md, session 41).
  struct Start {
    Pool* pool;
    void (*on_start)();
    cpu_set_t cpus;  // the creator's, given back after the hook
    bool placed;
  };
  static void* worker_main(void* arg) {
    const Start start = *static_cast<Start*>(arg);
    delete static_cast<Start*>(arg);
    if (start.on_start) start.on_start();
    if (start.placed) pthread_setaffinity_np(pthread_self(), sizeof start.cpus, &start.cpus);
    start.pool->work();
    return nullptr;
  }
  void start_worker() {
    auto* start = new Start{this, on_start_, {}, false};
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
    const int here = sched_getcpu();
    if (here >= 0 && sched_getaffinity(0, sizeof start->cpus, &start->cpus) == 0 &&
        CPU_ISSET(here, &start->cpus) && CPU_COUNT(&start->cpus) > 1) {
      cpu_set_t apart = start->cpus;
      CPU_CLR(here, &apart);
      start->placed = pthread_attr_setaffinity_np(&attr, sizeof apart, &apart) == 0;
    }
    pthread_t thread;
    const int error = pthread_create(&thread, &attr, worker_main, start);
    pthread_attr_destroy(&attr);
    if (error) {
      delete start;
      throw std::system_error(error, std::generic_category(), "pthread_create");
    }
  }

  void close_locked(Loop& loop) {
    if (!loop.open) return;
    loop.open = false;
    open_.erase(std::find(open_.begin(), open_.end(), &loop));
  }

  // A worker: sleeps until a loop wants it and the cap allows one more, runs tasks, again.
  void work() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      const auto wanted = [&] {
        const int cap = cap_locked();
        return !open_.empty() && (cap == 0 || busy_ < cap - 1);
      };
      work_.wait(lock, [&] { return ending_ || wanted(); });
      if (!wanted()) {
        lock.unlock();
        end_this_thread();
        return;
      }
      Loop& loop = *open_.front();
      const int thread = ++loop.joined;
      if (loop.joined == loop.helpers) close_locked(loop);
      ++loop.running;
      ++busy_;
      lock.unlock();
      {
        const FloatingPointMode callers(loop.mode);
        run_tasks(loop, thread, mutex_);
      }
      lock.lock();
      --busy_;
      if (--loop.running == 0) loop.finished.notify_one();
    }
  }

  std::mutex mutex_;
  std::condition_variable work_;  // the workers wait here
  std::deque<Loop*> open_;        // loops that workers may still join, oldest first
  std::vector<int> caps_;         // the caps held now (ThreadLimit), kept ones included
  int workers_ = 0;               // started
  int busy_ = 0;                  // in a loop now, over all loops (the cap counts these)
  int end_after_loops_ = 0;       // end_threads_after_loops: loops to open before ending_
  bool ending_ = false;           // a worker that no open loop wants ends
  void (*on_start_)() = nullptr;  // what a new worker runs first (start_threads)
};

}  // namespace

ThreadLimit::ThreadLimit(ThreadLimit&& other) noexcept : threads_(other.threads_) {
  other.threads_ = 0;
}
ThreadLimit& ThreadLimit::operator=(ThreadLimit&& other) noexcept {
  if (this != &other) {
    if (threads_) Pool::get().remove_cap(threads_);
    threads_ = other.threads_;
    other.threads_ = 0;
  }
  return *this;
}
ThreadLimit::~ThreadLimit() {
  if (threads_) Pool::get().remove_cap(threads_);
}

void ThreadLimit::keep_until_exit() {
  threads_ = 0;  // the pool's list keeps it; nothing removes it
}

ThreadLimit limit_threads(int threads) {
  ThreadLimit limit;
  if (threads > 0) {
    Pool::get().add_cap(threads);
    limit.threads_ = threads;
  }
  return limit;
}

void end_threads_after_loops(int loops) {
  Pool::get().end_after_loops(loops);
}

void start_threads(void (*on_start)()) {
  Pool& pool = Pool::get();
  pool.start(pool.threads_for(t_own_threads) - 1, on_start);
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
  // Read once, as TBB read it: the process's affinity when it first asks.
  static const int cores = [] {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
    return std::max(1, int(std::thread::hardware_concurrency()));
  }();
  return cores;
}

void run_on_threads(int threads, const std::function<void()>& work) {
  struct Own {
    explicit Own(int threads) : saved(t_own_threads) { t_own_threads = threads; }
    ~Own() { t_own_threads = saved; }
    const int saved;
  } own(threads);
  work();
}

int loop_threads() {
  return t_in_task ? 1 : Pool::get().threads_for(t_own_threads);
}

void parallel_each_thread(size_t count, int threads,
                          const std::function<void(size_t i, int thread)>& body) {
  const int helpers = int(std::min<size_t>(std::min(threads, loop_threads()), count)) - 1;
  if (helpers <= 0) {
    // Inline, in order: one thread, or a loop inside a task (its thread is busy with this task,
    // so waiting for workers could wait on itself).
    for (size_t i = 0; i < count; ++i) body(i, 0);
    return;
  }
  Loop loop;
  loop.count = count;
  loop.body = &body;
  loop.mode = FloatingPointMode::current();
  loop.helpers = helpers;
  loop.share = 2 * size_t(helpers + 1);
  if (count <= 0xffffffffu) loop.runs = std::vector<Loop::Run>(size_t(helpers + 1));
  Pool::get().run(loop);
  if (loop.error) std::rethrow_exception(loop.error);
}

void parallel_each(size_t count, const std::function<void(size_t)>& body) {
  parallel_each_thread(count, loop_threads(), [&](size_t i, int) { body(i); });
}

void parallel_ranges(size_t count, size_t grain,
                     const std::function<void(size_t begin, size_t end)>& body) {
  grain = std::max<size_t>(grain, 1);
  parallel_each((count + grain - 1) / grain,
                [&](size_t range) { body(range * grain, std::min(count, (range + 1) * grain)); });
}

}  // namespace softtrace
