// The rendered pixels and their output. Only this file's implementation includes OpenImageIO.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace softtrace {

struct AovSelection {
  bool depth = false, normal = false, steps = false;
};

// The pixels of a data window [x0, x0 + width) x [y0, y0 + height) of a full_width x full_height
// display window (a crop or tile of the frame; by default the whole frame).
struct Film {
  int width = 0, height = 0;
  int full_width = 0, full_height = 0, x0 = 0, y0 = 0;
  std::vector<float> rgba;    // linear RGB composited over the background; A = object coverage
  std::vector<float> depth;   // ray distance of the pixel-centre ray, +inf for background
  std::vector<float> normal;  // unit normal (x,y,z) at that hit, 0 for background
  std::vector<float> steps;   // field/interval evaluations of the pixel-centre ray (with shadows)
  std::map<std::string, std::string> attributes;  // string metadata, written to EXR headers

  Film(int w, int h)
      : width(w),
        height(h),
        full_width(w),
        full_height(h),
        rgba(size_t(w) * h * 4),
        depth(size_t(w) * h),
        normal(size_t(w) * h * 3),
        steps(size_t(w) * h) {}
};

// Parses "depth,normal,steps" (any subset); throws std::invalid_argument naming a bad entry.
AovSelection parse_aovs(const std::string& list);

// Checks, before any rendering, that `path` can be written: a known extension (.exr, .png), an
// existing folder we may write to. Throws std::invalid_argument with the reason.
void check_output_path(const std::string& path);
bool is_exr_path(const std::string& path);

// Writes the film: EXR with R,G,B,A (+ Z, N.X,N.Y,N.Z, steps as selected), the display and
// data windows and the attributes, or 8-bit sRGB PNG (the data window's RGB only: AOVs and
// metadata go to EXR outputs).
// The image goes to a temporary file in the target folder that is renamed over `path` only when
// complete, so an existing file is never half-overwritten. Throws std::runtime_error.
void write_image(const std::string& path, const Film& film, const AovSelection& aovs);

// The two halves of write_image, for writing several outputs all-or-nothing: write every
// temporary file (each registered as pending), then commit them all, then forget them.
std::string write_image_temp(const std::string& path, const Film& film, const AovSelection& aovs);
void commit_image(const std::string& tmp, const std::string& path);
void forget_pending_writes();

// Removes the temporary files of pending writes.
void abandon_pending_writes();
// The same, then _exit(status), with no temporary file created in between (the signal watcher's
// way out while writing, cmd_render.cpp).
[[noreturn]] void abandon_pending_writes_and_exit(int status);

}  // namespace softtrace
