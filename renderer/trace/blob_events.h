// The entries and exits of blobs' supports along one stretch of a ray (first_hit_blobs,
// tracer_blobs.cpp), read in order of u: an exit before an entry at the same u, and of two equal
// entries (or two equal exits) the one added first first.
//
// Kept as two streams, the entries and the exits, each in that order. A blob the camera sweep
// takes places its entry among the pending entries and its exit among the pending exits; in one
// array of both, each insertion also stepped over the other kind's pending events (blob1000 at
// 640x480: 85 M instructions of first_hit_blobs' 530 M), and the sort of a whole stretch's
// events compared entries with exits. The walk takes the lesser head, an exit on a tie: the order
// the one array held, to the event, so the same pieces with their terms in the same order.
#pragma once

#include <algorithm>
#include <cstdint>

#include "eval/blob_ray.h"

namespace softtrace {

struct BlobEvent {
  double u;
  int32_t index;  // the term's
};

// One event of the one array first_hit_blobs sorted before (take_all's larger case).
struct BlobEventOfBoth {
  double u;
  int32_t index;
  bool enters;
  bool operator<(const BlobEventOfBoth& o) const {
    return u < o.u || (u == o.u && enters < o.enters);
  }
};

class BlobEvents {
 public:
  // Empty, over buffers with room for every term the stretch may take.
  BlobEvents(BlobEvent* enters, BlobEvent* exits) : enters_(enters), exits_(exits) {}

  // Term `index`'s entry and exit, each after the pending events of its kind at or before it.
  void add(double enter, double exit, int32_t index) {
    place(enters_, enter_head_, enter_end_, {enter, index});
    place(exits_, exit_head_, exit_end_, {exit, index});
  }

  // terms[0, n)'s events into empty streams, in the order std::sort of the one array
  // [enter 0, exit 0, enter 1, ...] gave them. Up to 16 events that sort is an insertion sort,
  // which keeps equal events in their index order, as add() in index order does; past 16 it
  // partitions, and equal events (blobs the stretch's start or end cuts share u = 0 or len)
  // come in its own order, which the stretch's sums follow: so that sort itself, then split.
  void take_all(const BlobSum::Term* terms, int n, BlobEventOfBoth* both) {
    constexpr int kStable = 8;  // std::sort's threshold, 16 events
    if (n <= kStable) {
      for (int i = 0; i < n; ++i) add(terms[i].enter, terms[i].exit, i);
      return;
    }
    sort_apart(terms, n, both, enters_, exits_);
    enter_end_ = exit_end_ = n;
  }

  bool empty() const { return enter_head_ == enter_end_ && exit_head_ == exit_end_; }
  // Whether the next event (not empty()) is an exit: the lesser head, an exit on a tie.
  bool exit_next() const { return exit_first(enter_head_ < enter_end_); }
  // Whether an event is ahead at or before `limit`: then *exit is exit_next() and the event
  // next(*exit). The walk's one question per step (first_hit_blobs), in one pass over the heads:
  // empty(), exit_next() and next()'s u asked apart tested each head's bounds twice and loaded the
  // lesser head's u again.
  bool next_by(double limit, bool* exit) const {
    const bool entries = enter_head_ < enter_end_;
    if (exit_first(entries)) {
      *exit = true;
      return exits_[exit_head_].u <= limit;
    }
    *exit = false;
    return entries && enters_[enter_head_].u <= limit;
  }
  const BlobEvent& next(bool exit) const {
    return exit ? exits_[exit_head_] : enters_[enter_head_];
  }
  void pop(bool exit) { ++(exit ? exit_head_ : enter_head_); }

 private:
  // exit_next() given whether an entry is left (`entries`), which next_by also needs.
  bool exit_first(bool entries) const {
    return exit_head_ < exit_end_ && (!entries || exits_[exit_head_].u <= enters_[enter_head_].u);
  }
  // take_all's larger case, apart from the streams' state (given `this`, a call there may keep
  // that state in memory through the whole walk, every store to an event reloading it).
  static void sort_apart(const BlobSum::Term* terms, int n, BlobEventOfBoth* both,
                         BlobEvent* enters, BlobEvent* exits) {
    for (int i = 0; i < n; ++i) {
      both[2 * i] = {terms[i].enter, i, true};
      both[2 * i + 1] = {terms[i].exit, i, false};
    }
    std::sort(both, both + 2 * n);
    int entered = 0, exited = 0;
    for (int i = 0; i < 2 * n; ++i)
      (both[i].enters ? enters[entered++] : exits[exited++]) = {both[i].u, both[i].index};
  }

  // Insertion from the end: a new event rarely passes more than a few pending ones of its kind.
  static void place(BlobEvent* s, int head, int& end, const BlobEvent x) {
    int j = end++;
    for (; j > head && x.u < s[j - 1].u; --j) s[j] = s[j - 1];
    s[j] = x;
  }

  BlobEvent* enters_;
  BlobEvent* exits_;
  int enter_head_ = 0, enter_end_ = 0;
  int exit_head_ = 0, exit_end_ = 0;
};

}  // namespace softtrace
