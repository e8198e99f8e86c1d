// read_file_bounded: a text file stops at the first block holding a NUL (its parser then names
// the NUL's place), and any other read stops at the size limit.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_util.h"
#include "io/file_read.h"

namespace softtrace::test {
namespace {

std::string write_bytes(const std::string& name, const std::string& bytes) {
  const std::string path = temp_dir("file_read") + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// A NUL late in the first 64 KiB block and a file four times the limit: the read stops with that
// block, NUL included, before the limit is checked; reading on reaches the limit.
TEST(FileRead, ATextFileStopsAtTheBlockWithANul) {
  std::string bytes(300000, 'x');
  bytes[65535] = '\0';
  const std::string path = write_bytes("late_nul.json", bytes);
  const std::string read = read_file_bounded(path, 1 << 16, "scene", AtNul::Stop);
  EXPECT_EQ(read, bytes.substr(0, 1 << 16));
  EXPECT_THROW(read_file_bounded(path, 1 << 16, "scene", AtNul::ReadOn), FileReadError);
}

TEST(FileRead, WithoutANulTheLimitHolds) {
  std::string bytes(300000, 'x');
  bytes[65536] = '\0';  // the second block's first byte: the first block has none
  const std::string path = write_bytes("no_nul.json", bytes);
  EXPECT_THROW(read_file_bounded(path, 1000, "scene", AtNul::Stop), FileReadError);
  EXPECT_EQ(read_file_bounded(path, 1 << 20, "scene", AtNul::Stop), bytes.substr(0, 1 << 17));
}

}  // namespace
}  // namespace softtrace::test
