// Potential functions P: R+ -> [0,1] (docs/math.md §3): P(0)=1, P(0.5)=0.5 (Blanc, Wyvill), P=0 for
// d >= 1, non-increasing, P'(0)=P'(1)=0. Monotonicity makes the interval image exact:
// [P(hi), P(lo)]; the Lipschitz constant max|P'| is derived per potential below and is 0 on
// d >= 1.
#pragma once

#include <memory>

#include "interval.h"
#include "params.h"
#include "program.h"

namespace softtrace {

// The kernels, shared by the model classes below and the program evaluators (eval_*.cpp):
// P(max(d, 0)) with P' into *dP when dP is non-null.
double blanc(double d, double s, double* dP);  // 002 Eq. 2 (signs of R1), docs/math.md §3.2
double wyvill(double d, double* dP);           // Wyvill et al.'s sextic, docs/math.md §3.3
double murakami(double d, double* dP);         // (1 - d^2)^2, docs/math.md §3.3

class Potential {
 public:
  virtual ~Potential() = default;
  // P(max(d,0)) (docs/math.md §3.1 implementation rule), and P' into *dP when dP is non-null.
  virtual double eval(double d, double* dP) const = 0;
  virtual double lipschitz() const = 0;  // max over d of |P'(d)|
  // The program instruction that computes this potential, and its constant (Blanc's s).
  virtual Op op() const = 0;
  virtual double parameter() const { return 0; }

  Interval interval(Interval d) const;
  double lipschitz(Interval d) const { return d.lo >= 1 ? 0.0 : lipschitz(); }
};

using PotentialPtr = std::unique_ptr<Potential>;

std::unique_ptr<Potential> create_blanc(const Params& p);  // 002 Eq. 2, §3.2
PotentialPtr make_blanc(double s);                         // the default potential is make_blanc(0)
std::unique_ptr<Potential> create_wyvill(const Params& p);    // Wyvill's sextic, §3.3
std::unique_ptr<Potential> create_murakami(const Params& p);  // quartic (1-d^2)^2, §3.3

// The potential named by p["type"] (registry.cpp holds the table).
PotentialPtr build_potential(const Params& p);

}  // namespace softtrace
