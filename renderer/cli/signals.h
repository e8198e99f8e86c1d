// SIGINT and SIGTERM never reach a signal handler. `softtrace` (launcher.cpp) blocks them before
// the renderer's shared libraries load, main() blocks them again before anything else (for a
// renderer started directly), and one watcher thread takes them with sigwait: what a signal does
// is then ordinary code, which may take locks (film.cpp's pending writes).
#pragma once

namespace softtrace {

// Blocks SIGINT and SIGTERM in the calling thread. First thing in main(), before any thread
// exists, so that every thread inherits the mask and only the watcher receives them.
void block_interrupts();

// Starts the watcher thread, named "signal-watcher": on_interrupt(sig) runs on it for every
// signal, at once for one that arrived while the libraries were loading.
void watch_interrupts(void (*on_interrupt)(int sig));

// For commands that write nothing but their temporary files: removes those, then
// "softtrace: interrupted" and exit 128 + sig.
[[noreturn]] void exit_on_interrupt(int sig);

}  // namespace softtrace
