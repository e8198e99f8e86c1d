// The Adler-32 checksum of a zlib stream (RFC 1950), in SSE2: the PNG's bands are deflated raw and
// their checksum made apart (png_io.cpp), where zlib's adler32 took 3.6 instructions a byte, 1.1
// M of molecule's 320x240 process and 4.4 M of meets1's at 640x480; this takes under one.
#pragma once

#include <cstddef>
#include <cstdint>

namespace softtrace {

// zlib's adler32(adler, bytes, length): `adler` is the checksum of what came before (1 for
// nothing).
uint32_t adler32_of(uint32_t adler, const unsigned char* bytes, size_t length);

}  // namespace softtrace
