// Two traces of one ray that must agree to the bit (a faster way against the plain one): the same
// hit at the same t, bit for bit, after the same counted work (what the steps AOV sums), as one
// GoogleTest assertion.
#pragma once

#include <gtest/gtest.h>

#include <cstring>

#include "trace/tracer.h"

namespace softtrace::test {

inline ::testing::AssertionResult same_march(const MarchResult& a, const TraceCounters& wa,
                                             const MarchResult& b, const TraceCounters& wb) {
  if (a.hit != b.hit)
    return ::testing::AssertionFailure() << "hit " << a.hit << " against " << b.hit;
  if (std::memcmp(&a.t, &b.t, sizeof(double)) != 0)
    return ::testing::AssertionFailure() << "t " << a.t << " against " << b.t;
  if (wa.box_evals != wb.box_evals)
    return ::testing::AssertionFailure()
           << "box_evals " << wa.box_evals << " against " << wb.box_evals;
  if (wa.refine_iterations != wb.refine_iterations)
    return ::testing::AssertionFailure()
           << "refine_iterations " << wa.refine_iterations << " against " << wb.refine_iterations;
  if (wa.undecided != wb.undecided)
    return ::testing::AssertionFailure()
           << "undecided " << wa.undecided << " against " << wb.undecided;
  return ::testing::AssertionSuccess();
}

}  // namespace softtrace::test
