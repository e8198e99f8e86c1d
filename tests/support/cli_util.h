// Running the softtrace binary from tests: exit status, stdout and stderr of one command.
#pragma once

#include <string>

namespace softtrace::test {

// The scene most CLI tests render: the README's default (640x480).
inline const std::string kDefaultScene = "scenes/fig000_12b_soft_blend.json";

struct RunResult {
  int status = -1;
  std::string out, err;
};

// Runs `softtrace <args>` (args are passed to /bin/sh: quote as needed), optionally with stdin
// from a file.
RunResult run_softtrace(const std::string& args, const std::string& stdin_file = "");

// Runs any shell command line the same way (e.g. idiff, tests/integration/regression.sh).
RunResult run_command(const std::string& command, const std::string& stdin_file = "");

std::string source_path(const std::string& relative);  // a path in the source tree
std::string temp_dir(const std::string& name);         // a fresh, empty folder in the build tree
std::string read_file(const std::string& path);

// Runs `render` (softtrace's arguments, "render SCENE ..." without -o) as n tiles (--tile i/n)
// into `dir`, then merges them into dir/merged.exr; returns that path, or "" when a render or the
// merge fails.
std::string render_tiles_and_merge(const std::string& render, const std::string& dir, int n);

}  // namespace softtrace::test
