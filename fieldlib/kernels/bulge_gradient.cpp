#include "kernels/bulge_gradient.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

BulgeGradients bulge_gradients(const Vec3 g[2], const Mat3 H[2], const double r[2],
                               const double m[2]) {
  BulgeGradients d;
  const double a1 = length(g[0]), a2 = length(g[1]);
  // The same test as bulge_parameters: otherwise cosθ = 0 and G = 1 are constants.
  if (!(a1 > 0 && a2 > 0 && std::isfinite(a1) && std::isfinite(a2) && a1 / a2 > 0 &&
        std::isfinite(a1 / a2)))
    return d;
  const Vec3 n1 = g[0] / a1, n2 = g[1] / a2;
  const double c = std::min(1.0, std::max(-1.0, dot(g[0], g[1]) / (a1 * a2)));
  const double G = a1 / a2;
  const Vec3 dcos = H[0] * (n2 - n1 * c) / a1 + H[1] * (n1 - n2 * c) / a2;
  const Vec3 dG = (H[0] * n1 / a1 - H[1] * n2 / a2) * G;
  for (int i = 0; i < 2; ++i) d.P[i] = dcos * -r[i];
  const double cp = std::max(c, 0.0);
  const Vec3 dcp = c > 0 ? dcos : Vec3{};
  if (m[0] > m[1] * G)  // M_1 = m_1, M_2 = m_2 + (m_1/G - m_2)[cosθ]_+
    d.M[1] = dcp * (m[0] / G - m[1]) - dG * (cp * m[0] / (G * G));
  else  // M_1 = m_1 + (m_2 G - m_1)[cosθ]_+, M_2 = m_2
    d.M[0] = dcp * (m[1] * G - m[0]) + dG * (cp * m[1]);
  return d;
}

}  // namespace softtrace
