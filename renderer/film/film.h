// The rendered pixels and how they become image files (EXR through OpenEXR, PNG through libpng;
// no OpenImageIO).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "film/plane_memory.h"
#include "io/image_file.h"
#include "io/output_file.h"
#include "io/png_bands.h"
#include "math/vec.h"

namespace softtrace {

struct AovSelection {
  bool depth = false, normal = false, steps = false, albedo = false;
};

// A data window of width x height pixels at (x0, y0) inside a display window of
// full_width x full_height (the whole frame; a crop or tile renders part of it). The AOV planes
// not asked for stay empty: a process's fresh memory costs a page fault per 4 KiB (about 1 µs
// on this project's virtual machines, the kernel's zeroing included), and at 640x480 the three
// planes were 6 MB, some 1,500 faults. The planes' memory: film/plane_memory.h.
struct Film {
  int full_width = 0, full_height = 0;
  int x0 = 0, y0 = 0;
  int width = 0, height = 0;
  FilmPlane rgba;    // premultiplied: RGB = coverage-weighted object colour, A = coverage
  FilmPlane depth;   // ray distance of the pixel-centre ray, +inf for background
  FilmPlane normal;  // unit normal (x,y,z) at that hit, 0 for background
  FilmPlane steps;   // field/interval evaluations of the pixel-centre ray (with shadows)
  FilmPlane albedo;  // the material's colour (r,g,b) at that hit, 0 for background
  std::map<std::string, std::string> attributes;  // more string attributes for EXR headers

  Film(int w, int h, AovSelection aovs = {true, true, true})
      : full_width(w),
        full_height(h),
        width(w),
        height(h),
        rgba(size_t(w) * h * 4),
        depth(aovs.depth ? size_t(w) * h : 0),
        normal(aovs.normal ? size_t(w) * h * 3 : 0),
        steps(aovs.steps ? size_t(w) * h : 0),
        albedo(aovs.albedo ? size_t(w) * h * 3 : 0) {}
};

struct OutputOptions {
  AovSelection aovs;
  bool flatten = false;    // RGB over the scene's background, A = 1 (default: premultiplied)
  bool half = false;       // EXR R,G,B,A and N.* as half float (Z and steps stay float)
  bool png_alpha = false;  // PNG as RGBA with straight alpha (default: RGB over the background)
};

// What an EXR header records about the frame (frame_metadata.h fills it).
struct FrameInfo {
  std::string scene_name, scene_hash;
  int spp = 1;
  double render_seconds = 0;
  std::array<float, 16> world_to_camera{}, world_to_ndc{};  // row-vector M44f
  Vec3 background{0, 0, 0};
};

// Parses "depth,normal,steps,albedo" (any subset); throws std::invalid_argument naming a bad entry.
AovSelection parse_aovs(const std::string& list);

// check_output_path (output_file.h) for images: .exr or .png.
void check_image_output_path(const std::string& path);
bool is_exr_path(const std::string& path);

// The film's PNG (8-bit sRGB, RGB over the background or, with png_alpha, RGBA) as bands of rows
// to deflate (io/png_bands.h): a render counts the pixels its tiles make final, so that a band is
// deflated as soon as its rows are, while the frame goes on. The film, `opt` and `info` must
// outlive the bands.
std::unique_ptr<PngBands> film_png_bands(const Film& film, const OutputOptions& opt,
                                         const FrameInfo& info);

// Writes the film to a pending temporary file beside `path`'s target (stale temporary files of
// that target are removed first) and returns the temporary file's path; commit_image renames it
// over the target. EXR: R,G,B,A (+ Z, N.X,N.Y,N.Z, steps, albedo.R,albedo.G,albedo.B as selected)
// with the standard and softtrace header attributes (README "Usage"). PNG: 8-bit sRGB, RGB over the
// background or, with png_alpha, RGBA; its rows are converted and deflated in bands that `each`
// runs (io/image_file.h: the command line passes its worker threads; the same bytes either way),
// those of `png` where given (film_png_bands of the same film, options and info: some of its bands
// deflated already; it may serve several outputs). Throws std::runtime_error.
std::string write_image_temp(const std::string& path, const Film& film, const OutputOptions& opt,
                             const FrameInfo& info, const EachIndex& each = {},
                             PngBands* png = nullptr);
void commit_image(const std::string& tmp, const std::string& path);

}  // namespace softtrace
