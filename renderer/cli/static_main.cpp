// softtrace, the static program: renders and benchmarks what needs no shared library itself and
// execs softtrace-core for the rest. Its entry (launcher_entry.cpp) has blocked SIGINT and SIGTERM
// and sent every other command, and any EXR named on the command line, to softtrace-core before
// the C library started. What shows later: a scene whose tracers need Embree, handed over right
// after its load (hand_over_embree_scene); an EXR texture or a default .exr output, which throw
// NeedsCore (as rtcNewDevice does, should a scene pass that check). Standard error is held until
// the frame's tracers are built, so that softtrace-core does not print the load's warnings a
// second time.
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
