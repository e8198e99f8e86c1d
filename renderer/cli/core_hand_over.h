// What the static `softtrace` cannot do itself and hands to `softtrace-core` beside it: EXR (read
// and written through softtrace-exr.so) and Embree (libembree3), both shared libraries that a
// static program cannot open (glibc's static dlopen cannot load the C++ libraries safely). The
// need shows late: once the scene is loaded, Embree (its objects' kinds, trace/direct_paths.h)
// and a default .exr output (cli/exr_in_core.cpp). Until the tracers are built the static program
// holds what it writes to standard error, so that a hand-over drops it (softtrace-core prints the
// load's warnings again) and nothing is printed twice; softtrace-core itself never holds nor
// hands over, and these calls find nothing held and no arguments kept there.
#pragma once

namespace softtrace {

struct Scene;

// Thrown where the static program meets EXR or Embree (cli/exr_in_core.cpp,
// cli/embree_in_core.cpp). Not a std::exception: no handler that turns errors into messages
// (the loader's, the commands') may take it on its way to cli/static_main.cpp.
struct NeedsCore {};

// Standard error goes to a memory file from now until release_standard_error() or
// hand_over_to_core(), which execs softtrace-core with `argv`. Called once, first thing in the
// static program's main().
void hold_standard_error(char** argv);

// Writes what was held to standard error and sends later writes there again; nothing if nothing
// is held. Async-signal-safe (the interrupt handlers print what was held before their line), and
// the main thread calls it with the signals blocked, so the two never run at once.
void release_standard_error();

// Drops what was held and execs softtrace-core, in the folder of this program, with the arguments
// hold_standard_error() kept, the signals blocked (they wait for softtrace-core's handler). If it
// cannot, prints what was held and one line naming the program, and exits 2.
[[noreturn]] void hand_over_to_core();

// In the static program, hands a loaded scene whose tracers will ask for an Embree device to
// softtrace-core, before its fields are compiled and its tracers built (and without a throw: the
// first exception of a static program sorts every frame's unwinding entry, 24 M instructions);
// returns for any other scene, and always in softtrace-core. EmbreeScene's rtcNewDevice still
// throws NeedsCore, should a scene pass here that the tracers send to Embree.
void hand_over_embree_scene(const Scene& scene);

}  // namespace softtrace
