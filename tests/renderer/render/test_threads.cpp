// The worker threads' loops (render/threads.h): every index once at any thread count, the cap
// and each caller's own count held, the first exception handed to the caller with nothing started
// after it, a loop inside a task, parallel_ranges running each range in the caller's
// floating-point mode, as parallel_each runs each task (tests/renderer/io/test_png_bands.cpp),
// start_threads' hook run first on each worker it starts, and the workers' end after a given number
// of loops (a one-shot render's: cmd_render.cpp), and a worker's first run on another CPU than its
// creator's.
#include <dirent.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "render/threads.h"

namespace softtrace::test {
namespace {

// Here rounding towards zero, which the worker threads do not have: the arena is started first,
// in the usual mode (as a Python session's first render or batch starts it).
TEST(ParallelRanges, EachRangeTakesTheCallersFloatingPointMode) {
#if defined(__x86_64__) || defined(__i386__)
  // MXCSR's control bits; the low six are the exceptions' sticky flags, which any sum may set.
  const auto control = [] { return _mm_getcsr() & ~0x3Fu; };
  parallel_ranges(
      64, 1, [](size_t, size_t) { std::this_thread::sleep_for(std::chrono::microseconds(100)); });
  const unsigned before = _mm_getcsr();
  const unsigned mode = (before & ~0x3Fu) | 0x6000u;  // RC = 11: towards zero
  _mm_setcsr(mode);
  std::mutex m;
  std::vector<unsigned> seen;
  std::set<std::thread::id> threads;
  size_t covered = 0;
  parallel_ranges(64, 1, [&](size_t begin, size_t end) {
    std::this_thread::sleep_for(std::chrono::microseconds(200 * (end - begin)));
    const std::lock_guard<std::mutex> lock(m);
    seen.push_back(control());
    threads.insert(std::this_thread::get_id());
    covered += end - begin;
  });
  const unsigned after = control();
  _mm_setcsr(before);
  EXPECT_EQ(after, mode);
  EXPECT_EQ(covered, 64u);
  ASSERT_FALSE(seen.empty());
  for (const unsigned s : seen) EXPECT_EQ(s, mode);
  if (threads.size() < 2)
    GTEST_SKIP() << "every range ran on the calling thread (a loaded machine)";
#else
  GTEST_SKIP() << "x86 only";
#endif
}

// Counts the tasks running at once, and the most there were: a loop of `count` tasks that each
// sleep long enough for every thread of the loop to join.
struct AtOnce {
  void loop(size_t count) {
    parallel_each(count, [&](size_t) {
      const int n = ++now;
      for (int m = most.load(); n > m && !most.compare_exchange_weak(m, n);) {
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      --now;
    });
  }
  std::atomic<int> now{0}, most{0};
};

int most_at_once(size_t count) {
  AtOnce at_once;
  at_once.loop(count);
  return at_once.most.load();
}

TEST(ThreadLoops, EachIndexRunsOnceAtOneTwoAndEightThreads) {
  for (const int threads : {1, 2, 8}) {
    constexpr size_t kCount = 2000;  // each a few microseconds long, so that the workers join
    std::vector<std::atomic<int>> runs(kCount);
    std::atomic<int> bad_thread{0};
    run_on_threads(threads, [&] {
      EXPECT_EQ(loop_threads(), threads);
      parallel_each_thread(kCount, loop_threads(), [&](size_t i, int thread) {
        if (thread < 0 || thread >= threads) ++bad_thread;
        ++runs[i];
        std::this_thread::sleep_for(std::chrono::microseconds(20));
      });
    });
    for (size_t i = 0; i < kCount; ++i)
      ASSERT_EQ(runs[i].load(), 1) << threads << " threads, " << i;
    EXPECT_EQ(bad_thread.load(), 0) << threads << " threads";
  }
}

// Two threads over 2000 short tasks: each thread works through stretches of consecutive
// indices (threads.cpp's next_run), so that the two never trace neighbouring tiles at the same
// moment. A run's share shrinks by a quarter each time, to one index at the end: about 30
// stretches. Handed out one index at a time, the threads alternated some hundreds of times.
TEST(ThreadLoops, EachThreadWorksThroughStretchesOfConsecutiveIndices) {
  constexpr size_t kCount = 2000;
  std::vector<int> owner(kCount, -1);
  run_on_threads(2, [&] {
    parallel_each_thread(kCount, loop_threads(), [&](size_t i, int thread) {
      owner[i] = thread;  // each index once: its own element
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    });
  });
  size_t stretches = 1;
  for (size_t i = 1; i < kCount; ++i) stretches += owner[i] != owner[i - 1];
  if (stretches == 1) GTEST_SKIP() << "the worker never joined (a loaded machine)";
  EXPECT_LE(stretches, 64u);
}

// A thread held up in its first task leaves the rest of its run to the other: the task waits
// (a bounded wait, so that the loop without stealing fails rather than hangs) until every other
// index has run, which the other thread can do only by taking the held-up thread's run.
TEST(ThreadLoops, AThreadHeldUpInATaskHoldsUpNoOtherIndex) {
  constexpr size_t kCount = 64;
  std::atomic<int> done{0};
  std::atomic<bool> all_while_held{false};
  std::vector<int> owner(kCount, -1);
  run_on_threads(2, [&] {
    parallel_each_thread(kCount, loop_threads(), [&](size_t i, int thread) {
      owner[i] = thread;  // each index once: its own element
      if (i == 0) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (done.load() < int(kCount) - 1 && std::chrono::steady_clock::now() < deadline)
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        all_while_held = done.load() == int(kCount) - 1;
        return;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(50));
      ++done;
    });
  });
  if (std::count(owner.begin(), owner.end(), owner[0]) == int(kCount))
    GTEST_SKIP() << "the worker never joined (a loaded machine)";
  EXPECT_TRUE(all_while_held.load());
  EXPECT_EQ(done.load(), int(kCount) - 1);
}

// The cap holds over a run's own larger count, and a run's count holds without a cap: never
// more tasks at once than either allows. (At least two at once shows the count is not vacuous.)
// Under the cap, two callers each run their own loops and share its one worker: three at most,
// though two workers are started by then.
TEST(ThreadLoops, TheCapAndTheRunsCountHold) {
  run_on_threads(3, [&] {
    EXPECT_EQ(loop_threads(), 3);
    const int most = most_at_once(96);
    EXPECT_LE(most, 3);
    EXPECT_GE(most, 2) << "the workers never joined";
  });
  {
    const ThreadLimit cap = limit_threads(2);
    run_on_threads(8, [&] {
      EXPECT_EQ(loop_threads(), 2);
      EXPECT_LE(most_at_once(64), 2);
    });
    AtOnce both;
    const auto loop = [&] { run_on_threads(2, [&] { both.loop(64); }); };
    std::thread other(loop);
    loop();
    other.join();
    EXPECT_LE(both.most.load(), 3);
  }
}

// The first task to start throws once every other thread's first task is asleep (200 ms each):
// the caller gets its exception, only after the sleeping tasks have finished, and no task starts
// once it has been thrown. (`thrown` is set just before the throw, and the loop stops starting
// tasks once the exception is caught: the sleeps keep every other thread away from its next task
// in between, so a task counted late is the loop's fault, not the test's timing.)
TEST(ThreadLoops, TheFirstExceptionReachesTheCallerAndNothingStartsAfterIt) {
  for (const int threads : {1, 2, 8}) {
    std::atomic<bool> thrown{false};
    std::atomic<int> running{0}, started{0}, late{0};
    run_on_threads(threads, [&] {
      try {
        parallel_each(64, [&](size_t) {
          const bool first = started++ == 0;
          if (thrown) ++late;
          if (first) {
            // The other threads' first tasks: asleep before the throw (a bounded wait, so that a
            // loop that never gave them a task fails the assertions below rather than hanging).
            const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
            while (running.load() < threads - 1 && std::chrono::steady_clock::now() < deadline)
              std::this_thread::sleep_for(std::chrono::milliseconds(1));
            thrown = true;
            throw std::runtime_error("the first task");
          }
          ++running;
          std::this_thread::sleep_for(std::chrono::milliseconds(200));
          --running;
        });
        ADD_FAILURE() << "no exception reached the caller";
      } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "the first task");
        EXPECT_EQ(running.load(), 0) << threads << " threads: a task was still running";
      }
    });
    EXPECT_EQ(late.load(), 0) << threads << " threads";
    EXPECT_LE(started.load(), threads) << threads << " threads";
  }
}

