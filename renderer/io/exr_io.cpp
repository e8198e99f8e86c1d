// EXR reading and writing with OpenEXR 3 (Imf::InputFile / Imf::OutputFile).
#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <fcntl.h>
#include <half.h>
#include <strings.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "io/image_file.h"
#include "io/image_io.h"

namespace softtrace {

namespace {

// OpenImageIO's canonical channel order (its OpenEXR reader): by layer, then by these names
// (case-insensitive), then by name. A layer with X and Y or Z (a position or normal) puts X,Y,Z
// right after the colours.
int special_rank(const std::string& suffix, bool xyz_layer) {
  static const char* const plain[] = {"R",    "Red",  "G",  "Green", "B",     "Blue",  "Y",
                                      "real", "imag", "A",  "Alpha", "AR",    "RA",    "AG",
                                      "GA",   "AB",   "BA", "Z",     "Depth", "Zback", nullptr};
  static const char* const xyz[] = {"R",  "Red",  "G",    "Green", "B",     "Blue", "X",  "Y",
                                    "Z",  "real", "imag", "A",     "Alpha", "AR",   "RA", "AG",
                                    "GA", "AB",   "BA",   "Depth", "Zback", nullptr};
  const char* const* names = xyz_layer ? xyz : plain;
  for (int i = 0; names[i]; ++i)
    if (::strcasecmp(suffix.c_str(), names[i]) == 0) return i;
  return 10000;
}

struct ChannelKey {
  std::string name, layer, suffix;
  int rank = 0;
};

std::vector<std::string> canonical_order(std::vector<std::string> names) {
  std::vector<ChannelKey> keys;
  for (const auto& n : names) {
    const size_t dot = n.find_last_of('.');
    keys.push_back({n, dot == std::string::npos ? "" : n.substr(0, dot),
                    dot == std::string::npos ? n : n.substr(dot + 1), 0});
  }
  const auto has = [&](const std::string& layer, const char* suffix) {
    return std::any_of(keys.begin(), keys.end(), [&](const ChannelKey& k) {
      return k.layer == layer && ::strcasecmp(k.suffix.c_str(), suffix) == 0;
    });
  };
  for (auto& k : keys)
    k.rank = special_rank(k.suffix, has(k.layer, "X") && (has(k.layer, "Y") || has(k.layer, "Z")));
  std::sort(keys.begin(), keys.end(), [](const ChannelKey& a, const ChannelKey& b) {
    if (a.layer != b.layer) return a.layer < b.layer;
    if (a.rank != b.rank) return a.rank < b.rank;
    return a.suffix < b.suffix;
  });
  for (size_t i = 0; i < keys.size(); ++i) names[i] = keys[i].name;
  return names;
}

// An EXR written straight to a file descriptor, every write checked. OpenEXR's own file stream
// reports a failed write (a full disk) only from OutputFile's destructor, which swallows it: a
// small image then came out as a 0-byte file. The destructor still writes (the line offset
// table), so an error is also recorded, for write_exr to check once the file is closed.
class FdOStream : public Imf::OStream {
 public:
  FdOStream(const char* path, int fd) : Imf::OStream(path), fd_(fd) {}

  void write(const char c[], int n) override {
    for (int done = 0; done < n;) {
      const ssize_t w = ::pwrite(fd_, c + done, size_t(n - done), off_t(pos_));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        if (error_.empty()) error_ = w < 0 ? std::strerror(errno) : "nothing written";
        throw std::runtime_error("cannot write the file: " + error_);
      }
      done += int(w);
      pos_ += uint64_t(w);
    }
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }

  const std::string& error() const { return error_; }

 private:
  int fd_;
  uint64_t pos_ = 0;
  std::string error_;  // the first failed write's reason
};

}  // namespace

