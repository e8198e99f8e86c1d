// SIGINT/SIGTERM against a real `softtrace render` process: while its libraries load, while it
// loads a scene, during rendering and while the image files are being written. Every time the
// existing output files keep their old contents, no temporary file (.NAME.XXXXXX) is left
// behind, and the exit status is 128 + the signal.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
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
  fs::remove(err_file);  // no stale text from an earlier run for the caller to wait on
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

// Whether `pid` has a handler for `sig` (its SigCgt mask in /proc/PID/status, Linux): past
// start-up, its command line parsed.
bool catches(pid_t pid, int sig) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("SigCgt:", 0) == 0)
      return (std::stoull(line.substr(7), nullptr, 16) >> (sig - 1)) & 1;
  return false;
}

// The threads `pid` has (/proc/PID/task, Linux).
int thread_count(pid_t pid) {
  std::error_code ec;
  int n = 0;
  for (fs::directory_iterator t("/proc/" + std::to_string(pid) + "/task", ec), end; !ec && t != end;
       t.increment(ec))
    ++n;
  return n;
}

// Polls (up to a minute) until `ready` holds; false if it never did.
template <class Ready>
bool wait_until(Ready ready) {
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < deadline) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return false;
}

// Whether `pid` runs the renderer proper: `softtrace` has exec'd softtrace-core, which is then
// loading its shared libraries (a few tenths of a second) or past that.
bool runs_core(pid_t pid) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec);
  return !ec && fs::equivalent(exe, SOFTTRACE_CORE_BIN, ec);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

class Signal : public testing::TestWithParam<int> {};

INSTANTIATE_TEST_SUITE_P(Signals, Signal, testing::Values(SIGINT, SIGTERM),
                         [](const testing::TestParamInfo<int>& i) {
                           return std::string(i.param == SIGINT ? "SIGINT" : "SIGTERM");
                         });

// A signal as soon as the renderer proper has been exec'd: its libraries are loading, long before
// its main() runs. The launcher's mask holds the signal for the handler (it once killed the
// process without a word).
TEST_P(Signal, WhileTheLibrariesLoadExitsWithNothingWritten) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_start_" + std::to_string(sig));
  const std::string err = dir + "/../stderr_start_" + std::to_string(sig);
  const pid_t pid = spawn({"render", source_path("scenes/fig000_12b_soft_blend.json"), "-o",
                           dir + "/image.exr", "--quiet"},
                          err);
  ASSERT_TRUE(wait_until([&] { return runs_core(pid); }));
  ASSERT_EQ(::kill(pid, sig), 0);
  EXPECT_EQ(wait_status(pid), 128 + sig);
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_EQ(read_file(err), "softtrace: interrupted; no image written\n");
}

// A scene of 100,000 children takes most of a second to read before it is refused: a signal
// once the handler is in place lands while the scene loads, and stops it there (it once let the
// load go on to its error, exit 2, or killed the process through a thread that a library had
// started before main() blocked the signal).
TEST_P(Signal, WhileASceneLoadsExitsAtOnce) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_load_" + std::to_string(sig));
  const std::string scene = dir + "/../wide_" + std::to_string(sig) + ".json";
  {
    std::ofstream f(scene);
    f << R"({"camera":{"eye":[40,-55,32],"target":[0,0,0]},"objects":[{"field":)"
      << R"({"type":"soft_blend","children":[)";
    for (int i = 0; i < 100000; ++i)
      f << (i ? "," : "")
        << R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[1,1,1],"n":2}})";
    f << "]}}]}";
  }
  const std::string err = dir + "/../stderr_load_" + std::to_string(sig);
  const pid_t pid = spawn({"render", scene, "-o", dir + "/image.exr", "--quiet"}, err);
  ASSERT_TRUE(wait_until([&] { return catches(pid, sig); }));
  ASSERT_EQ(::kill(pid, sig), 0);
  EXPECT_EQ(wait_status(pid), 128 + sig);
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_EQ(read_file(err), "softtrace: interrupted; no image written\n");
}

