// What `render` writes, as compositors and other tools read it: premultiplied or flattened RGBA,
// OpenEXR's standard header attributes, half channels, PNG's sRGB chunk and straight alpha, data
// windows, writing through symlinks and clearing stale temporary files. Images are read back
// with OpenImageIO and OpenEXR (not softtrace's own reader) where the format is in question.
#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfStringAttribute.h>
#include <OpenImageIO/imagebuf.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <future>
#include <thread>

#include "cli_util.h"
#include "film/film.h"
#include "io/image_file.h"
#include "render/camera.h"
#include "render/frame.h"
#include "render/frame_metadata.h"
#include "scene/scene.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

constexpr int kW = 40, kH = 30;

std::string render_args(const std::string& extra) {
  return "render " + source_path(kDefaultScene) + " --width " + std::to_string(kW) + " --height " +
         std::to_string(kH) + " --quiet " + extra;
}

struct Pixels {
  int w = 0, h = 0;
  std::vector<std::string> channels;
  std::vector<float> px;
  float at(int i, int c) const { return px[size_t(i) * channels.size() + c]; }
};

Pixels oiio_read(const std::string& path) {
  OIIO::ImageBuf buf(path);
  EXPECT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << path << ": " << buf.geterror();
  Pixels p{buf.spec().width, buf.spec().height, buf.spec().channelnames, {}};
  p.px.resize(size_t(p.w) * p.h * p.channels.size());
  buf.get_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, p.px.data());
  return p;
}

Vec3 background() {
  return load_scene(source_path(kDefaultScene)).background;
}

