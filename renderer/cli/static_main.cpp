// softtrace, the static program: renders and benchmarks what needs no shared library itself and
// execs softtrace-core for the rest. Its entry (launcher_entry.cpp) has blocked SIGINT and SIGTERM
// and sent every other command, and any EXR named on the command line, to softtrace-core before
// the C library started; what shows later (an EXR texture, a default .exr output, a scene whose
// tracers need Embree) throws NeedsCore, and standard error is held until the frame's tracers
// are built, so that softtrace-core does not print the load's warnings a second time.
#include "cli/commands.h"
#include "cli/core_hand_over.h"
#include "cli/signals.h"

int main(int argc, char** argv) {
  using namespace softtrace;
  block_interrupts();  // already blocked by the entry; here for a start that skipped it
  hold_standard_error(argv);
  try {
    const int status = run_command_line(argc, argv);
    release_standard_error();
    return status;
  } catch (const NeedsCore&) {
    hand_over_to_core();
  }
}
