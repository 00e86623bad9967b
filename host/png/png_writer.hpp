// scatterlut — a minimal PNG encoder for pictures the tools write (render_fog's images,
// `scatterlut inspect --preview`). Not part of the runtime library's API and not
// installed: the internal static library scatterlut_png.
//
// 8-bit RGB, no interlace, filter type 0 on every row, and the zlib stream made of
// stored (uncompressed) deflate blocks (RFC 1950/1951), so no zlib dependency; any PNG
// reader decodes it. Files are larger than compressed PNGs (≈ 3 bytes per pixel).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scatterlut::png {

// rgb: width·height pixels, row-major from the top row, 3 bytes (R, G, B) each.
// Throws std::invalid_argument if the sizes disagree or a dimension is not in
// [1, 2^31 − 1]. Write the result with scatterlut::write_file_atomic.
std::vector<uint8_t> encode_rgb8(const std::vector<uint8_t> &rgb, int width, int height);

// CRC-32 (ISO 3309 / PNG, polynomial 0xedb88320 reflected) and Adler-32 (RFC 1950) of
// the bytes, as PNG chunks and zlib streams need them.
uint32_t crc32(const uint8_t *data, size_t size);
uint32_t adler32(const uint8_t *data, size_t size);

} // namespace scatterlut::png
