// softtrace, the static program: renders and benchmarks what needs no shared library itself and
// execs softtrace-core for the rest. Its entry (launcher_entry.cpp) has blocked SIGINT and SIGTERM
// and sent every other command, and any EXR named on the command line, to softtrace-core before
// the C library started. What shows later, after the scene's load, is handed over where it shows:
// a scene whose tracers need Embree (hand_over_embree_scene) and a default .exr output
// (load_exr_module). What reaches EXR or Embree past those throws NeedsCore, caught here.
// Standard error is held until the frame's tracers are built, so that softtrace-core does not
// print the load's warnings a second time.
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
