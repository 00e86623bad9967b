// PNG with stored deflate blocks; layout: PNG specification (W3C, 2nd ed.) §5 (signature,
// chunks: length, type, data, CRC over type + data), §11.2.2 (IHDR), §10 (zlib stream:
// CMF/FLG, deflate data, Adler-32 of the uncompressed bytes); RFC 1951 §3.2.4 (a stored
// block: BFINAL/BTYPE=00 byte, LEN, NLEN = ~LEN, then LEN literal bytes, LEN ≤ 65535).
#include "png_writer.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace scatterlut::png {
namespace {

const std::array<uint32_t, 256> &crc_table() {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t k = 0; k < 256; ++k) {
            uint32_t v = k;
            for (int b = 0; b < 8; ++b) v = (v & 1) ? 0xedb88320u ^ (v >> 1) : v >> 1;
            t[k] = v;
        }
        return t;
    }();
    return table;
}

void put_u32_be(std::vector<uint8_t> &out, uint32_t x) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<uint8_t>(x >> s));
}

void put_chunk(std::vector<uint8_t> &png, const char type[4], const std::vector<uint8_t> &data) {
    put_u32_be(png, static_cast<uint32_t>(data.size()));
    const size_t start = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data.begin(), data.end());
    put_u32_be(png, crc32(&png[start], png.size() - start));
}

} // namespace

uint32_t crc32(const uint8_t *data, size_t size) {
    const auto &table = crc_table();
    uint32_t c = 0xffffffffu;
    for (size_t k = 0; k < size; ++k) c = table[(c ^ data[k]) & 0xff] ^ (c >> 8);
    return c ^ 0xffffffffu;
}

uint32_t adler32(const uint8_t *data, size_t size) {
    uint32_t a = 1, b = 0;
    for (size_t k = 0; k < size; ++k) {
        a = (a + data[k]) % 65521;
        b = (b + a) % 65521;
    }
    return b << 16 | a;
}

std::vector<uint8_t> encode_rgb8(const std::vector<uint8_t> &rgb, int width, int height) {
    if (width < 1 || height < 1)
        throw std::invalid_argument("PNG: image size " + std::to_string(width) + " x " + std::to_string(height) +
                                    " must be at least 1 x 1");
    const size_t row_bytes = 3 * static_cast<size_t>(width);
    if (rgb.size() / row_bytes != static_cast<size_t>(height) || rgb.size() % row_bytes != 0)
        throw std::invalid_argument("PNG: " + std::to_string(rgb.size()) + " bytes of pixels for a " +
                                    std::to_string(width) + " x " + std::to_string(height) + " RGB image");

    // Scanlines, each preceded by its filter type (0: none).
    std::vector<uint8_t> raw;
    raw.reserve(static_cast<size_t>(height) * (1 + row_bytes));
    for (size_t j = 0; j < static_cast<size_t>(height); ++j) {
        raw.push_back(0);
        raw.insert(raw.end(), rgb.begin() + static_cast<std::ptrdiff_t>(j * row_bytes),
                   rgb.begin() + static_cast<std::ptrdiff_t>((j + 1) * row_bytes));
    }

    // zlib: CMF 0x78 (deflate, 32 KiB window), FLG 0x01 (check bits: 0x7801 % 31 == 0).
    std::vector<uint8_t> z = {0x78, 0x01};
    z.reserve(raw.size() + raw.size() / 65535 * 5 + 16);
    for (size_t pos = 0; pos < raw.size();) {
        const size_t n = std::min<size_t>(65535, raw.size() - pos);
        const bool last = pos + n == raw.size();
        z.push_back(last ? 1 : 0); // BFINAL, BTYPE = 00 (stored)
        z.push_back(static_cast<uint8_t>(n));
        z.push_back(static_cast<uint8_t>(n >> 8));
        z.push_back(static_cast<uint8_t>(~n));
        z.push_back(static_cast<uint8_t>(~n >> 8));
        z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(pos),
                 raw.begin() + static_cast<std::ptrdiff_t>(pos + n));
        pos += n;
    }
    put_u32_be(z, adler32(raw.data(), raw.size()));

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<uint8_t> ihdr;
    put_u32_be(ihdr, static_cast<uint32_t>(width));
    put_u32_be(ihdr, static_cast<uint32_t>(height));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0}); // bit depth 8, colour type 2 (RGB), deflate, filter 0, no interlace
    put_chunk(png, "IHDR", ihdr);
    put_chunk(png, "IDAT", z);
    put_chunk(png, "IEND", {});
    return png;
}

} // namespace scatterlut::png