// Each task of a loop starts a loop of its own: all finish (a loop never waits on workers busy
// with the loop around it), every inner index once. On a thread of its own, waited for with a
// deadline and left behind after it, so that a deadlock fails the test rather than hanging it.
TEST(ThreadLoops, ALoopInsideATaskFinishes) {
  constexpr size_t kOuter = 16, kInner = 64;
  struct Shared {
    std::vector<std::atomic<int>> runs = std::vector<std::atomic<int>>(kOuter * kInner);
    std::promise<void> finished;
  };
  const auto shared = std::make_shared<Shared>();
  std::future<void> done = shared->finished.get_future();
  std::thread([shared] {
    run_on_threads(2, [&] {
      parallel_each(kOuter, [&](size_t o) {
        parallel_each(kInner, [&](size_t i) { ++shared->runs[o * kInner + i]; });
      });
    });
    shared->finished.set_value();
  }).detach();
  ASSERT_EQ(done.wait_for(std::chrono::seconds(60)), std::future_status::ready) << "deadlock";
  for (size_t i = 0; i < shared->runs.size(); ++i) ASSERT_EQ(shared->runs[i].load(), 1) << i;
}

// Two threads in runs of their own at 1 and 3 threads, both inside their runs at once: each keeps
// its own count (the first's tasks all on its own thread), and both loops finish.
TEST(ThreadLoops, TwoCallersKeepTheirOwnCounts) {
  std::promise<void> one_in, three_in;
  std::shared_future<void> one_entered = one_in.get_future(), three_entered = three_in.get_future();
  std::atomic<int> one_elsewhere{0}, three_beyond{0};
  std::atomic<size_t> one_done{0}, three_done{0};
  int one_count = 0, three_count = 0;
  std::thread one([&] {
    run_on_threads(1, [&] {
      one_in.set_value();
      three_entered.wait();
      one_count = loop_threads();
      const auto me = std::this_thread::get_id();
      parallel_each(200, [&](size_t) {
        if (std::this_thread::get_id() != me) ++one_elsewhere;
        std::this_thread::sleep_for(std::chrono::microseconds(50));
        ++one_done;
      });
    });
  });
  std::thread three([&] {
    run_on_threads(3, [&] {
      three_in.set_value();
      one_entered.wait();
      three_count = loop_threads();
      parallel_each_thread(200, three_count, [&](size_t, int thread) {
        if (thread >= 3) ++three_beyond;
        std::this_thread::sleep_for(std::chrono::microseconds(50));
        ++three_done;
      });
    });
  });
  one.join();
  three.join();
  EXPECT_EQ(one_count, 1);
  EXPECT_EQ(three_count, 3);
  EXPECT_EQ(one_elsewhere.load(), 0);
  EXPECT_EQ(three_beyond.load(), 0);
  EXPECT_EQ(one_done.load(), 200u);
  EXPECT_EQ(three_done.load(), 200u);
}

