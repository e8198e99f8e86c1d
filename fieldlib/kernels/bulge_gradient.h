// The spatial gradients of bulge elimination's position functions P_i and M_i (003 §5,
// docs/math.md §7.6), which the true gradient of a bulge-eliminated BT_2 adds to the partial one:
//   ∇BT = Σ_i ∂_iBT ∇g_i + Σ_i (∂_{r_i}BT ∇P_i + ∂_{m_i}BT ∇M_i).
// With a_i = |∇g_i|, n_i = ∇g_i/a_i and the operands' Hessians H_i:
//   ∇cosθ = H_1(n_2 - cosθ n_1)/a_1 + H_2(n_1 - cosθ n_2)/a_2   (∇n_i = (I - n_i n_i^T)H_i/a_i),
//   ∇G    = G (H_1 n_1/a_1 - H_2 n_2/a_2)                        (∇a_i = H_i n_i),
//   ∇P_i  = -r_i ∇cosθ,
// and M_i by the cases of §7.6, e.g. where m_1 <= m_2 G: ∇M_1 = (m_2 G - m_1)∇[cosθ]_+ +
// [cosθ]_+ m_2 ∇G, ∇M_2 = 0. One-sided choices at the kinks (measure zero, tested away from them):
// ∇[cosθ]_+ = 0 at cosθ = 0 (the side cosθ < 0, where M = m); at m_1 = m_2 G the "otherwise"
// case (m_1 <= m_2 G), as bulge_weights evaluates it; cosθ's clamp to [-1, 1] only absorbs
// rounding and is not differentiated. Where a gradient vanishes bulge_parameters fixes cosθ = 0
// and G = 1, so both gradients are 0.
#pragma once

#include "math/vec.h"

namespace softtrace {

struct BulgeGradients {
  Vec3 P[2], M[2];  // ∇P_i, ∇M_i
};

// From the union operands' gradients g[i] = ∇g_i and Hessians H[i] (symmetric, row-major), the
// ranges r and weights m of the operator.
BulgeGradients bulge_gradients(const Vec3 g[2], const Mat3 H[2], const double r[2],
                               const double m[2]);

}  // namespace softtrace