ImageFile read_exr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow(), disp = header.displayWindow();
    // In 64 bits: a tampered header's windows may span more than int holds.
    const auto span = [](int lo, int hi) { return static_cast<long long>(hi) - lo + 1; };
    const auto offset = [](int a, int b) { return static_cast<long long>(a) - b; };
    const long long full_width = span(disp.min.x, disp.max.x),
                    full_height = span(disp.min.y, disp.max.y), x0 = offset(dw.min.x, disp.min.x),
                    y0 = offset(dw.min.y, disp.min.y);
    const long long width = span(dw.min.x, dw.max.x), height = span(dw.min.y, dw.max.y);
    constexpr long long kLimit = 1LL << 30;
    for (const long long v : {full_width, full_height, x0, y0, width, height})
      if (v <= -kLimit || v >= kLimit)
        throw std::runtime_error("unsupported data or display window");
    ImageFile img;
    img.full_width = int(full_width);
    img.full_height = int(full_height);
    img.x0 = int(x0);
    img.y0 = int(y0);
    img.width = int(width);
    img.height = int(height);
    std::vector<std::string> names;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
        throw std::runtime_error(std::string("subsampled channel '") + it.name() +
                                 "' is not supported");
      names.push_back(it.name());
    }
    if (names.empty()) throw std::runtime_error("no channels");
    img.channels = canonical_order(names);
    // What is allocated is bounded, whatever the header claims: 2^28 pixels, 2^28 values (1 GiB),
    // and 1024 values per byte of the file, or 2^20 for a small file (zip, which softtrace
    // writes, compresses at most about 1032 to 1: 516 half values per byte).
    std::error_code ec;
    const uintmax_t file_bytes = std::filesystem::file_size(path, ec);
    const size_t values = size_t(img.width) * img.height * names.size();
    if (img.width <= 0 || img.height <= 0 || size_t(img.width) * img.height > (size_t(1) << 28) ||
        values > (size_t(1) << 28) ||
        (!ec && values > std::max<uintmax_t>(uintmax_t(1) << 20, file_bytes << 10)))
      throw std::runtime_error("unsupported data window");
    const size_t nc = img.channels.size();
    img.pixels.assign(size_t(img.width) * img.height * nc, 0.0f);

    // OpenEXR addresses the buffer by absolute pixel coordinates: point each slice at where
    // pixel (0, 0) would be.
    const size_t xstride = nc * sizeof(float), ystride = size_t(img.width) * xstride;
    char* origin =
        reinterpret_cast<char*>(img.pixels.data()) -
        (ptrdiff_t(dw.min.x) * ptrdiff_t(xstride) + ptrdiff_t(dw.min.y) * ptrdiff_t(ystride));
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < nc; ++c)
      fb.insert(img.channels[c],
                Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), xstride, ystride));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);

    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        img.attributes[it.name()] = s->value();
    return img;
  } catch (const std::runtime_error&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what());
  }
}

void write_exr(const std::string& path, const ImageFile& img, const ExrExtras& extras) {
  const size_t nc = img.channels.size(), npix = size_t(img.width) * img.height;
  Imf::Header header(
      Imath::Box2i({0, 0}, {img.full_width - 1, img.full_height - 1}),
      Imath::Box2i({img.x0, img.y0}, {img.x0 + img.width - 1, img.y0 + img.height - 1}));
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const auto& [name, value] : img.attributes) header.insert(name, Imf::StringAttribute(value));
  for (const auto& [name, m] : extras.matrices)
    header.insert(
        name, Imf::M44fAttribute(Imath::M44f(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8],
                                             m[9], m[10], m[11], m[12], m[13], m[14], m[15])));
  for (const auto& [name, v] : extras.floats) header.insert(name, Imf::FloatAttribute(v));
  for (const auto& [name, v] : extras.ints) header.insert(name, Imf::IntAttribute(v));

  // Float channels are read where they lie, interleaved (a copy would be fresh memory: a page
  // fault per 4 KiB); half channels are converted into planes of their own.
  std::vector<std::vector<half>> halves(nc);
  Imf::FrameBuffer fb;
  for (size_t c = 0; c < nc; ++c) {
    const bool as_half = c < extras.half.size() && extras.half[c];
    header.channels().insert(img.channels[c], Imf::Channel(as_half ? Imf::HALF : Imf::FLOAT));
    char* first;  // pixel (x0, y0)
    size_t xstride;
    if (as_half) {
      halves[c].resize(npix);
      for (size_t i = 0; i < npix; ++i) halves[c][i] = half(img.pixels[i * nc + c]);
      first = reinterpret_cast<char*>(halves[c].data());
      xstride = sizeof(half);
    } else {
      // OpenEXR's Slice takes a char* for reading and writing alike; writing only reads it.
      first = reinterpret_cast<char*>(const_cast<float*>(img.pixels.data() + c));
      xstride = nc * sizeof(float);
    }
    const size_t ystride = xstride * img.width;
    char* origin =
        first - ptrdiff_t(img.x0) * ptrdiff_t(xstride) - ptrdiff_t(img.y0) * ptrdiff_t(ystride);
    fb.insert(img.channels[c],
              Imf::Slice(as_half ? Imf::HALF : Imf::FLOAT, origin, xstride, ystride));
  }
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0)
    throw std::runtime_error(std::string("cannot open the file: ") + std::strerror(errno));
  FdOStream stream(path.c_str(), fd);
  std::string error;
  try {
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(fb);
    file.writePixels(img.height);
  } catch (const std::exception& e) {
    error = e.what();
  }
  // The destructor above wrote the offset table: only now is the file complete, or not.
  if (error.empty() && !stream.error().empty()) error = "cannot write the file: " + stream.error();
  if (error.empty() && ::fsync(fd) != 0)
    error = std::string("cannot write the file: ") + std::strerror(errno);
  if (::close(fd) != 0 && error.empty())
    error = std::string("cannot write the file: ") + std::strerror(errno);
  if (!error.empty()) throw std::runtime_error(error);
}

}  // namespace softtrace