// The frame's loop: each task in the caller's floating-point mode on whichever of the loop's
// threads runs it (the worker threads start in the usual mode).
TEST(ThreadLoops, EachThreadsTaskTakesTheCallersFloatingPointMode) {
#if defined(__x86_64__) || defined(__i386__)
  const auto control = [] { return _mm_getcsr() & ~0x3Fu; };
  run_on_threads(2, [&] {
    const unsigned before = _mm_getcsr();
    const unsigned mode = (before & ~0x3Fu) | 0x6000u;  // RC = 11: towards zero
    _mm_setcsr(mode);
    std::atomic<int> wrong{0}, on_workers{0};
    parallel_each_thread(64, loop_threads(), [&](size_t, int thread) {
      std::this_thread::sleep_for(std::chrono::microseconds(300));
      if (control() != mode) ++wrong;
      if (thread > 0) ++on_workers;
    });
    _mm_setcsr(before);
    EXPECT_EQ(wrong.load(), 0);
    if (on_workers == 0) GTEST_SKIP() << "every task ran on the calling thread (a loaded machine)";
  });
#else
  GTEST_SKIP() << "x86 only";
#endif
}

// start_threads' hook, in a process of its own (a death-test child: the pool is the process's,
// and a worker started by an earlier test would not run it): it runs on each worker started, on
// that worker, before any task of a loop.
thread_local bool t_hooked = false;
std::atomic<int> g_hooks{0};
void hook() {
  t_hooked = true;
  ++g_hooks;
}

