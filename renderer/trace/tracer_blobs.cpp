// first_hit for a sum of polynomial blobs (blob_ray.h): the ray is taken a stretch at a time (a
// sum of a few blobs: its whole way at once). One query of the sum's BVH (or the block's list)
// gives the blobs whose supports the stretch passes through, and
// their entries and exits cut it into pieces over which the field is one polynomial, walked
// front to back. A piece whose blobs' peaks cannot reach iso is skipped unread; any other is
// decided by its Bernstein form (bernstein.h), and a crossing refined on the polynomial itself,
// with no evaluation of the field. So every skip is certified by the hull of the exact
// polynomial, not by a Lipschitz bound. A shadow ray (Query::Any) stops at the first stretch
// whose blobs certainly hold one of its points (surely_inside), before reading any piece.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "eval/blob_frame_terms.h"
#include "kernels/potentials.h"
#include "trace/blob_events.h"
#include "trace/shadow_list_lanes.h"
#include "trace/tracer.h"
#include "trace/tracer_limits.h"
#include "trace/unlisted_stretches.h"

namespace softtrace {

using namespace tracer_limits;

namespace {
// The first stretch is this fraction of the ray's way through the box, or at most kFirstRadii
// typical blob radii (a stretch meets about as many blobs whatever their number). Measured at
// 320x240 on one thread: on 1000 blobs 1/4 took 0.16 s, 1/2 0.19 s, 1/8 0.17 s, the whole box at
// once 0.26 s; the cap of 2 radii took 10,000 blobs from 0.235 to 0.200 s (4 radii: no change).
constexpr double kFirstStretch = 4;
constexpr double kFirstRadii = 2;
// A stretch whose query finds more blobs than this makes the next one half as long, and one that
// finds fewer than kFewTerms twice as long: each query then costs about the same.
constexpr int kManyTerms = 16;
constexpr int kFewTerms = 4;
// A camera ray of a sum of more than BlobSum::kListed blobs sweeps its block's list
// (first_hit_blobs), whatever its length: the sweep reads no blob behind the hit, and a blob's
// terms one at a time cost what a list's do (BlobSum::terms_of_one: a ball's inline, a capsule's
// or ellipsoid's through frame_terms). Only sums with capsules took the short lists' blobs at
// once, while a capsule's terms took a call of terms_of each (pov:chain +1.8 % with the sweep
// then); since, sweeping every list against only those over 16 blobs, callgrind, whole
// process, 1 thread, 320x240: pov:chain -0.6 %, pov:golfball -1.0 %, cloud300 -0.8 %, the same
// bits (the terms are taken in the list's order either way, and their events ordered alike).

// A shadow ray with a block's list whose blobs on its way number at most this many takes its way
// as one stretch (first_hit_blobs): a choice measured on pov:chain and pov:golfball, not a
// certificate.
constexpr int kWholeShadowList = 16;
// The entries whole_shadow's count (first_hit_blobs) reads between its tests of the count so far.
constexpr int kCountBlock = 8;

// One thread's buffers, grown to the largest sum traced (no allocation per ray after that).
struct BlobScratch {
  std::vector<BlobSum::Term> terms;
  std::vector<int32_t> ids;
  std::vector<BlobBeam::Entry> line;     // a shadow ray's entries its line meets (first_hit_blobs)
  std::vector<BlobEvent> enters, exits;  // blob_events.h
  std::vector<BlobEventOfBoth> both;
  std::vector<int> active;
  // The sizes the buffers have room for (`ids`; the others, terms): two loads to compare, where
  // the vectors' sizes were two subtractions and shifts each.
  int ids_room = 0, terms_room = 0;
  // Out of line: it runs once per thread and sum, and inline its resizes would crowd every ray's
  // lookup (blob_scratch).
  [[gnu::noinline]] void fit(const BlobSum& blobs) {
    const int n = blobs.max_terms();
    if (static_cast<int>(ids.size()) < blobs.size()) {
      ids.resize(blobs.size());
      line.resize(blobs.size());
    }
    if (static_cast<int>(terms.size()) < n) {
      terms.resize(n);
      enters.resize(n);
      exits.resize(n);
      both.resize(2 * n);
      active.resize(n);
    }
    ids_room = static_cast<int>(ids.size());
    terms_room = static_cast<int>(terms.size());
  }
};

// The thread's scratch, with room for `blobs`. Inline, with fit() out of line: a ray's lookup was
// a call of 38 instructions (9.7 M of blob1000's at 640x480), most of them the size checks.
inline BlobScratch& blob_scratch(const BlobSum& blobs) {
  thread_local BlobScratch scratch;
  if (blobs.size() > scratch.ids_room || blobs.max_terms() > scratch.terms_room) scratch.fit(blobs);
  return scratch;
}

// A point u of a stretch certainly in the solid, if this finds one: the sum at u of the polynomials
// the pieces are read from (stretch_polynomial's P(r(u)) of every term whose range holds u) is
// above iso by far more than its rounding. A shadow ray needs no more: any point of the solid on it
// blocks the light, and the pieces before u, searched front to back, would find a crossing there
// or before it. Tried where the strongest blob comes nearest the ray, unless that is the ray's
// own start (`at_start`: the first stretch from t0): a shadow ray starts at a lit point lifted off
// its surface, outside the solid, where the sum is below iso. pov:golfball's rays leave its big
// ball, whose nearest point to its centre lies behind them: the test there read every term and
// failed (6 of its 128 M shadow instructions). A ray that does start inside is found by its
// first piece (Rise::AtStart), for one evaluation as here.
// `peaks`: the sum of the terms' peaks in their order (first_hit_blobs took it for its own test).
std::optional<double> surely_inside(const BlobSum::Term* terms, int n, double peaks, double iso,
                                    bool at_start) {
  int best = -1;
  for (int i = 0; i < n; ++i)
    if (best < 0 || terms[i].peak > terms[best].peak) best = i;
  if (best < 0 || peaks < iso) return std::nullopt;
  const BlobSum::Term& b = terms[best];
  const double u = std::min(std::max(b.mid, b.enter), b.exit);  // its range's point nearest mid
  if (at_start && !(u > 0)) return std::nullopt;
  double sum = 0, magnitude = iso;
  for (int i = 0; i < n; ++i) {
    const BlobSum::Term& k = terms[i];
    if (!(u >= k.enter && u <= k.exit)) continue;
    const double r = k.h2 - k.alpha * (u - k.mid) * (u - k.mid);
    const double p = polynomial_potential(r, k.c2, k.c3);
    sum += p;
    magnitude += std::abs(p);
  }
  if (sum - iso > 1e-9 * magnitude) return u;
  return std::nullopt;
}

// Whether `peak`, a sum of terms' peaks (each >= 0: BlobSum::Term), certifies that every piece
// made of some of those terms fails its own peak test (first_hit_blobs): a piece sums some of
// them in another order, which rounds them otherwise by less than 1e-15 of the sum per term, and
// counts at most max_terms() terms; the margin here is larger than both.
bool peaks_below_iso(double peak, const BlobSum& blobs, double iso) {
  const double n = blobs.max_terms();
  return peak * (1 + 1e-12 + 1e-15 * n) + n * 1e-15 < iso;
}

// Whether the field stays below iso all along the stretch o + u d, u in [0, len], of a camera
// ray whose list is sifted (BlobBeam::adders), from the terms of its blobs that may add alone:
// those whose ranges meet [lo, hi], the entries the sweep would take. The field is the sum of all
// the blobs' potentials, each blob that only subtracts adds at most 0, and each term's peak bounds
// its potential over its range (BlobSum::Term), so the field stays below the sum of the adders'
// peaks. Tested by peaks_below_iso (a subtracting term's peak is 0). So where this holds,
// every piece of the sweep would fail its own peak test: the same miss and the same count of
// work, without taking the subtracting blobs' terms (pov:golfball: a ray through the big ball's
// support beside its surface takes none of its dimples'). `terms` is scratch.
bool adders_below_iso(const BlobSum& blobs, const BlobBeam& list, const Vec3& o, const Vec3& d,
                      double dd, double len, double lo, double hi, double iso,
                      BlobSum::Term* terms) {
  double peak = 0;
  for (const int32_t i : list.adders) {
    const BlobBeam::Entry& e = list.entries[i];
    if (e.near > hi) break;  // sorted by near
    if (e.far < lo) continue;
    const int k = blobs.terms_of_one(e.id, o, d, dd, len, terms);
    for (int j = 0; j < k; ++j) peak += terms[j].peak;
  }
  return peaks_below_iso(peak, blobs, iso);
}

// first_rise_of and refine_rise_of (bernstein.h) for a piece's polynomial, whose degree is 4 or 6
// (stretch_polynomial: 6 where a term has c3 != 0; a lower one would be searched as 6, its higher
// coefficients zero: the same polynomial). first_rise's dispatch over all seven degrees put the
// code of the five a piece never has into the pieces' loop: callgrind, whole process, blob1000 at
// 640x480 -3.6 M, pov:golfball at 320x240 -0.6 M.
Rise first_rise_of_piece(const StretchPolynomial& sp, double tol, double finest) {
  static_assert(kMaxDegree == 6, "a piece's degree is 4 or kMaxDegree");
  return sp.degree == 4 ? first_rise_of<4>(sp.a, sp.err, tol, finest)
                        : first_rise_of<6>(sp.a, sp.err, tol, finest);
}
Rise refine_rise_of_piece(const StretchPolynomial& sp, Rise r, double tol, int* steps) {
  return sp.degree == 4 ? refine_rise_of<4>(sp.a, r, tol, steps)
                        : refine_rise_of<6>(sp.a, r, tol, steps);
}
}  // namespace

Vec3 ObjectTracer::blob_gradient(const Vec3& p, double* terms, const BlobBeam* list) const {
  Vec3 grad;
  if (!list) {
    blobs_->gradient(program_, p, &grad, blob_scratch(*blobs_).ids.data(), terms);
    return grad;
  }
  // A list of up to kOnStack blobs (most camera lists) takes its ids on the stack: the
  // thread-local scratch's lookup and size checks were a third of this function's instructions.
  constexpr size_t kOnStack = 256;
  int32_t on_stack[kOnStack];
  int32_t* ids = list->entries.size() <= kOnStack ? on_stack : blob_scratch(*blobs_).ids.data();
  // A sum of at most kListed blobs gives gradient_among its whole list: that keeps the blobs whose
  // support holds p and no other, whatever it is given, so the ranges' test below only spares it
  // blobs, and for so few its own comparisons and p's distance cost more (callgrind, whole
  // process, 320x240: pov:blob1a -0.42 %, blob1b -0.38 %, molecule -0.29 %; the same sums, the
  // same bits).
  if (blobs_->size() <= BlobSum::kListed) {
    int n = 0;
    for (const BlobBeam::Entry& e : list->entries) ids[n++] = e.id;
    blobs_->gradient_among(program_, p, ids, n, &grad, terms);
    return grad;
  }
  // A blob whose support holds p is on the list, and p's distance from the eye lies in its range
  // (tracer_blob_beam.cpp; the ranges' slack is far above p's rounding): the list's blobs whose
  // ranges hold it are all the point query could give, for a few comparisons each (the query's
  // walk was 8 % of a dense cloud's frame).
  // A larger sum's camera list is sorted by near (blob_beam): none past the first beyond dist
  // holds p.
  const bool sorted = list->camera();
  const double dist = length(p - list->eye);
  int n = 0;
  for (const BlobBeam::Entry& e : list->entries) {
    if (sorted && e.near > dist) break;
    ids[n] = e.id;
    n += e.near <= dist && e.far >= dist;
  }
  blobs_->gradient_among(program_, p, ids, n, &grad, terms);
  return grad;
}

MarchResult ObjectTracer::unlisted_stretches(double t0, double t1, TraceCounters& work) const {
  // first_hit_blobs' loop below with no blob on the list (its stretches after one of fewer than
  // kFewTerms terms twice as long).
  static_assert(kFewTerms > 0);
  double t = t0;
  if (count_unlisted_stretches(t, t1, work)) return {};
  ++work.give_ups;
  return {true, t, false, true};
}

MarchResult ObjectTracer::first_hit_unlisted(const Ray& ray, double tfar, double clear_to,
                                             TraceCounters& work) const {
  // first_hit's clip and start (tnear = 0, a camera ray), then first_hit_blobs' answer for a
  // camera list that holds the ray and no blob: its stretches, counted.
  double t0 = 0, t1 = tfar;
  if (!clip_to_box(ray, target_.bounds, t0, t1)) return {};
  work.entered_box = true;
  t0 = std::max(t0, clear_to);
  if (t0 > t1) return {};
  return unlisted_stretches(t0, t1, work);
}

MarchResult ObjectTracer::few_blobs_shadow(const Ray& ray, bool face, double t0, double t1,
                                           TraceCounters& work) const {
  // first_hit_blobs' first turn for such a ray (no list: not held; at most kListed blobs: the
  // whole way, s = t1 - t0), to the bit: the same stretch, the same terms in the same order and
  // the same sum of their peaks. Where that turn would give up or leave more of the way (no way
  // at all, or t short of t1 by rounding), first_hit_blobs takes the ray from the start.
  if (!(t0 < t1) || work.evaluations() >= kMaxSteps)
    return first_hit_blobs(ray, face, t0, t1, work, Query::Any, nullptr);
  const double len = std::min(t0 + (t1 - t0), t1) - t0;
  if (t0 + len < t1) return first_hit_blobs(ray, face, t0, t1, work, Query::Any, nullptr);
  const Segment seg = segment(ray, t0, t0 + len);
  // On the stack: a capsule's terms are at most three (max_terms()); the thread's scratch, looked
  // up, cost more than most rays' terms.
  BlobSum::Term terms[3 * BlobSum::kListed];
  int32_t ids[BlobSum::kListed];
  const int n = blobs_->terms(program_, seg.a, ray.d, len, seg.pad, terms, ids);
  double peaks = 0;
  for (int i = 0; i < n; ++i) peaks += terms[i].peak;
  if (peaks_below_iso(peaks, *blobs_, target_.iso)) {
    ++work.box_evals;
    return {};
  }
  // Negative blobs near the surface, a ray grazing it, one into the solid: its pieces are read.
  const TakenTerms taken{terms, n};
  return first_hit_blobs(ray, face, t0, t1, work, Query::Any, nullptr, &taken);
}

MarchResult ObjectTracer::first_hit_blobs(const Ray& ray, bool face, double t0, double t1,
                                          TraceCounters& work, Query query, const BlobBeam* beam,
                                          const TakenTerms* taken) const {
  // A camera ray of a block with a list (tracer_blob_beam.cpp), or a shadow ray of a block with
  // one (tracer_shadow_beam.cpp), takes its stretches' blobs from it.
  double base = 0;   // the ray's start on the list's axis
  double across[2];  // a shadow list's ray: its origin's x and y on the prism's axes
  // Whether the ray takes its blobs from the list: an empty list holds no blob for it (its
  // entries' data() may then be null or not, as the vector's past left it, so it decides nothing;
  // taken for "no list", it cost a thread's first tiles walks that later ones skipped, and their
  // steps differed with the thread count).
  const bool held = beam && beam->holds(ray, &base, t1, &across);
  const bool camera_list = held && beam->camera() && query == Query::Nearest;
  // A camera ray whose list holds no blob (most of a sparse frame's background, the unmet beams
  // of EmbreeScene::intersect_unmet) only counts its stretches: before the scratch is looked up.
  if (camera_list && beam->entries.empty()) return unlisted_stretches(t0, t1, work);
  // A shadow ray of a block its blockers shut: blocked_by's answer and work, without its terms
  // (tracer_shadow_beam.cpp). A shadow ray's hit is read for its answer alone, not its t.
  if (held && query == Query::Any && beam->shut && shut_decides(ray, t0, t1, base, *beam)) {
    ++work.point_evals;
    return MarchResult{true, t0};
  }
  BlobScratch& scratch = blob_scratch(*blobs_);
  BlobSum::Term* terms = taken ? taken->terms : scratch.terms.data();
  int* active = scratch.active.data();
  const double iso = target_.iso;

  // The piece [u0, u0 + S] of the stretch from t, where terms[active[0..n)] are the blobs: the
  // first crossing in it, if any (a hit that is no crossing: the box's face).
  const auto piece = [&](double t, double u0, double S, int n) -> std::optional<MarchResult> {
    double peak = 0;  // rounded to a few ulps of each term's (r to a few ulps of 1)
    for (int i = 0; i < n; ++i) peak += terms[active[i]].peak;
    if (peak * (1 + 1e-12) + n * 1e-15 < iso) return std::nullopt;
    if (piece_peak(terms, active, n, u0, u0 + S) < iso) return std::nullopt;
    ++work.box_evals;
    const StretchPolynomial sp = stretch_polynomial(terms, active, n, u0, S, iso);
    const double tol = kDecide * footprint(ray, t + u0) / S;
    // Down to kFinestDeep of the tolerance: the hull's excess shrinks with the piece, so most
    // near-tangencies are decided there; what is not is passed and counted, never a hit.
    const Rise rise = first_rise_of_piece(sp, tol, kFinestDeep * tol);
    work.undecided += rise.undecided;
    const auto at = [&](double x) { return t + u0 + x * S; };
    switch (rise.kind) {
      case Rise::Clear:
        return std::nullopt;
      case Rise::AtStart:  // where the ray enters the box: the box cuts the solid (its face)
        return MarchResult{true, at(0), face && u0 == 0 && t == t0};
      case Rise::Bracket:
        break;
    }
    if (query == Query::Any) return MarchResult{true, at(rise.hi)};
    // On the polynomial, whose values cost a few multiplications, to the footprint at the
    // bracket's near end (the nearest the root can be).
    const double close = kRefine * footprint(ray, at(rise.lo)) / S;
    return MarchResult{true, at(refine_rise_of_piece(sp, rise, close, &work.refine_iterations).hi)};
  };

  const BlobBeam::Entry* listed = nullptr;
  int n_listed = 0;
  if (held) {
    listed = beam->entries.data();
    n_listed = static_cast<int>(beam->entries.size());
    // A shadow ray of a block whose blockers certify it ends before any stretch is read.
    if (query == Query::Any && !beam->blockers.empty())
      if (const std::optional<double> u = blocked_by(ray, t0, t1, *beam)) {
        ++work.point_evals;
        return MarchResult{true, *u};
      }
  }
  // A sum of at most kListed blobs takes the ray's whole way as one stretch: each blob's terms
  // once, not once per stretch. Stretches bound the terms one query gives where a ray may meet
  // many blobs (1000 blobs: a quarter of the way took 0.16 s, the whole way 0.26 s, above); with
  // a few, the second and later stretches only computed the same blobs' terms again (pov:blob, 3
  // balls: 2.7 stretches per camera ray, the terms 17 % of the frame).
  //
  // So does a camera ray with a block's list. A sum's of at most kListed blobs are all taken at
  // once. A larger sum's, sorted by `near` (the blobs' least distance from the eye, blob_beam),
  // is swept: its blobs' terms are taken in that order, each once, only as far as
  // the pieces need them. A piece [u0, u1] is read once every blob not yet taken has near - pad
  // beyond t0 + u1: none of their supports reaches back into it (tracer_blob_beam.cpp; the ray's
  // point at t is at distance t from the eye, to rounding within pad). So no blob behind the hit
  // is read, and the list once, not once per stretch (1000 blobs: stretches re-read the list and
  // recomputed the terms of each blob a stretch's end cut). Either way the pieces are one
  // stretch's over the whole way, rounded otherwise than a list-less ray's stretches: the root
  // agrees with that ray's within the refinement's tolerance, not to the bit. The lists are the
  // blocks' own, the same for any thread count, so the picture's bits are too.
  const bool sweep = camera_list && blobs_->size() > BlobSum::kListed;
  //
  // A shadow ray with a block's list whose blobs on its way (their ranges meeting [t0, t1] on the
  // list's axis) number at most kWholeShadowList takes its way as one stretch as well: each of
  // those blobs' terms once. In stretches of two typical radii (chain's 48 capsules: 3.0 stretches
  // a shadow ray), a blob that two stretches' ends cut had its terms taken twice, and each stretch
  // paid its segment, its scan of the list and its events. The count is a choice, not a
  // certificate: each stretch takes the listed blobs whose ranges meet its own, whatever its
  // length. A longer list (a floor's under a dense cloud) keeps the stretches, whose first may
  // end the ray (surely_inside) before the farther blobs' terms are taken.
  //
  // The count stops once it passes kWholeShadowList, a block of kCountBlock entries at a time
  // (the test between blocks, not a branch per entry): the same answer, and a long list lies
  // mostly on its rays' way. meets10 at 640x480: of 11,151 rays with lists over 16 entries,
  // 10,896 go in stretches, their lists 79 entries long on average; the count read each whole
  // (8.9 M instructions) where two or three blocks decide it (1.8 M).
  const auto whole_shadow = [&] {
    if (n_listed <= kWholeShadowList) return true;
    const double way_lo = base + t0, way_hi = base + t1;
    const auto on = [&](int i) { return listed[i].near <= way_hi && listed[i].far >= way_lo; };
    int on_way = 0, i = 0;
    for (; i + kCountBlock <= n_listed; i += kCountBlock) {
      for (int k = 0; k < kCountBlock; ++k) on_way += on(i + k);
      if (on_way > kWholeShadowList) return false;
    }
    for (; i < n_listed; ++i) on_way += on(i);
    return on_way <= kWholeShadowList;
  };
  const bool whole = blobs_->size() <= BlobSum::kListed || camera_list ||
                     (held && query == Query::Any && whole_shadow());
  // A ray of a prism's list runs along the prism's axis at its origin's (x, y) = across, so it
  // meets a blob's support only where its line passes within the blob's bounding sphere: within
  // `reach` (the radius with shadow_beam's slack, 1e-9 of the magnitudes) of the sphere's centre's
  // (x, y), as its block's prism meets the sphere within reach of its rectangle. A blob it does
  // not pass gives no term (its line misses the support by that slack, far above the terms'
  // rounding), so each stretch takes its blobs from the listed ones it passes, in the list's
  // order: the same terms in the same order, and its range test reads a few entries where it read
  // the list. meets10 at 640x480: a stretch of a shadow ray found 15.7 blobs by their ranges,
  // most of whose terms were none. The count of blobs on the way (whole_shadow) still reads the
  // whole list: it decides the stretches, and so the steps. A list built without its `across`
  // (by hand) is read whole. From here on, `listed` is what the stretches read.
  if (held && beam->parallel && beam->across.size() == beam->entries.size()) {
    n_listed = entries_on_line(*beam, across, scratch.line.data());
    listed = scratch.line.data();
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double dd = dot(ray.d, ray.d);  // terms_of's, for the sweep's blobs one at a time
  double t = t0;
  double s =
      whole ? t1 - t0 : std::min((t1 - t0) / kFirstStretch, kFirstRadii * blobs_->typical_radius());
  // Past a stretch of `len` whose terms numbered n: the next one shorter where they were many,
  // longer where they were few.
  const auto next_stretch = [&](double len, int n) {
    t += len;
    if (n > kManyTerms) s = 0.5 * len;
    if (n < kFewTerms) s = 2 * len;
  };
  while (t < t1) {
    if (work.evaluations() >= kMaxSteps) {
      ++work.give_ups;
      return {true, t, false, true};
    }
    const double len = std::min(t + s, t1) - t;
    ++work.box_evals;
    const Segment seg = segment(ray, t, t + len);
    const double lo = base + t - seg.pad, hi = base + t + len + seg.pad;
    int n = 0;
    if (sweep) {
      // Taken in the loop below, unless the blobs that may add cannot reach iso on the stretch.
      if (beam->sifted &&
          adders_below_iso(*blobs_, *beam, seg.a, ray.d, dd, len, lo, hi, iso, terms)) {
        t += len;
        continue;
      }
    } else if (held) {
      // The list's blobs whose ranges on its axis meet the stretch's, in the list's order.
      int32_t* ids = scratch.ids.data();
      int found = 0;
      // Four entries a turn: the loop's own count and branch were 2 of an entry's 10 instructions
      // (meets10 at 640x480: 2.27 M entries; callgrind, whole process, -3.9 M; eight a turn
      // another -0.65 M, for twice the code).
#pragma GCC unroll 4
      for (int i = 0; i < n_listed; ++i) {
        ids[found] = listed[i].id;
        found += listed[i].near <= hi && listed[i].far >= lo;
      }
      n = blobs_->terms_of(ids, found, seg.a, ray.d, len, terms);
    } else if (taken) {  // this very stretch's, taken by few_blobs_shadow
      n = taken->n;
      taken = nullptr;
    } else {
      n = blobs_->terms(program_, seg.a, ray.d, len, seg.pad, terms, scratch.ids.data());
    }
    // A stretch whose terms, all taken (no sweep), have peaks summing below iso: every piece
    // would fail its peak test (peaks_below_iso), so its events and pieces are not walked, for
    // the same miss and the same count of work. Most shadow rays leave their lit point so
    // (pov:chain at 640x480: of 193,876 pieces of its 64,045 shadow rays, 893 passed the test).
    // Before surely_inside, which takes the same sum and finds no point where it is below iso.
    // (A sweep has taken no term yet: n is 0, and so is the sum.)
    double peaks = 0;
    for (int i = 0; i < n; ++i) peaks += terms[i].peak;
    if (!sweep && peaks_below_iso(peaks, *blobs_, iso)) {
      next_stretch(len, n);
      continue;
    }
    if (query == Query::Any)
      if (const std::optional<double> u = surely_inside(terms, n, peaks, iso, t == t0)) {
        ++work.point_evals;
        return MarchResult{true, t + *u};
      }
    // Between consecutive events the active terms are fixed: one polynomial. `events` holds
    // those still ahead; a sweep's next blob to take is listed[next].
    BlobEvents events(scratch.enters.data(), scratch.exits.data());
    events.take_all(terms, n, scratch.both.data());
    int next = sweep ? 0 : n_listed;
    int n_active = 0;
    double u0 = 0;
    // No blob not yet taken has support before `frontier`.
    const auto frontier_at = [&](int i) {
      return i < n_listed ? listed[i].near - base - t - seg.pad : kInf;
    };
    double frontier = frontier_at(next);
    // A cloud's sweep takes its balls four list entries at a time: their terms at once
    // (ball_terms4: the same bits as terms_of_one's, lane by lane), listed[i]'s in terms[i] where
    // bit i - from of `has` is set, and then the events of all four, before the walk reads on.
    // One ball at a time, each term's division, square root and branches waited on the one
    // before (perf: a fifth of this function's time on blob1000 at 640x480). The last four
    // entries may be computed twice: the same bits again in the same slots.
    //
    // A blob taken sooner than the walk needs it leaves the walk as it was: its events take the
    // same places among the events ahead (an entry's u is at or past the frontier, past every
    // event read; of equal events, those of the blob taken first first, exits before entries,
    // whenever each was taken), so the same pieces with their terms in the same order, and the
    // same hit. It costs the events of a block's balls past the hit, and saves the walk's return
    // between two entries (its next event's choice and the frontier's test): callgrind, whole
    // process, 1 thread, the 1000-blob frame at 640x480 -2.1 %, meets10 -0.7 %.
    const bool four_at_once = sweep && blobs_->all_balls() && n_listed >= 4;
    while (true) {
      bool exit;
      if (events.next_by(frontier, &exit)) {
        const BlobEvent ev = events.next(exit);
        events.pop(exit);
        const double u1 = ev.u;
        // The hit's fields returned one by one: `return *hit` copied the optional in words that
        // straddled the bytes and word it was built from, two failed store forwardings a hit
        // (perf, meets10 at 640x480: 2 % of this function's time on that load). A piece's hit
        // never gave up.
        if (u1 > u0 && n_active > 0)
          if (const auto hit = piece(t, u0, u1 - u0, n_active))
            return MarchResult{true, hit->t, hit->on_box_face};
        u0 = std::max(u0, u1);
        if (!exit) {
          active[n_active++] = ev.index;
          continue;
        }
        *std::find(active, active + n_active, ev.index) = active[n_active - 1];
        --n_active;
        continue;
      }
      if (next >= n_listed) break;
      if (four_at_once) {
        // Slots [from, from + 4): within terms' room, which holds max_terms() = size() >=
        // n_listed.
        const int from = std::min(next, n_listed - 4);
        const BlobBeam::Entry* f = listed + from;
        const unsigned has =
            blobs_->ball_terms4({f[0].id, f[1].id, f[2].id, f[3].id}, seg.a, ray.d, dd, len,
                                *reinterpret_cast<BlobSum::Term(*)[4]>(terms + from));
        for (; next < from + 4; ++next) {
          const BlobBeam::Entry& e = listed[next];
          if (e.near > hi) {  // sorted: no blob from here on reaches the way
            next = n_listed;
            break;
          }
          if (e.far < lo || !(has >> (next - from) & 1)) continue;
          events.add(terms[next].enter, terms[next].exit, next);
          ++n;
        }
        frontier = frontier_at(next);
        continue;
      }
      const BlobBeam::Entry& e = listed[next++];
      frontier = frontier_at(next);
      if (e.near > hi) {  // sorted: no blob from here on reaches the way
        next = n_listed;
        frontier = kInf;
        continue;
      }
      if (e.far < lo) continue;
      // BlobSum::terms_of_one with a capsule's or ellipsoid's terms inline (blob_frame_terms.h).
      const int k = blob_frame::terms_of_one(*blobs_, e.id, seg.a, ray.d, dd, len, terms + n);
      // Their events among those ahead, kept in order (of equal events, the one taken first
      // first).
      for (int i = n; i < n + k; ++i) events.add(terms[i].enter, terms[i].exit, i);
      n += k;
    }
    next_stretch(len, n);
  }
  return {};
}

}  // namespace softtrace
