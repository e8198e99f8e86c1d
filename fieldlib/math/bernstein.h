// The first rise of a polynomial through 0 on [0, 1], certified by its Bernstein form: over any
// piece of [0, 1] the polynomial lies in the hull of its Bernstein coefficients there (de
// Casteljau's halving gives the coefficients of each half), so a piece whose coefficients are all
// below -err, err bounding the rounding of the coefficients, holds no root. A piece whose
// derivative's coefficients are all positive rises through 0 at most once. This is how the tracer
// decides a stretch of ray over which a sum of polynomial blobs is one polynomial (blob_ray.h).
#pragma once

#include <algorithm>
#include <type_traits>

#include "math/illinois.h"

namespace softtrace {

constexpr int kMaxDegree = 6;

struct Rise {
  enum Kind {
    Clear,    // h < 0 on [0, 1]
    AtStart,  // h(0) >= 0 as computed
    Bracket,  // h(lo) < 0 <= h(hi) as computed, and no root before lo
  } kind;
  double lo = 0, hi = 0;
  // Pieces passed undecided: their hull straddles 0 (within err) down to `finest`, a tangency
  // within rounding, and no value >= 0 shows h reaching 0 there. They are passed, not reported.
  int undecided = 0;
};

// h(x) = Σ a[j] x^j by Horner's rule.
inline double power_value(const double* a, int degree, double x) {
  double v = a[degree];
  for (int j = degree - 1; j >= 0; --j) v = v * x + a[j];
  return v;
}

namespace bernstein_detail {
inline constexpr double kBinom[kMaxDegree + 1][kMaxDegree + 1] = {{1},
                                                                  {1, 1},
                                                                  {1, 2, 1},
                                                                  {1, 3, 3, 1},
                                                                  {1, 4, 6, 4, 1},
                                                                  {1, 5, 10, 10, 5, 1},
                                                                  {1, 6, 15, 20, 15, 6, 1}};
// C(i,j)/C(m,j) for degree m, row i, column j <= i: the power basis's coefficients' weights in
// the Bernstein coefficients, b_i = Σ_{j<=i} C(i,j)/C(m,j) a_j. Divided once here, as the
// compiler rounds a division (to nearest), so each weight is the one a division per use gave.
struct Weights {
  double w[kMaxDegree + 1][kMaxDegree + 1][kMaxDegree + 1] = {};
  constexpr Weights() {
    for (int m = 0; m <= kMaxDegree; ++m)
      for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= i; ++j) w[m][i][j] = kBinom[i][j] / kBinom[m][j];
  }
};
inline constexpr Weights kWeights{};
}  // namespace bernstein_detail

// The first x in [0, 1] where h = Σ a[j] x^j (degree D <= kMaxDegree) reaches 0, to within `tol`
// (a bracket no wider than tol, or one of any width over which h rises), halving down to
// `finest`; a piece still undecided there is passed and counted (Rise::undecided), and the
// search goes on past it. `err` bounds |computed - exact| of the coefficients' hulls on every
// piece. One function per degree, the loops over the coefficients unrolled and a piece's
// coefficients halved in place of copies (blob1a at 320x240: the generic loops, the pieces'
// copies and a memcpy per halving were most of a runtime degree's 680 instructions a call). The
// tracer calls the two degrees a blob sum's pieces have (tracer_blobs.cpp); first_rise, below,
// takes a degree known only at run time.
template <int D>
Rise first_rise_of(const double* a, double err, double tol, double finest) {
  const auto& weight = bernstein_detail::kWeights.w[D];
  // The piece searched now stays in registers: a halving goes on with its left half (searched
  // first) and stacks only the right one, read back once the left's are done. The same pieces in
  // the same order as stacking both halves and popping the left at once, and `top` counts what
  // that stack held below the popped piece, so the depth's limit passes the same pieces
  // undecided. Every loop over the coefficients is unrolled by pragma, so that each is a
  // constant index before GCC decides which arrays stay in memory: left to its late unrolling,
  // `row` and the pieces stayed on the stack, written and read in pairs that straddled each
  // other's stores, and a halving waited on failed store forwardings (perf, meets10 at 640x480:
  // most of this function's time on the loads after those stores).
  struct Piece {
    double lo, hi, b[D + 1];
  };
  constexpr int kDepth = 64;
  Piece stack[kDepth];
  int top = 0, undecided = 0;
  double lo = 0, hi = 1, row[D + 1];
#pragma GCC unroll 8
  for (int i = 0; i <= D; ++i) {
    double s = 0;
#pragma GCC unroll 8
    for (int j = 0; j <= i; ++j) s += weight[i][j] * a[j];
    row[i] = s;
  }
  if (row[0] >= 0) return {Rise::AtStart, 0, 0};
  while (true) {
    // max_element's value: the first of the largest, as its `<` keeps it.
    double most = row[0];
#pragma GCC unroll 8
    for (int i = 1; i <= D; ++i) most = std::max(most, row[i]);
    // Whether the piece goes on: halved into the left half, or none (the next is popped).
    bool halve = false;
    if (!(most + err < 0)) {
      // Every difference taken (no exit at the first that fails): the same answer, without a
      // branch per coefficient.
      bool rising = true;
#pragma GCC unroll 8
      for (int i = 0; i < D; ++i) rising &= row[i + 1] - row[i] > 2 * err;
      if (row[D] >= 0 && (rising || hi - lo <= tol)) return {Rise::Bracket, lo, hi, undecided};
      // Not rising to a negative end (which the hull allowed): halved, unless too fine or deep.
      if (!(rising && row[D] < 0)) {
        halve = !(hi - lo <= finest || top + 2 > kDepth);
        undecided += !halve;
      }
    }
    if (halve) {
      // de Casteljau at the middle: the left half's coefficients are the first of each row, the
      // right half's the last.
      Piece& right = stack[top++];
      const double mid = 0.5 * (lo + hi);
      right.lo = mid;
      right.hi = hi;
      double left[D + 1];
#pragma GCC unroll 8
      for (int k = 0; k <= D; ++k) {
        left[k] = row[0];
        right.b[D - k] = row[D - k];
#pragma GCC unroll 8
        for (int i = 0; i < D - k; ++i) row[i] = 0.5 * (row[i] + row[i + 1]);
      }
#pragma GCC unroll 8
      for (int i = 0; i <= D; ++i) row[i] = left[i];
      hi = mid;
      continue;
    }
    if (top == 0) break;
    const Piece& next = stack[--top];
    lo = next.lo;
    hi = next.hi;
#pragma GCC unroll 8
    for (int i = 0; i <= D; ++i) row[i] = next.b[i];
  }
  return {Rise::Clear, 1, 1, undecided};
}