// softtrace renders a PNG of one field in its own process, holding standard error until the
// tracers are built (cli/core_hand_over.h): a signal while it loads or renders prints what was
// held (here the load's warning) before its line. The signal is sent once the warning is written,
// to the held file or to standard error (/proc/PID/fd/2 is either).
TEST_P(Signal, AfterTheLoadsWarningPrintsItThenItsLine) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_warning_" + std::to_string(sig));
  const std::string scene = dir + "/../warning_" + std::to_string(sig) + ".json";
  {
    std::ofstream f(scene);
    // A child whose radius modulation fails its side condition near the skeleton (a warning),
    // then 9,999 overlapping balls (the most a blend takes with it): seconds of work at 64x64.
    f << R"({"camera":{"eye":[0,-60,0],"target":[0,0,0],"up":[0,0,1]},)"
      << R"("image":{"width":64,"height":64,"spp":1},"objects":[{"field":)"
      << R"({"type":"soft_blend","children":[{"type":"soft_object","distance":)"
      << R"({"type":"lp_metric","radii":[4,4,4],"n":2},"radii":{"type":"T_an","modulation":)"
      << R"({"type":"lp_metric","radii":[8,8,8],"n":2,"translate":[0.5,0,0]}}})";
    for (int i = 0; i < 9999; ++i)
      f << R"(,{"type":"soft_object","translate":[)" << (i % 10) - 4.5 << "," << (i / 10 % 10) - 4.5
        << "," << (i / 100 % 10) * 0.1
        << R"(],"distance":{"type":"lp_metric","radii":[10,10,10],"n":2}})";
    f << "]}}]}";
  }
  const std::string err = dir + "/../stderr_warning_" + std::to_string(sig);
  const pid_t pid = spawn({"render", scene, "-o", dir + "/image.png", "--quiet"}, err);
  const std::string held = "/proc/" + std::to_string(pid) + "/fd/2";
  ASSERT_TRUE(wait_until([&] { return catches(pid, sig) && !read_file(held).empty(); }));
  ASSERT_EQ(::kill(pid, sig), 0);
  EXPECT_EQ(wait_status(pid), 128 + sig);
  EXPECT_TRUE(fs::is_empty(dir));
  const std::string text = read_file(err);
  EXPECT_EQ(text.rfind("softtrace: warning: " + scene + ": /objects/0/field/children/0/", 0), 0u)
      << text;
  const std::string last = "\nsofttrace: interrupted; no image written\n";
  EXPECT_TRUE(text.size() > last.size() && text.substr(text.size() - last.size()) == last) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2) << text;
}

// Other commands stop at once too, with the status and one line: here `eval` waiting to open
// a FIFO that nobody writes.
TEST_P(Signal, StopsEval) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_eval_" + std::to_string(sig));
  ASSERT_EQ(::mkfifo((dir + "/points").c_str(), 0600), 0);
  const pid_t pid =
      spawn({"eval", source_path("scenes/fig000_12b_soft_blend.json"), "--points", dir + "/points"},
            dir + "/stderr");
  ASSERT_TRUE(wait_until([&] { return catches(pid, sig); }));
  ASSERT_EQ(::kill(pid, sig), 0);
  EXPECT_EQ(wait_status(pid), 128 + sig);
  EXPECT_EQ(read_file(dir + "/stderr"), "softtrace: interrupted\n");
}

// The handler runs on the thread the signal interrupts: a command takes its signals without a
// thread of its own for them (a watcher thread in sigwait cost every process about 0.4 ms of
// CPU), so `eval` waiting to open its points has only its main thread.
TEST_P(Signal, NeedNoThreadOfTheirOwn) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_threads_" + std::to_string(sig));
  ASSERT_EQ(::mkfifo((dir + "/points").c_str(), 0600), 0);
  const pid_t pid =
      spawn({"eval", source_path("scenes/fig000_12b_soft_blend.json"), "--points", dir + "/points"},
            dir + "/stderr");
  ASSERT_TRUE(wait_until([&] { return catches(pid, SIGINT) && catches(pid, SIGTERM); }));
  EXPECT_EQ(thread_count(pid), 1);
  ASSERT_EQ(::kill(pid, sig), 0);
  EXPECT_EQ(wait_status(pid), 128 + sig);
  EXPECT_EQ(read_file(dir + "/stderr"), "softtrace: interrupted\n");
}

