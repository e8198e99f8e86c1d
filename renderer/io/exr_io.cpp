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
#include <fstream>
#include <stdexcept>
#include <utility>

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

// The size OpenEXR 3.1's reader of an attribute type reads whatever size the file declares, for
// the types of fixed size; -1 for the rest.
long long fixed_attribute_size(const std::string& type) {
  static const std::pair<const char*, int> kSizes[] = {{"box2i", 16},
                                                       {"box2f", 16},
                                                       {"chromaticities", 32},
                                                       {"compression", 1},
                                                       {"deepImageState", 1},
                                                       {"double", 8},
                                                       {"envmap", 1},
                                                       {"float", 4},
                                                       {"int", 4},
                                                       {"keycode", 28},
                                                       {"lineOrder", 1},
                                                       {"m33f", 36},
                                                       {"m33d", 72},
                                                       {"m44f", 64},
                                                       {"m44d", 128},
                                                       {"rational", 8},
                                                       {"tiledesc", 9},
                                                       {"timecode", 8},
                                                       {"v2i", 8},
                                                       {"v2f", 8},
                                                       {"v2d", 16},
                                                       {"v3i", 12},
                                                       {"v3f", 12},
                                                       {"v3d", 24}};
  for (const auto& [name, size] : kSizes)
    if (type == name) return size;
  return -1;
}

// OpenEXR 3.1 allocates what a header declares before it reads it (a string attribute's size, a
// preview's width x height, a string vector's lengths), so a tampered 12 KB header can ask for
// gigabytes. Walk the header(s) first, reading every attribute (name\0 type\0 int32 size, value)
// exactly as OpenEXR will, and refuse a size beyond the bytes the file has left. Where OpenEXR's
// reader goes by a value's contents rather than its declared size (a fixed-size type, a channel
// list, a preview), the two must agree, or OpenEXR would read on from another place than this
// walk (a fuzzer found a 1.8 GB string behind a channel list longer than declared). Names and
// types are at most 255 characters, as OpenEXR reads them.
void check_exr_attribute_sizes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // OpenEXR reports it
  in.seekg(0, std::ios::end);
  const long long file_size = static_cast<long long>(in.tellg());
  unsigned char version[8];  // the magic number, then the version field's flags
  if (!in.seekg(0).read(reinterpret_cast<char*>(version), 8)) return;
  const bool multipart = version[5] & 0x10;  // bit 12 of the version field
  const auto read_name = [&](std::string& out) {
    out.clear();
    char c;
    while (in.get(c) && c != 0)
      if ((out += c).size() > 255)
        throw std::runtime_error("an attribute, type or channel name longer than 255 characters");
    return bool(in);
  };
  const auto read_int = [&](long long* v) {
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
    *v = static_cast<long long>(int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 |
                                        uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24));
    return true;
  };
  const auto at = [&] { return static_cast<long long>(in.tellg()); };
  std::string name, type, channel;
  for (int headers = 0; headers < 1024 && in; ++headers) {
    if (!read_name(name) || name.empty()) return;  // the end of the headers (or of the file)
    do {
      long long size;
      if (!read_name(type) || !read_int(&size)) return;
      const long long start = at(), left = file_size - start;
      const auto refuse = [&](const std::string& why) {
        throw std::runtime_error("attribute '" + name + "' " + why);
      };
      if (size < 0 || size > left)
        refuse("declares " + std::to_string(size) + " bytes, but the file has " +
               std::to_string(left) + " left");
      long long read = size;  // what OpenEXR's reader of the type will take
      if (const long long fixed = fixed_attribute_size(type); fixed >= 0) {
        read = fixed;
      } else if (type == "chlist") {  // name\0 and 16 bytes a channel, then an empty name
        while (read_name(channel) && !channel.empty() && at() - start <= size)
          in.seekg(16, std::ios::cur);
        read = in ? at() - start : size + 1;
      } else if (type == "preview") {  // width, height, then 4 bytes a pixel
        long long w, h;
        if (!read_int(&w) || !read_int(&h)) return;
        const double bytes = 8 + 4.0 * double(uint32_t(w)) * double(uint32_t(h));
        read = bytes > double(size) ? size + 1 : static_cast<long long>(bytes);
      } else if (type == "stringvector") {  // int32 length, then the characters, to the size
        long long n;
        while (at() - start < size && read_int(&n) && n >= 0 && at() - start + n <= size)
          in.seekg(n, std::ios::cur);
        read = in ? at() - start : size + 1;
      } else if (type == "floatvector" && size % 4 != 0) {
        read = size - size % 4;
      }
      if (read != size)
        refuse("declares " + std::to_string(size) + " bytes, but its " + type + " value takes " +
               std::to_string(read));
      in.clear();
      in.seekg(start + size);
    } while (read_name(name) && !name.empty());
    // A single-part file has one header; a multi-part file ends its list with an empty header.
    if (!multipart || in.peek() == 0) return;
  }
}

}  // namespace

ImageFile read_exr(const std::string& path) {
  try {
    check_exr_attribute_sizes(path);
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
  // The destructor above wrote the offset table: only now is the file complete, or not. The data
  // reaches the disk in commit_temp (output_file.h), which syncs every output once before its
  // rename.
  if (error.empty() && !stream.error().empty()) error = "cannot write the file: " + stream.error();
  if (::close(fd) != 0 && error.empty())
    error = std::string("cannot write the file: ") + std::strerror(errno);
  if (!error.empty()) throw std::runtime_error(error);
}

}  // namespace softtrace
