#include "registry.h"

#include <cmath>

#include "blends.h"
#include "blends_bt.h"
#include "distances.h"
#include "offset.h"
#include "placement.h"
#include "potentials.h"
#include "soft_object.h"

namespace softtrace {

const std::vector<NodeKind>& node_kinds() {
  static const std::vector<NodeKind> kinds = {
      // Distance functions, MATH.md §2.
      {"parallel_planes", "distance", "|p.n|/a; normal, a (000 Eq.2)", create_parallel_planes},
      {"one_branch_plane", "distance", "max(p.n,0)/a; normal, a (002 s4.5)",
       create_one_branch_plane},
      {"lp_metric", "distance", "(|x/a|^n+|y/b|^n+|z/c|^n)^(1/n); radii [a,b,c], n",
       create_lp_metric},
      {"superquadric", "distance",
       "000 Eq.3; radii [a1,a2,a3], n1, n2, optional t [t1..t6] (002 Eq.15)", create_superquadric},
      {"generalized_distance", "distance",
       "000 Eq.4 / 002 Eq.16; normals, a, n, optional t_pos, t_neg", create_generalized_distance},
      {"segment", "distance", "distance to the segment p0-p1 / radius (000 Eq.5)", create_segment},
      {"superelliptic_cylinder", "distance",
       "002 Eq.17/18; radii [a1,a2,a3], n, half_length, optional t [t1..t6]",
       create_superelliptic_cylinder},
      {"torus", "distance", "((|rho-R|/a)^n+(|z|/b)^n)^(1/n); major_radius, radii [a,b], n",
       create_torus},
      {"polar_prism", "distance",
       "(h^n+|z/c|^n)^(1/n), h = rho/R(phi); radius, lobes, amplitude, profile, half_height, n",
       create_polar_prism},
      {"super_ellipsoidal_union", "distance", "(sum x_i^-n)^(-1/n) of distances (000 Eq.6)",
       create_super_ellipsoidal_union},
      {"super_ellipsoidal_intersection", "distance", "(sum x_i^n)^(1/n) of distances (000 Eq.6)",
       create_super_ellipsoidal_intersection},
      // Soft objects, MATH.md §4.
      {"soft_object", "object", "P(T(d)): distance, potential (default blanc s=0), radii",
       create_soft_object},
      // Blends, MATH.md §5-§7.
      {"soft_blend", "blend", "sum of the children (000 Eq.12)", create_soft_blend},
      {"offset", "blend", "s*(child - c): a distance function as a zero-surface function (003)",
       create_offset},
      {"bt_union", "blend", "BT_k union, zero convention (003 Eqs.2-5)", create_bt_union},
      {"bt_intersection", "blend", "-BT_k(-f_1..-f_k), zero convention (003 3.3)",
       create_bt_intersection},
      {"bt_difference", "blend", "-BT_k(-f_1,f_2..f_k), zero convention (003 3.3)",
       create_bt_difference},
      {"displacement_union", "blend", "BD_k = BT_k with all m = 1 (003 2.2)",
       create_displacement_union},
      {"perlin_union", "blend", "1 - prod(1 - f_i) (002 Eq.4)", create_perlin_union},
      {"perlin_intersection", "blend", "prod f_i (002 Eq.5)", create_perlin_intersection},
      {"perlin_difference", "blend", "f_1 prod_{i>=2}(1 - f_i) (002 Eq.6)",
       create_perlin_difference},
      {"ricci_union", "blend", "Ricci union in the object's convention; n", create_ricci_union},
      {"ricci_intersection", "blend", "Ricci intersection in the object's convention; n",
       create_ricci_intersection},
      {"ricci_difference", "blend", "Ricci difference (first child minus the others); n",
       create_ricci_difference},
      {"min", "blend", "sharp minimum of the children", create_min},
      {"max", "blend", "sharp maximum of the children", create_max},
      {"scale_union", "blend", "scale method union (BSA2 / BSS2 on soft fields); r1, r2, p",
       create_scale_union},
      {"scale_intersection", "blend",
       "scale method intersection (BSS2 / BSA2 on soft fields); r1, r2, p",
       create_scale_intersection},
      {"complement", "blend", "1-f (soft), -f (zero), 1/f (constructive); one child",
       create_complement},
  };
  return kinds;
}

namespace {

struct PotentialKind {
  const char* name;
  PotentialPtr (*create)(const Params&);
};

const PotentialKind kPotentials[] = {
    {"blanc", create_blanc},
    {"wyvill", create_wyvill},
    {"murakami", create_murakami},
};

template <class Kinds>
std::string names_of(const Kinds& kinds) {
  std::string s;
  for (const auto& k : kinds) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

}  // namespace

PotentialPtr build_potential(const Params& p) {
  const std::string type = p.string("type");
  for (const auto& k : kPotentials)
    if (type == k.name) {
      PotentialPtr P = k.create(p);
      p.finish();
      return P;
    }
  p.fail("type",
         "unknown potential '" + type + "' (expected one of: " + names_of(kPotentials) + ")");
}

NodePtr build_field(const Params& p, const BuildContext& ctx) {
  const std::string type = p.string("type");
  const NodeKind* kind = nullptr;
  for (const auto& k : node_kinds())
    if (type == k.name) kind = &k;
  if (!kind)
    p.fail("type",
           "unknown node type '" + type + "' (expected one of: " + names_of(node_kinds()) + ")");
  if (ctx.depth >= kMaxFieldDepth)
    p.fail("", "field nodes nested deeper than " + std::to_string(kMaxFieldDepth) + " levels");
  BuildContext inner = ctx;
  ++inner.depth;
  NodePtr node = kind->create(p, inner);

  const Vec3 translate = p.vec3("translate", {});
  Mat3 rotation;
  bool rotated = false;
  if (p.has("rotate")) {
    const Params r = p.object("rotate");
    const Vec3 axis = r.vec3("axis");
    r.check(length(axis) > 0 && std::isfinite(length(axis)), "axis", "expected a non-zero axis");
    rotation = Mat3::rotation(axis, r.number("deg"));
    r.finish();
    rotated = true;
  }
  p.finish();
  if (rotated || translate.x != 0 || translate.y != 0 || translate.z != 0)
    node = place(std::move(node), rotation, translate);
  return node;
}

std::vector<NodePtr> build_children(const Params& p, const std::string& key,
                                    const BuildContext& ctx, size_t min_count) {
  std::vector<Params> items = p.objects(key);
  if (items.size() < min_count)
    p.fail(key, "expected at least " + std::to_string(min_count) + " children, got " +
                    std::to_string(items.size()));
  if (items.size() > kMaxChildren)
    p.fail(key, "expected at most " + std::to_string(kMaxChildren) + " children, got " +
                    std::to_string(items.size()));
  std::vector<NodePtr> out;
  out.reserve(items.size());
  for (const auto& item : items) out.push_back(build_field(item, ctx));
  return out;
}

}  // namespace softtrace
