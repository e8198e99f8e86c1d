// Reading a whole input file (a scene, a mesh) with the refusals every input needs: a path with a
// NUL byte, a folder, and a file larger than the caller's limit, read in blocks so that an endless
// input (/dev/zero, a pipe) stops there instead of filling the memory.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace softtrace {

// Why a read was refused or failed: one line naming the path. Callers rethrow it as their own
// error (SceneError, MeshReadError) with the same message.
struct FileReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws FileReadError "<path up to the NUL>...: a path with a NUL byte" when `path` holds one: a
// C string would end there, and "x.json\0junk" must not open x.json.
void refuse_nul_in_path(const std::string& path);

// Whether the read stops after the first 64 KiB block that holds a NUL byte (a text format, whose
// parser then names the NUL's line and column) or reads on to the end.
enum class AtNul { Stop, ReadOn };

// The bytes of the file at `path`, read in 64 KiB blocks. Throws FileReadError, `what` naming the
// file ("scene", "mesh"): "<path>...: a path with a NUL byte", "<path>: is a folder, not a <what>
// file", "<path>: cannot open the <what> file", "<path>: larger than <limit in MiB> MiB; a <what>
// file may be at most that" (once more than `limit` bytes are read), "<path>: cannot read the
// <what> file".
std::string read_file_bounded(const std::string& path, size_t limit, const std::string& what,
                              AtNul at_nul);

}  // namespace softtrace