TEST(Outputs, PremultipliedByDefaultFlattenedOverTheBackground) {
  const std::string dir = temp_dir("outputs_premult");
  ASSERT_EQ(run_softtrace(render_args("--spp 4 -o " + dir + "/pre.exr")).status, 0);
  ASSERT_EQ(run_softtrace(render_args("--spp 4 --flatten -o " + dir + "/flat.exr")).status, 0);
  const Pixels pre = oiio_read(dir + "/pre.exr"), flat = oiio_read(dir + "/flat.exr");
  ASSERT_EQ(pre.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  ASSERT_EQ(flat.channels, pre.channels);
  const Vec3 bg = background();
  int empty = 0, partial = 0;
  for (int i = 0; i < kW * kH; ++i) {
    const float a = pre.at(i, 3);
    EXPECT_EQ(flat.at(i, 3), 1.0f);
    for (int k = 0; k < 3; ++k) {
      if (a == 0) {
        EXPECT_EQ(pre.at(i, k), 0.0f) << "pixel " << i;  // the background adds nothing
        EXPECT_EQ(flat.at(i, k), float(bg[k])) << "pixel " << i;
      }
      EXPECT_NEAR(pre.at(i, k) + float(bg[k]) * (1 - a), flat.at(i, k), 1e-6f) << "pixel " << i;
      EXPECT_LE(pre.at(i, k), a + 1e-6f);  // premultiplied: colour within coverage
    }
    empty += a == 0;
    partial += a > 0 && a < 1;
  }
  EXPECT_GT(empty, 100);
  EXPECT_GT(partial, 5);
}

// A compositor's "over" of the premultiplied image onto the background is the flattened render.
TEST(Outputs, OverTheBackgroundInOiiotoolEqualsFlatten) {
  const std::string dir = temp_dir("outputs_over");
  ASSERT_EQ(run_softtrace(render_args("--spp 4 -o " + dir + "/pre.exr")).status, 0);
  ASSERT_EQ(run_softtrace(render_args("--spp 4 --flatten -o " + dir + "/flat.exr")).status, 0);
  const Vec3 bg = background();
  char colour[96];
  std::snprintf(colour, sizeof colour, "%.9g,%.9g,%.9g,1", bg[0], bg[1], bg[2]);
  const RunResult over = run_command(
      "oiiotool " + dir + "/pre.exr --pattern constant:color=" + colour + " " + std::to_string(kW) +
      "x" + std::to_string(kH) + " 4 --over -o " + dir + "/over.exr");
  ASSERT_EQ(over.status, 0) << over.err;
  const RunResult d = run_softtrace("diff -fail 1e-6 " + dir + "/flat.exr " + dir + "/over.exr");
  EXPECT_EQ(d.status, 0) << d.out << d.err;
  EXPECT_EQ(run_command("idiff -fail 1e-6 " + dir + "/flat.exr " + dir + "/over.exr").status, 0);
}

TEST(Outputs, ExrHeaderHasStandardAndSofttraceAttributes) {
  const std::string dir = temp_dir("outputs_header");
  ASSERT_EQ(run_softtrace(render_args("--spp 2 --aov depth -o " + dir + "/h.exr")).status, 0);
  Imf::InputFile file((dir + "/h.exr").c_str());
  const Imf::Header& h = file.header();
  const auto* software = h.findTypedAttribute<Imf::StringAttribute>("software");
  ASSERT_NE(software, nullptr);
  EXPECT_EQ(software->value().rfind("softtrace ", 0), 0u) << software->value();
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("softtrace/scene").value(),
            "fig000_12b_soft_blend");
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("softtrace/sceneHash").value(),
            fnv1a64_hex(read_file(source_path(kDefaultScene))));
  EXPECT_EQ(h.typedAttribute<Imf::IntAttribute>("softtrace/spp").value(), 2);
  EXPECT_GT(h.typedAttribute<Imf::FloatAttribute>("renderTimeSeconds").value(), 0.0f);

  // worldToCamera: the eye at the origin, the target straight ahead (+z) at its distance.
  const Scene scene = load_scene(source_path(kDefaultScene));
  const Imath::M44f w2c = h.typedAttribute<Imf::M44fAttribute>("worldToCamera").value();
  const Imath::M44f w2ndc = h.typedAttribute<Imf::M44fAttribute>("worldToNDC").value();
  const auto v3 = [](const Vec3& v) { return Imath::V3f(float(v[0]), float(v[1]), float(v[2])); };
  Imath::V3f eye, target, up;
  w2c.multVecMatrix(v3(scene.camera.eye), eye);
  w2c.multVecMatrix(v3(scene.camera.target), target);
  w2c.multVecMatrix(v3(scene.camera.eye + scene.camera.up), up);
  const float dist = float(length(scene.camera.target - scene.camera.eye));
  EXPECT_NEAR(eye.length(), 0, 1e-3f * dist);
  EXPECT_NEAR(target.x, 0, 1e-4f * dist);
  EXPECT_NEAR(target.y, 0, 1e-4f * dist);
  EXPECT_NEAR(target.z, dist, 1e-4f * dist);
  EXPECT_GT(up.y, 0);  // y is up in the picture

  // worldToNDC: each hit point (from the depth AOV) lands on its pixel centre, (0,0) being the
  // top-left corner and (1,1) the bottom-right one.
  const Pixels z = oiio_read(dir + "/h.exr");
  ASSERT_EQ(z.channels[4], "Z");
  const ViewCamera camera(scene.camera, kW, kH);
  int checked = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float t = z.at(y * kW + x, 4);
      if (!std::isfinite(t)) continue;
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      Imath::V3f ndc;
      w2ndc.multVecMatrix(v3(ray.o + ray.d * t), ndc);
      EXPECT_NEAR(ndc.x, (x + 0.5f) / kW, 1e-4f) << x << "," << y;
      EXPECT_NEAR(ndc.y, (y + 0.5f) / kH, 1e-4f) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 100);
}

