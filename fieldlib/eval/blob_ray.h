// A sum of polynomial blobs along a ray, as POV-Ray's blob solves it. Murakami's, Wyvill's and the
// cubic potentials are polynomials in r = 1 - d^2 (r^2, (5 r^2 + 4 r^3)/9 and r^3, docs/math.md
// §3.3-§3.4), and
// an ellipsoidal distance's d^2 is quadratic along a line. So between the points where a ray
// enters and leaves the blobs' supports, a soft_blend of such soft objects is one polynomial of
// degree at most 6 in t, which bernstein.h decides exactly, with no Lipschitz bound and no step.
//
// Along the ray x = o + u d, a blob whose support is |L x + k| <= 1 has d^2 = q(u) = 1 - h2 +
// alpha (u - mid)^2 (mid the point nearest its centre, h2 = 1 - q(mid)), hence r = h2 - alpha
// (u - mid)^2: three numbers per blob and ray, well conditioned however far the ray starts.
#pragma once

#include <optional>
#include <vector>

#include "math/bernstein.h"
#include "program/program.h"

namespace softtrace {

class BlobSum {
 public:
  // The blobs of `p` if its field is exactly a sum of soft objects, each Murakami's, Wyvill's or
  // the cubic potential of an lp_metric with n = 2 under translations and rotations, of any
  // strength; nullopt otherwise.
  static std::optional<BlobSum> of(const Program& p);

  // One blob's part of a stretch of ray: its potential is P(r(u)) over [enter, exit] (the
  // support clipped to the stretch), r(u) = h2 - alpha (u - mid)^2, P(r) = c2 r^2 + c3 r^3.
  struct Term {
    double enter, exit;
    double mid, alpha, h2;
    double c2, c3;
    double peak;  // an upper bound of P's values over [enter, exit] (0 for a negative strength)
  };
  // The terms of the blobs whose supports the stretch o + u d, u in [0, len], passes through (d a
  // unit vector; `pad` the rounding of the points the caller will take along it), in out[];
  // returns their number. `ids` and `out` need room for size() entries.
  int terms(const Program& p, const Vec3& o, const Vec3& d, double len, double pad, Term* out,
            int32_t* ids) const;
  // f(x) and ∇f(x) from the blobs whose supports hold x (∇ of c2 r^2 + c3 r^3 with r = 1 - |Lx +
  // k|^2): the compiled gradient's value without pruning the program first. `ids` as for terms.
  double gradient(const Program& p, const Vec3& x, Vec3* grad, int32_t* ids) const;
  int size() const { return static_cast<int>(blobs_.size()); }
  // The median of the blobs' mean support radii: how long a stretch meets a few of them.
  double typical_radius() const { return typical_radius_; }

  // Where a blob's support is |L x + k| <= 1.
  struct Frame {
    Mat3 L;
    Vec3 k;
  };
  // What terms() reads first, in half a Frame's memory: the potential, and for a ball
  // (translations only, equal radii) its centre and 1 / radius^2, with which a ray's nearest
  // point to it costs a third of what L's does.
  struct Blob {
    Vec3 centre;
    double inv_r2;  // 0 where the blob is no ball
    double c2, c3;
  };

 private:
  std::vector<Frame> frames_;  // by child of the sum
  std::vector<Blob> blobs_;    // the same
  int group_ = 0;
  double typical_radius_ = 0;
};

// The sum of the potentials of terms[active[i]], i < n, minus iso over [s0, s0 + S], as a
// polynomial in x = (u - s0) / S on [0, 1], with a bound on the rounding of its coefficients, of
// their Bernstein form and of its halvings (first_rise's err).
struct StretchPolynomial {
  double a[kMaxDegree + 1];
  int degree;
  double err;
};
StretchPolynomial stretch_polynomial(const BlobSum::Term* terms, const int* active, int n,
                                     double s0, double S, double iso);

}  // namespace softtrace