// The default scene at 1024x1024 with 4 samples takes far longer than half a second here. The
// progress bar's first line (forced off a terminal) says the frame has begun.
TEST_P(Signal, DuringRenderLeavesTheOldFileAndNoTemporaryFile) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_render_" + std::to_string(sig));
  const std::string out = dir + "/image.exr", err = dir + "/../stderr_" + std::to_string(sig);
  write_text(out, "old image");
  const pid_t pid = spawn({"render", source_path("scenes/fig000_12b_soft_blend.json"), "-o", out,
                           "--width", "1024", "--height", "1024", "--spp", "4", "--progress"},
                          err);
  ASSERT_TRUE(wait_until([&] { return read_file(err).rfind("\rrendering [", 0) == 0; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // well into the frame
  ASSERT_EQ(::kill(pid, sig), 0);
  EXPECT_EQ(wait_status(pid), 128 + sig);
  EXPECT_EQ(read_file(out), "old image");
  EXPECT_TRUE(temp_files(dir).empty()) << temp_files(dir)[0];
  const std::string text = read_file(err);
  const std::string last = "\nsofttrace: interrupted; no image written\n";
  EXPECT_TRUE(text.size() > last.size() && text.substr(text.size() - last.size()) == last) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2) << "the bar's line, then the message";
}

// A 10,000-child blend of overlapping balls (every point is in every support, so each
// evaluation sums every child) seen from 60 units, with `image` and `lights` (JSON members).
void write_slow_blend(const std::string& path, const std::string& image,
                      const std::string& lights) {
  std::ofstream f(path);
  f << R"({"camera":{"eye":[0,-60,0],"target":[0,0,0],"up":[0,0,1]},)" << image << "," << lights
    << R"("objects":[{"field":{"type":"soft_blend","children":[)";
  for (int i = 0; i < 10000; ++i)
    f << (i ? "," : "") << R"({"type":"soft_object","translate":[)" << (i % 10) - 4.5 << ","
      << (i / 10 % 10) - 4.5 << "," << (i / 100 % 10) * 0.1
      << R"(],"distance":{"type":"lp_metric","radii":[10,10,10],"n":2}})";
  f << "]}}]}";
}

// Renders `scene` on one thread, sends `sig` `delay` after the frame has begun and returns the
// seconds until the process ended (it is killed, and the test fails, after 10 s). The process
// must have exited with 128 + sig and written nothing into `dir`.
double seconds_to_stop(const std::string& scene, const std::string& dir, int sig,
                       std::chrono::milliseconds delay) {
  const std::string err = dir + "/../stderr_" + fs::path(scene).stem().string();
  const pid_t pid =
      spawn({"render", scene, "-o", dir + "/image.exr", "--threads", "1", "--progress"}, err);
  EXPECT_TRUE(wait_until([&] { return read_file(err).rfind("\rrendering [", 0) == 0; }));
  std::this_thread::sleep_for(delay);
  EXPECT_EQ(::kill(pid, sig), 0);
  const auto sent = Clock::now();
  int raw = 0;
  while (::waitpid(pid, &raw, WNOHANG) != pid) {
    if (Clock::now() - sent > std::chrono::seconds(10)) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &raw, 0);
      ADD_FAILURE() << scene << ": still rendering 10 s after the signal";
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 128 + sig);
  EXPECT_TRUE(fs::is_empty(dir));
  return std::chrono::duration<double>(Clock::now() - sent).count();
}

// One 16x16 tile of a 10,000-child blend at 64 spp takes minutes (each sample sums every
// child): a signal checked only between tiles once went unheeded for 97 s. It is checked before
// every sample now, a few tens of milliseconds apart here, so the process must end well within
// the README's 0.5 s; the test allows 5 s for a loaded machine.
TEST_P(Signal, WithinASlowTileStopsSoon) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_slow_tile_" + std::to_string(sig));
  const std::string scene = dir + "/../slow_tile_" + std::to_string(sig) + ".json";
  write_slow_blend(scene, R"("image":{"width":16,"height":16,"spp":64})", "");
  EXPECT_LT(seconds_to_stop(scene, dir, sig, std::chrono::milliseconds(300)), 5.0);
}

// One sample can be slow too: under one 64x64 area light a sample of the same blend casts 4096
// shadow rays, about 2 s of work here (a check before every sample alone let a signal wait 4.9 s
// on a loaded machine); under these 32 such lights about a minute. The flag is checked before
// every light and every shadow or reflected ray, so the wait is about one ray's (0.02 s). The
// test allows 2 s for a loaded machine.
TEST_P(Signal, WithinASlowSampleStopsSoon) {
  const int sig = GetParam();
  const std::string dir = temp_dir("signal_slow_sample_" + std::to_string(sig));
  const std::string scene = dir + "/../slow_sample_" + std::to_string(sig) + ".json";
  std::string lights = R"("lights":[)";
  for (int i = 0; i < 32; ++i)
    lights += std::string(i ? "," : "") + R"({"type":"point","position":[)" +
              std::to_string(2 * i - 31) +
              R"(,-80,60],"area":{"axis1":[10,0,0],"axis2":[0,0,10],"size1":64,"size2":64}})";
  write_slow_blend(scene, R"("image":{"width":4,"height":4,"spp":1})", lights + "],");
  EXPECT_LT(seconds_to_stop(scene, dir, sig, std::chrono::milliseconds(300)), 2.0);
}

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
