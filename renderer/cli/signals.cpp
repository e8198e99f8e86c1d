#include "cli/signals.h"

#include <pthread.h>
#include <unistd.h>

#include <csignal>
#include <cstring>

#include "cli/core_hand_over.h"
#include "film/film.h"

namespace softtrace {

sigset_t interrupt_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

void block_interrupts() {
  const sigset_t set = interrupt_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

void unblock_interrupts() {
  const sigset_t set = interrupt_signals();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

void watch_interrupts(void (*on_interrupt)(int sig)) {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  action.sa_mask = interrupt_signals();  // the other signal waits until this one's handler returns
  action.sa_flags = SA_RESTART;  // a rename or fsync it interrupts (render's commit) goes on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  unblock_interrupts();
}

void report_from_handler(const char* line) {
  release_standard_error();  // what the static program held comes first (core_hand_over.h)
  // Standard error may be a pipe that takes part of it: the rest follows.
  for (size_t left = std::strlen(line); left > 0;) {
    const ssize_t n = ::write(STDERR_FILENO, line, left);
    if (n <= 0) return;
    line += n;
    left -= size_t(n);
  }
}

void exit_on_interrupt(int sig) {
  report_from_handler("softtrace: interrupted\n");
  abandon_pending_writes_and_exit(128 + sig);
}

}  // namespace softtrace
