#include "program/program.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace softtrace {

const char* op_name(Op op) {
  switch (op) {
#define SOFTTRACE_OP_NAME(name) \
  case Op::name:                \
    return #name;
    SOFTTRACE_OPS(SOFTTRACE_OP_NAME)
#undef SOFTTRACE_OP_NAME
  }
  return "?";
}

int Group::kept_at(const Vec3& p, int32_t* out) const {
  return merge_always(out, bvh.query(Box(p, p), out, 0));
}

int Group::merge_always(int32_t* kept, int n) const {
  // From the back, in place: std::inplace_merge may allocate.
  int i = n - 1, j = static_cast<int>(always.size()) - 1, w = n + j;
  while (j >= 0) kept[w--] = i >= 0 && kept[i] > always[j] ? kept[i--] : always[j--];
  return n + static_cast<int>(always.size());
}

}  // namespace softtrace
