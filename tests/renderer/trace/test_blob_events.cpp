// The entries and exits of a stretch's blobs as two streams (renderer/trace/blob_events.h) give
// the events in the very order first_hit_blobs' one array gave them: a stretch's whole set sorted
// by std::sort, and a sweep's blobs inserted one by one among the events still ahead. Ties are
// the point: blobs the stretch's start or end cuts share u = 0 or u = len, and the order of equal
// events is the order of the stretch's sums.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "trace/blob_events.h"

namespace softtrace::test {
namespace {

struct Read {
  double u;
  int32_t index;
  bool enters;
  bool operator==(const Read& o) const {
    return u == o.u && index == o.index && enters == o.enters;
  }
};

std::ostream& operator<<(std::ostream& os, const Read& r) {
  return os << (r.enters ? "enter " : "exit ") << r.index << " at " << r.u;
}

// A term's range [enter, exit] (enter < exit), from a few values so that many coincide.
BlobSum::Term random_term(std::mt19937_64& rng) {
  static constexpr double kValues[] = {0, 0.25, 0.5, 0.75, 1};
  std::uniform_int_distribution<int> pick(0, 4);
  int a = pick(rng), b = pick(rng);
  while (a == b) b = pick(rng);
  BlobSum::Term t{};
  t.enter = kValues[std::min(a, b)];
  t.exit = kValues[std::max(a, b)];
  return t;
}

// Reads every event ahead, or up to `limit` of them.
std::vector<Read> read(BlobEvents& events, int limit = 1 << 30) {
  std::vector<Read> out;
  while (!events.empty() && static_cast<int>(out.size()) < limit) {
    const bool exit = events.exit_next();
    const BlobEvent ev = events.next(exit);
    events.pop(exit);
    out.push_back({ev.u, ev.index, !exit});
  }
  return out;
}

}  // namespace

TEST(BlobEvents, AStretchsEventsComeInTheOneArraysSortedOrder) {
  std::mt19937_64 rng(25);
  int larger = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int n = 1 + trial % 24;  // both sides of std::sort's 16 events
    std::vector<BlobSum::Term> terms(n);
    for (BlobSum::Term& t : terms) t = random_term(rng);
    // first_hit_blobs before: the one array, by std::sort.
    std::vector<BlobEventOfBoth> one(2 * n);
    for (int i = 0; i < n; ++i) {
      one[2 * i] = {terms[i].enter, i, true};
      one[2 * i + 1] = {terms[i].exit, i, false};
    }
    std::sort(one.begin(), one.end());
    std::vector<Read> expected;
    for (const BlobEventOfBoth& e : one) expected.push_back({e.u, e.index, e.enters});

    std::vector<BlobEvent> enters(n), exits(n);
    std::vector<BlobEventOfBoth> both(2 * n);
    BlobEvents events(enters.data(), exits.data());
    events.take_all(terms.data(), n, both.data());
    ASSERT_EQ(read(events), expected) << "trial " << trial << ", " << n << " terms";
    larger += n > 8;
  }
  EXPECT_GT(larger, 5000);
}

TEST(BlobEvents, ASweepsBlobsTakeTheirPlacesAmongTheEventsAhead) {
  std::mt19937_64 rng(26);
  std::bernoulli_distribution take(0.5);
  for (int trial = 0; trial < 20000; ++trial) {
    const int n = 1 + trial % 30;
    std::vector<BlobSum::Term> terms(n);
    for (BlobSum::Term& t : terms) t = random_term(rng);
    // first_hit_blobs before: each blob's entry, then its exit, inserted from the end of the
    // events ahead, [head, n_events) of one array.
    std::vector<BlobEventOfBoth> one(2 * n);
    int head = 0, n_events = 0;
    const auto insert = [&](const BlobEventOfBoth x) {
      int j = n_events++;
      for (; j > head && x < one[j - 1]; --j) one[j] = one[j - 1];
      one[j] = x;
    };
    std::vector<BlobEvent> enters(n), exits(n);
    BlobEvents events(enters.data(), exits.data());
    // The blobs are taken one at a time, and between two a few events read (as the sweep reads
    // those before its frontier), until every event is read.
    int taken = 0;
    while (taken < n || head < n_events) {
      if (taken < n && (head == n_events || take(rng))) {
        const BlobSum::Term& t = terms[taken];
        insert({t.enter, taken, true});
        insert({t.exit, taken, false});
        events.add(t.enter, t.exit, taken);
        ++taken;
        continue;
      }
      const int count = std::uniform_int_distribution<int>(1, n_events - head)(rng);
      std::vector<Read> expected;
      for (int k = 0; k < count; ++k, ++head)
        expected.push_back({one[head].u, one[head].index, one[head].enters});
      ASSERT_EQ(read(events, count), expected) << "trial " << trial;
    }
    EXPECT_TRUE(events.empty());
  }
}

// next_by, the walk's one question (first_hit_blobs), asks what empty(), exit_next() and next()
// answer apart: whether the next event lies at or before a limit, and in which stream. Limits
// on, between and beyond the events' values, ties between an entry and an exit among them.
TEST(BlobEvents, NextByAnswersAsTheHeadsDoApart) {
  std::mt19937_64 rng(27);
  static constexpr double kLimits[] = {-1, 0, 0.1, 0.25, 0.5, 0.6, 0.75, 1, 2};
  int ahead = 0, exits = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const int n = 1 + trial % 12;
    std::vector<BlobSum::Term> terms(n);
    for (BlobSum::Term& t : terms) t = random_term(rng);
    std::vector<BlobEvent> enters(n), exits_of(n);
    BlobEvents events(enters.data(), exits_of.data());
    for (int i = 0; i < n; ++i) events.add(terms[i].enter, terms[i].exit, i);
    while (true) {
      for (const double limit : kLimits) {
        const bool exit = events.exit_next();
        const bool expected = !events.empty() && events.next(exit).u <= limit;
        bool got_exit = !exit;
        ASSERT_EQ(events.next_by(limit, &got_exit), expected) << "trial " << trial;
        if (!expected) continue;
        ASSERT_EQ(got_exit, exit) << "trial " << trial << ", limit " << limit;
        ++ahead;
        exits += exit;
      }
      if (events.empty()) break;
      events.pop(events.exit_next());
    }
  }
  EXPECT_GT(exits, 1000);
  EXPECT_GT(ahead - exits, 1000);
}

}  // namespace softtrace::test