TEST(Outputs, SceneHashIsFnv1a64) {
  EXPECT_EQ(fnv1a64_hex(""), "cbf29ce484222325");
  EXPECT_EQ(fnv1a64_hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(fnv1a64_hex("foobar"), "85944171f73967e8");
}

TEST(Outputs, HalfStoresColourAsHalfAndDepthAsFloat) {
  const std::string dir = temp_dir("outputs_half");
  ASSERT_EQ(run_softtrace(render_args("--half --aov depth,steps -o " + dir + "/h.exr")).status, 0);
  ASSERT_EQ(run_softtrace(render_args("--aov depth,steps -o " + dir + "/f.exr")).status, 0);
  Imf::InputFile file((dir + "/h.exr").c_str());
  const Imf::ChannelList& ch = file.header().channels();
  for (const char* c : {"R", "G", "B", "A"}) EXPECT_EQ(ch.findChannel(c)->type, Imf::HALF) << c;
  EXPECT_EQ(ch.findChannel("Z")->type, Imf::FLOAT);
  EXPECT_EQ(ch.findChannel("steps")->type, Imf::FLOAT);
  EXPECT_EQ(Imf::InputFile((dir + "/f.exr").c_str()).header().channels().findChannel("R")->type,
            Imf::FLOAT);
  const RunResult d = run_softtrace("diff -fail 0.001 " + dir + "/f.exr " + dir + "/h.exr");
  EXPECT_EQ(d.status, 0) << d.out;
}

float srgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

TEST(Outputs, PngSaysSrgbAndKeepsStraightAlpha) {
  const std::string dir = temp_dir("outputs_png");
  ASSERT_EQ(
      run_softtrace(render_args("--spp 4 -o " + dir + "/pre.exr -o " + dir + "/rgb.png")).status,
      0);
  ASSERT_EQ(run_softtrace(render_args("--spp 4 --png-alpha -o " + dir + "/rgba.png")).status, 0);
  for (const char* name : {"/rgb.png", "/rgba.png"}) {
    const std::string bytes = read_file(dir + name);
    const size_t srgb_chunk = bytes.find("sRGB"), data = bytes.find("IDAT");
    EXPECT_NE(srgb_chunk, std::string::npos) << name;
    EXPECT_LT(srgb_chunk, data) << name;
  }
  const Pixels pre = oiio_read(dir + "/pre.exr");
  const ImageFile rgb = read_image(dir + "/rgb.png"), rgba = read_image(dir + "/rgba.png");
  ASSERT_EQ(rgb.channels, (std::vector<std::string>{"R", "G", "B"}));
  ASSERT_EQ(rgba.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  const Vec3 bg = background();
  for (int i = 0; i < kW * kH; ++i) {
    const float a = pre.at(i, 3);
    EXPECT_NEAR(rgba.pixels[i * 4 + 3], a, 0.51f / 255) << i;
    for (int k = 0; k < 3; ++k) {
      const float straight = a > 0 ? pre.at(i, k) / a : 0.0f;
      EXPECT_NEAR(rgba.pixels[i * 4 + k], srgb(straight), 0.51f / 255) << i;
      EXPECT_NEAR(rgb.pixels[i * 3 + k], srgb(pre.at(i, k) + float(bg[k]) * (1 - a)), 0.51f / 255)
          << i;
    }
  }
}

// A film holds only the AOV planes asked for, and the frame fills what it holds: the same colour
// and depth whichever planes are there.
TEST(Outputs, FilmHoldsOnlyTheAovPlanesAskedFor) {
  Scene scene = load_scene(source_path(kDefaultScene));
  scene.image.width = kW;
  scene.image.height = kH;
  const TracedScene rt(scene, LipschitzMode::Local);
  Film all(kW, kH), depth_only(kW, kH, AovSelection{true, false, false}),
      none(kW, kH, AovSelection{});
  for (Film* f : {&all, &depth_only, &none})
    ASSERT_TRUE(render_frame(scene, rt, RenderOptions{}, *f, nullptr, nullptr));
  const size_t n = size_t(kW) * kH;
  EXPECT_EQ(all.normal.size(), n * 3);
  EXPECT_EQ(all.steps.size(), n);
  EXPECT_EQ(depth_only.depth.size(), n);
  EXPECT_TRUE(depth_only.normal.empty() && depth_only.steps.empty());
  EXPECT_TRUE(none.depth.empty() && none.normal.empty() && none.steps.empty());
  EXPECT_EQ(none.rgba, all.rgba);
  EXPECT_EQ(depth_only.rgba, all.rgba);
  EXPECT_EQ(depth_only.depth, all.depth);
  EXPECT_GT(std::count(all.depth.begin(), all.depth.end(), INFINITY), 100);  // background
}

// A crop's pixels go to the data window inside the whole frame's display window.
TEST(Outputs, DataWindowInsideDisplayWindow) {
  const std::string dir = temp_dir("outputs_window");
  Film film(8, 6);
  film.full_width = 20;
  film.full_height = 10;
  film.x0 = 5;
  film.y0 = 3;
  for (size_t i = 0; i < film.rgba.size(); ++i) film.rgba[i] = float(i % 97) / 97;
  const std::string path = dir + "/crop.exr";
  commit_image(write_image_temp(path, film, OutputOptions(), FrameInfo()), path);
  forget_pending_writes();
  OIIO::ImageBuf buf(path);
  ASSERT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << buf.geterror();
  const OIIO::ImageSpec& spec = buf.spec();
  EXPECT_EQ(spec.x, 5);
  EXPECT_EQ(spec.y, 3);
  EXPECT_EQ(spec.width, 8);
  EXPECT_EQ(spec.height, 6);
  EXPECT_EQ(spec.full_x, 0);
  EXPECT_EQ(spec.full_width, 20);
  EXPECT_EQ(spec.full_height, 10);
  EXPECT_EQ(buf.getchannel(5 + 2, 3 + 1, 0, 1), film.rgba[(1 * 8 + 2) * 4 + 1]);
  const ImageFile img = read_image(path);
  EXPECT_EQ(img.x0, 5);
  EXPECT_EQ(img.y0, 3);
  EXPECT_EQ(img.full_width, 20);
  EXPECT_EQ(img.full_height, 10);
  EXPECT_EQ(img.pixels, std::vector<float>(film.rgba.begin(), film.rgba.end()));
}

// OpenImageIO's channel order, as idiff reports channels.
TEST(Outputs, ReaderListsChannelsAsOpenImageIO) {
  const std::string dir = temp_dir("outputs_order");
  const std::vector<std::string> names = {"foo", "Y",   "N.Z", "diffuse.B", "diffuse.R",
                                          "A",   "b",   "Z",   "P.X",       "P.Y",
                                          "L.q", "L.A", "L.B", "real"};
  OIIO::ImageSpec spec(3, 2, int(names.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  OIIO::ImageBuf buf(spec);
  ASSERT_TRUE(buf.write(dir + "/odd.exr"));
  EXPECT_EQ(read_image(dir + "/odd.exr").channels, oiio_read(dir + "/odd.exr").channels);
}

TEST(Outputs, SymlinkKeepsTheLinkAndReplacesItsTarget) {
  const std::string dir = temp_dir("outputs_symlink");
  fs::create_directories(dir + "/real");
  std::ofstream(dir + "/real/target.exr") << "old";
  fs::create_symlink("real/target.exr", dir + "/link.exr");
  fs::create_symlink("link.exr", dir + "/link2.exr");         // a chain
  fs::create_symlink("real/new.png", dir + "/dangling.png");  // a target yet to be made
  const RunResult r =
      run_softtrace(render_args("-o " + dir + "/link2.exr -o " + dir + "/dangling.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(dir + "/link.exr"));
  EXPECT_TRUE(fs::is_symlink(dir + "/link2.exr"));
  EXPECT_TRUE(fs::is_symlink(dir + "/dangling.png"));
  EXPECT_EQ(fs::read_symlink(dir + "/link2.exr"), "link.exr");
  EXPECT_EQ(read_image(dir + "/real/target.exr").width, kW);
  EXPECT_EQ(read_image(dir + "/real/new.png").width, kW);
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    left.push_back(e.path().lexically_relative(dir).string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"dangling.png", "link.exr", "link2.exr", "real",
                                            "real/new.png", "real/target.exr"}));
}

void set_mtime(const std::string& path, time_t t) {
  const timespec times[2] = {{t, 0}, {t, 0}};
  ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), times, AT_SYMLINK_NOFOLLOW), 0) << path;
}

// A SIGKILL leaves `.NAME.XXXXXX` behind; the next run writing NAME removes it, and nothing
// else: not a file some process holds locked, not one newer than the run, not other names.
TEST(Outputs, StaleTemporariesOfTheSameOutputAreRemoved) {
  const std::string dir = temp_dir("outputs_stale");
  const time_t hour_ago = std::time(nullptr) - 3600, in_an_hour = std::time(nullptr) + 3600;
  const auto make = [&](const std::string& name, time_t mtime) {
    std::ofstream(dir + "/" + name) << "partial";
    set_mtime(dir + "/" + name, mtime);
  };
  make(".out.exr.ABC123", hour_ago);    // stale: goes
  make(".out.exr.zz9Q0a", hour_ago);    // stale: goes
  make(".out.exr.LOCKED", hour_ago);    // held by a live writer (this test): stays
  make(".out.exr.FRESH1", in_an_hour);  // not older than the run: stays
  make(".out.exr.ABC12", hour_ago);     // not the pattern: stays
  make(".out.exr.ABC1234", hour_ago);   // not the pattern: stays
  make(".out.exr.AB-123", hour_ago);    // not the pattern: stays
  make(".other.exr.ABC123", hour_ago);  // another output's: stays
  make("victim.txt", hour_ago);
  fs::create_symlink("victim.txt", dir + "/.out.exr.LINK01");  // not a regular file: stays
  set_mtime(dir + "/.out.exr.LINK01", hour_ago);
  const int held = ::open((dir + "/.out.exr.LOCKED").c_str(), O_RDONLY);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX), 0);

  const RunResult r = run_softtrace(render_args("-o " + dir + "/out.exr"));
  ::close(held);
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left,
            (std::vector<std::string>{".other.exr.ABC123", ".out.exr.AB-123", ".out.exr.ABC12",
                                      ".out.exr.ABC1234", ".out.exr.FRESH1", ".out.exr.LINK01",
                                      ".out.exr.LOCKED", "out.exr", "victim.txt"}));
  EXPECT_EQ(read_file(dir + "/victim.txt"), "partial");
}

