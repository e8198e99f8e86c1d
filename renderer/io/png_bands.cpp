// A PNG's bands of rows, filtered and deflated with zlib (png_bands.h).
#include "io/png_bands.h"

#include <zlib.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "io/adler32.h"

namespace softtrace {

// A band of rows, filtered and deflated: a run of the image's zlib stream (raw deflate).
struct PngBands::Band {
  std::vector<unsigned char> data;
  uLong adler = 1;   // Adler-32 of the filtered bytes, for the stream's trailer (adler32.h)
  uLong length = 0;  // filtered bytes
  bool ok = false;
  bool deflated = false;
  // Pixels of the rows the band reads not yet counted final (pixels_final): the thread that
  // counts the last ones deflates the band. Acquire and release, so that it sees their pixels.
  std::atomic<long> unfinished{0};
};

namespace {

// A band's filtered rows are about this many bytes: 10 bands at 320x240 with alpha, so two or more
// threads share the converting and deflating evenly.
constexpr size_t kBandBytes = size_t(1) << 15;
// A larger image takes larger bands, up to about this many bytes: each band pays a deflateReset
// (its hash table cleared) and its history's deflateSetDictionary, 6.5 M instructions for the 38
// bands of 32 KiB at 640x480 with alpha. A band and its history stay within zlib's 64 KiB window
// buffer: beyond it deflate slides the window and rehashes its tables (fill_window, 7.3 M with
// bands of 77 kB).
constexpr size_t kLargestBandBytes = size_t(56) << 10;
constexpr size_t kMostBands = 16;
// The rows before a band that it takes as its history (deflateSetDictionary, at most 32 KiB):
// without them a band's first rows find no matches above them, and 320x240 files were up to 7 %
// larger than one stream's; with 2 they are -1.5 to +2.6 %.
constexpr int kHistoryRows = 2;

// A thread's buffers for its bands, kept from one band to the next: each band's own filtered rows
// (zeroed, then written over), deflate state (some 270 KB) and output buffer (the bound, 36 KB at
// 640x480, kept until the file was written) took fresh memory, a page fault per 4 KiB, 205 of a
// 640x480 process's 250 in the PNG. deflateReset is deflateEnd then deflateInit2 without
// freeing the state (zlib.h): the same stream.
struct BandScratch {
  std::vector<unsigned char> rows, out;
  z_stream z{};
  bool z_made = false;
  bool busy = false;  // a band of this thread's in progress
  BandScratch() = default;
  BandScratch(const BandScratch&) = delete;
  BandScratch& operator=(const BandScratch&) = delete;
  ~BandScratch() {
    if (z_made) deflateEnd(&z);
  }
  // A raw deflate stream at level 1, as new.
  bool fresh_stream() {
    if (z_made) return deflateReset(&z) == Z_OK;
    z_made = deflateInit2(&z, 1, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) == Z_OK;
    return z_made;
  }
};

// At least `n` bytes of `v`, whose contents the caller writes over.
unsigned char* at_least(std::vector<unsigned char>& v, size_t n) {
  if (v.size() < n) v.resize(n);
  return v.data();
}

// Rows [y0, y1), each its filter byte (0: None, as libpng's simplified writer's FAST flag chose)
// and its samples, deflated at zlib's level 1 (a 320x240 render's image in 1.07 ms instead of
// 1.33 at the level 3 that flag took, its file 7 % larger). A band but the last ends with a sync
// flush, on a byte boundary, so that the next band's blocks follow it in one stream (as pigz joins
// its pieces); the last ends the stream.
void deflate_band(const PngRow& row, int y0, int y1, size_t row_bytes, bool last,
                  PngBands::Band& out) {
  // A row that ran parallel tasks could start another band on this thread before this one ends:
  // that one takes buffers of its own.
  thread_local BandScratch kept;
  BandScratch spare;
  BandScratch& scratch = kept.busy ? spare : kept;
  scratch.busy = true;
  struct Release {
    BandScratch& s;
    ~Release() { s.busy = false; }
  } release{scratch};
  // The rows before the band first, as its history: made again here, they give the band's first
  // rows the matches one stream would find above them.
  const int p0 = std::max(0, y0 - kHistoryRows);
  const size_t rows_bytes = (row_bytes + 1) * size_t(y1 - p0);
  unsigned char* const rows = at_least(scratch.rows, rows_bytes);
  for (int y = p0; y < y1; ++y) {
    unsigned char* r = &rows[(row_bytes + 1) * size_t(y - p0)];
    r[0] = 0;
    row(y, r + 1);
  }
  const unsigned char* history = rows;
  const size_t history_bytes = (row_bytes + 1) * size_t(y0 - p0);
  const unsigned char* band = history + history_bytes;
  const size_t band_bytes = rows_bytes - history_bytes;
  out.length = uLong(band_bytes);
  out.adler = adler32_of(1, band, band_bytes);
  if (!scratch.fresh_stream()) return;
  z_stream& z = scratch.z;
  const size_t window = std::min<size_t>(history_bytes, size_t(1) << 15);
  if (window > 0 &&
      deflateSetDictionary(&z, history + history_bytes - window, uInt(window)) != Z_OK)
    return;
  // deflateBound is for one whole stream; a sync flush adds an empty stored block (5 bytes).
  const size_t bound = deflateBound(&z, uLong(band_bytes)) + 16;
  z.next_in = const_cast<unsigned char*>(band);
  z.avail_in = uInt(band_bytes);
  z.next_out = at_least(scratch.out, bound);
  z.avail_out = uInt(bound);
  const int status = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
  out.ok = last ? status == Z_STREAM_END : status == Z_OK && z.avail_in == 0 && z.avail_out > 0;
  out.data.assign(scratch.out.data(), scratch.out.data() + (bound - z.avail_out));
}

}  // namespace

PngBands::PngBands(int width, int height, int channels, PngRow row)
    : width_(width), height_(height), channels_(channels), row_(std::move(row)) {
  if (channels < 1 || channels > 4) throw std::runtime_error("a PNG holds 1 to 4 channels");
  if (width < 1 || height < 1) throw std::runtime_error("a PNG holds at least one pixel");
  const size_t row_bytes = size_t(width) * channels;
  const size_t band_bytes =
      std::clamp((row_bytes + 1) * size_t(height) / kMostBands, kBandBytes, kLargestBandBytes);
  band_rows_ = int(std::clamp<size_t>(band_bytes / (row_bytes + 1), 1, size_t(height)));
  count_ = size_t((height + band_rows_ - 1) / band_rows_);
  bands_.reset(new Band[count_]);
  for (size_t b = 0; b < count_; ++b)
    bands_[b].unfinished.store(long(end_row(b) - first_row_read(b)) * width,
                               std::memory_order_relaxed);
}

PngBands::~PngBands() = default;

int PngBands::first_row_read(size_t b) const {
  return std::max(0, int(b) * band_rows_ - kHistoryRows);
}

int PngBands::end_row(size_t b) const {
  return std::min(height_, (int(b) + 1) * band_rows_);
}

void PngBands::deflate(size_t b) {
  const int y0 = int(b) * band_rows_;
  deflate_band(row_, y0, end_row(b), size_t(width_) * channels_, b + 1 == count_, bands_[b]);
  bands_[b].deflated = true;
}

void PngBands::pixels_final(int y0, int y1, int width) {
  // The bands whose rows read meet [y0, y1): from the one holding y0 to the one whose history
  // holds y1 - 1.
  const size_t first = size_t(std::max(0, y0) / band_rows_);
  const size_t last = std::min(count_ - 1, size_t((y1 - 1 + kHistoryRows) / band_rows_));
  for (size_t b = first; b <= last && y0 < y1; ++b) {
    const int rows = std::min(y1, end_row(b)) - std::max(y0, first_row_read(b));
    if (rows <= 0) continue;
    const long counted = long(rows) * width;
    if (bands_[b].unfinished.fetch_sub(counted, std::memory_order_acq_rel) == counted) deflate(b);
  }
}

bool PngBands::deflate_rest(const EachIndex& each) {
  std::vector<size_t> rest;
  for (size_t b = 0; b < count_; ++b)
    if (!bands_[b].deflated) rest.push_back(b);
  const auto band = [&](size_t i) { deflate(rest[i]); };
  if (each && rest.size() > 1)
    each(rest.size(), band);
  else
    for (size_t i = 0; i < rest.size(); ++i) band(i);
  for (size_t b = 0; b < count_; ++b)
    if (!bands_[b].ok) return false;
  return true;
}

const std::vector<unsigned char>& PngBands::data(size_t b) const {
  return bands_[b].data;
}

unsigned long PngBands::adler(size_t b) const {
  return bands_[b].adler;
}

unsigned long PngBands::length(size_t b) const {
  return bands_[b].length;
}

}  // namespace softtrace
