// The PNG's Adler-32 (io/adler32.h) against zlib's own, at every length up to a few chunks past a
// block, from unaligned starts and a running checksum, and on bytes of 255 (the sums' largest) up
// to several blocks.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <random>
#include <vector>

#include "io/adler32.h"

namespace softtrace {
namespace {

uint32_t zlib_adler(uint32_t start, const unsigned char* p, size_t n) {
  return uint32_t(adler32(start, p, uInt(n)));
}

TEST(Adler32, MatchesZlibAtEveryLengthFromAnyStart) {
  std::mt19937 random(7);
  std::vector<unsigned char> bytes(6000 + 64);
  for (auto& b : bytes) b = static_cast<unsigned char>(random());
  for (const uint32_t start : {1u, 0xfff0fff0u % (65521u << 16), 0x1234abcdu % (65521u << 16)}) {
    for (size_t offset = 0; offset < 3; ++offset) {
      for (size_t n = 0; n <= 6000; n += n < 700 ? 1 : 37) {
        const unsigned char* p = bytes.data() + offset;
        ASSERT_EQ(adler32_of(start, p, n), zlib_adler(start, p, n))
            << "start " << start << ", offset " << offset << ", " << n << " bytes";
      }
    }
  }
}

TEST(Adler32, MatchesZlibOnTheLargestBytesOverSeveralBlocks) {
  const std::vector<unsigned char> bytes(70000, 255);
  for (const size_t n : {size_t(5551), size_t(5552), size_t(5553), size_t(5552 * 2 + 15),
                         size_t(16 * 347), size_t(16 * 347 + 1), size_t(33331), size_t(70000)}) {
    ASSERT_EQ(adler32_of(1, bytes.data(), n), zlib_adler(1, bytes.data(), n)) << n << " bytes";
    ASSERT_EQ(adler32_of(0xfff0fff0u, bytes.data(), n), zlib_adler(0xfff0fff0u, bytes.data(), n))
        << n << " bytes from a start near the modulus";
  }
}

}  // namespace
}  // namespace softtrace
