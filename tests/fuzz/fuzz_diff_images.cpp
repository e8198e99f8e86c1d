// libFuzzer target: arbitrary bytes through `diff`'s image reader (EXR through OpenEXR, PNG of 8
// or 16 bits through libpng, told apart by their first bytes), and for an image that reads, the
// comparison and the difference image against itself and against a small fixed image. Bad input
// must end in a std::runtime_error, never a crash or a sanitizer report. Built by tools/dev.sh
// test in build-fuzz/ and run there for a bounded time, seeded with images softtrace wrote and
// reference_images/.
#include <cstdint>
#include <cstdlib>

#include "fuzz_image_input.h"
#include "io/image_compare.h"
#include "io/image_file.h"

using namespace softtrace;

namespace {

// 3x2 R,G,B,A in the middle of a 5x4 frame.
ImageFile reference() {
  ImageFile r;
  r.full_width = 5;
  r.full_height = 4;
  r.x0 = r.y0 = 1;
  r.width = 3;
  r.height = 2;
  r.channels = {"R", "G", "B", "A"};
  for (int i = 0; i < 24; ++i) r.pixels.push_back(float(i) / 23);
  return r;
}

// Channels of `a` that `b` has, by name (as diff pairs them).
ChannelPairs shared(const ImageFile& a, const ImageFile& b) {
  ChannelPairs p;
  for (size_t c = 0; c < a.channels.size(); ++c) {
    const int other = b.channel(a.channels[c]);
    if (other >= 0) {
      p.a.push_back(int(c));
      p.b.push_back(other);
    }
  }
  return p;
}

void require(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const FuzzImageInput input("diff");
  ImageFile img;
  if (!input.read(data, size, &img)) return 0;
  require(img.width > 0 && img.height > 0 && !img.channels.empty() &&
          img.pixels.size() == size_t(img.width) * img.height * img.channels.size());
  // Against itself no pixel fails but for NaN and infinities.
  const ChannelPairs self = shared(img, img);
  const CompareResults same = compare_images(img, img, self, {});
  require(same.nfail <= same.nonfinite);
  difference_image(img, img, self, true, 2.0f);
  // Against the reference over the union of the windows, as diff does when it is not too large.
  const ImageFile ref = reference();
  const ChannelPairs with_ref = shared(img, ref);
  if (!with_ref.a.empty() && union_pixels(img, ref) <= (1LL << 20)) {
    compare_images(img, ref, with_ref, {});
    difference_image(img, ref, with_ref, false, 1.0f);
  }
  return 0;
}
