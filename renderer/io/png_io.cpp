// 8-bit PNG through libpng.
#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

#include "io/image_io.h"
#include "io/png_bands.h"

namespace softtrace {

namespace {

// libpng reports errors by longjmp: the functions that call it (reading or writing) hold nothing
// with a destructor, and the message goes to a buffer the caller owns, which starts with what to
// say if libpng gives no text.
struct PngCall {
  explicit PngCall(const char* fallback) { std::snprintf(message, sizeof message, "%s", fallback); }
  png_structp png = nullptr;
  png_infop info = nullptr;
  char message[200];
};

void on_png_error(png_structp png, png_const_charp text) {
  auto* call = static_cast<PngCall*>(png_get_error_ptr(png));
  std::snprintf(call->message, sizeof call->message, "%s", text);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// The header, with the transforms that give 8 or 16 bits per sample of grey or RGB, with alpha
// where the file has it (a palette expanded, tRNS as alpha), and no gamma conversion.
bool read_png_header(PngCall& r, FILE* f, png_uint_32& width, png_uint_32& height, int& channels,
                     int& bit_depth, size_t& row_bytes) {
  if (setjmp(png_jmpbuf(r.png))) return false;
  png_init_io(r.png, f);
  png_read_info(r.png, r.info);
  const int type = png_get_color_type(r.png, r.info);
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(r.png);
  if (type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(r.png, r.info) < 8)
    png_set_expand_gray_1_2_4_to_8(r.png);
  if (png_get_valid(r.png, r.info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(r.png);
  png_set_interlace_handling(r.png);
  png_read_update_info(r.png, r.info);
  width = png_get_image_width(r.png, r.info);
  height = png_get_image_height(r.png, r.info);
  channels = png_get_channels(r.png, r.info);
  bit_depth = png_get_bit_depth(r.png, r.info);
  row_bytes = png_get_rowbytes(r.png, r.info);
  return true;
}

bool read_png_rows(PngCall& r, png_bytep* rows) {
  if (setjmp(png_jmpbuf(r.png))) return false;
  png_read_image(r.png, rows);
  png_read_end(r.png, nullptr);
  return true;
}

}  // namespace

// Samples as stored, 8 or 16 bits, divided by 255 or 65535 as OpenImageIO converts them: a
// 16-bit PNG is as sRGB-encoded as an 8-bit one (libpng's simplified reader took it for linear
// and encoded it again).
ImageFile read_png(const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open the file");
  PngCall r("not a readable PNG");
  r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r, on_png_error, on_png_warning);
  if (r.png) r.info = png_create_info_struct(r.png);
  png_uint_32 width = 0, height = 0;
  int channels = 0, bit_depth = 0;
  size_t row_bytes = 0;
  bool ok = r.info && read_png_header(r, f, width, height, channels, bit_depth, row_bytes);
  ImageFile img;
  std::vector<png_byte> bytes;
  // Deflate expands at most about 1032 times: a header claiming more than the file can hold
  // is refused before the rows are allocated (bounding what any input makes us allocate).
  std::error_code ec;
  const uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  const uintmax_t most = std::max<uintmax_t>(uintmax_t(1) << 22, ec ? 0 : file_bytes * 1100);
  if (ok) {
    if (width == 0 || height == 0 || size_t(width) * height > (size_t(1) << 28) ||
        uintmax_t(row_bytes + 1) * height > most || (bit_depth != 8 && bit_depth != 16) ||
        channels < 1 || channels > 4 || row_bytes != size_t(width) * channels * (bit_depth / 8)) {
      std::snprintf(r.message, sizeof r.message, "image too large or of an unsupported kind");
      ok = false;
    } else {
      bytes.resize(row_bytes * height);
      std::vector<png_bytep> rows(height);
      for (png_uint_32 y = 0; y < height; ++y) rows[y] = bytes.data() + y * row_bytes;
      ok = read_png_rows(r, rows.data());
    }
  }
  png_destroy_read_struct(r.png ? &r.png : nullptr, r.info ? &r.info : nullptr, nullptr);
  std::fclose(f);
  if (!ok) throw std::runtime_error(r.message);
  img.full_width = img.width = int(width);
  img.full_height = img.height = int(height);
  img.channels =
      channels >= 3 ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"Y"};
  if (channels == 2 || channels == 4) img.channels.push_back("A");
  const size_t n = size_t(width) * height * channels;
  img.pixels.resize(n);
  // Times the float reciprocal, as OpenImageIO converts, so idiff and diff see the same values.
  if (bit_depth == 8) {
    constexpr float kScale = 1.0f / 255.0f;
    for (size_t i = 0; i < n; ++i) img.pixels[i] = bytes[i] * kScale;
  } else {
    constexpr float kScale = 1.0f / 65535.0f;
    for (size_t i = 0; i < n; ++i)  // big-endian samples
      img.pixels[i] = float((unsigned(bytes[2 * i]) << 8) | bytes[2 * i + 1]) * kScale;
  }
  return img;
}

void write_png(const std::string& path, const ImageFile& img, bool srgb) {
  PngPixels png{img.width, img.height, int(img.channels.size()), {}};
  png.bytes.resize(img.pixels.size());
  for (size_t i = 0; i < png.bytes.size(); ++i) png.bytes[i] = png_sample(img.pixels[i]);
  write_png(path, png, srgb);
}

namespace {

// IDAT chunks of at most this many bytes (the PNG limit is 2^31 - 1).
constexpr size_t kIdatBytes = size_t(1) << 20;

// The header and chunks libpng's simplified writer wrote (IHDR, then sRGB, or gAMA 1/2.2 where
// the samples are not sRGB), the zlib stream of the bands in IDAT chunks, and IEND.
bool write_png_chunks(PngCall& w, FILE* f, bool srgb, const PngBands& bands) {
  const int width = bands.width(), height = bands.height(), nc = bands.channels();
  if (setjmp(png_jmpbuf(w.png))) return false;
  png_init_io(w.png, f);
  png_set_IHDR(
      w.png, w.info, png_uint_32(width), png_uint_32(height), 8,
      (nc >= 3 ? PNG_COLOR_MASK_COLOR : 0) | (nc == 2 || nc == 4 ? PNG_COLOR_MASK_ALPHA : 0),
      PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  if (srgb)
    png_set_sRGB(w.png, w.info, PNG_sRGB_INTENT_PERCEPTUAL);
  else
    png_set_gAMA_fixed(w.png, w.info, 45455);  // 1/2.2, libpng's PNG_GAMMA_sRGB_INVERSE
  png_write_info(w.png, w.info);
  // The zlib stream: its header (deflate, 32 KiB window, level 1's "fastest"), the bands' runs,
  // and the Adler-32 of all the filtered bytes, big-endian.
  static const unsigned char kHeader[2] = {0x78, 0x01};
  uLong adler = bands.adler(0);
  for (size_t b = 1; b < bands.count(); ++b)
    adler = adler32_combine(adler, bands.adler(b), z_off_t(bands.length(b)));
  const unsigned char trailer[4] = {
      static_cast<unsigned char>(adler >> 24), static_cast<unsigned char>(adler >> 16),
      static_cast<unsigned char>(adler >> 8), static_cast<unsigned char>(adler)};
  std::vector<std::pair<const unsigned char*, size_t>> pieces{{kHeader, 2}};
  for (size_t b = 0; b < bands.count(); ++b)
    pieces.emplace_back(bands.data(b).data(), bands.data(b).size());
  pieces.emplace_back(trailer, 4);
  size_t left = 0;
  for (const auto& p : pieces) left += p.second;
  size_t piece = 0, used = 0;  // the next byte: pieces[piece].first[used]
  while (left > 0) {
    size_t n = std::min(left, kIdatBytes);
    left -= n;
    png_write_chunk_start(w.png, reinterpret_cast<png_const_bytep>("IDAT"), png_uint_32(n));
    while (n > 0) {
      const size_t take = std::min(n, pieces[piece].second - used);
      png_write_chunk_data(w.png, pieces[piece].first + used, take);
      n -= take;
      used += take;
      if (used == pieces[piece].second) ++piece, used = 0;
    }
    png_write_chunk_end(w.png);
  }
  png_write_chunk(w.png, reinterpret_cast<png_const_bytep>("IEND"), nullptr, 0);
  return true;
}

}  // namespace

void write_png(const std::string& path, int width, int height, int nc, bool srgb, const PngRow& row,
               const EachIndex& each) {
  PngBands bands(width, height, nc, row);
  write_png(path, srgb, bands, each);
}

void write_png(const std::string& path, bool srgb, PngBands& bands, const EachIndex& each) {
  if (!bands.deflate_rest(each)) throw std::runtime_error("cannot deflate the PNG's rows");
  // The whole file in one write: stdio's own buffer is a block (4 KiB here), a system call for
  // each (24 for a 95 kB image at 640x480). The chunks' frames, the header's and the trailer's
  // bytes take under 128 bytes and 12 bytes per IDAT chunk; a file that outgrew the estimate would
  // only take a second write.
  size_t deflated = 0;
  for (size_t b = 0; b < bands.count(); ++b) deflated += bands.data(b).size();
  const size_t file_bytes = 128 + deflated + 12 * (deflated / kIdatBytes + 1);
  const std::unique_ptr<char[]> file_buffer(new char[file_bytes]);  // outlives the FILE
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot open the file for writing");
  std::setvbuf(f, file_buffer.get(), _IOFBF, file_bytes);
  PngCall w("cannot write the PNG");
  w.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &w, on_png_error, on_png_warning);
  if (w.png) w.info = png_create_info_struct(w.png);
  const bool written = w.info && write_png_chunks(w, f, srgb, bands);
  png_destroy_write_struct(w.png ? &w.png : nullptr, w.info ? &w.info : nullptr);
  // A full disk may show only when the buffer is flushed (or when the data reaches the disk: in
  // commit_temp, output_file.h, which syncs every output once before its rename).
  const bool flushed = written && std::fflush(f) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written) throw std::runtime_error(w.message);
  if (!flushed || !closed)
    throw std::runtime_error(std::string("cannot write the file: ") +
                             std::strerror(flushed ? errno : flush_errno));
}

void write_png(const std::string& path, const PngPixels& img, bool srgb) {
  const size_t row_bytes = size_t(img.width) * std::max(img.channels, 0);
  write_png(path, img.width, img.height, img.channels, srgb, [&](int y, uint8_t* row) {
    std::memcpy(row, img.bytes.data() + size_t(y) * row_bytes, row_bytes);
  });
}

}  // namespace softtrace
