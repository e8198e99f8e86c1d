#include "model/potential.h"

#include <cstdlib>

namespace softtrace {

Op Potential::op() const {
  switch (type()) {
    case PotentialType::Blanc:
      return Op::Blanc;
    case PotentialType::Wyvill:
      return Op::Wyvill;
    case PotentialType::Murakami:
      return Op::Murakami;
    case PotentialType::Cubic:
      return Op::Cubic;
  }
  std::abort();  // not reached: the switch names every type, and -Werror=switch keeps it so
}

namespace {

// Blanc's potential with softness s >= 0   — 002 Eq. 2 (signs of R1), docs/math.md §3.2
class Blanc final : public Potential {
 public:
  explicit Blanc(double s) : s_(s) {}
  double eval(double d, double* dP) const override { return blanc(d, s_, dP); }
  double lipschitz() const override { return blanc_lipschitz(s_); }
  PotentialType type() const override { return PotentialType::Blanc; }
  double parameter() const override { return s_; }
  std::unique_ptr<Potential> clone() const override { return std::make_unique<Blanc>(*this); }

 private:
  double s_;
};

// A potential without a parameter: its kernel P(d) (kernels/potentials.h) and its bound, as
// template arguments. Blanc, whose softness is a parameter, is the class above.
template <PotentialType T, double (&P)(double, double*), double (&Lipschitz)()>
class FixedPotential final : public Potential {
 public:
  double eval(double d, double* dP) const override { return P(d, dP); }
  double lipschitz() const override { return Lipschitz(); }
  PotentialType type() const override { return T; }
  std::unique_ptr<Potential> clone() const override {
    return std::make_unique<FixedPotential>(*this);
  }
};

// 1 - 4/9 d^6 + 17/9 d^4 - 22/9 d^2   — Wyvill et al., docs/math.md §3.3
using Wyvill = FixedPotential<PotentialType::Wyvill, wyvill, wyvill_lipschitz>;
// (1 - d^2)^2, POV-Ray's blob density   — docs/math.md §3.3; its 0.5 level is d = 0.5412
using Murakami = FixedPotential<PotentialType::Murakami, murakami, murakami_lipschitz>;
// (1 - d^2)^3   — Galin et al. 2020 (Segment Tracing), docs/math.md §3.4
using Cubic = FixedPotential<PotentialType::Cubic, cubic, cubic_lipschitz>;

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
std::unique_ptr<Potential> create_cubic(const Params&) {
  return std::make_unique<Cubic>();
}

}  // namespace softtrace