TEST(ThreadLoops, EachStartedWorkerRunsTheStartHookBeforeItsTasks) {
  EXPECT_EXIT(
      {
        std::atomic<int> unhooked{0};
        const std::thread::id caller = std::this_thread::get_id();
        run_on_threads(3, [&] {
          start_threads(&hook);
          parallel_each(200, [&](size_t) {
            if (std::this_thread::get_id() != caller && !t_hooked) ++unhooked;
            std::this_thread::sleep_for(std::chrono::microseconds(200));
          });
        });
        // The two workers may start after the loop on a busy machine: waited for, 10 s at most.
        for (int i = 0; i < 1000 && g_hooks.load() < 2; ++i)
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        std::exit(g_hooks.load() == 2 && !t_hooked && unhooked.load() == 0 ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

// The process's threads now, from /proc/self/task.
int threads_now() {
  DIR* dir = opendir("/proc/self/task");
  if (!dir) return -1;
  int n = 0;
  while (const dirent* entry = readdir(dir))
    if (entry->d_name[0] != '.') ++n;
  closedir(dir);
  return n;
}

// Waits (10 s at most, for a loaded machine) until the process has `threads` threads.
bool threads_become(int threads) {
  for (int i = 0; i < 1000 && threads_now() != threads; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return threads_now() == threads;
}

// In processes of their own (death-test children, which start with one thread and no worker):
// told to end after the next loop, the worker is gone after it, whether it joined the loop or was
// only woken by it, and a later loop still runs every index, on its caller.
TEST(ThreadLoops, WorkersEndAfterTheLoopsTheyWereGiven) {
  EXPECT_EXIT(
      {
        bool ok = true;
        run_on_threads(2, [&] {
          start_threads();
          ok = ok && threads_now() == 2;
          end_threads_after_loops(2);
          for (int loop = 0; loop < 2; ++loop) {
            std::atomic<int> ran{0};
            parallel_each(100, [&](size_t) {
              ++ran;
              std::this_thread::sleep_for(std::chrono::microseconds(200));
            });
            ok = ok && ran.load() == 100;
            // Not before the second loop: the first leaves the worker asleep, not ended.
            if (loop == 0) ok = ok && threads_now() == 2;
          }
          ok = ok && threads_become(1);
          std::atomic<int> later{0};
          parallel_each(100, [&](size_t) { ++later; });
          ok = ok && later.load() == 100 && threads_now() == 1;
        });
        std::exit(ok ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

// Where a worker's start hook ran, and the worker.
std::atomic<int> g_first_cpu{-1};
std::atomic<pid_t> g_worker{0};
void record_first_cpu() {
  g_first_cpu = sched_getcpu();
  g_worker = static_cast<pid_t>(syscall(SYS_gettid));
}

// A worker's start, its hook included, runs on another of the process's CPUs than its creator's
// (a scheduler that packs a new thread onto its creator's CPU made it wait there), and the worker
// has all of them again after it. In processes of their own (forked: no worker yet); a child whose
// creator ran on another CPU after the spawn than before cannot tell and is tried again.
TEST(ThreadLoops, AWorkerStartsOnAnotherCpuThanItsCreatorThenMayRunOnAny) {
  cpu_set_t all;
  ASSERT_EQ(sched_getaffinity(0, sizeof all, &all), 0);
  if (CPU_COUNT(&all) < 2) GTEST_SKIP() << "the process may run on one CPU only";
  int status = 2;
  for (int attempt = 0; attempt < 20 && status == 2; ++attempt) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      int code = 1;
      run_on_threads(2, [&] {
        const int before = sched_getcpu();
        start_threads(&record_first_cpu);
        const int after = sched_getcpu();
        // Busy while the worker starts, as a scene's load is: a worker placed on this CPU would
        // wait for it. 10 s at most, for a loaded machine.
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (g_worker.load() == 0 && std::chrono::steady_clock::now() < give_up) {
        }
        bool freed = false;
        for (int i = 0; i < 1000 && g_worker.load() != 0 && !freed; ++i) {
          cpu_set_t now;
          freed =
              sched_getaffinity(g_worker.load(), sizeof now, &now) == 0 && CPU_EQUAL(&now, &all);
          if (!freed) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        if (before != after)
          code = 2;
        else
          code = g_worker.load() != 0 && g_first_cpu.load() != before && freed ? 0 : 1;
      });
      std::_Exit(code);
    }
    int child_status = 0;
    ASSERT_EQ(waitpid(child, &child_status, 0), child);
    status = WIFEXITED(child_status) ? WEXITSTATUS(child_status) : 1;
  }
  EXPECT_EQ(status, 0);
}

}  // namespace
}  // namespace softtrace::test
