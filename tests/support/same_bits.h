// Comparing two rendered images to the bit in tests (GoogleTest expectations).
#pragma once

#include <string>

namespace softtrace::test {

// Same windows, channels and bits in every channel of every pixel of the images at the two paths
// (NaN payloads and signed zeros included).
void expect_same_bits(const std::string& a_path, const std::string& b_path);

}  // namespace softtrace::test
