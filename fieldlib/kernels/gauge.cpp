#include "kernels/gauge.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/int_power.h"
#include "math/scratch.h"

namespace softtrace {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// The papers' exponents are mostly small integers (n = 20 for cubes and bars) or halves of them
// (the bevelled contours' n1 = 1.5): squaring, times a correctly rounded square root for a half,
// is several times faster than std::pow there and within a few ulps of it.
bool by_squaring(double n) {
  return n >= 0.5 && n <= 64 && 2 * n == static_cast<int>(2 * n);
}

// x^n for x >= 0.
double pow_fast(double x, double n) {
  if (by_squaring(n)) {
    const int k = static_cast<int>(n);
    return k == n ? pow_by_squaring(x, k) : pow_by_squaring(x, k) * std::sqrt(x);
  }
  return std::pow(x, n);
}

// m s^(1/n), s a power sum relative to its largest term m (power_root: n = 2, ellipsoids and
// most blobs, the correctly rounded square root; n = 1, a superquadric's inner sum, none).
double scale_root(double m, double s, double n) {
  return m * power_root(s, n);
}

// power_sum with the powers x^n and x^(n-1) and the root s^(1/n) as given: pow_fast's and
// power_root, or the same operations with the exponent known at compile time (no test of n per
// term, nor in the root).
template <class PowN, class PowN1, class Root>
double power_sum_with(const double* u, int k, double* dfdu, const PowN& pow_n, const PowN1& pow_n1,
                      const Root& root_n) {
  double m = 0;
  for (int i = 0; i < k; ++i) m = std::max(m, u[i]);
  if (m == 0) {
    if (dfdu) std::fill(dfdu, dfdu + k, 0.0);
    return 0;
  }
  double s = 0;
  for (int i = 0; i < k; ++i) s += pow_n(u[i] / m);
  const double f = m * root_n(s);
  if (dfdu)
    for (int i = 0; i < k; ++i) dfdu[i] = u[i] > 0 ? pow_n1(u[i] / f) : 0.0;
  return f;
}
}  // namespace

double power_sum(const double* u, int k, double n, double* dfdu) {
  // The papers' cubes and bars (n = 20) by pow_fast's multiplications unrolled and power_root's
  // n = 20 branch inline (its call was 62 instructions a point); a superquadric's inner L^1 sum
  // (n = 1) with its partials u^0 = 1, which pow_fast takes from std::pow, and no root.
  if (n == 1)
    return power_sum_with(
        u, k, dfdu, [](double x) { return x; }, [](double) { return 1.0; },
        [](double s) { return s; });
  if (n == 20)
    return power_sum_with(
        u, k, dfdu, [](double x) { return pow_by_squaring<20>(x); },
        [](double x) { return pow_by_squaring<19>(x); }, [](double s) { return root_20(s); });
  return power_sum_with(
      u, k, dfdu, [n](double x) { return pow_fast(x, n); },
      [n](double x) { return pow_fast(x, n - 1); }, [n](double s) { return power_root(s, n); });
}

void power_sum_lanes(const double* const* u, int k, double n, int lanes, double* f) {
  // power_sum's operations in its order, one loop over the lanes at a time.
  double m[16], s[16], b[16], r[16], h[16];
  for (int l = 0; l < lanes; ++l) m[l] = 0;
  for (int i = 0; i < k; ++i)
    for (int l = 0; l < lanes; ++l) m[l] = std::max(m[l], u[i][l]);
  for (int l = 0; l < lanes; ++l) s[l] = 0;
  const bool squaring = by_squaring(n);  // as pow_fast
  for (int i = 0; i < k; ++i) {
    for (int l = 0; l < lanes; ++l) b[l] = u[i][l] / m[l];
    if (!squaring) {
      for (int l = 0; l < lanes; ++l) s[l] += std::pow(b[l], n);
      continue;
    }
    const int whole = static_cast<int>(n);
    const bool half = whole != n;
    if (half)
      for (int l = 0; l < lanes; ++l) h[l] = std::sqrt(b[l]);
    for (int l = 0; l < lanes; ++l) r[l] = 1;
    for (int e = whole; e; e >>= 1) {
      if (e & 1)
        for (int l = 0; l < lanes; ++l) r[l] *= b[l];
      if (e == 1) break;
      for (int l = 0; l < lanes; ++l) b[l] *= b[l];
    }
    if (half)  // pow_by_squaring's product times the root, as pow_fast
      for (int l = 0; l < lanes; ++l) r[l] *= h[l];
    for (int l = 0; l < lanes; ++l) s[l] += r[l];
  }
  for (int l = 0; l < lanes; ++l) f[l] = m[l] == 0 ? 0 : scale_root(m[l], s[l], n);
}

