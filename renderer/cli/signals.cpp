#include "cli/signals.h"

#include <pthread.h>

#include <csignal>
#include <cstdio>
#include <thread>

#include "film/film.h"

namespace softtrace {

namespace {

sigset_t interrupts() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

}  // namespace

void block_interrupts() {
  const sigset_t set = interrupts();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

void watch_interrupts(void (*on_interrupt)(int sig)) {
  block_interrupts();
  std::thread([on_interrupt] {
    pthread_setname_np(pthread_self(), "signal-watcher");  // for ps, gdb and the tests
    const sigset_t set = interrupts();
    int sig;
    while (sigwait(&set, &sig) == 0) on_interrupt(sig);
  }).detach();
}

void exit_on_interrupt(int sig) {
  std::fprintf(stderr, "softtrace: interrupted\n");
  abandon_pending_writes_and_exit(128 + sig);
}

}  // namespace softtrace
