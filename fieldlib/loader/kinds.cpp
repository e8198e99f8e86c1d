#include "loader/kinds.h"

#include <cmath>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "kernels/offset.h"
#include "model/blends.h"
#include "model/blends_bt.h"
#include "model/distances.h"
#include "model/potential.h"
#include "model/soft_object.h"

namespace softtrace {

namespace {

// A ParamSpec written as `Spec("radii", ParamType::Vec3).above(0).called("a radius")`.
struct Spec : ParamSpec {
  Spec(const char* n, ParamType t) {
    name = n;
    type = t;
  }
  Spec& optional(const char* def) {
    need = Need::Optional;
    fallback = def;
    return *this;
  }
  Spec& when(const char* condition) {
    need = Need::Conditional;
    fallback = condition;
    return *this;
  }
  Spec& above(double v) {
    lo = v;
    lo_closed = false;
    return *this;
  }
  Spec& at_least(double v) {
    lo = v;
    lo_closed = true;
    return *this;
  }
  Spec& below(double v) {
    hi = v;
    hi_closed = false;
    return *this;
  }
  Spec& at_most(double v) {
    hi = v;
    hi_closed = true;
    return *this;
  }
  Spec& called(const char* n) {
    noun = n;
    return *this;
  }
  Spec& count(size_t n) {
    min_count = max_count = n;
    return *this;
  }
  Spec& takes(Family f, size_t lo_count, size_t hi_count = 0) {
    slot = f;
    min_count = lo_count;
    max_count = hi_count;
    return *this;
  }
  Spec& one_of(const char* c) {
    choices = c;
    return *this;
  }
  Spec& noted(const char* n) {
    note = n;
    return *this;
  }
};

using T = ParamType;
constexpr Family kConv = Family::ConventionField;

Spec radii3() {
  return Spec("radii", T::Vec3).above(0).called("a radius");
}
Spec exponent(const char* name) {
  return Spec(name, T::Number).above(0).called("an exponent");
}
Spec sides6() {
  return Spec("t", T::Numbers)
      .optional("all 1")
      .count(6)
      .above(0)
      .called("a side length")
      .noted("t1..t6 scale +x, -x, +y, -y, +z, -z (002 Eq. 15)");
}
Spec children(Family f, size_t lo, size_t hi = 0) {
  return Spec("children", T::Nodes).takes(f, lo, hi);
}
Spec w_min() {
  return Spec("w_min", T::Number).optional("1e-4").above(0).below(0.5);
}

// BT_k blends (003): the base and its ranges; `with_m` for all but the displacement union.
std::vector<ParamSpec> bt_params(bool with_m) {
  std::vector<ParamSpec> v = {
      children(Family::ZeroSurface, 2),
      Spec("base", T::Choice).one_of("conic|hyperellipsoid"),
      Spec("r1", T::Number).when("base \"conic\"").above(0).called("a range"),
      Spec("r2", T::Number).when("base \"conic\"").above(0).called("a range"),
      Spec("r", T::NumberOrList)
          .when("base \"hyperellipsoid\"")
          .above(0)
          .called("a range")
          .noted("one per child, or a number for all"),
      Spec("p", T::NumberOrList)
          .noted(
              "conic: a number p < r1*r2; hyperellipsoid: one per child (or a number), each > 1"),
  };
  if (with_m)
    v.push_back(Spec("m", T::NumberOrList)
                    .optional("1")
                    .above(0)
                    .called("a weight")
                    .noted("one per child, or a number for all"));
  v.push_back(Spec("bulge_elimination", T::Object)
                  .optional("none")
                  .noted("{\"omega\": number > 0}; exactly 2 children; conic needs p < "
                         "omega^2*r1*r2 (003 §5)"));
  return v;
}

KindInfo node(const char* name, Family f, std::vector<ParamSpec> params, const char* summary,
              NodeCreate create, const char* skeleton = "") {
  KindInfo k{name, KindGroup::Node, f, std::move(params), summary, skeleton};
  k.create_node = create;
  return k;
}
KindInfo potential(const char* name, std::vector<ParamSpec> params, const char* summary,
                   PotentialCreate create) {
  KindInfo k{name, KindGroup::Potential, Family::Potential, std::move(params), summary};
  k.create_potential = create;
  return k;
}
KindInfo transform(const char* name, std::vector<ParamSpec> params, const char* summary,
                   RadiusCreate create) {
  KindInfo k{name, KindGroup::RadiusTransform, Family::RadiusTransform, std::move(params), summary};
  k.create_radius = create;
  return k;
}

std::vector<KindInfo> make_kinds() {
  const Family D = Family::Distance, S = Family::SoftField, Z = Family::ZeroSurface;
  const Spec normal = Spec("normal", T::Vec3).noted("non-zero; normalised when read");
  const Spec plane_a = Spec("a", T::Number).above(0).called("a distance");
  const Spec modulation =
      Spec("modulation", T::Node).takes(D, 1, 1).noted("same skeleton structure as the distance");
  return {
      // Distance functions, docs/math.md §2.
      node("parallel_planes", D, {normal, plane_a},
           "|p.n|/a: two parallel planes (000 Eq. 2, 002 f_p)", create_parallel_planes, "plane"),
      node("one_branch_plane", D, {normal, plane_a},
           "max(p.n, 0)/a: one side of a plane (002 §4.5 f_o)", create_one_branch_plane, "plane"),
      node("lp_metric", D, {radii3(), exponent("n")},
           "(|x/a|^n + |y/b|^n + |z/c|^n)^(1/n) (000 Eq. 2)", create_lp_metric, "point"),
      node("superquadric", D, {radii3(), exponent("n1"), exponent("n2"), sides6()},
           "superquadric (000 Eq. 3); with t, six side lengths (002 Eq. 15)", create_superquadric,
           "point"),
      node("generalized_distance", D,
           {Spec("normals", T::Vec3List).noted("each non-zero; normalised when read"),
            Spec("a", T::NumberOrList)
                .above(0)
                .called("a distance")
                .noted("one per normal, or a number for all"),
            exponent("n"),
            Spec("t_pos", T::Numbers)
                .optional("all 1")
                .above(0)
                .called("a side length")
                .noted("one per normal (002 Eq. 16)"),
            Spec("t_neg", T::Numbers)
                .optional("all 1")
                .above(0)
                .called("a side length")
                .noted("one per normal (002 Eq. 16)")},
           "(Σ |p.n_i/a_i|^n)^(1/n) (000 Eq. 4, 002 Eq. 16; Akleman-Chen)",
           create_generalized_distance, "point"),
      node("segment", D,
           {Spec("p0", T::Vec3), Spec("p1", T::Vec3), Spec("radius", T::Number).above(0)},
           "distance to the segment p0-p1 over radius (000 Eq. 5)", create_segment, "segment"),
      node("superelliptic_cylinder", D,
           {radii3(), exponent("n"),
            Spec("half_length", T::Number)
                .at_least(0)
                .called("a half-length L")
                .noted("spine along z, length 2L"),
            sides6()},
           "super-elliptic cylinder about the z axis (002 Eq. 17; with t, Eq. 18)",
           create_superelliptic_cylinder, "segment"),
      node("torus", D,
           {Spec("major_radius", T::Number).at_least(0).called("a major radius R"),
            Spec("radii", T::Numbers)
                .count(2)
                .above(0)
                .called("a radius")
                .noted("[a, b]: radial and axial"),
            exponent("n").optional("2")},
           "((|rho - R|/a)^n + (|z|/b)^n)^(1/n): a circle skeleton (docs/math.md §2.9)",
           create_torus, "circle"),
      node("polar_prism", D,
           {Spec("radius", T::Number).above(0).called("a radius r0"),
            Spec("lobes", T::Integer).at_least(1).at_most(1000),
            Spec("amplitude", T::Number).at_least(0).below(1).called("an amplitude A"),
            Spec("profile", T::Choice).one_of("cosine|triangle"),
            Spec("half_height", T::Number).above(0).called("a half-height c"),
            exponent("n").optional("20")},
           "(h^n + |z/c|^n)^(1/n), h = rho/R(phi): rose or star prism (docs/math.md §10.1)",
           create_polar_prism, "point"),
      node("super_ellipsoidal_union", D, {exponent("n"), children(D, 2)},
           "(Σ x_i^-n)^(-1/n) of distance functions (000 Eq. 6, 002 §4.5)",
           create_super_ellipsoidal_union),
      node("super_ellipsoidal_intersection", D, {exponent("n"), children(D, 2)},
           "(Σ x_i^n)^(1/n) of distance functions (000 Eq. 6, 002 §4.5)",
           create_super_ellipsoidal_intersection),
      // Soft objects, docs/math.md §4.
      node("soft_object", S,
           {Spec("distance", T::Node).takes(D, 1, 1),
            Spec("potential", T::Potential).optional("blanc, s = 0"),
            Spec("radii", T::RadiusTransform).optional("none: P(d)"),
            Spec("strength", T::Number)
                .optional("1")
                .noted("s != 0; the field is s*P(T(d)); negative subtracts (soft_blend, min, "
                       "max, complement)")},
           "s*P(T(d)): a soft object (000 Eq. 9, 002 Eq. 1)", create_soft_object),
      // Blends, docs/math.md §5-§7.
      node("soft_blend", S, {children(S, 1)}, "Σ f_i (000 Eq. 12, 002 Eq. 3)", create_soft_blend),
      node("perlin_union", S, {children(S, 2)}, "1 - Π(1 - f_i) (002 Eq. 4)", create_perlin_union),
      node("perlin_intersection", S, {children(S, 2)}, "Π f_i (002 Eq. 5)",
           create_perlin_intersection),
      node("perlin_difference", S, {children(S, 2)}, "f_1 Π_{i>=2}(1 - f_i) (002 Eq. 6)",
           create_perlin_difference),
      node("ricci_union", kConv, {exponent("n"), children(kConv, 2)},
           "Ricci union, soft or constructive convention (000 Eq. 6, 002 Eq. 7)",
           create_ricci_union),
      node("ricci_intersection", kConv, {exponent("n"), children(kConv, 2)},
           "Ricci intersection, soft or constructive convention (000 Eq. 6, 002 Eq. 8)",
           create_ricci_intersection),
      node("ricci_difference", kConv, {exponent("n"), children(kConv, 2)},
           "Ricci difference: the first child minus the others (docs/math.md §5.3, §5.4)",
           create_ricci_difference),
      node("min", kConv, {children(kConv, 2)}, "sharp minimum of the children", create_min),
      node("max", kConv, {children(kConv, 2)}, "sharp maximum of the children", create_max),
      node("scale_union", kConv,
           {Spec("r1", T::Number).above(0).called("a range"),
            Spec("r2", T::Number).above(0).called("a range"),
            Spec("p", T::Number).noted("p < r1*r2; BSS2 (soft union) needs r1, r2 < 1"),
            children(kConv, 2, 2)},
           "scale method union: BSA2 constructive, BSS2 soft (000 Eq. 8, docs/math.md §6.3)",
           create_scale_union),
      node("scale_intersection", kConv,
           {Spec("r1", T::Number).above(0).called("a range"),
            Spec("r2", T::Number).above(0).called("a range"),
            Spec("p", T::Number)
                .noted("p < r1*r2; BSS2 (constructive intersection) needs r1, r2 < 1"),
            children(kConv, 2, 2)},
           "scale method intersection: BSS2 constructive, BSA2 soft (000 Eq. 8, docs/math.md §6.3)",
           create_scale_intersection),
      node("complement", kConv, {children(kConv, 1, 1)},
           "1 - f (soft), -f (zero), 1/f (constructive) (docs/math.md §1)", create_complement),
      node("offset", Z,
           {children(D, 1, 1), Spec("scale", T::Number).optional("1").noted("s != 0"),
            Spec("level", T::Number).optional("1")},
           "s*(child - c): a distance function as a zero-surface function (003 §2.1)",
           create_offset),
      node("bt_union", Z, bt_params(true), "BT_k union (003 Eqs. 2-5)", create_bt_union),
      node("bt_intersection", Z, bt_params(true), "-BT_k(-f_1, ..., -f_k) (003 §3.3)",
           create_bt_intersection),
      node("bt_difference", Z, bt_params(true), "-BT_k(-f_1, f_2, ..., f_k) (003 §3.3)",
           create_bt_difference),
      node("displacement_union", Z, bt_params(false), "BD_k: BT_k with all m = 1 (003 §2.2)",
           create_displacement_union),
      // Potentials, docs/math.md §3.
      potential("blanc", {Spec("s", T::Number).optional("0").at_least(0).called("a softness s")},
                "Blanc's potential with softness s (000 Eq. 11, 002 Eq. 2)", create_blanc),
      potential("wyvill", {}, "Wyvill's sixth-degree soft-object polynomial (docs/math.md §3.3)",
                create_wyvill),
      potential("murakami", {},
                "(1 - d^2)^2, POV-Ray's blob; 0.5 level at d = 0.5412 (docs/math.md §3.3)",
                create_murakami),
      potential("cubic", {},
                "(1 - d^2)^3, Galin et al. 2020's kernel; 0.5 level at d = 0.4542 (docs/math.md "
                "§3.4)",
                create_cubic),
      // Radius transforms, docs/math.md §4.2-§4.8.
      transform("T_n",
                {Spec("w1", T::Number).above(0).called("an outer radius factor w1"),
                 Spec("w2", T::Number)
                     .above(0)
                     .at_most(1)
                     .called("an inner radius factor w2")
                     .noted("w2 <= 2*w1")},
                "normalisation and affine transform (000 Eq. 13, 002 Eq. 10)", create_T_n),
      transform("T_l", {Spec("w1", T::Number).above(0).called("an outer radius factor w1")},
                "log transform for the outer radius (002 Eq. 13)", create_T_l),
      transform("T_r",
                {Spec("w2", T::Number).above(0).at_most(1).called("an inner radius factor w2")},
                "log transform for the inner radius (002 Eq. 14)", create_T_r),
      transform("T_an", {Spec(modulation).noted("f_a <= d, same skeleton structure"), w_min()},
                "T_n with w1 = d/f_a - 1, outer radius to f_a = 0.5 (002 Eq. 11)", create_T_an),
      transform("T_al", {Spec(modulation).noted("f_a <= d, same skeleton structure"), w_min()},
                "T_l with w1 = d/f_a - 1, outer radius to f_a = 0.5 (002 Eq. 11)", create_T_al),
      transform("T_sn", {Spec(modulation).noted("f_s >= d, same skeleton structure"), w_min()},
                "T_n with w2 = w1 = 1 - d/f_s, inner radius to f_s = 0.5 (002 Eq. 12)",
                create_T_sn),
      transform("T_sr", {Spec(modulation).noted("f_s >= d, same skeleton structure"), w_min()},
                "T_r with w2 = 1 - d/f_s, inner radius to f_s = 0.5 (002 Eq. 12)", create_T_sr),
      transform("contour",
                {Spec("contour", T::Node).takes(D, 1, 1).noted("fc <= 2d, same skeleton structure"),
                 w_min()},
                "T_n with w1 = 2d/fc - 1, outer radius to fc = 1 (000 Eqs. 14-15)", create_contour),
  };
}

}  // namespace

const std::vector<KindInfo>& kinds() {
  static const std::vector<KindInfo> table = make_kinds();
  return table;
}

const KindInfo* find_kind(const std::string& name, KindGroup group) {
  // Every node's type is looked up: the scan of the table compared a 1000-component scene's
  // 3,000 types with some 30 names each (0.8 M instructions). Names are unique across groups
  // (test Kinds.TableIsWellFormed).
  static const std::unordered_map<std::string_view, const KindInfo*> index = [] {
    std::unordered_map<std::string_view, const KindInfo*> m;
    for (const auto& k : kinds()) m.emplace(k.name, &k);
    return m;
  }();
  const auto it = index.find(name);
  return it != index.end() && it->second->group == group ? it->second : nullptr;
}

const ParamSpec* find_param(const KindInfo& kind, const std::string& name) {
  for (const auto& p : kind.params)
    if (same_name(name, p.name)) return &p;
  return nullptr;
}

std::string describe_kinds() {
  static const char* const kGroups[] = {"node", "potential", "radius transform"};
  std::ostringstream out;
  for (const auto& k : kinds()) {
    const std::string family = k.group == KindGroup::Node
                                   ? std::string(family_phrase(k.family)).substr(2)
                                   : kGroups[int(k.group)];
    out << k.name << "  (" << family << ")  " << k.summary << "\n";
    for (const auto& p : k.params) {
      out << "    " << p.name << ": " << type_text(p);
      const std::string range = range_text(p);
      if (!range.empty()) out << ", " << range;
      out << "; " << default_text(p);
      if (*p.note) out << "; " << p.note;
      out << "\n";
    }
  }
  return out.str();
}

std::string fuzz_dictionary() {
  std::ostringstream out;
  std::vector<std::string> seen;
  const auto add = [&](const std::string& word) {
    for (const auto& s : seen)
      if (s == word) return;
    seen.push_back(word);
    out << "\"\\\"" << word << "\\\"\"\n";
  };
  for (const auto& k : kinds()) {
    add(k.name);
    for (const auto& p : k.params) {
      add(p.name);
      std::string c = p.choices;
      for (size_t at = 0; !c.empty() && at <= c.size();) {
        const size_t bar = std::min(c.find('|', at), c.size());
        add(c.substr(at, bar - at));
        at = bar + 1;
      }
    }
  }
  for (const char* placement : {"translate", "rotate", "scale", "matrix", "axis", "deg", "omega"})
    add(placement);
  return out.str();
}

}  // namespace softtrace
