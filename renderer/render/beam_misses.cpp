#include "render/beam_misses.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softtrace {

namespace {

// At most this many objects are tried one by one where their union is not missed: each costs a
// beam up to five plane tests.
constexpr size_t kEach = 8;

// A plane through the eye, normal n (not unit), that the beam's rays may cross by at most `slack`
// (in units of n) per unit of distance from the eye: rounding, or a corner on its outside.
struct BeamSide {
  Vec3 n;
  double slack = 0;
  double scale = 0;  // max_abs(n)
};

// The beam's four side planes (normals pointing inside, through adjacent corners) and the plane
// facing forward through the eye. A ray's direction is a convex combination of the exact corners
// (its column and row lie between theirs), so n . d >= min over the corners of n . corner, which
// is computed here, less the corners' and the direction's rounding (a few ulps of their
// magnitudes; 1e-12 of them here, far above that).
void sides_of(const Frustum& f, BeamSide (&out)[5]) {
  // corner[0..3] are the rectangle's (x0, y0), (x1, y0), (x0, y1), (x1, y1): around it 0, 1, 3, 2.
  static constexpr int kAround[5] = {0, 1, 3, 2, 0};
  const Vec3 middle = f.corner[0] + f.corner[1] + f.corner[2] + f.corner[3];
  double corners = 0;
  for (const Vec3& c : f.corner) corners = std::max(corners, max_abs(c));
  for (int i = 0; i < 5; ++i) {
    Vec3 n = f.forward;
    if (i < 4) {
      n = cross(f.corner[kAround[i]], f.corner[kAround[i + 1]]);
      if (dot(n, middle) < 0) n = -n;
    }
    double least = dot(f.corner[0], n);
    for (int k = 1; k < 4; ++k) least = std::min(least, dot(f.corner[k], n));
    out[i].n = n;
    out[i].scale = max_abs(n);
    out[i].slack = std::max(0.0, -least) + 1e-12 * corners * out[i].scale;
  }
}

// Whether `box` lies past `side` with the margin of beam_misses.h: every point of it (moved by
// clip_to_box's rounding) at most -margin along n from the eye, where no ray's point within
// 2 * scale of the eye reaches (a box point is no farther: |p - eye| <= sqrt(3) * scale). NaN
// anywhere certifies nothing.
bool past(const BeamSide& side, const Vec3& eye, const Box& box) {
  const double scale = max_abs(eye) + std::max(max_abs(box.lo), max_abs(box.hi));
  const Vec3 half = box.extent() * 0.5;
  const Vec3& n = side.n;
  // The box's farthest point along n: its centre's, plus its half extents' reach.
  const double far = dot(box.center() - eye, n) + std::abs(n.x) * half.x + std::abs(n.y) * half.y +
                     std::abs(n.z) * half.z;
  const double margin = 2 * scale * side.slack + 1e-5 * scale * side.scale;
  return far < -margin;
}

bool past_any(const BeamSide (&sides)[5], const Vec3& eye, const Box& box) {
  for (const BeamSide& s : sides)
    if (past(s, eye, box)) return true;
  return false;
}

}  // namespace

BeamMisses::BeamMisses(const SceneTracers& tracers, const ViewCamera& camera) {
  // Without one eye there is no beam (ViewCamera::frustum), nor an outline to see the boxes by.
  if (!camera.single_eye()) {
    never_ = true;
    return;
  }
  std::vector<Box> boxes;
  for (int i = 0; i < tracers.size(); ++i) {
    const TracedObject& o = tracers.object(i);
    Box box = o.bounds;
    if (o.field) box = box.united(o.field->bounds);
    if (!box.bounded()) {
      never_ = true;
      return;
    }
    all_ = all_.united(box);
    boxes.push_back(box);
  }
  if (boxes.size() > 1 && boxes.size() <= kEach) each_ = std::move(boxes);
  if (all_.empty()) return;
  // Where each box is seen: its corners' pixels, padded (the estimate's rounding is far below a
  // pixel). A box wholly behind the eye is seen nowhere; one across the eye's plane everywhere,
  // and then no beam is tested.
  const auto outline = [&](const Box& box) {
    constexpr double kInf = std::numeric_limits<double>::infinity(), kPad = 2;
    Seen s{kInf, kInf, -kInf, -kInf};
    int behind = 0;
    for (int c = 0; c < 8; ++c) {
      double px, py;
      if (!camera.pixel_of(box.corner(c), px, py)) {
        ++behind;
        continue;
      }
      s = {std::min(s.x0, px - kPad), std::min(s.y0, py - kPad), std::max(s.x1, px + kPad),
           std::max(s.y1, py + kPad)};
    }
    if (behind == 8) return;
    if (behind > 0) never_ = true;  // seen everywhere: no beam would be tested (a floor)
    seen_.push_back(s);
  };
  if (each_.empty()) {
    outline(all_);
    outline_ = outline_of(camera.eye(), all_);
  } else {
    for (const Box& box : each_) outline(box);
  }
}

