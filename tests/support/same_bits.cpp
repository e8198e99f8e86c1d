#include "same_bits.h"

#include <gtest/gtest.h>

#include <cstring>

#include "io/image_file.h"

namespace softtrace::test {

void expect_same_bits(const std::string& a_path, const std::string& b_path) {
  const ImageFile a = read_image(a_path), b = read_image(b_path);
  EXPECT_EQ(a.full_width, b.full_width);
  EXPECT_EQ(a.full_height, b.full_height);
  EXPECT_EQ(a.x0, b.x0);
  EXPECT_EQ(a.y0, b.y0);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  ASSERT_EQ(a.channels, b.channels);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    differing += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0u) << a_path << " vs " << b_path;
}

}  // namespace softtrace::test