// Threads writing at once (Python renders) each own their pending files: one thread's failure
// (abandon) removes its own temporary files and never another thread's, which then commits.
TEST(Outputs, PendingWritesBelongToTheirThread) {
  const std::string dir = temp_dir("outputs_pending_threads");
  std::promise<std::string> created;
  std::promise<void> abandoned;
  std::thread writer([&] {
    const std::string tmp = create_pending_temp(dir + "/kept.exr", "kept.exr");
    created.set_value(tmp);
    abandoned.get_future().wait();
    commit_temp(tmp, dir + "/kept.exr", "kept.exr");
    forget_pending_writes();
  });
  const std::string kept = created.get_future().get();
  const std::string own = create_pending_temp(dir + "/failed.exr", "failed.exr");
  abandon_pending_writes();
  EXPECT_FALSE(fs::exists(own));
  EXPECT_TRUE(fs::exists(kept));
  abandoned.set_value();
  writer.join();
  EXPECT_TRUE(fs::exists(dir + "/kept.exr"));
  EXPECT_FALSE(fs::exists(kept));
}

// A commit syncs through the lock's descriptor of the calling thread's own pending file: another
// thread's file is refused and left as it is (not renamed, not removed), for its owner to commit.
TEST(Outputs, ACommitTakesOnlyTheCallingThreadsPendingFile) {
  const std::string dir = temp_dir("outputs_commit_owner");
  std::promise<std::string> created;
  std::promise<void> tried;
  std::thread writer([&] {
    const std::string tmp = create_pending_temp(dir + "/theirs.exr", "theirs.exr");
    std::ofstream(tmp) << "complete";
    created.set_value(tmp);
    tried.get_future().wait();
    commit_temp(tmp, dir + "/theirs.exr", "theirs.exr");
    forget_pending_writes();
  });
  const std::string tmp = created.get_future().get();
  EXPECT_THROW(commit_temp(tmp, dir + "/theirs.exr", "theirs.exr"), std::runtime_error);
  EXPECT_TRUE(fs::exists(tmp));
  EXPECT_FALSE(fs::exists(dir + "/theirs.exr"));
  tried.set_value();
  writer.join();
  EXPECT_EQ(read_file(dir + "/theirs.exr"), "complete");
  EXPECT_FALSE(fs::exists(tmp));
}

// The header's scene hash is that of the text parsed: a scene parsed from text, named as no
// file is, has one, and a file edited after loading does not change it.
TEST(Outputs, SceneHashIsOfTheParsedText) {
  const std::string text = read_file(source_path(kDefaultScene));
  const Scene parsed = parse_scene(text, "no/such/scene.json");
  EXPECT_EQ(frame_info(parsed, kW, kH).scene_hash, fnv1a64_hex(text));
  const std::string dir = temp_dir("outputs_hash_edit");
  const std::string path = dir + "/scene.json";
  std::ofstream(path) << text;
  const Scene loaded = load_scene(path);
  std::ofstream(path) << "{}";
  EXPECT_EQ(frame_info(loaded, kW, kH).scene_hash, fnv1a64_hex(text));
}

}  // namespace
}  // namespace softtrace::test
