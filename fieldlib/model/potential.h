// The potential as a model object (docs/math.md §3): a kind of the scene format with its own
// program instruction. The maths are the kernels of kernels/potentials.h.
#pragma once

#include <memory>

#include "describe/params.h"
#include "kernels/potentials.h"
#include "program/program.h"

namespace softtrace {

class Potential {
 public:
  virtual ~Potential() = default;
  // P(max(d,0)) (docs/math.md §3.1 implementation rule), and P' into *dP when dP is non-null.
  virtual double eval(double d, double* dP) const = 0;
  virtual double lipschitz() const = 0;  // max over d of |P'(d)|
  // Which potential this is, and its constant (Blanc's s).
  virtual PotentialType type() const = 0;
  virtual double parameter() const { return 0; }
  // An equal potential, for a copied soft object (FieldNode::clone).
  virtual std::unique_ptr<Potential> clone() const = 0;

  // The program instruction that computes this potential.
  Op op() const;

  PotentialKind kind() const { return {type(), parameter()}; }

  Interval interval(Interval d) const { return kind().interval(d); }
  double lipschitz(Interval d) const { return kind().lipschitz(d); }
};

using PotentialPtr = std::unique_ptr<Potential>;

std::unique_ptr<Potential> create_blanc(const Params& p);  // 002 Eq. 2, §3.2
PotentialPtr make_blanc(double s);                         // the default potential is make_blanc(0)
std::unique_ptr<Potential> create_wyvill(const Params& p);    // Wyvill's sextic, §3.3
std::unique_ptr<Potential> create_murakami(const Params& p);  // quartic (1-d^2)^2, §3.3
std::unique_ptr<Potential> create_cubic(const Params& p);     // (1-d^2)^3, Galin et al., §3.4

// The potential named by p["type"] (registry.cpp holds the table).
PotentialPtr build_potential(const Params& p);

}  // namespace softtrace
