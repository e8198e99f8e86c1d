#include "eval.h"

namespace softtrace {

double evaluate(const Program& p, const Vec3& point, Vec3* grad, Workspace& ws) {
  ws.fit(p);
  if (!p.has_pruning) return grad ? gradient(p, point, grad, ws) : value(p, point, ws);
  if (!grad) return value_pruned(p, point, ws);
  prune(p, Box(point, point), ws);
  return gradient(ws.view, point, grad, ws);
}

}  // namespace softtrace
