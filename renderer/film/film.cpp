#include "film/film.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "film/srgb_bytes.h"
#include "io/image_file.h"

#ifndef SOFTTRACE_VERSION
#error "SOFTTRACE_VERSION comes from the project's version (renderer/CMakeLists.txt)"
#endif

namespace softtrace {

namespace {

const char* const kImageExtensions[] = {".exr", ".png", nullptr};

ImageFile exr_image(const Film& film, const OutputOptions& opt, const FrameInfo& info,
                    ExrExtras& extras) {
  ImageFile img;
  img.full_width = film.full_width;
  img.full_height = film.full_height;
  img.x0 = film.x0;
  img.y0 = film.y0;
  img.width = film.width;
  img.height = film.height;
  img.channels = {"R", "G", "B", "A"};
  if (opt.aovs.depth) img.channels.push_back("Z");
  if (opt.aovs.normal) img.channels.insert(img.channels.end(), {"N.X", "N.Y", "N.Z"});
  if (opt.aovs.steps) img.channels.push_back("steps");
  if (opt.aovs.albedo)
    img.channels.insert(img.channels.end(), {"albedo.R", "albedo.G", "albedo.B"});
  const size_t nc = img.channels.size(), npix = size_t(film.width) * film.height;
  img.pixels.resize(npix * nc);
  for (size_t i = 0; i < npix; ++i) {
    float* out = &img.pixels[i * nc];
    const float* in = &film.rgba[i * 4];
    for (int k = 0; k < 3; ++k)
      out[k] = opt.flatten ? in[k] + float(info.background[k]) * (1 - in[3]) : in[k];
    out[3] = opt.flatten ? 1.0f : in[3];
    size_t c = 4;
    if (opt.aovs.depth) out[c++] = film.depth[i];
    if (opt.aovs.normal)
      for (int k = 0; k < 3; ++k) out[c++] = film.normal[i * 3 + k];
    if (opt.aovs.steps) out[c++] = film.steps[i];
    if (opt.aovs.albedo)
      for (int k = 0; k < 3; ++k) out[c++] = film.albedo[i * 3 + k];
  }
  // Depth needs float's precision, and step counts above 2048 are not exact in half.
  for (const auto& name : img.channels)
    extras.half.push_back(opt.half && name != "Z" && name != "steps");

  img.attributes["software"] = "softtrace " SOFTTRACE_VERSION;
  img.attributes["softtrace/scene"] = info.scene_name;
  img.attributes["softtrace/sceneHash"] = info.scene_hash;
  for (const auto& [name, value] : film.attributes) img.attributes[name] = value;
  extras.matrices["worldToCamera"] = info.world_to_camera;
  extras.matrices["worldToNDC"] = info.world_to_ndc;
  extras.floats["renderTimeSeconds"] = float(info.render_seconds);
  extras.ints["softtrace/spp"] = info.spp;
  return img;
}

// A PNG's row y of the film: 8-bit sRGB, RGB over the background or, with png_alpha, RGBA with
// straight alpha.
class FilmPngRows {
 public:
  FilmPngRows(const Film& film, const OutputOptions& opt, const FrameInfo& info)
      : film_(film),
        opt_(opt),
        info_(info),
        nc_(opt.png_alpha ? 4 : 3),
        straight_(opt.png_alpha && !opt.flatten),
        srgb_byte_(SrgbBytes::get()) {
    // A pixel nothing covers (most of a sparse frame) takes the bytes below, which are what the
    // loop's expressions give it: with straight alpha its colour is 0 and png_sample(0) is 0;
    // flattened, 0 + background * (1 - 0) is the background.
    if (!straight_) {
      for (int k = 0; k < 3; ++k)
        empty_[k] = srgb_byte_(0.0f + float(info.background[k]) * (1 - 0.0f));
      empty_[3] = png_sample(1.0f);
    }
  }
  int channels() const { return nc_; }

