#include "cli_util.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace softtrace::test {

namespace fs = std::filesystem;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string source_path(const std::string& relative) {
  return std::string(SOFTTRACE_SOURCE_DIR) + "/" + relative;
}

std::string temp_dir(const std::string& name) {
  // Per process: CTest runs test cases in parallel processes.
  const fs::path p = fs::path(SOFTTRACE_TEST_TMP) / std::to_string(::getpid()) / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

RunResult run_softtrace(const std::string& args, const std::string& stdin_file) {
  return run_command(std::string(SOFTTRACE_BIN) + " " + args, stdin_file);
}

RunResult run_command(const std::string& command, const std::string& stdin_file) {
  static int counter = 0;
  if (counter == 0) temp_dir("run");
  const std::string base = (fs::path(SOFTTRACE_TEST_TMP) / std::to_string(::getpid()) / "run" /
                            std::to_string(counter++))
                               .string();
  const std::string cmd = command + " >" + base + ".out 2>" + base + ".err" +
                          (stdin_file.empty() ? "" : " <" + stdin_file);
  const int raw = std::system(cmd.c_str());
  RunResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  r.out = read_file(base + ".out");
  r.err = read_file(base + ".err");
  return r;
}

std::string render_tiles_and_merge(const std::string& render, const std::string& dir, int n) {
  std::string tiles;
  for (int i = 0; i < n; ++i) {
    const std::string tile = dir + "/t" + std::to_string(i) + ".exr";
    const std::string part = " --tile " + std::to_string(i) + "/" + std::to_string(n);
    if (run_softtrace(render + part + " -o " + tile).status != 0) return "";
    tiles += " " + tile;
  }
  const std::string merged = dir + "/merged.exr";
  return run_softtrace("merge" + tiles + " -o " + merged).status == 0 ? merged : "";
}

}  // namespace softtrace::test