bool BeamMisses::misses(const Frustum& f, int x0, int y0, int x1, int y1) const {
  if (never_) return false;
  if (all_.empty()) return true;  // no object: every ray misses
  for (const Seen& s : seen_)
    if (x0 <= s.x1 && s.x0 <= x1 && y0 <= s.y1 && s.y0 <= y1) return beyond(outline_, f);
  BeamSide sides[5];
  sides_of(f, sides);
  if (past_any(sides, f.eye, all_)) return true;
  if (each_.empty()) return false;
  for (const Box& box : each_)
    if (!past_any(sides, f.eye, box)) return false;
  return true;
}

BeamMisses::Outline BeamMisses::outline_of(const Vec3& eye, const Box& box) {
  Outline out;
  if (box.empty() || !box.bounded()) return out;
  // A lower bound of the eye's distance from the box; the box is taken padded by `pad`, which
  // holds clip_to_box's rounding (a few ulps of the coordinates, as beam_misses.h says) many
  // times over.
  double gap = 0;
  for (int i = 0; i < 3; ++i) gap = std::max({gap, box.lo[i] - eye[i], eye[i] - box.hi[i]});
  const double scale = max_abs(eye) + std::max(max_abs(box.lo), max_abs(box.hi));
  const double pad = 1e-7 * scale;
  if (!(gap > 4 * pad)) return out;
  const Vec3 centre = box.center() - eye;
  for (int axis = 0; axis < 3 && out.sides < 6; ++axis)
    for (int c = 0; c < 8 && out.sides < 6; ++c) {
      if (c & (1 << axis)) continue;
      Vec3 n = cross(box.corner(c) - eye, box.corner(c | 1 << axis) - eye);
      if (dot(n, centre) < 0) n = -n;
      const double n1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
      if (!(n1 > 0)) continue;
      double least = dot(box.corner(0) - eye, n);
      for (int k = 1; k < 8; ++k) least = std::min(least, dot(box.corner(k) - eye, n));
      // An edge of the silhouette leaves every corner on its plane's side (the two of its own on
      // the plane, up to rounding); another edge's plane cuts the box and separates nothing.
      if (least < -1e-12 * n1 * scale) continue;
      // A point q of the padded box has n . (q - eye) >= least - |n|_1 pad and |q - eye| >= gap
      // - pad; a ray's point eye + t d with n . d < -limit |d| has n . (q - eye) < -limit |q -
      // eye| <= -2 (|n|_1 pad + max(0, -least)), below that: it is never in the box.
      // The corners', the directions' and beyond()'s products' rounding are far below 1e-12 of
      // them: taken into the limit here, once.
      const double limit =
          2 * (n1 * pad + std::max(0.0, -least)) / (gap - pad) + 1e-12 * max_abs(n);
      out.side[out.sides++] = {n, limit};
    }
  return out;
}

bool BeamMisses::beyond(const Outline& outline, const Frustum& f) {
  if (outline.sides == 0) return false;
  // A ray's direction is a positive combination of the corners (up to rounding), so n . d <
  // -limit |d| holds for it where it holds for each corner c with |c|_1 >= |c|. Most beams asked
  // lie inside the outline, where each side fails at the first corner: the others' sums are
  // taken only when needed.
  const auto reach = [&f](int k) {
    return std::abs(f.corner[k].x) + std::abs(f.corner[k].y) + std::abs(f.corner[k].z);
  };
  const double first = reach(0);
  for (int s = 0; s < outline.sides; ++s) {
    const Outline::Side& side = outline.side[s];
    if (!(dot(f.corner[0], side.n) < -side.limit * first)) continue;
    int k = 1;
    while (k < 4 && dot(f.corner[k], side.n) < -side.limit * reach(k)) ++k;
    if (k == 4) return true;
  }
  return false;
}

bool BeamMisses::misses_box(const Frustum& f, const Box& box) {
  BeamSide sides[5];
  sides_of(f, sides);
  return past_any(sides, f.eye, box);
}

}  // namespace softtrace
