#include "potentials.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

double PotentialKind::lipschitz() const {
  switch (op) {
    case Op::Wyvill:
      return wyvill_lipschitz();
    case Op::Murakami:
      return murakami_lipschitz();
    default:
      return blanc_lipschitz(s);
  }
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

// |P'| = 4d(1-d^2) peaks at d = 1/sqrt(3) with 8/(3 sqrt 3).
namespace {

// Blanc's potential with softness s >= 0   — 002 Eq. 2 (signs of R1), docs/math.md §3.2
class Blanc final : public Potential {
 public:
  explicit Blanc(double s) : s_(s) {}
  double eval(double d, double* dP) const override { return blanc(d, s_, dP); }
  double lipschitz() const override { return blanc_lipschitz(s_); }
  Op op() const override { return Op::Blanc; }
  double parameter() const override { return s_; }

 private:
  double s_;
};

// 1 - 4/9 d^6 + 17/9 d^4 - 22/9 d^2   — Wyvill et al., docs/math.md §3.3
class Wyvill final : public Potential {
 public:
  double eval(double d, double* dP) const override { return wyvill(d, dP); }
  double lipschitz() const override { return wyvill_lipschitz(); }
  Op op() const override { return Op::Wyvill; }
};

// (1 - d^2)^2, POV-Ray's blob density   — docs/math.md §3.3; its 0.5 level is d = 0.5412
class Murakami final : public Potential {
 public:
  double eval(double d, double* dP) const override { return murakami(d, dP); }
  double lipschitz() const override { return murakami_lipschitz(); }
  Op op() const override { return Op::Murakami; }
};

}  // namespace

std::unique_ptr<Potential> create_blanc(const Params& p) {
  const double s = p.number("s", 0.0);  // >= 0 (the table; docs/math.md §3.2)
  return make_blanc(s);
}
PotentialPtr make_blanc(double s) {
  return std::make_unique<Blanc>(s);
}
std::unique_ptr<Potential> create_wyvill(const Params&) {
  return std::make_unique<Wyvill>();
}
std::unique_ptr<Potential> create_murakami(const Params&) {
  return std::make_unique<Murakami>();
}

}  // namespace softtrace
