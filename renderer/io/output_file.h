// Writing an output file all or nothing: the data goes to a temporary file `.NAME.XXXXXX` beside
// the target (beside a symlink's final target: the link itself stays), which is renamed over
// the target only when complete. Temporary files are registered as pending so that a signal
// can remove them (cmd_render.cpp), and hold an flock(2) for as long as they live, so that a
// later run can tell a stale one (left by SIGKILL) from one being written.
#pragma once

#include <string>

namespace softtrace {

// Checks, before any work, that `path` can be written: one of `extensions` (lower case, with
// the dot), an existing folder we may write to (the folder of a symlink's final target).
// Throws std::invalid_argument with the reason.
void check_output_path(const std::string& path, const char* const* extensions);

std::string output_extension(const std::string& path);  // lower case, with the dot

// The file a write to `path` replaces: `path` with symlinks followed (the last one may dangle).
std::string resolve_output_target(const std::string& path);

// Removes stale temporary files of `target` (an already resolved path): entries of its folder
// named exactly `.NAME.` + 6 characters of mkstemp's alphabet, regular files owned by this
// user, last modified before `started` (seconds since the epoch, this run's start) and not
// locked by any process (flock). Returns how many were removed.
int remove_stale_temporaries(const std::string& target, double started);

// Creates a locked, pending temporary file beside `target`; returns its path.
// Throws std::runtime_error naming `display` when it cannot.
std::string create_pending_temp(const std::string& target, const std::string& display);

// Renames a finished temporary file over `target` (with a new file's usual permissions), after
// one fsync of it: the writers only check their writes and close, so this is the output's one
// sync, and the rename never makes a file the output before its data is on the disk. `tmp` is a
// pending file of the calling thread's (create_pending_temp), synced through its lock's
// descriptor. Throws std::runtime_error naming `display`; the temporary file is then removed
// (unless it is not the calling thread's pending file: then nothing is touched).
void commit_temp(const std::string& tmp, const std::string& target, const std::string& display);

// Pending files belong to the thread that created them: a write is one thread's work, and
// threads writing at once (Python renders) must never remove each other's files.
// Forgets the calling thread's pending files (after committing them): closes their locks.
void forget_pending_writes();
// Removes the calling thread's pending temporary files (renamed ones are gone already) and
// forgets them.
void abandon_pending_writes();
// Removes every thread's pending temporary files, then _exit(status), with no temporary file
// created in between (an interrupt's handler's way out while writing, cmd_render.cpp): safe in
// a handler, since no thread holds the list's lock with SIGINT or SIGTERM open.
[[noreturn]] void abandon_pending_writes_and_exit(int status);

// This process's start (seconds since the epoch), for remove_stale_temporaries.
double process_start_time();

}  // namespace softtrace
