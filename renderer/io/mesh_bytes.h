// Little-endian binary output for the mesh writers (every target softtrace builds for is
// little-endian; the static_assert below keeps it so).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the mesh writers write memory as is");

namespace softtrace::mesh_bytes {

inline void put(std::FILE* out, const void* data, size_t size) {
  if (size && std::fwrite(data, 1, size, out) != size)
    throw std::runtime_error("write failed (disk full?)");
}
template <class T>
void put_value(std::FILE* out, T v) {
  put(out, &v, sizeof v);
}

}  // namespace softtrace::mesh_bytes
