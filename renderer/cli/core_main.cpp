// softtrace-core: the whole command line with EXR (softtrace-exr.so) and Embree (libembree3),
// both opened on demand. The static softtrace execs it for what needs them (core_hand_over.h);
// it also runs on its own.
#include "cli/commands.h"

int main(int argc, char** argv) {
  return softtrace::run_command_line(argc, argv);
}
