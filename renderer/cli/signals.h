// SIGINT and SIGTERM are blocked from the start: the static `softtrace` blocks them by plain
// system calls before its C library starts (launcher_entry.cpp) and keeps them blocked across an
// exec of softtrace-core; sanitizer builds' launcher.cpp does the same before the renderer's shared
// libraries load, and the command line blocks them again before anything else (for
// softtrace-core started directly). Once the command line is parsed, it gives them a handler.
// The handler runs on the thread it interrupts, so what it does must be safe there: atomics,
// write(2), unlink and _exit, and the pending files' lock, which no thread holds with the signals
// open (io/output_file.cpp). A watcher thread waiting in sigwait did this
// as ordinary code, but its start, stack and end cost every process about half a millisecond of
// CPU. `render`'s frame workers keep them blocked (cmd_render.cpp): the handler runs on the main
// thread, and the processes measured faster so.
#pragma once

#include <csignal>

namespace softtrace {

// The set {SIGINT, SIGTERM}.
sigset_t interrupt_signals();

// Blocks SIGINT and SIGTERM in the calling thread. First thing in main(), before any thread
// exists, so that threads libraries start inherit the mask.
void block_interrupts();

// Unblocks them in the calling thread again (after starting threads that are not to take them).
void unblock_interrupts();

// Makes on_interrupt(sig) SIGINT's and SIGTERM's handler and unblocks them in the calling thread
// (threads it starts later inherit that): a signal that arrived while the libraries were loading
// is taken at once. The handler must be async-signal-safe (above); one signal's handler is never
// interrupted by the other's, and system calls it interrupts are restarted.
void watch_interrupts(void (*on_interrupt)(int sig));

// Writes `line` (a constant message with its newline) to standard error as one write(2): the
// way a handler reports, where stdio is not safe. Held lines (core_hand_over.h) come first.
void report_from_handler(const char* line);

// For commands that write nothing but their temporary files: removes those, then
// "softtrace: interrupted" and exit 128 + sig.
[[noreturn]] void exit_on_interrupt(int sig);

}  // namespace softtrace
