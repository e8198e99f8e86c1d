// softtrace merge: tiles of one frame (render --tile/--crop/--pixel-bounds outputs) put back
// together (render/tile_merge.h) and written all or nothing.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "film/film.h"
#include "io/image_file.h"
#include "render/tile_merge.h"

namespace softtrace {

// SIGINT/SIGTERM: main()'s handler, exit_on_interrupt, removes the temporary output file, if
// any, and exits (signals.h). A signal after the rename changes nothing: the output is complete.
int run_merge(const MergeArgs& a) {
  try {
    check_image_output_path(a.output);
    std::vector<ImageFile> tiles;
    for (const auto& path : a.tiles) tiles.push_back(read_image(path));

    const Film film = merge_tiles(tiles, a.tiles);
    const auto attribute = [&](const std::string& name) {
      const auto it = tiles[0].attributes.find(name);
      return it == tiles[0].attributes.end() ? std::string() : it->second;
    };
    // The tiles' pixels go out as they came in (already premultiplied or flattened), with the
    // header facts the tiles carry as strings.
    OutputOptions opt;
    opt.aovs = {!film.depth.empty(), !film.normal.empty(), !film.steps.empty(),
                !film.albedo.empty()};
    FrameInfo info;
    info.scene_name = attribute("softtrace/scene");
    info.scene_hash = attribute("softtrace/sceneHash");
    const std::string settings = attribute("softtrace/render");
    const size_t spp_at = settings.find(" spp=");
    if (spp_at != std::string::npos) info.spp = std::atoi(settings.c_str() + spp_at + 5);
    const std::string tmp = write_image_temp(a.output, film, opt, info);
    commit_image(tmp, a.output);
    forget_pending_writes();
    if (!a.quiet)
      std::fprintf(stderr, "%zu tiles -> %dx%d %s\n", tiles.size(), film.width, film.height,
                   a.output.c_str());
    return 0;
  } catch (const std::exception& e) {
    abandon_pending_writes();  // a failed write leaves no temporary file behind
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace
