// translate_box against transform_box: a placement without a rotation bounds its boxes by a few
// additions, and every bound must be transform_box's bit for bit (the signs of zeros included),
// since the boxes decide the blobs' tree and the tracers' steps.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "model/placement.h"

namespace softtrace {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(TranslateBox, IsTransformBoxWithTheIdentityBitForBit) {
  std::mt19937_64 rng(7);
  // Zeros of both signs are the cases the shortcut must leave to transform_box.
  const double picks[] = {0.0, -0.0, 1.0, -2.5, 1e-300, -3e150, 0.1, 1e150};
  std::uniform_int_distribution<int> pick(0, 7), coin(0, 1);
  std::uniform_real_distribution<double> real(-50, 50);
  const auto value = [&] { return coin(rng) ? picks[pick(rng)] : real(rng); };
  int checked = 0;
  for (int n = 0; n < 200000; ++n) {
    Box b;
    for (int i = 0; i < 3; ++i) {
      double a = value(), c = value();
      if (c < a) std::swap(a, c);
      b.lo[i] = a;
      b.hi[i] = c;
    }
    if (!b.bounded()) continue;
    Vec3 t;
    for (int i = 0; i < 3; ++i) t[i] = value();
    Mat3 I;  // the identity, some of its zeros negative (a Placed takes such a matrix as one)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (i != j && coin(rng)) I.r[i][j] = -0.0;
    const Box want = transform_box(b, I, t), got = translate_box(b, I, t);
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(same_bits(got.lo[i], want.lo[i]) && same_bits(got.hi[i], want.hi[i]))
          << "box " << n << " axis " << i << ": [" << got.lo[i] << ", " << got.hi[i]
          << "] against [" << want.lo[i] << ", " << want.hi[i] << "]";
    }
    ++checked;
  }
  EXPECT_GT(checked, 100000);
}

}  // namespace
}  // namespace softtrace
