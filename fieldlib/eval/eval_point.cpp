#include "eval/eval.h"

namespace softtrace {

double evaluate(const Program& p, const Vec3& point, Vec3* grad, Workspace& ws) {
  ws.fit(p);
  return grad ? gradient_pruned(p, point, grad, ws) : value_pruned(p, point, ws);
}

}  // namespace softtrace
