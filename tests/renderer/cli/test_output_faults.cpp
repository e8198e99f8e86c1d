// Output faults (issue 35): a full disk, non-regular targets and an unwritable standard output.
// Nothing may be committed that is not complete on the disk, no existing output lost, no
// temporary file left, and the exit status must say it failed.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_util.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

// A 64 KiB tmpfs mounted on a fresh folder for the test's life, with a file "old.exr" holding
// "old" and the rest filled until the disk is full. Mounting needs root (CAP_SYS_ADMIN):
// `mounted()` is false elsewhere and the test skips.
class FullDisk {
 public:
  explicit FullDisk(const std::string& name) : dir_(temp_dir(name) + "/disk") {
    fs::create_directories(dir_);
    if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=64k,mode=0755") != 0) {
      reason_ = std::string("cannot mount a tmpfs: ") + std::strerror(errno);
      return;
    }
    mounted_ = true;
    std::ofstream(dir_ + "/old.exr") << "old";
    std::ofstream(dir_ + "/old.png") << "old";
    std::ofstream filler(dir_ + "/filler", std::ios::binary);
    const std::string block(4096, 'x');
    for (int i = 0; i < 64 && filler; ++i) filler.write(block.data(), long(block.size())).flush();
  }
  ~FullDisk() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  bool mounted() const { return mounted_; }
  const std::string& reason() const { return reason_; }
  const std::string& dir() const { return dir_; }
  // Names in the folder other than the ones the constructor made: temporaries, new outputs.
  std::vector<std::string> extra_files() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string n = e.path().filename().string();
      if (n != "old.exr" && n != "old.png" && n != "filler") out.push_back(n);
    }
    return out;
  }

 private:
  std::string dir_, reason_;
  bool mounted_ = false;
};

#define REQUIRE_FULL_DISK(disk) \
  if (!(disk).mounted()) GTEST_SKIP() << (disk).reason()

// An 8x6 EXR is about 1.5 KB: it once went out as a 0-byte file, exit 0, since the only error
// was thrown in OpenEXR's destructor and swallowed there. Both outputs stay as they were.
TEST(FullDisk, RenderCommitsNothingAndFails) {
  const FullDisk disk("full_render");
  REQUIRE_FULL_DISK(disk);
  const RunResult r =
      run_softtrace("render " + source_path(kDefaultScene) + " --width 8 --height 6 --quiet -o " +
                    disk.dir() + "/old.exr -o " + disk.dir() + "/old.png");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(disk.dir() + "/old.exr"), "old");
  EXPECT_EQ(read_file(disk.dir() + "/old.png"), "old");
  EXPECT_TRUE(disk.extra_files().empty()) << disk.extra_files()[0];
}

TEST(FullDisk, PngAloneCommitsNothingAndFails) {
  const FullDisk disk("full_png");
  REQUIRE_FULL_DISK(disk);
  const RunResult r = run_softtrace("render " + source_path(kDefaultScene) +
                                    " --width 8 --height 6 --quiet -o " + disk.dir() + "/old.png");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(read_file(disk.dir() + "/old.png"), "old");
  EXPECT_TRUE(disk.extra_files().empty()) << disk.extra_files()[0];
}

// merge once left its temporary file behind when the write failed.
TEST(FullDisk, MergeLeavesNoTemporaryFile) {
  const FullDisk disk("full_merge");
  REQUIRE_FULL_DISK(disk);
  const std::string tiles = temp_dir("full_merge_tiles");
  for (int i = 0; i < 2; ++i)
    ASSERT_EQ(run_softtrace("render " + source_path(kDefaultScene) +
                            " --width 8 --height 6 --quiet --tile " + std::to_string(i) + "/2 -o " +
                            tiles + "/t" + std::to_string(i) + ".exr")
                  .status,
              0);
  const RunResult r = run_softtrace("merge " + tiles + "/t0.exr " + tiles + "/t1.exr --quiet -o " +
                                    disk.dir() + "/old.exr");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(read_file(disk.dir() + "/old.exr"), "old");
  EXPECT_TRUE(disk.extra_files().empty()) << disk.extra_files()[0];
}

TEST(FullDisk, DiffOutputFailsWithFour) {
  const FullDisk disk("full_diff");
  REQUIRE_FULL_DISK(disk);
  const std::string dir = temp_dir("full_diff_in");
  ASSERT_EQ(run_softtrace("render " + source_path(kDefaultScene) +
                          " --width 8 --height 6 --quiet -o " + dir + "/a.exr")
                .status,
            0);
  const RunResult r =
      run_softtrace("diff " + dir + "/a.exr " + dir + "/a.exr -o " + disk.dir() + "/old.exr");
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_EQ(read_file(disk.dir() + "/old.exr"), "old");
  EXPECT_TRUE(disk.extra_files().empty()) << disk.extra_files()[0];
}

// Renaming over a FIFO or a device node would put a regular file in its place (as root, through
// a link to /dev/null, /dev/null itself). The device here is a copy of /dev/null's numbers made
// for the test, so that a regression cannot harm the machine.
TEST(NonRegularOutput, FifoIsRefused) {
  const std::string dir = temp_dir("fifo_out");
  ASSERT_EQ(::mkfifo((dir + "/out.exr").c_str(), 0600), 0);
  const RunResult r = run_softtrace("render " + source_path(kDefaultScene) +
                                    " --width 8 --height 6 --quiet -o " + dir + "/out.exr");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("out.exr: is a FIFO; outputs must be regular files or links to them"),
            std::string::npos)
      << r.err;
  struct stat st {};
  ASSERT_EQ(::lstat((dir + "/out.exr").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
}

TEST(NonRegularOutput, LinkToADeviceIsRefused) {
  const std::string dir = temp_dir("device_out");
  if (::mknod((dir + "/null").c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
    GTEST_SKIP() << "cannot make a device node: " << std::strerror(errno);
  fs::create_symlink(dir + "/null", dir + "/out.exr");
  for (const std::string& command : {"render " + source_path(kDefaultScene) +
                                         " --width 8 --height 6 --quiet -o " + dir + "/out.exr",
                                     "diff " + source_path(kDefaultScene) + " " +
                                         source_path(kDefaultScene) + " -o " + dir + "/out.exr"}) {
    const RunResult r = run_softtrace(command);
    EXPECT_NE(r.status, 0) << command;
    EXPECT_NE(r.err.find("out.exr: is a character device"), std::string::npos) << r.err;
    struct stat st {};
    ASSERT_EQ(::lstat((dir + "/null").c_str(), &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << command << " replaced the device";
  }
}

// Results that cannot be written are a failure, not exit 0 with nothing written.
TEST(StandardOutput, UnwritableIsAFailure) {
  const std::string points = temp_dir("stdout_full") + "/points";
  std::ofstream(points) << "0 0 0\n1 2 3\n";
  for (const std::string& command : {"eval " + source_path(kDefaultScene) + " --points " + points,
                                     std::string("nodes"), std::string("nodes --dict"),
                                     "bench " + source_path(kDefaultScene) +
                                         " --width 8 --height 6 --repeat 1 --quiet --json"}) {
    const RunResult r =
        run_command("{ " + std::string(SOFTTRACE_BIN) + " " + command + " >/dev/full; }");
    EXPECT_EQ(r.status, 2) << command << ": " << r.err;
    EXPECT_EQ(r.err.rfind("softtrace: cannot write the standard output: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
}  // namespace softtrace::test