// h(x) for degree D: power_value with the degree known, so its loop unrolled.
template <int D>
double power_value_of(const double* a, double x) {
  return power_value(a, D, x);
}

// Narrows a Bracket of first_rise_of<D> to at most `tol`: the Anderson-Bjorck variant of regula
// falsi on h's values, each point kept half a tolerance inside the bracket, so that once one end
// sits at the root (as false position leaves it on convex stretches) the next point lands past it
// and closes the bracket from the other side. Adds its steps to *steps. Per degree, as
// first_rise_of (pov:blob1a: Horner's loop was 2.6 % of the process's instructions).
template <int D>
Rise refine_rise_of(const double* a, Rise r, double tol, int* steps) {
  IllinoisBracket br{r.lo, power_value_of<D>(a, r.lo), r.hi, power_value_of<D>(a, r.hi)};
  br.anderson_bjorck = true;
  for (int i = 0; i < 100 && br.hi - br.lo > tol; ++i) {
    double m = std::clamp(br.false_position(), br.lo + 0.5 * tol, br.hi - 0.5 * tol);
    if (!(m > br.lo && m < br.hi)) m = 0.5 * (br.lo + br.hi);  // 0/0 after the values vanished
    ++*steps;
    const double hm = power_value_of<D>(a, m);
    br.update(m, hm, hm >= 0);
  }
  return {Rise::Bracket, br.lo, br.hi};
}

// f(std::integral_constant<int, D>{}) for D = degree, 0 to kMaxDegree (any other as kMaxDegree,
// a larger degree being no polynomial of this header's): the per-degree functions above for a
// degree known only at run time.
template <class F>
auto by_degree(int degree, F&& f) {
  static_assert(kMaxDegree == 6, "a case per degree below");
  switch (degree) {
    case 0:
      return f(std::integral_constant<int, 0>{});
    case 1:
      return f(std::integral_constant<int, 1>{});
    case 2:
      return f(std::integral_constant<int, 2>{});
    case 3:
      return f(std::integral_constant<int, 3>{});
    case 4:
      return f(std::integral_constant<int, 4>{});
    case 5:
      return f(std::integral_constant<int, 5>{});
    default:
      return f(std::integral_constant<int, kMaxDegree>{});
  }
}

// first_rise_of and refine_rise_of for a degree known at run time.
inline Rise first_rise(const double* a, int degree, double err, double tol, double finest) {
  return by_degree(degree,
                   [&](auto d) { return first_rise_of<decltype(d)::value>(a, err, tol, finest); });
}
inline Rise refine_rise(const double* a, int degree, Rise r, double tol, int* steps) {
  return by_degree(degree,
                   [&](auto d) { return refine_rise_of<decltype(d)::value>(a, r, tol, steps); });
}

}  // namespace softtrace
