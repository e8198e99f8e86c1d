#include "eval/batch.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace softtrace {

namespace {
// Spreads the low 10 bits of v to every third bit.
uint32_t spread(uint32_t v) {
  v &= 0x3ff;
  v = (v | (v << 16)) & 0x030000ff;
  v = (v | (v << 8)) & 0x0300f00f;
  v = (v | (v << 4)) & 0x030c30c3;
  v = (v | (v << 2)) & 0x09249249;
  return v;
}
}  // namespace

std::vector<size_t> spatial_order(const double* xyz, size_t n) {
  Box box;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 q{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
      throw std::invalid_argument("point " + std::to_string(i) +
                                  ": expected three finite coordinates");
    box.extend(q);
  }
  // About kBatch points per cell: cells of G^3 with G a power of two, at most 64 (2^18 cells).
  uint32_t g = 1;
  while (g < 64 && size_t(g) * g * g * kBatch < n) g *= 2;
  const Vec3 extent = box.extent();
  const auto cell = [&](size_t i) {
    uint32_t code = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double t = extent[axis] > 0 ? (xyz[3 * i + axis] - box.lo[axis]) / extent[axis] : 0;
      const uint32_t c = std::min(g - 1, uint32_t(t * g));
      code |= spread(c) << axis;
    }
    return code;
  };
  // A counting sort: linear in n.
  std::vector<uint32_t> codes(n);
  std::vector<size_t> start(size_t(g) * g * g + 1, 0);
  for (size_t i = 0; i < n; ++i) ++start[(codes[i] = cell(i)) + 1];
  for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[start[codes[i]]++] = i;
  return order;
}

void eval_ordered(const Program& p, const double* xyz, const std::vector<size_t>& order,
                  size_t begin, size_t end, double* f, double* grad, Workspace& ws) {
  ws.fit(p);
  double x[kBatch], y[kBatch], z[kBatch], v[kBatch];
  for (size_t b = begin; b < end; b += kBatch) {
    const int n = int(std::min<size_t>(kBatch, end - b));
    Box box;
    for (int l = 0; l < n; ++l) {
      const double* q = xyz + 3 * order[b + l];
      x[l] = q[0], y[l] = q[1], z[l] = q[2];
      box.extend({q[0], q[1], q[2]});
    }
    if (p.has_pruning) prune(p, box, ws);
    const Code code = p.has_pruning ? Code(ws.view) : Code(p);
    if (grad) {
      for (int l = 0; l < n; ++l) {
        Vec3 g;
        const size_t i = order[b + l];
        f[i] = gradient(code, {x[l], y[l], z[l]}, &g, ws);
        grad[3 * i] = g.x, grad[3 * i + 1] = g.y, grad[3 * i + 2] = g.z;
      }
      continue;
    }
    values(code, x, y, z, n, v, ws);
    for (int l = 0; l < n; ++l) f[order[b + l]] = v[l];
  }
}

void eval_points(const Program& p, const double* xyz, size_t n, double* f, double* grad,
                 Workspace& ws) {
  const std::vector<size_t> order = spatial_order(xyz, n);
  eval_ordered(p, xyz, order, 0, n, f, grad, ws);
}

}  // namespace softtrace
