// SIGINT/SIGTERM against a real `softtrace render` process: during rendering and while the
// image files are being written. Either way the existing output files keep their old contents,
// no temporary file (.NAME.XXXXXX) is left behind, and the exit status is 128 + the signal.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli_util.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Starts softtrace with `args`, stderr to `err_file`; returns the child's pid.
pid_t spawn(const std::vector<std::string>& args, const std::string& err_file) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(SOFTTRACE_BIN));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(SOFTTRACE_BIN, argv.data());
    ::_exit(127);
  }
  return pid;
}

int wait_status(pid_t pid) {
  int raw = 0;
  ::waitpid(pid, &raw, 0);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : 1000 + WTERMSIG(raw);  // 1000+: killed, a failure
}

// Files in `dir` whose names start with '.': the temporary files of unfinished writes.
std::vector<std::string> temp_files(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string()[0] == '.') out.push_back(e.path().filename().string());
  return out;
}

// Whether the process takes `sig` itself: its main thread blocks it for the signal watcher
// (SigBlk) or has a handler for it (SigCgt), in /proc/PID/status (Linux). Either way it is past
// start-up, and the signal can no longer kill it outright.
bool catches(pid_t pid, int sig) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  bool taken = false;
  while (std::getline(status, line))
    if (line.rfind("SigBlk:", 0) == 0 || line.rfind("SigCgt:", 0) == 0)
      taken = taken || ((std::stoull(line.substr(7), nullptr, 16) >> (sig - 1)) & 1);
  return taken;
}

// Waits (up to a minute) until `pid` catches `sig`; false if it exited or never did.
bool wait_until_catching(pid_t pid, int sig) {
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < deadline) {
    if (catches(pid, sig)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

class SignalDuringRender : public testing::TestWithParam<int> {};

// The default scene at 1024x1024 with 4 samples takes far longer than half a second here.
TEST_P(SignalDuringRender, LeavesTheOldFileAndNoTemporaryFile) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_render_" + std::to_string(sig));
  const std::string out = dir + "/image.exr";
  write_text(out, "old image");
  const pid_t pid = spawn({"render", source_path("scenes/fig12b_soft_blend.json"), "-o", out,
                           "--width", "1024", "--height", "1024", "--spp", "4", "--quiet"},
                          dir + "/../stderr_" + std::to_string(sig));
  ASSERT_TRUE(wait_until_catching(pid, sig));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // well into the frame
  ASSERT_EQ(::kill(pid, sig), 0);
  EXPECT_EQ(wait_status(pid), 128 + sig);
  EXPECT_EQ(read_file(out), "old image");
  EXPECT_TRUE(temp_files(dir).empty()) << temp_files(dir)[0];
  EXPECT_EQ(read_file(dir + "/../stderr_" + std::to_string(sig)),
            "softtrace: interrupted; no image written\n");
}

INSTANTIATE_TEST_SUITE_P(Signals, SignalDuringRender, testing::Values(SIGINT, SIGTERM),
                         [](const testing::TestParamInfo<int>& i) {
                           return std::string(i.param == SIGINT ? "SIGINT" : "SIGTERM");
                         });

// A camera looking away from the object renders a large frame in a moment; writing its two EXRs
// with every AOV then takes a good fraction of a second. The signal is sent as soon as the
// second output's temporary file appears, so it lands while that file is being written, after
// the first one is complete: neither output may be replaced (all or nothing).
TEST(SignalDuringWrite, NeitherOutputIsReplaced) {
  const std::string dir = temp_dir("signal_write");
  const std::string scene = dir + "/../miss.json";
  write_text(scene, R"({"camera":{"eye":[0,0,100],"target":[0,0,200],"up":[0,1,0]},
    "objects":[{"field":{"type":"soft_object","distance":{"type":"lp_metric","radii":[1,1,1],"n":2}}}]})");
  write_text(dir + "/a.exr", "old a");
  write_text(dir + "/b.exr", "old b");
  const pid_t pid = spawn({"render", scene, "-o", dir + "/a.exr", "-o", dir + "/b.exr", "--width",
                           "2048", "--height", "1024", "--aov", "depth,normal,steps", "--quiet"},
                          dir + "/../stderr_write");
  bool sent = false;
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  while (!sent && Clock::now() < deadline) {
    int raw;
    if (::waitpid(pid, &raw, WNOHANG) == pid) FAIL() << "finished before the second write began";
    for (const auto& t : temp_files(dir))
      if (t.rfind(".b.exr.", 0) == 0) sent = ::kill(pid, SIGTERM) == 0;
    if (!sent) std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  ASSERT_TRUE(sent) << "the second output's temporary file never appeared";
  EXPECT_EQ(wait_status(pid), 128 + SIGTERM);
  EXPECT_EQ(read_file(dir + "/a.exr"), "old a");
  EXPECT_EQ(read_file(dir + "/b.exr"), "old b");
  EXPECT_TRUE(temp_files(dir).empty()) << temp_files(dir)[0];
}

}  // namespace
}  // namespace softtrace::test
