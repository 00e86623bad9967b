// scatterlut runtime — the pre-scan of an EXR file's header: the attribute list walked the way
// OpenEXR will read it, every declared size checked against the value's structure and the
// bytes that remain, before OpenEXR reads (and allocates from) any of it.
#include "scatterlut/io.hpp"

#include <algorithm>
#include <cstring>

#include "io_exr_format.hpp"

namespace scatterlut::exr_format {

namespace {

[[noreturn]] void fail(const std::string &file, const std::string &what) { throw LoadError(file + ": " + what); }

// The pre-scan. OpenEXR's Header::readFrom reads an attribute's name, type and declared
// size, then hands the stream to the type's readValueFrom, and never checks that the value
// used up exactly the declared size. Most types read by their own structure: a chlist
// reads channel records up to its empty name, an int reads 4 bytes, whatever the size
// says. A file whose sizes disagree with the values therefore puts OpenEXR out of step
// with any walk that trusts the sizes: it parses bytes inside a value as further
// attributes, and a string attribute found there is allocated at its declared size
// (tests/fuzz/known/exr-oom-1: a chlist claiming 2327 bytes holds 22, OpenEXR reads on and
// meets a "string" whose size field is four bytes of text, 2.0 GB). So the walk reads
// every value the way OpenEXR will and requires the declared size to agree, which keeps
// both walks on the same attribute boundaries; each size is then bounded by the bytes
// that remain before OpenEXR allocates from it.

// Types OpenEXR 3 reads as a fixed number of bytes (Xdr sizes of their fields).
struct FixedSizeType {
    const char *name;
    size_t bytes;
};
constexpr FixedSizeType kFixedSizeTypes[] = {
    {"box2f", 16}, {"box2i", 16},   {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
    {"double", 8}, {"envmap", 1},   {"float", 4},           {"int", 4},         {"keycode", 28},
    {"lineOrder", 1}, {"m33d", 72}, {"m33f", 36},           {"m44d", 128},      {"m44f", 64},
    {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},      {"v2d", 16},        {"v2f", 8},
    {"v2i", 8},    {"v3d", 24},     {"v3f", 12},            {"v3i", 12},
};

int32_t le_i32(const uint8_t *p) {
    return static_cast<int32_t>(uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24);
}

// Checks that OpenEXR reads the value v[0, len) of attribute `name` of type `type` as
// exactly len bytes, and that nothing in it sizes an allocation beyond len.
void check_exr_value(const std::string &file, const std::string &name, const std::string &type, const uint8_t *v,
                     size_t len) {
    const std::string what = "EXR header: attribute '" + name + "' of type " + type + " declares " +
                             std::to_string(len) + " bytes";
    for (const FixedSizeType &f : kFixedSizeTypes)
        if (type == f.name) {
            if (len != f.bytes) fail(file, what + ", but a value of type " + type + " is " + std::to_string(f.bytes) + " bytes");
            return;
        }
    if (type == "string") return; // read as exactly len bytes
    if (type == "floatvector") {
        if (len % 4 != 0) fail(file, what + ", not a multiple of 4 (floats)");
        return;
    }
    if (type == "stringvector") { // {i32 n, n bytes}* up to len
        size_t pos = 0;
        while (pos < len) {
            if (len - pos < 4) fail(file, what + ": a string length at value byte " + std::to_string(pos) + " runs past it");
            const int32_t n = le_i32(v + pos);
            pos += 4;
            if (n < 0 || static_cast<size_t>(n) > len - pos)
                fail(file, what + ": a string at value byte " + std::to_string(pos - 4) + " claims " + std::to_string(n) +
                       " bytes, " + std::to_string(len - pos) + " remain");
            pos += static_cast<size_t>(n);
        }
        return;
    }
    if (type == "chlist") { // {name\0, i32 type, u8 pLinear, 3 reserved, i32 xs, i32 ys}*, \0
        size_t pos = 0;
        for (;;) {
            const size_t limit = std::min<size_t>(256, len - pos);
            const void *nul = limit ? std::memchr(v + pos, 0, limit) : nullptr;
            if (!nul) fail(file, what + ": a channel name at value byte " + std::to_string(pos) + " is unterminated or longer than 255 bytes");
            const size_t n = static_cast<size_t>(static_cast<const uint8_t *>(nul) - (v + pos));
            pos += n + 1;
            if (n == 0) break;
            if (len - pos < 16) fail(file, what + ": channel record at value byte " + std::to_string(pos) + " runs past it");
            pos += 16;
        }
        if (pos != len) fail(file, what + ", but its channel list ends after " + std::to_string(pos));
        return;
    }
    if (type == "preview") { // i32 width, i32 height, 4·width·height bytes
        if (len < 8) fail(file, what + ", less than a preview's 8-byte size");
        const int32_t w = le_i32(v), h = le_i32(v + 4);
        if (w < 0 || h < 0 || static_cast<uint64_t>(w) * static_cast<uint64_t>(h) * 4 + 8 != len)
            fail(file, what + ", but a " + std::to_string(w) + " x " + std::to_string(h) + " preview needs " +
                   std::to_string(static_cast<uint64_t>(std::max(w, 0)) * static_cast<uint64_t>(std::max(h, 0)) * 4 + 8));
        return;
    }
    // A type OpenEXR does not know is kept opaque: exactly len bytes. One it knows but we do
    // not (idmanifest, …) could read any amount: scatterlut tables never carry them.
    if (Imf::Attribute::knownType(type.c_str()))
        fail(file, "EXR header: attribute '" + name + "' has type " + type +
               ", which scatterlut tables do not use and this reader does not check");
}

} // namespace

// Walks the attribute list (name\0 type\0 i32 size value …, then \0) as OpenEXR will read
// it, checking every size against the value's structure and the bytes that remain.
// Returns the end of the header.
size_t prescan_exr_header(const std::string &file, const uint8_t *data, size_t size) {
    Imf::staticInitialize(); // the attribute type registry, for knownType
    size_t pos = 8;
    for (;;) {
        if (pos >= size) fail(file, "truncated: the EXR header ends at byte " + std::to_string(size) + " without its terminator");
        if (data[pos] == 0) return pos + 1;
        std::string fields[2];
        for (std::string &f : fields) {
            const size_t limit = std::min<size_t>(256, size - pos);
            const void *nul = std::memchr(data + pos, 0, limit);
            if (!nul) {
                if (limit < 256) fail(file, "truncated inside the EXR header at byte " + std::to_string(size));
                fail(file, "EXR header: attribute name or type at byte " + std::to_string(pos) + " is longer than 255 bytes");
            }
            f.assign(reinterpret_cast<const char *>(data + pos), static_cast<const uint8_t *>(nul) - (data + pos));
            pos += f.size() + 1;
        }
        if (fields[1].empty()) fail(file, "EXR header: attribute '" + fields[0] + "' has an empty type name");
        if (size - pos < 4) fail(file, "truncated inside the EXR header at byte " + std::to_string(size));
        const int32_t len = le_i32(data + pos);
        pos += 4;
        if (len < 0 || static_cast<size_t>(len) > size - pos)
            fail(file, "truncated or corrupt EXR header: attribute '" + fields[0] + "' claims " + std::to_string(len) +
                   " bytes but only " + std::to_string(size - pos) + " remain");
        check_exr_value(file, fields[0], fields[1], data + pos, static_cast<size_t>(len));
        pos += static_cast<size_t>(len);
        if (pos > kMaxExrHeaderBytes)
            fail(file, "EXR header is larger than " + std::to_string(kMaxExrHeaderBytes) + " bytes");
    }
}

} // namespace scatterlut::exr_format
