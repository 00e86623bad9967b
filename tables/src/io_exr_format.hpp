// scatterlut runtime, internal — the OpenEXR mapping of a table (docs/FORMAT.md §4) that the
// EXR encoder (io_exr_encode.cpp) and decoder (io_exr_decode.cpp, io_exr_prescan.cpp) share:
// attribute names, the in-memory output stream, the header checksum. Not installed.
//
// One single-part scanline image, width = axis-0 count. A 1-D table is one row, a 2-D
// table has one row per axis-1 node, and the 2-D slices of a 3-D/4-D table are stacked
// vertically (an atlas): row y = i1 + c1·(i2 + c2·i3), which is exactly the order of
// Table::values, so a slice is a contiguous block of rows and the whole image uploads
// as a 3-D texture of depth c2·c3. One EXR channel per table channel, HALF for f16 and
// FLOAT for f32; f64 has no EXR pixel type. All metadata are `scatterlut.*` header
// attributes, protected by a checksum over their canonical serialization; the pixels
// are protected by the same FNV-1a payload checksum as the binary format.
//
// Mapping version 2 (written) names the channels as engine loaders expect (Y, or R, G,
// B, A; exr_channel_name) and keeps the table's channel names in attributes; every real
// number is a decimal string attribute (loaders such as three.js's skip `double`).
// Version 1 files (semantic channel names, `double` attributes) are still read.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <ImfAttribute.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfVersion.h>

#include "scatterlut/io.hpp"

namespace scatterlut::exr_format {

namespace Imf = OPENEXR_IMF_NAMESPACE;

inline const std::string kPrefix = "scatterlut.";
inline const std::string kChecksumPrefix = "scatterlut.checksum.";
inline constexpr const char *kLayout = "vertical_atlas";
// The binary header bound plus room for the attribute names and types.
inline constexpr size_t kMaxExrHeaderBytes = kMaxHeaderBytes + (1u << 20);

inline std::string axis_key(size_t i, const char *field) { return kPrefix + "axis." + std::to_string(i) + "." + field; }
inline std::string channel_key(size_t i, const char *field) {
    return kPrefix + "channel." + std::to_string(i) + "." + field;
}

// An OpenEXR output stream into memory.
class MemOStream : public Imf::OStream {
public:
    MemOStream() : Imf::OStream("<memory>") {}
    void write(const char c[], int n) override {
        if (n <= 0) return;
        const size_t end = pos_ + static_cast<size_t>(n);
        if (end > bytes.size()) bytes.resize(end);
        std::memcpy(bytes.data() + pos_, c, static_cast<size_t>(n));
        pos_ = end;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }
    std::vector<uint8_t> bytes;

private:
    size_t pos_ = 0;
};

// Checksum of the scatterlut.* attributes except scatterlut.checksum.*, in the header's
// (strcmp-sorted) order: for each, name, 0, type name, 0, u32 LE value size, value bytes
// as OpenEXR serializes them (little-endian, file version 2). Attributes this reader does
// not know are included, so a newer minor version's additions are protected too.
inline uint64_t header_checksum(const Imf::Header &h) {
    uint64_t sum = kFnv1a64Basis;
    const uint8_t zero = 0;
    for (auto it = h.begin(); it != h.end(); ++it) {
        const std::string name = it.name();
        if (name.compare(0, kPrefix.size(), kPrefix) != 0 || name.compare(0, kChecksumPrefix.size(), kChecksumPrefix) == 0)
            continue;
        MemOStream value;
        it.attribute().writeValueTo(value, Imf::EXR_VERSION);
        const char *type = it.attribute().typeName();
        uint8_t size_le[4];
        const uint32_t n = static_cast<uint32_t>(value.bytes.size());
        for (int k = 0; k < 4; ++k) size_le[k] = static_cast<uint8_t>(n >> (8 * k));
        sum = fnv1a64(name.data(), name.size(), sum);
        sum = fnv1a64(&zero, 1, sum);
        sum = fnv1a64(type, std::strlen(type), sum);
        sum = fnv1a64(&zero, 1, sum);
        sum = fnv1a64(size_le, 4, sum);
        sum = fnv1a64(value.bytes.data(), value.bytes.size(), sum);
    }
    return sum;
}

// Walks the raw attribute list of the EXR file data[0, size) (from byte 8, after magic and
// version) the way OpenEXR will read it, before OpenEXR reads it (io_exr_prescan.cpp).
// Returns the end of the header; LoadError naming `file` otherwise.
size_t prescan_exr_header(const std::string &file, const uint8_t *data, size_t size);

} // namespace scatterlut::exr_format
