// The vocabulary of the one list of kinds (loader/kinds.h holds the list itself): what a kind
// yields (its family), what each parameter is (type, range, default) and the create function that
// builds it. Below the model, so that a kind's `create` can read its specs without the list.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "math/convention.h"

namespace softtrace {

class FieldNode;
class Potential;
class Params;
struct BuildContext;
using NodeCreate = std::unique_ptr<FieldNode> (*)(const Params&, const BuildContext&);
using PotentialCreate = std::unique_ptr<Potential> (*)(const Params&);
// A radius transform turns the soft object's distance and potential into the transformed field.
using RadiusCreate = std::unique_ptr<FieldNode> (*)(const Params&, std::unique_ptr<FieldNode> d,
                                                    std::unique_ptr<Potential> P,
                                                    const BuildContext&);

// What a value is. Node-valued parameters (slots) declare the family they take.
enum class Family {
  Distance,         // ray-linear distance function, 1 on its surface (docs/math.md §2)
  SoftField,        // soft convention: [0, 1], inside f >= 0.5
  ZeroSurface,      // zero convention: inside f <= 0
  Constructive,     // constructive convention: inside f <= 1 (a distance function is one)
  ConventionField,  // the family of the object's convention (blends that follow it)
  Any,              // a node built on its own (tests, tools): every family fits
  Potential,
  RadiusTransform,
};

// "a distance function", "a soft field", ...: for error messages and the docs.
const char* family_phrase(Family f);
// The family a convention's object field has.
Family convention_family(Convention c);
// ConventionField resolved under `c`; any other family unchanged.
Family resolve(Family f, Convention c);
// Whether a value of family `given` may fill a slot taking `wanted` (both resolved; Any takes all).
bool fits(Family wanted, Family given);

enum class ParamType {
  Number,           // a finite number
  Integer,          // an integer
  Choice,           // one of `choices`
  Vec3,             // [x, y, z]
  Numbers,          // an array of `count` numbers (any non-empty length when count is 0)
  NumberOrList,     // a number, or one number per child (or per normal)
  Vec3List,         // a non-empty array of [x, y, z]
  Node,             // one node of family `slot`
  Nodes,            // an array of nodes of family `slot`, between min_count and max_count of them
  Potential,        // a potential object
  RadiusTransform,  // a radius transform object
  Object,           // an object with its own keys (described in `note`)
};

enum class Need { Required, Optional, Conditional };

// Every number a node reads lies within this magnitude (and every number > 0 above its inverse),
// so that squares, sums and angle conversions of parameters cannot overflow (docs/scene-format.md).
constexpr double kMaxMagnitude = 1e150;
constexpr double kMinPositive = 1e-150;

struct ParamSpec {
  const char* name;
  ParamType type;
  Need need = Need::Required;
  const char* fallback = "";  // the default (Optional) or when it is needed (Conditional), as text
  // Numbers (and every element of a list): lo < x < hi, with the ends included when closed.
  // Infinite ends state no bound beyond kMaxMagnitude; lo = 0 open means kMinPositive.
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_closed = true, hi_closed = true;
  const char* noun = "a number";        // "expected <noun> > 0"
  Family slot = Family::Distance;       // Node, Nodes
  size_t min_count = 0, max_count = 0;  // Nodes (0 = no limit), Numbers (count = min_count)
  const char* choices = "";             // Choice: names separated by '|'
  const char* note = "";  // constraints the table cannot state, checked by the kind's create
};

enum class KindGroup { Node, Potential, RadiusTransform };

struct KindInfo {
  const char* name;
  KindGroup group;
  Family family;  // what the kind yields (nodes); Potential or RadiusTransform otherwise
  std::vector<ParamSpec> params;
  const char* summary;        // one line: the formula and the paper's equation
  const char* skeleton = "";  // distances: the skeleton structure (002 §4.1 (b))
  NodeCreate create_node = nullptr;
  PotentialCreate create_potential = nullptr;
  RadiusCreate create_radius = nullptr;
};

// The list and its lookups. The list itself is the loader's (loader/kinds.cpp): it names every
// kind's create function, so it sits above the model; create functions and checks below it look
// kinds up through these.
const std::vector<KindInfo>& kinds();
// Whether `key` is the table's `name`, in one pass that stops at the first differing letter:
// std::string's compare with a C string takes its strlen first, and every key of every node of
// a scene is compared with a kind's names (a key with a NUL in it matches no name).
inline bool same_name(const std::string& key, const char* name) {
  const size_t n = key.size();
  for (size_t i = 0; i < n; ++i)
    if (name[i] == '\0' || name[i] != key[i]) return false;
  return name[n] == '\0';
}
const KindInfo* find_kind(const std::string& name, KindGroup group);
const ParamSpec* find_param(const KindInfo& kind, const std::string& name);

// "> 0", "[0, 1)", ...: a spec's range as text; empty when unrestricted.
std::string range_text(const ParamSpec& p);
// "number", "[x, y, z]", "distance node", ...
std::string type_text(const ParamSpec& p);
// The default as shown to users: "required", "0", "all 1", ...
std::string default_text(const ParamSpec& p);

}  // namespace softtrace
