// The frame's nesting of blob beams, for tests that check what each level of it certifies.
#pragma once

#include <gtest/gtest.h>

#include "render/camera.h"
#include "trace/tracer.h"

namespace softtrace::test {

// A 16-pixel block's beam from no list, its four 8-pixel blocks' from it, and their four 4-pixel
// blocks' from those, over a w x h view (multiples of 16). `visit(level, x4, y4)` sees each
// 4-pixel block with the three levels' beams; the walk stops at the first fatal failure.
template <class Visit>
void for_each_nested_beam(const ObjectTracer& tr, const ViewCamera& camera, int w, int h,
                          Visit&& visit) {
  BlobBeam level[3];
  for (int y = 0; y < h; y += 16)
    for (int x = 0; x < w; x += 16) {
      tr.blob_beam(camera.frustum(x, y, x + 16, y + 16), nullptr, &level[0]);
      for (int q = 0; q < 4; ++q) {
        const int x8 = x + (q & 1) * 8, y8 = y + (q >> 1) * 8;
        tr.blob_beam(camera.frustum(x8, y8, x8 + 8, y8 + 8), &level[0], &level[1]);
        for (int k = 0; k < 4; ++k) {
          const int x4 = x8 + (k & 1) * 4, y4 = y8 + (k >> 1) * 4;
          tr.blob_beam(camera.frustum(x4, y4, x4 + 4, y4 + 4), &level[1], &level[2]);
          visit(level, x4, y4);
          if (testing::Test::HasFatalFailure()) return;
        }
      }
    }
}

}  // namespace softtrace::test
