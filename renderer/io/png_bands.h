// A PNG's rows made and deflated in bands, each band a run of the image's one zlib stream
// (png_io.cpp writes the file around them). A band's bytes depend on the image's size and on the
// rows it reads alone, so bands deflated in any order, on any threads, at any time once those rows
// are final, make the same file. A render deflates each band as soon as the tiles that cover its
// rows are traced, while the frame's other tiles are still traced (pixels_final).
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "io/image_file.h"

namespace softtrace {

class PngBands {
 public:
  // The image's rows are row(y, ...) (io/image_file.h's PngRow), which must stay valid while the
  // bands are deflated. Throws std::runtime_error for a shape no PNG holds.
  PngBands(int width, int height, int channels, PngRow row);
  ~PngBands();
  PngBands(const PngBands&) = delete;
  PngBands& operator=(const PngBands&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  size_t count() const { return count_; }
  // The rows band b reads, [first, end): its own and, before them, the rows it takes as history.
  int first_row_read(size_t b) const;
  int end_row(size_t b) const;

  // Counts `width` pixels of each row in [y0, y1) as final (no longer written): a band all of
  // whose rows read are final is deflated at once, on the calling thread, before this returns.
  // Every pixel is to be counted once at most; calls may come from several threads at once.
  void pixels_final(int y0, int y1, int width);

  // Deflates every band not yet deflated (those of rows never counted final), through `each`
  // (image_file.h; empty: in order on this thread). Then false if any band failed to deflate.
  bool deflate_rest(const EachIndex& each);

  // Band b's deflated bytes, its rows' filtered bytes' Adler-32 and their count (after
  // deflate_rest).
  const std::vector<unsigned char>& data(size_t b) const;
  unsigned long adler(size_t b) const;
  unsigned long length(size_t b) const;

  struct Band;  // png_bands.cpp

 private:
  void deflate(size_t b);

  const int width_, height_, channels_;
  const PngRow row_;
  int band_rows_ = 1;
  size_t count_ = 0;
  std::unique_ptr<Band[]> bands_;
};

// Writes the PNG of `bands` to `path`, deflating first the bands not yet deflated through `each`
// (deflate_rest). With `srgb` the file says so. Throws std::runtime_error.
void write_png(const std::string& path, bool srgb, PngBands& bands, const EachIndex& each = {});

}  // namespace softtrace
