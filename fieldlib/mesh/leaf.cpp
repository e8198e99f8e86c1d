#include "mesh/leaf.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "math/illinois.h"
#include "mesh/tetra.h"

namespace softtrace {

double LeafMesher::solved(double f, const Vec3& p, bool capped) const {
  const double g = field_.inside_sign > 0 ? f - field_.iso : field_.iso - f;
  if (!capped) return g;
  const double d = lattice_.inside_distance(p);
  return g < d ? g : d;  // a value that is not a number is outside the box's part
}

void LeafMesher::run(const int c0[3], const int c1[3], SamplerScratch& scratch, LeafMesh* out) {
  keys_.clear();
  place_.clear();
  cuts_.clear();
  edges_.clear();
  for (int a = 0; a < 3; ++a) m_[a] = c1[a] - c0[a] + 1;
  const int stride[3] = {1, m_[0], m_[0] * m_[1]};
  const int points = m_[0] * m_[1] * m_[2];
  if (points > kMaxLeafPoints)  // mesh.cpp's leaves have at most 9^3
    throw std::logic_error("mesh: a leaf of more than 8,192 points");

  sampler_.prepare(lattice_.span(c0, c1), scratch);

  // The corners' values, in the order of the local points.
  values_.resize(points);
  inside_.resize(points);
  for (int a = 0; a < 3; ++a) {
    axis_[a].resize(size_t(m_[a]));
    for (int i = 0; i < m_[a]; ++i) axis_[a][size_t(i)] = lattice_.coordinate(a, c0[a] + i);
  }
  sampler_.grid(axis_[0].data(), axis_[1].data(), axis_[2].data(), m_, values_.data(), scratch);
  for (int k = 0, p = 0; k < m_[2]; ++k)
    for (int j = 0; j < m_[1]; ++j)
      for (int i = 0; i < m_[0]; ++i, ++p)
        inside_[p] = !lattice_.padding(c0[0] + i, c0[1] + j, c0[2] + k) && inside(values_[p]);

  slot_.assign(size_t(points) * 8, -1);
  auto local = [&](int base, int corner) {
    return base + (corner & 1) * stride[0] + (corner >> 1 & 1) * stride[1] +
           (corner >> 2 & 1) * stride[2];
  };
  // The vertex on the edge from cube corner `in` to `outside` of the cell at local (i, j, k).
  auto vertex = [&](const int cell[3], int in, int outside) -> uint16_t {
    const int lo = in & outside, d = in ^ outside;
    auto corner = [&](int c, int q[3]) {
      for (int a = 0; a < 3; ++a) q[a] = cell[a] + (c >> a & 1);
      return q[0] + q[1] * stride[1] + q[2] * stride[2];
    };
    int q[3], qa[3], qb[3];
    const int p = corner(lo, q);
    int32_t& s = slot_[size_t(p) * 8 + d];
    if (s >= 0) return uint16_t(s);
    s = int32_t(edges_.size());
    EdgePlace place = EdgePlace::Interior;
    for (int a = 0; a < 3; ++a) {
      if (d >> a & 1) continue;
      if (q[a] == 0 && c0[a] > 0) {
        place = EdgePlace::Borrowed;
        break;
      }
      if (q[a] == 0 || q[a] == m_[a] - 1) place = EdgePlace::Solved;
    }
    keys_.push_back(lattice_.edge_key(c0[0] + q[0], c0[1] + q[1], c0[2] + q[2], d));
    place_.push_back(place);
    const int pa = corner(in, qa), pb = corner(outside, qb);
    const int ga[3] = {c0[0] + qa[0], c0[1] + qa[1], c0[2] + qa[2]};
    const int gb[3] = {c0[0] + qb[0], c0[1] + qb[1], c0[2] + qb[2]};
    Edge e;
    e.a = lattice_.point(ga[0], ga[1], ga[2]);
    e.b = lattice_.point(gb[0], gb[1], gb[2]);
    e.capped = lattice_.padding(ga[0], ga[1], ga[2]) || lattice_.padding(gb[0], gb[1], gb[2]);
    e.code = uint8_t(d | (lo == in ? 0 : kEdgeDown) | (e.capped ? kEdgeCapped : 0));
    e.ga = solved(values_[pa], e.a, e.capped);
    e.gb = solved(values_[pb], e.b, e.capped);
    e.solve = place != EdgePlace::Borrowed;
    edges_.push_back(e);
    return uint16_t(s);
  };

  for (int k = 0; k + 1 < m_[2]; ++k)
    for (int j = 0; j + 1 < m_[1]; ++j)
      for (int i = 0; i + 1 < m_[0]; ++i) {
        const int base = i + j * stride[1] + k * stride[2];
        int mask = 0;
        for (int c = 0; c < 8; ++c) mask |= inside_[local(base, c)] << c;
        if (mask == 0 || mask == 255) continue;
        for (int t = 0; t < 6; ++t) {
          int in = 0;
          for (int v = 0; v < 4; ++v) in |= (mask >> kKuhnTetrahedra[t][v] & 1) << v;
          const TetCut& cut = tet_cut(t, in);
          if (cut.count == 0) continue;
          LeafCut c{{0, 0, 0, 0}, cut.count == 4};
          const int cell[3] = {i, j, k};
          for (int e = 0; e < cut.count; ++e) c.v[e] = vertex(cell, cut.in[e], cut.out[e]);
          cuts_.push_back(c);
        }
      }

  // Every leaf's mesh is kept until the weld: copied from this mesher's buffers at its size, in
  // one allocation each (growing the leaf's own arrays, then trimming them, copied them twice).
  out->keys.assign(keys_.begin(), keys_.end());
  out->place.assign(place_.begin(), place_.end());
  out->cuts.assign(cuts_.begin(), cuts_.end());
  solve_edges(scratch, out);
}

namespace {
// The zero of the quadratic in g through three points (x_i, g_i): x as a function of g
// interpolated at g = 0 (Brent 1973). Not a number where two g_i are equal.
double inverse_quadratic(double x0, double g0, double x1, double g1, double x2, double g2) {
  return x0 * g1 * g2 / ((g0 - g1) * (g0 - g2)) + x1 * g0 * g2 / ((g1 - g0) * (g1 - g2)) +
         x2 * g0 * g1 / ((g2 - g0) * (g2 - g1));
}
}  // namespace

// Each edge's crossing on its bracket [inside end, outside end]: first the false position, then
// the inverse quadratic through the last three values (the ends and the first step, then the last
// three steps) where it falls inside the bracket, else the Illinois method's false position, with a
// bisection after two steps in a row that did not halve the bracket; kBatch edges per call of the
// values evaluator. The inverse quadratic, as in Brent's method, takes 2.9 evaluations an edge on
// the 1000 blobs at 64^3 where the Illinois steps alone took 4.2. An edge is done when its bracket
// is kEdgeTolerance of the edge, or when the secant through its last two values says the crossing
// is within that of the last point (the error estimate of a superlinear method). Each edge's steps
// depend on its own values only, so a vertex has the same bits whichever block solves it.
void LeafMesher::solve_edges(SamplerScratch& scratch, LeafMesh* out) {
  const size_t n = edges_.size();
  std::vector<EdgeState>& state = state_;
  std::vector<uint32_t>& active = active_;
  state.assign(n, EdgeState());
  active.clear();
  for (size_t e = 0; e < n; ++e) {
    EdgeState& st = state[e];
    st.bracket = {1, edges_[e].gb, 0, edges_[e].ga};
    st.px = 1;
    st.pg = edges_[e].gb;
    st.qx = 0;
    st.qg = edges_[e].ga;
    if (!edges_[e].solve)
      st.t = std::numeric_limits<double>::quiet_NaN();  // the solving leaf's, after the weld
    else if (edges_[e].ga > 0)
      active.push_back(uint32_t(e));
    else
      st.t = 0;  // ga == 0: the inside end is on the surface
  }
  double x[kSamplerBatch], y[kSamplerBatch], z[kSamplerBatch], f[kSamplerBatch], at[kSamplerBatch];
  const size_t batch = size_t(sampler_.batch());
  // A queue: an edge not done goes to the back, so that every batch but the leaf's last is full
  // (the evaluator's cost is mostly per batch). Each edge's steps are the same in any order.
  for (size_t first = 0, m; first < active.size(); first += m) {
    m = std::min(batch, active.size() - first);
    for (size_t l = 0; l < m; ++l) {
      const EdgeState& st = state[active[first + l]];
      const IllinoisBracket& b = st.bracket;
      double s = st.steps > 0 ? inverse_quadratic(st.rx, st.rg, st.qx, st.qg, st.px, st.pg)
                              : b.false_position();
      if (!(s > b.hi && s < b.lo)) s = b.false_position();
      if (st.slow >= 2 || !(s > b.hi && s < b.lo)) s = 0.5 * (b.lo + b.hi);
      at[l] = s;
      const Edge& e = edges_[active[first + l]];
      const Vec3 p = e.a + s * (e.b - e.a);
      x[l] = p.x, y[l] = p.y, z[l] = p.z;
    }
    sampler_.values(x, y, z, int(m), f, scratch);
    for (size_t l = 0; l < m; ++l) {
      const uint32_t id = active[first + l];
      EdgeState& st = state[id];
      IllinoisBracket& b = st.bracket;
      const double g = solved(f[l], {x[l], y[l], z[l]}, edges_[id].capped);
      const double width = b.lo - b.hi;
      if (g == 0) {
        st.t = at[l];
        continue;
      }
      b.update(at[l], g, g > 0);
      st.slow = b.lo - b.hi > 0.5 * width && st.slow < 2 ? st.slow + 1 : 0;
      const double secant = g * (at[l] - st.px) / (g - st.pg);  // the secant's next step
      st.rx = st.qx;
      st.rg = st.qg;
      st.qx = st.px;
      st.qg = st.pg;
      st.px = at[l];
      st.pg = g;
      if (b.lo - b.hi <= kEdgeTolerance || st.steps >= 200) {
        st.t = b.false_position();
      } else if (std::abs(secant) <= kEdgeTolerance) {
        st.t = at[l] - secant;
      } else {
        ++st.steps;
        active.push_back(id);
        continue;
      }
      if (!(st.t >= b.hi && st.t <= b.lo)) st.t = 0.5 * (b.lo + b.hi);
    }
  }

  out->positions.resize(n);  // one allocation each where *out is a new LeafMesh (mesh.cpp)
  out->edge.resize(n);
  for (size_t id = 0; id < n; ++id) {
    const double s =
        edges_[id].solve ? std::clamp(state[id].t, kEdgeMargin, 1 - kEdgeMargin) : state[id].t;
    const Edge& e = edges_[id];
    out->positions[id] = e.a + s * (e.b - e.a);
    out->edge[id] = e.code;
  }
}

Vec3 vertex_normal(const MeshField& field, const FieldSampler& sampler, const Lattice& lattice,
                   const Vec3& p, uint8_t edge, SamplerScratch& scratch) {
  // Outward is where inside_sign (f - iso) falls: -inside_sign grad f; on the cap, the face's.
  Vec3 grad;
  const double f = sampler.gradient(p, &grad, scratch);
  Vec3 nrm = grad * -field.inside_sign;
  const double g = field.inside_sign > 0 ? f - field.iso : field.iso - f;
  if ((edge & kEdgeCapped) && lattice.inside_distance(p) < g) nrm = lattice.cap_normal(p);
  const double len = length(nrm);
  // A critical point on the surface has no normal: the edge's direction out stands in.
  return len > 0 && std::isfinite(len) ? nrm / len : normalize(edge_outward(edge));
}

}  // namespace softtrace