Interval power_sum(const Interval* u, int k, double n) {
  Slots<double> lo(k), hi(k);  // written below before read
  for (int i = 0; i < k; ++i) {
    lo.set(i, std::max(0.0, u[i].lo));
    hi.set(i, std::max(0.0, u[i].hi));
  }
  // pow is faithfully but not correctly rounded: widen by a relative margin well above its error.
  const double l = power_sum(lo.data(), k, n, nullptr), h = power_sum(hi.data(), k, n, nullptr);
  // An infinite term (a box without bounds) makes the scaled sum inf/inf: the sum is infinite.
  const bool unbounded = std::find(hi.data(), hi.data() + k, kInf) != hi.data() + k;
  return {std::max(0.0, l * (1 - 1e-13)), unbounded ? kInf : h * (1 + 1e-13)};
}

double power_sum_partial_bound(Interval ui, Interval f_range, double n) {
  if (n >= 1) {
    // (u/f)^(n-1) <= min(1, (u_hi/f_lo)^(n-1)).
    if (f_range.lo <= 0) return 1;
    if (n == 2) return std::min(1.0, std::max(0.0, ui.hi) / f_range.lo * (1 + 1e-13));
    // pow_fast errs by a few ulps where it squares (n - 1 <= 63 integer): far inside the margin.
    return std::min(1.0, pow_fast(std::max(0.0, ui.hi) / f_range.lo, n - 1) * (1 + 1e-13));
  }
  if (ui.lo <= 0) return std::numeric_limits<double>::infinity();
  return std::pow(std::max(f_range.hi, ui.lo) / ui.lo, 1 - n) * (1 + 1e-13);
}

namespace {

// The lower end of ∂f/∂u_i = (u_i/f)^(n-1) over ui and f_range, n > 1: (u_lo/f_hi)^(n-1), as it
// rises with u/f; pow_fast errs by a few ulps, far inside the margin.
double power_sum_partial_lower(Interval ui, Interval f_range, double n) {
  const double q = std::max(0.0, ui.lo) / f_range.hi;
  const double lo = q > 0 ? pow_fast(std::min(1.0, q), n - 1) * (1 - 1e-13) : 0.0;
  return std::max(0.0, lo);
}

// Σ w_i du_i over w_i in [w_lo(i), w_hi(i)] (>= 0) and du_i in du[i]: each end of du takes the w
// that moves it outward, and each end of w is computed only where one of du's ends takes it (a
// rate of either sign takes only w_hi). Widened for the k products and sums, each within a few
// ulps of at most mag.
template <class Lo, class Hi>
Interval weighted_rate_sum(const Interval* du, int k, const Lo& w_lo, const Hi& w_hi) {
  double lo = 0, hi = 0, mag = 0;
  for (int i = 0; i < k; ++i) {
    if (du[i].lo == 0 && du[i].hi == 0) continue;  // a constant term (whatever its partial)
    const bool lo_takes_hi = du[i].lo<0, hi_takes_hi = du[i].hi> 0;
    const double wh = lo_takes_hi || hi_takes_hi ? w_hi(i) : 0.0;
    const double wl = !lo_takes_hi || !hi_takes_hi ? w_lo(i) : 0.0;
    const double l = du[i].lo * (lo_takes_hi ? wh : wl);
    const double h = du[i].hi * (hi_takes_hi ? wh : wl);
    lo += l;
    hi += h;
    mag += std::abs(l) + std::abs(h);
  }
  const double grow = 1e-12 * mag + 1e-300;
  if (!(std::isfinite(lo) && std::isfinite(hi))) return Interval::entire();
  return {lo - grow, hi + grow};
}

}  // namespace

Interval power_sum_partial(Interval ui, Interval f_range, double n) {
  if (n < 1) return {0, kInf};
  if (n == 1) return {1, 1};
  return {power_sum_partial_lower(ui, f_range, n), power_sum_partial_bound(ui, f_range, n)};
}

Interval power_sum_slope(const Interval* u, const Interval* du, int k, Interval f_range, double n) {
  if (n < 1) return Interval::entire();
  if (n == 1) {
    const auto one = [](int) { return 1.0; };
    return weighted_rate_sum(du, k, one, one);
  }
  return weighted_rate_sum(
      du, k, [&](int i) { return power_sum_partial_lower(u[i], f_range, n); },
      [&](int i) { return power_sum_partial_bound(u[i], f_range, n); });
}

Interval power_sum_slope(const Interval* u, const Interval* du, int k, Interval f_range, double n,
                         const double* partial_hi) {
  if (!(n > 1)) return power_sum_slope(u, du, k, f_range, n);
  return weighted_rate_sum(
      du, k, [&](int i) { return power_sum_partial_lower(u[i], f_range, n); },
      [&](int i) { return partial_hi[i]; });
}

double gauge_lipschitz(const double* w, int k, double n) {
  if (n < 1) return std::numeric_limits<double>::infinity();
  if (n >= 2) {
    double m = 0;
    for (int i = 0; i < k; ++i) m = std::max(m, std::abs(w[i]));
    return m;
  }
  const double r = 2 * n / (2 - n);
  double s = 0;
  for (int i = 0; i < k; ++i) s += std::pow(std::abs(w[i]), r);
  return std::pow(s, 1 / r) * (1 + 1e-13);
}

}  // namespace softtrace