  void operator()(int y, uint8_t* row) const {
    const float* in = &film_.rgba[size_t(y) * film_.width * 4];
    if (straight_) return straight_row(in, row);
    // Over the background. What the loop reads of the members, read once: a byte stored through
    // `row` may be any of them, for all the compiler knows, and each store had the loop load them
    // again (the width, nc_, the empty bytes, the background, the table: pov:chain at 640x480,
    // 17.7 M instructions for its 307,200 pixels). The same values: float(background[k]) is
    // what each pixel converted.
    const int width = film_.width, nc = nc_;
    const uint8_t e0 = empty_[0], e1 = empty_[1], e2 = empty_[2], e3 = empty_[3];
    const float background[3] = {float(info_.background[0]), float(info_.background[1]),
                                 float(info_.background[2])};
    const bool alpha = opt_.png_alpha, flatten = opt_.flatten;
    const SrgbBytes& srgb = srgb_byte_;
    for (int x = 0; x < width; ++x, in += 4, row += nc) {
      if (in[3] == 0 && in[0] == 0 && in[1] == 0 && in[2] == 0) {
        // Byte by byte: std::copy of nc_ bytes, a count not known here, was a call of memcpy per
        // pixel (pov:chain at 640x480: 267,016 of them, 11 M instructions).
        row[0] = e0;
        row[1] = e1;
        row[2] = e2;
        if (nc == 4) row[3] = e3;
        continue;
      }
      uint8_t bytes[3];
      for (int k = 0; k < 3; ++k) bytes[k] = srgb(in[k] + background[k] * (1 - in[3]));
      row[0] = bytes[0];
      row[1] = bytes[1];
      row[2] = bytes[2];
      if (alpha) row[3] = png_sample(flatten ? 1.0f : in[3]);
    }
  }

 private:
  // operator()'s loop with straight alpha (RGBA, not flattened), the same bytes: a pixel every
  // sample of which met something has alpha 1 exactly, and x / 1 is x and png_sample(1) is 255,
  // so it takes neither the three divisions nor the alpha's rounding (most covered pixels of a
  // frame at 1 sample; the row loop was 2 % of pov:blob1a's process at 320x240).
  void straight_row(const float* in, uint8_t* row) const {
    for (int x = 0; x < film_.width; ++x, in += 4, row += 4) {
      const float a = in[3];
      if (a == 1.0f) {
        for (int k = 0; k < 3; ++k) row[k] = srgb_byte_(in[k]);
        row[3] = 255;
      } else if (!(a > 0)) {
        std::fill_n(row, 4, uint8_t(0));
      } else {
        for (int k = 0; k < 3; ++k) row[k] = srgb_byte_(in[k] / a);
        row[3] = png_sample(a);
      }
    }
  }

  const Film& film_;
  const OutputOptions& opt_;
  const FrameInfo& info_;
  const int nc_;
  const bool straight_;
  const SrgbBytes& srgb_byte_;
  uint8_t empty_[4] = {0, 0, 0, 0};
};

}  // namespace

bool is_exr_path(const std::string& path) {
  return output_extension(path) == ".exr";
}

void check_image_output_path(const std::string& path) {
  check_output_path(path, kImageExtensions);
}

AovSelection parse_aovs(const std::string& list) {
  AovSelection a;
  size_t start = 0;
  while (start <= list.size() && !list.empty()) {
    const size_t comma = list.find(',', start);
    const std::string item = list.substr(start, comma == std::string::npos ? comma : comma - start);
    if (item == "depth")
      a.depth = true;
    else if (item == "normal")
      a.normal = true;
    else if (item == "steps")
      a.steps = true;
    else if (item == "albedo")
      a.albedo = true;
    else
      throw std::invalid_argument("unknown AOV '" + item +
                                  "' (expected depth, normal, steps, albedo)");
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return a;
}

std::unique_ptr<PngBands> film_png_bands(const Film& film, const OutputOptions& opt,
                                         const FrameInfo& info) {
  const FilmPngRows rows(film, opt, info);
  return std::make_unique<PngBands>(film.width, film.height, rows.channels(), rows);
}

std::string write_image_temp(const std::string& path, const Film& film, const OutputOptions& opt,
                             const FrameInfo& info, const EachIndex& each, PngBands* png) {
  const std::string target = resolve_output_target(path);
  remove_stale_temporaries(target, process_start_time());
  const std::string tmp = create_pending_temp(target, path);
  try {
    if (is_exr_path(path)) {
      ExrExtras extras;
      write_exr(tmp, exr_image(film, opt, info, extras), extras);
    } else if (png) {
      write_png(tmp, true, *png, each);
    } else {
      write_png(tmp, true, *film_png_bands(film, opt, info), each);
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());  // the caller abandons the pending file
  }
  return tmp;
}

void commit_image(const std::string& tmp, const std::string& path) {
  commit_temp(tmp, resolve_output_target(path), path);
}

}  // namespace softtrace
