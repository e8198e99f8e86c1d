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

// Whether two materials are the same in every key (the cut objects must show one material).
bool same(const Material& a, const Material& b) {
  const auto eq = [](const Vec3& u, const Vec3& v) {
    return u.x == v.x && u.y == v.y && u.z == v.z;
  };
  return eq(a.color, b.color) && eq(a.ambient, b.ambient) && a.diffuse == b.diffuse &&
         a.brilliance == b.brilliance && a.phong == b.phong && a.phong_size == b.phong_size &&
         a.specular == b.specular && a.roughness == b.roughness && a.metallic == b.metallic &&
         eq(a.reflection, b.reflection) && a.fresnel == b.fresnel &&
         eq(a.reflection_min, b.reflection_min) && a.conserve_energy == b.conserve_energy &&
         a.filter == b.filter && a.transmit == b.transmit && a.ior == b.ior;
}

bool cuts(Csg::Op op) {
  return op == Csg::Op::Intersection || op == Csg::Op::Difference;
}

// The materials POV-Ray's cutaway_textures may show on an untextured part's face: the textures
// of the objects the face lies in, found as its CSG::Determine_Textures finds them (a
// difference's first operand only, every operand of the other operations). `bare`: the operands
// are the untextured parts of a cutting CSG, which have none of their own (POV-Ray gives them no
// default); a union's parts have the default or their union's.
void cut_materials(const Params& p, const Csg& csg, bool bare, std::vector<Material>& out) {
  const std::vector<Params> operands = p.objects("operands");
  const size_t n = csg.op == Csg::Op::Difference ? 1 : operands.size();
  for (size_t i = 0; i < n; ++i) {
    const SceneObject& operand = csg.operands[i];
    const bool own = operands[i].has("material");
    if (!operand.csg) {
      if (own || !bare) out.push_back(operand.material);
      continue;
    }
    cut_materials(operands[i], *operand.csg, bare && !own && cuts(operand.csg->op), out);
  }
}

// Gives `cut` to the untextured parts of a cutting CSG without a material, down through the
// intersections and differences among them (POV-Ray passes the flag down).
void cut_away(const Params& p, Csg& csg, const Material& cut) {
  const std::vector<Params> operands = p.objects("operands");
  for (size_t i = 0; i < operands.size(); ++i) {
    SceneObject& operand = csg.operands[i];
    if (operands[i].has("material")) continue;
    if (!operand.csg) {
      operand.material = cut;
    } else if (cuts(operand.csg->op)) {
      // load_csg made it and nothing shares it yet: it may still be changed.
      cut_away(operands[i], *std::const_pointer_cast<Csg>(operand.csg), cut);
    }
  }
}

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
  // POV-Ray's cutaway_textures: an untextured part's face shows the texture of what it cuts.
  // Where nothing above passes a material on, the untextured parts take the one material the
  // cut objects show; objects showing several (mixed point by point in POV-Ray) are refused.
  if (p.has("cutaway_textures") && !cuts(csg->op))
    p.fail("cutaway_textures", "cutaway_textures belongs to an intersection or a difference");
  if (p.boolean("cutaway_textures", false) && !passed_on) {
    std::vector<Material> shown;
    cut_materials(p, *csg, true, shown);
    for (const Material& m : shown)
      if (!same(m, shown.front()))
        p.fail("cutaway_textures",
               "the cut objects show more than one material here (POV-Ray mixes them point by "
               "point): not supported, give the cutting parts materials instead");
    if (!shown.empty()) cut_away(p, *csg, shown.front());
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
