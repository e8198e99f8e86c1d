// x^k for an integer k >= 0 by repeated squaring, with the multiplications always in one order
// (r = 1; for each bit of k from the lowest: r *= x where the bit is set, then x *= x), so every
// caller's power has the same bits whichever form it takes. The papers' exponents (cubes and bars
// at n = 20, so the partials' n - 1 = 19; bars and cylinders at 4 and 8) take a form unrolled at
// compile time: the loop's counter, test and branch per bit cost more than its multiplications.
#pragma once

namespace softtrace {

// The loop's order with K known: the same multiplications, unrolled.
template <int K>
inline double pow_by_squaring(double x, double r = 1) {
  if constexpr (K == 0) {
    return r;
  } else {
    if constexpr ((K & 1) != 0) r *= x;
    return pow_by_squaring<(K >> 1)>(x * x, r);
  }
}

inline double pow_by_squaring(double x, int k) {
  switch (k) {
    case 2:
      return pow_by_squaring<2>(x);
    case 3:
      return pow_by_squaring<3>(x);
    case 4:
      return pow_by_squaring<4>(x);
    case 7:
      return pow_by_squaring<7>(x);
    case 8:
      return pow_by_squaring<8>(x);
    case 19:
      return pow_by_squaring<19>(x);
    case 20:
      return pow_by_squaring<20>(x);
  }
  double r = 1;
  for (; k; k >>= 1, x *= x)
    if (k & 1) r *= x;
  return r;
}

}  // namespace softtrace
