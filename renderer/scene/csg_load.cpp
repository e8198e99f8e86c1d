#include "scene/csg_load.h"

#include <string>

#include "scene/mesh_closure.h"
#include "scene/placement.h"
#include "scene/ranges.h"

namespace softtrace {

const char* csg_name(Csg::Op op) {
  switch (op) {
    case Csg::Op::Union:
      return "union";
    case Csg::Op::Merge:
      return "merge";
    case Csg::Op::Intersection:
      return "intersection";
    case Csg::Op::Difference:
      return "difference";
  }
  return "?";
}

namespace {
// Operands per CSG object: each costs every ray through the object's box a search.
constexpr size_t kMaxOperands = 1000;

Csg::Op load_op(const Params& p) {
  const std::string name = p.string("csg");
  for (const Csg::Op op :
       {Csg::Op::Union, Csg::Op::Merge, Csg::Op::Intersection, Csg::Op::Difference})
    if (name == csg_name(op)) return op;
  p.fail("csg",
         "unknown operation '" + name + "' (expected union, merge, intersection or difference)");
}
}  // namespace

void load_csg(const Params& p, SceneObject& o, const Material* passed_on,
              const OperandLoader& load_operand) {
  auto csg = std::make_shared<Csg>();
  csg->op = load_op(p);
  const std::vector<Params> operands = p.objects("operands");
  if (operands.size() < 2) p.fail("operands", "expected at least two operands");
  if (operands.size() > kMaxOperands)
    p.fail("operands", "expected at most " + std::to_string(kMaxOperands) + " operands");
  for (size_t i = 0; i < operands.size(); ++i) {
    csg->operands.push_back(load_operand(operands[i], i, passed_on));
    const SceneObject& operand = csg->operands.back();
    if (operand.shape && operand.shape->shape == Primitive::Shape::Disc)
      operands[i].fail("shape", "a disc has no inside: it cannot be a CSG operand");
    if (operand.mesh) {
      const std::string problem = mesh_closure_problem(*operand.mesh);
      if (!problem.empty())
        operands[i].fail("mesh",
                         "a CSG operand must be a closed mesh (its inside is what the "
                         "CSG combines), but " +
                             problem);
    }
  }
  Box box = csg->operands[0].bounds;
  for (size_t i = 1; i < csg->operands.size(); ++i) {
    const Box& b = csg->operands[i].bounds;
    switch (csg->op) {
      case Csg::Op::Union:
      case Csg::Op::Merge:
        box = box.united(b);
        break;
      case Csg::Op::Intersection:
        box = box.intersected(b);
        break;
      case Csg::Op::Difference:
        break;  // what is taken away leaves the first operand's box
    }
  }
  if (box.empty())
    p.fail("operands", "the operands' boxes do not overlap: the intersection is empty");
  if (has_placement(p)) {
    csg->placed = true;
    csg->to_parent = load_placement(p);
    p.check(invert(csg->to_parent.linear, csg->to_local), "",
            "expected an invertible placement (scale and matrix)");
    // An infinite plane's box is the whole range (primitive.h): placed, it is that range still.
    const bool infinite = std::max(max_abs(box.lo), max_abs(box.hi)) >= kMaxPosition;
    Box placed;
    for (int c = 0; c < 8; ++c) placed.extend(csg->to_parent.apply(box.corner(c)));
    const Vec3 far{kMaxPosition, kMaxPosition, kMaxPosition};
    if (infinite) placed = placed.intersected(Box(far * -1.0, far));
    p.check(std::max(max_abs(placed.lo), max_abs(placed.hi)) <= kMaxPosition, "",
            std::string("expected a placed CSG ") + kPositionRule);
    box = placed;
  }
  o.bounds = box;
  o.csg = std::move(csg);
}

}  // namespace softtrace
