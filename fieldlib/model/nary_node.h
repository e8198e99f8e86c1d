// The base of the nodes that combine a list of children (soft_blend, the Perlin and Ricci set
// blends, min/max, the scale method, BT_k, the super-ellipsoidal combinations): it owns the
// children and answers the box question by asking each child's bounds() once, so each kind's
// combine() works on bounds already gathered and never walks its children again for the other
// half of the answer (a blend of blends would otherwise ask its grandchildren twice per level).
#pragma once

#include <vector>

#include "math/scratch.h"
#include "model/node.h"

namespace softtrace {

// Kind is the derived class (class Kind final : public NaryNode<Kind>), which writes
//   NodeBounds combine(const Box& b, const Interval* I, const double* L) const;
// its bounds over b from its children's there (I and L of c_.size() each; b for kinds that ask
// the children more than their bounds, BT_k's bulge elimination), and declares `friend NaryNode;`
// when combine is private. The gather calls it directly: an oracle blend answers this for every
// box, and a virtual combine plus heap-capable scratch arrays cost the conic BT scenes about 85
// instructions per call (docs/performance.md, issue 29).
template <class Kind>
class NaryNode : public FieldNode {
 protected:
  explicit NaryNode(std::vector<NodePtr> children) : c_(std::move(children)) {}

  // The children's bounds over b, child i's interval in I[i] and Lipschitz bound in L[i], handed
  // to Kind::combine() (Slots: on the stack up to 16 children, each slot written before combine
  // reads it). combine has this one call site, so the compiler inlines it here: the oracle's
  // box question on a BT blend is then one call, as it was before NaryNode (issue 29).
  NodeBounds box_bounds(const Box& b) const final {
    const size_t k = c_.size();
    Slots<Interval> I(k);
    Slots<double> L(k);
    for (size_t i = 0; i < k; ++i) {
      const NodeBounds child = c_[i]->bounds(b);
      I.set(i, child.value);
      L.set(i, child.lipschitz);
    }
    return static_cast<const Kind&>(*this).combine(b, I.data(), L.data());
  }

  std::vector<NodePtr> c_;  // the children, in the scene's order
};

}  // namespace softtrace
