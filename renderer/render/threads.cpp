#include "render/threads.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

namespace softtrace {

struct ThreadLimit::Control {
  explicit Control(int threads)
      : control(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads)) {}
  tbb::global_control control;
};

ThreadLimit::ThreadLimit() = default;
ThreadLimit::ThreadLimit(ThreadLimit&&) noexcept = default;
ThreadLimit& ThreadLimit::operator=(ThreadLimit&&) noexcept = default;
ThreadLimit::~ThreadLimit() = default;

ThreadLimit limit_threads(int threads) {
  ThreadLimit limit;
  if (threads) limit.control_ = std::make_unique<ThreadLimit::Control>(threads);
  return limit;
}

int default_threads() {
  return tbb::info::default_concurrency();
}

}  // namespace softtrace
