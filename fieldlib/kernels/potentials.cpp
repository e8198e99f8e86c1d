#include "kernels/potentials.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace softtrace {

double PotentialKind::lipschitz() const {
  switch (type) {
    case PotentialType::Blanc:
      return blanc_lipschitz(s);
    case PotentialType::Wyvill:
      return wyvill_lipschitz();
    case PotentialType::Murakami:
      return murakami_lipschitz();
    case PotentialType::Cubic:
      return cubic_lipschitz();
  }
  std::abort();  // not reached: the switch names every type, and -Werror=switch keeps it so
}

double blanc_lipschitz(double s) {
  return (2 + 16.0 / 9.0 * s) * (1 + 1e-12);  // [PB-5]
}

// |P'| peaks where P'' = -(120u^2 - 204u + 44)/9 = 0, u = d^2 in [0,1].
double wyvill_peak() {
  static const double d = std::sqrt((204 - std::sqrt(204.0 * 204 - 4 * 120 * 44)) / 240);
  return d;
}

double wyvill_lipschitz() {
  static const double L = [] {
    double dP;
    wyvill(wyvill_peak(), &dP);
    return std::abs(dP) * (1 + 1e-12);
  }();
  return L;
}

}  // namespace softtrace
