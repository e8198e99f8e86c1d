#include "film.h"

#include <OpenImageIO/imageio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace softtrace {

namespace fs = std::filesystem;

namespace {

std::string extension_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

float srgb_encode(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

// Temporary files of writes not yet renamed into place. The lock is held from creating a file to
// recording its name, so whoever abandons the writes (the signal watcher, cmd_render.cpp) sees
// every file that exists.
std::mutex g_pending_mutex;
std::vector<std::string> g_pending;

}  // namespace

bool is_exr_path(const std::string& path) {
  return extension_of(path) == ".exr";
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
    else
      throw std::invalid_argument("unknown AOV '" + item + "' (expected depth, normal, steps)");
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return a;
}

void check_output_path(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".exr" && ext != ".png")
    throw std::invalid_argument(path + ": unsupported output format '" + ext +
                                "' (expected .exr or .png)");
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw std::invalid_argument(path + ": the folder '" + dir.string() + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::invalid_argument(path + ": the folder '" + dir.string() + "' is not writable");
  if (fs::is_directory(path, ec)) throw std::invalid_argument(path + ": is a folder");
}

std::string write_image_temp(const std::string& path, const Film& film, const AovSelection& aovs) {
  using namespace OIIO;
  const bool png = extension_of(path) == ".png";
  const size_t npix = size_t(film.width) * film.height;

  std::vector<std::string> names = {"R", "G", "B"};
  if (!png) names.push_back("A");
  if (!png && aovs.depth) names.push_back("Z");
  if (!png && aovs.normal) names.insert(names.end(), {"N.X", "N.Y", "N.Z"});
  if (!png && aovs.steps) names.push_back("steps");
  const int nc = static_cast<int>(names.size());

  std::vector<float> pixels(npix * nc);
  for (size_t i = 0; i < npix; ++i) {
    float* out = &pixels[i * nc];
    int c = 0;
    for (int k = 0; k < 3; ++k)
      out[c++] = png ? srgb_encode(film.rgba[i * 4 + k]) : film.rgba[i * 4 + k];
    if (png) continue;
    out[c++] = film.rgba[i * 4 + 3];
    if (aovs.depth) out[c++] = film.depth[i];
    if (aovs.normal)
      for (int k = 0; k < 3; ++k) out[c++] = film.normal[i * 3 + k];
    if (aovs.steps) out[c++] = film.steps[i];
  }

  ImageSpec spec(film.width, film.height, nc, png ? TypeDesc::UINT8 : TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.alpha_channel = png ? -1 : 3;
  spec.z_channel = (!png && aovs.depth) ? 4 : -1;
  if (!png) {
    spec.attribute("compression", "zip");
    spec.x = film.x0;
    spec.y = film.y0;
    spec.full_x = spec.full_y = 0;
    spec.full_width = film.full_width;
    spec.full_height = film.full_height;
    for (const auto& [name, value] : film.attributes) spec.attribute(name, value);
  }

  const fs::path target(path);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::string tmp = (dir / ("." + target.filename().string() + ".XXXXXX")).string();
  {
    const std::lock_guard<std::mutex> lock(g_pending_mutex);
    const int fd = ::mkstemp(tmp.data());
    if (fd < 0) throw std::runtime_error(path + ": cannot create a file in '" + dir.string() + "'");
    ::close(fd);
    g_pending.push_back(tmp);
  }

  const auto fail = [&](const std::string& why) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": " + why);
  };
  auto out = ImageOutput::create(png ? "png" : "openexr");
  if (!out) fail("no image writer: " + OIIO::geterror());
  if (!out->open(tmp, spec)) fail(out->geterror());
  if (!out->write_image(TypeDesc::FLOAT, pixels.data())) fail(out->geterror());
  if (!out->close()) fail(out->geterror());
  return tmp;
}

void commit_image(const std::string& tmp, const std::string& path) {
  // mkstemp makes the file private; give it the usual permissions of a new file.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  std::error_code ec;
  fs::permissions(tmp, static_cast<fs::perms>(0666 & ~mask), ec);
  if (!ec) fs::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": cannot replace the file: " + ec.message());
  }
}

void write_image(const std::string& path, const Film& film, const AovSelection& aovs) {
  try {
    commit_image(write_image_temp(path, film, aovs), path);
  } catch (...) {
    forget_pending_writes();
    throw;
  }
  forget_pending_writes();
}

void forget_pending_writes() {
  const std::lock_guard<std::mutex> lock(g_pending_mutex);
  g_pending.clear();
}

void abandon_pending_writes() {
  const std::lock_guard<std::mutex> lock(g_pending_mutex);
  for (const auto& t : g_pending) ::unlink(t.c_str());  // renamed ones are gone: ENOENT
}

void abandon_pending_writes_and_exit(int status) {
  g_pending_mutex.lock();  // held to the end: no temporary file can be created after these
  for (const auto& t : g_pending) ::unlink(t.c_str());
  _exit(status);
}

}  // namespace softtrace
