#include "io/mesh_file.h"

#include <cstdint>
#include <memory>
#include <stdexcept>

#include "io/output_file.h"

namespace softtrace {

const char* const kMeshExtensions[] = {".obj", ".ply", ".stl", ".glb", nullptr};

MeshFormat mesh_format(const std::string& path) {
  const std::string ext = output_extension(path);
  if (ext == ".stl") return MeshFormat::Stl;
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".glb") return MeshFormat::Glb;
  throw std::invalid_argument(path + ": unsupported mesh format '" + ext +
                              "' (expected .obj, .ply, .stl or .glb)");
}

void write_mesh(const std::string& path, const Mesh& m) {
  const MeshFormat format = mesh_format(path);
  const size_t nv = m.vertices.size();
  if (m.normals.size() != nv || m.colors.size() != nv)
    throw std::invalid_argument(path + ": a mesh needs one normal and one colour per vertex");
  if (nv > size_t(INT32_MAX)) throw std::invalid_argument(path + ": more than 2^31 vertices");
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (uint32_t v : m.faces[f])
      if (v >= nv)
        throw std::invalid_argument(path + ": face " + std::to_string(f) + " names vertex " +
                                    std::to_string(v) + " of " + std::to_string(nv));
  const std::string target = resolve_output_target(path);
  remove_stale_temporaries(target, process_start_time());
  const std::string tmp = create_pending_temp(target, path);
  try {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(tmp.c_str(), "wb"), std::fclose);
    if (!out) throw std::runtime_error("cannot open the temporary file");
    switch (format) {
      case MeshFormat::Stl:
        write_stl(out.get(), m);
        break;
      case MeshFormat::Obj:
        write_obj(out.get(), m);
        break;
      case MeshFormat::Ply:
        write_ply(out.get(), m);
        break;
      case MeshFormat::Glb:
        write_glb(out.get(), m);
        break;
    }
    if (std::fflush(out.get()) != 0 || std::ferror(out.get()))
      throw std::runtime_error("write failed (disk full?)");
    if (std::fclose(out.release()) != 0) throw std::runtime_error("write failed (disk full?)");
    commit_temp(tmp, target, path);
  } catch (const std::exception& e) {
    abandon_pending_writes();
    throw std::runtime_error(path + ": " + e.what());
  }
  forget_pending_writes();
}

}  // namespace softtrace
