// A compiled case and random segments: the set-up the program tests and the sweep's program tests
// share. A model built from JSON, the program compiled from it and a workspace fitted to that;
// and segments whose ends lie in a random box of a domain, with their length and direction.
#pragma once

#include <random>
#include <string>

#include "eval/eval.h"
#include "model/program_builder.h"
#include "sweep.h"

namespace softtrace::test {

struct CompiledCase {
  explicit CompiledCase(const std::string& json, Convention convention = Convention::Soft)
      : node(build_from_json(json, convention)), prog(compile(*node)) {
    ws.fit(prog);
  }
  NodePtr node;
  Program prog;
  Workspace ws;
};

// A segment from a to b, its length and (where the length is positive) unit direction.
struct RandomSegment {
  Segment seg;
  double len = 0;
  Vec3 dir;
};

// Both ends uniform in one random_box of `domain`; a zero length where they coincide, which the
// caller skips (nothing lies along it).
inline RandomSegment random_segment(std::mt19937_64& rng, const Box& domain) {
  const Box box = random_box(rng, domain);
  RandomSegment s;
  s.seg = {uniform_in(rng, box), uniform_in(rng, box)};
  s.len = length(s.seg.b - s.seg.a);
  if (s.len > 0) s.dir = (s.seg.b - s.seg.a) / s.len;
  return s;
}

}  // namespace softtrace::test
