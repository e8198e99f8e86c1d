#include "io/adler32.h"

#if defined(__x86_64__) || defined(__i386__)
#include <emmintrin.h>
#endif

namespace softtrace {

namespace {

constexpr uint32_t kBase = 65521;  // the largest prime below 2^16
// At most this many 16-byte chunks between two reductions: zlib's NMAX (5552 bytes), the most for
// which the scalar tail's s2 stays below 2^32 from any start below kBase. The vector lanes' largest
// sum, `before`, stays under 2^27 there.
constexpr size_t kChunksPerBlock = 5552 / 16;

// The scalar sums over at most kChunksPerBlock * 16 bytes.
void add_bytes(uint32_t& s1, uint32_t& s2, const unsigned char* p, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    s1 += p[i];
    s2 += s1;
  }
}

}  // namespace

uint32_t adler32_of(uint32_t adler, const unsigned char* p, size_t n) {
  uint32_t s1 = adler & 0xffff, s2 = adler >> 16;
#if defined(__x86_64__) || defined(__i386__)
  // Over k chunks of 16 bytes c[j][i]: s1 += sum c, and s2 += 16 k s1 + 16 sum_j (k - 1 - j)
  // S_j + sum_j sum_i (16 - i) c[j][i], with S_j chunk j's sum. `before` adds up, at each chunk,
  // the sums of the chunks before it (the middle term's), `weighted` the last term; 32-bit lanes
  // hold them within a block.
  const __m128i zero = _mm_setzero_si128();
  const __m128i weights_low = _mm_setr_epi16(16, 15, 14, 13, 12, 11, 10, 9);
  const __m128i weights_high = _mm_setr_epi16(8, 7, 6, 5, 4, 3, 2, 1);
  while (n >= 16) {
    const size_t chunks = n / 16 < kChunksPerBlock ? n / 16 : kChunksPerBlock;
    __m128i sums = zero, before = zero, weighted = zero;
    for (size_t j = 0; j < chunks; ++j, p += 16) {
      const __m128i c = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
      before = _mm_add_epi32(before, sums);
      sums = _mm_add_epi32(sums, _mm_sad_epu8(c, zero));  // two 64-bit lanes' sums, each < 2^12
      weighted = _mm_add_epi32(weighted, _mm_madd_epi16(_mm_unpacklo_epi8(c, zero), weights_low));
      weighted = _mm_add_epi32(weighted, _mm_madd_epi16(_mm_unpackhi_epi8(c, zero), weights_high));
    }
    n -= chunks * 16;
    alignas(16) uint32_t lanes[3][4];
    _mm_store_si128(reinterpret_cast<__m128i*>(lanes[0]), sums);
    _mm_store_si128(reinterpret_cast<__m128i*>(lanes[1]), before);
    _mm_store_si128(reinterpret_cast<__m128i*>(lanes[2]), weighted);
    const uint64_t sum = uint64_t(lanes[0][0]) + lanes[0][2];
    const uint64_t earlier = uint64_t(lanes[1][0]) + lanes[1][2];
    const uint64_t weight = uint64_t(lanes[2][0]) + lanes[2][1] + lanes[2][2] + lanes[2][3];
    s2 = uint32_t((s2 + 16 * uint64_t(chunks) * s1 + 16 * earlier + weight) % kBase);
    s1 = uint32_t((s1 + sum) % kBase);
  }
#endif
  while (n > 0) {
    const size_t take = n < kChunksPerBlock * 16 ? n : kChunksPerBlock * 16;
    add_bytes(s1, s2, p, take);
    p += take;
    n -= take;
    s1 %= kBase;
    s2 %= kBase;
  }
  return (s2 << 16) | s1;
}

}  // namespace softtrace
