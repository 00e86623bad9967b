// scatterlut runtime — tables as OpenEXR images (docs/FORMAT.md §4).
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
#include "scatterlut/io.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <limits>
#include <set>
#include <sstream>

#include <ImfAttribute.h>
#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfStringVectorAttribute.h>
#include <ImfVersion.h>

#include "io_text.hpp"

namespace scatterlut {

using detail::digits17;
using detail::hex64;

namespace {

namespace Imf = OPENEXR_IMF_NAMESPACE;

const std::string kPrefix = "scatterlut.";
const std::string kChecksumPrefix = "scatterlut.checksum.";
const char *kLayout = "vertical_atlas";
// The binary header bound plus room for the attribute names and types.
constexpr size_t kMaxExrHeaderBytes = kMaxHeaderBytes + (1u << 20);

// --- in-memory streams ----------------------------------------------------------------

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

class MemIStream : public Imf::IStream {
public:
    MemIStream(const uint8_t *data, size_t size, const std::string &name)
        : Imf::IStream(name.c_str()), data_(data), size_(size) {}
    bool read(char c[], int n) override {
        if (n < 0 || pos_ > size_ || static_cast<size_t>(n) > size_ - pos_)
            throw std::runtime_error("unexpected end of file");
        std::memcpy(c, data_ + pos_, static_cast<size_t>(n));
        pos_ += static_cast<size_t>(n);
        return pos_ < size_;
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = pos > size_ ? size_ + 1 : static_cast<size_t>(pos); }
    void clear() override {}

private:
    const uint8_t *data_;
    size_t size_;
    size_t pos_ = 0;
};

// Checksum of the scatterlut.* attributes except scatterlut.checksum.*, in the header's
// (strcmp-sorted) order: for each, name, 0, type name, 0, u32 LE value size, value bytes
// as OpenEXR serializes them (little-endian, file version 2). Attributes this reader does
// not know are included, so a newer minor version's additions are protected too.
uint64_t header_checksum(const Imf::Header &h) {
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

std::string axis_key(size_t i, const char *field) { return kPrefix + "axis." + std::to_string(i) + "." + field; }
std::string channel_key(size_t i, const char *field) {
    return kPrefix + "channel." + std::to_string(i) + "." + field;
}

const char *pixel_type_name(Imf::PixelType t) {
    switch (t) {
    case Imf::UINT: return "UINT";
    case Imf::HALF: return "HALF";
    case Imf::FLOAT: return "FLOAT";
    default: return "unknown";
    }
}

} // namespace

bool have_openexr() { return true; }

// =====================================================================================
// Writer
// =====================================================================================

std::vector<uint8_t> encode_exr(const Table &t) {
    if (t.storage == Storage::F64)
        throw std::invalid_argument("EXR cannot store f64 (its pixel types are HALF and FLOAT): use the binary "
                                    "format for f64 tables, or storage f32/f16");
    detail::check_limits(t);
    if (t.quantity_version > static_cast<uint32_t>(std::numeric_limits<int>::max()))
        throw std::invalid_argument("quantity_version " + std::to_string(t.quantity_version) +
                                    " does not fit an EXR int attribute");
    const std::vector<uint8_t> payload = detail::encode_payload(t); // rounds, refuses overflow

    const size_t nc = t.channels.size();
    const size_t width = static_cast<size_t>(t.axes[0].map.count);
    const size_t height = t.node_count() / width; // ≤ 2^30, fits int
    Imf::Header h(static_cast<int>(width), static_cast<int>(height));
    h.compression() = Imf::ZIP_COMPRESSION;
    const Imf::PixelType type = t.storage == Storage::F16 ? Imf::HALF : Imf::FLOAT;
    std::vector<std::string> exr_names;
    for (size_t i = 0; i < nc; ++i) exr_names.push_back(exr_channel_name(nc, i, t.channels[i].name));
    for (const std::string &n : exr_names) h.channels().insert(n, Imf::Channel(type));
    // Every real number as text: the shortest decimal that reads back exactly.
    auto real = [](double x) { return Imf::StringAttribute(detail::decimal_text(x)); };

    h.insert(kPrefix + "format_major", Imf::IntAttribute(static_cast<int>(kExrFormatMajor)));
    h.insert(kPrefix + "format_minor", Imf::IntAttribute(static_cast<int>(kExrFormatMinor)));
    h.insert(kPrefix + "kind", Imf::StringAttribute(t.kind));
    h.insert(kPrefix + "quantity_version", Imf::IntAttribute(static_cast<int>(t.quantity_version)));
    h.insert(kPrefix + "storage", Imf::StringAttribute(to_string(t.storage)));
    h.insert(kPrefix + "layout", Imf::StringAttribute(kLayout));
    h.insert(kPrefix + "axes", Imf::IntAttribute(static_cast<int>(t.axes.size())));
    for (size_t i = 0; i < t.axes.size(); ++i) {
        const Axis &a = t.axes[i];
        h.insert(axis_key(i, "name"), Imf::StringAttribute(a.name));
        h.insert(axis_key(i, "meaning"), Imf::StringAttribute(a.meaning));
        h.insert(axis_key(i, "min"), real(a.map.min));
        h.insert(axis_key(i, "max"), real(a.map.max));
        h.insert(axis_key(i, "scale"), real(a.map.scale));
        h.insert(axis_key(i, "warp"), Imf::IntAttribute(a.map.warp));
        h.insert(axis_key(i, "warp_name"), Imf::StringAttribute(warp_name(a.map.warp)));
        h.insert(axis_key(i, "count"), Imf::IntAttribute(a.map.count));
    }
    h.insert(kPrefix + "channels", Imf::IntAttribute(static_cast<int>(nc)));
    for (size_t i = 0; i < nc; ++i) {
        h.insert(channel_key(i, "name"), Imf::StringAttribute(t.channels[i].name));
        h.insert(channel_key(i, "meaning"), Imf::StringAttribute(t.channels[i].meaning));
        h.insert(channel_key(i, "encoding"), Imf::StringAttribute(to_string(t.channels[i].encoding)));
        h.insert(channel_key(i, "exr_channel"), Imf::StringAttribute(exr_names[i]));
    }
    const Accuracy &ac = t.accuracy;
    h.insert(kPrefix + "accuracy.integration_max_rel", real(ac.integration_max_rel));
    h.insert(kPrefix + "accuracy.sampling_max_rel", real(ac.sampling_max_rel));
    h.insert(kPrefix + "accuracy.sampling_p99_rel", real(ac.sampling_p99_rel));
    h.insert(kPrefix + "accuracy.sampling_median_rel", real(ac.sampling_median_rel));
    h.insert(kPrefix + "accuracy.storage_max_rel", real(ac.storage_max_rel));
    h.insert(kPrefix + "accuracy.sampling_points", Imf::StringAttribute(std::to_string(ac.sampling_points)));
    h.insert(kPrefix + "accuracy.sampling_domain", Imf::StringAttribute(ac.sampling_domain));
    const Provenance &pv = t.provenance;
    h.insert(kPrefix + "provenance.generator_version", Imf::StringAttribute(pv.generator_version));
    h.insert(kPrefix + "provenance.command_line", Imf::StringAttribute(pv.command_line));
    h.insert(kPrefix + "provenance.scene", Imf::StringAttribute(pv.scene));
    h.insert(kPrefix + "provenance.device", Imf::StringAttribute(pv.device));
    h.insert(kPrefix + "provenance.created_by", Imf::StringAttribute(pv.created_by));
    Imf::StringVector extra;
    for (const auto &kv : t.extra) {
        extra.push_back(kv.first);
        extra.push_back(kv.second);
    }
    h.insert(kPrefix + "extra", Imf::StringVectorAttribute(extra));
    h.insert(kChecksumPrefix + "header", Imf::StringAttribute(hex64(header_checksum(h))));
    h.insert(kChecksumPrefix + "payload", Imf::StringAttribute(hex64(fnv1a64(payload.data(), payload.size()))));

    // Pixels in native layout, built from the little-endian payload (host-independent).
    const size_t n = t.values.size();
    std::vector<uint16_t> half_px;
    std::vector<float> float_px;
    char *base;
    size_t elem;
    if (type == Imf::HALF) {
        half_px.resize(n);
        for (size_t i = 0; i < n; ++i)
            half_px[i] = static_cast<uint16_t>(payload[2 * i] | payload[2 * i + 1] << 8);
        base = reinterpret_cast<char *>(half_px.data());
        elem = 2;
    } else {
        float_px.resize(n);
        for (size_t i = 0; i < n; ++i) {
            const uint8_t *p = &payload[4 * i];
            const uint32_t w = uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
            std::memcpy(&float_px[i], &w, 4);
        }
        base = reinterpret_cast<char *>(float_px.data());
        elem = 4;
    }
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < nc; ++c)
        fb.insert(exr_names[c], Imf::Slice::Make(type, base + c * elem, h.dataWindow(), nc * elem, nc * elem * width));

    MemOStream out;
    try {
        Imf::OutputFile file(out, h);
        file.setFrameBuffer(fb);
        file.writePixels(static_cast<int>(height));
    } catch (const std::exception &e) {
        throw std::runtime_error(std::string("OpenEXR could not encode the table: ") + e.what());
    }
    return std::move(out.bytes);
}

void save_exr(const Table &table, const std::string &path) { write_file_atomic(path, encode_exr(table)); }

// =====================================================================================
// Reader
// =====================================================================================

namespace {

struct ExrReader {
    std::string name;
    const Imf::Header *h = nullptr;
    std::set<std::string> used; // scatterlut.* attributes this reader understood
    int major = 0;              // the file's mapping version (1: double attributes, table channel names)
    std::vector<std::string> exr_channels; // the EXR channel of each table channel

    [[noreturn]] void fail(const std::string &what) const { throw LoadError(name + ": " + what); }
    [[noreturn]] void fail_checksum(const std::string &what) const { throw ChecksumError(name + ": " + what); }

    template <class A> const A *typed(const std::string &key, const char *want) {
        auto it = h->find(key);
        if (it == h->end()) fail("missing attribute '" + key + "' (" + want + ")");
        const A *a = dynamic_cast<const A *>(&it.attribute());
        if (!a) fail("attribute '" + key + "' has type " + it.attribute().typeName() + ", expected " + want);
        used.insert(key);
        return a;
    }
    int integer(const std::string &key) { return typed<Imf::IntAttribute>(key, "int")->value(); }
    // A real number: a `double` attribute in version 1, decimal text from version 2 on.
    double real(const std::string &key) {
        if (major < 2) return typed<Imf::DoubleAttribute>(key, "double")->value();
        const std::string s = text(key, 64);
        double v;
        if (!detail::parse_decimal_text(s, &v)) fail("attribute '" + key + "' = '" + s + "' is not a decimal number");
        return v;
    }
    std::string text(const std::string &key, size_t max) {
        const std::string &s = typed<Imf::StringAttribute>(key, "string")->value();
        if (s.size() > max)
            fail("attribute '" + key + "' is " + std::to_string(s.size()) + " bytes, more than the limit " +
                 std::to_string(max));
        return s;
    }
    uint64_t hex(const std::string &key) {
        const std::string s = text(key, 64);
        uint64_t v = 0;
        if (s.size() != 18 || s[0] != '0' || s[1] != 'x') fail("attribute '" + key + "' = '" + s + "' is not 0x + 16 hex digits");
        for (size_t i = 2; i < s.size(); ++i) {
            const char c = s[i];
            int d;
            if (c >= '0' && c <= '9') d = c - '0';
            else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
            else fail("attribute '" + key + "' = '" + s + "' is not 0x + 16 lowercase hex digits");
            v = v << 4 | static_cast<uint64_t>(d);
        }
        return v;
    }
};

Table decode_exr_header(ExrReader &r, const Imf::Header &h) {
    if (h.find(kPrefix + "format_major") == h.end())
        r.fail("is an OpenEXR image but not a scatterlut table (no attribute 'scatterlut.format_major')");

    // Version before anything else.
    const int major = r.integer(kPrefix + "format_major");
    const int minor = r.integer(kPrefix + "format_minor");
    const std::string version = std::to_string(major) + "." + std::to_string(minor);
    const std::string ours = std::to_string(kExrFormatMajor) + ".x";
    if (major > static_cast<int>(kExrFormatMajor))
        r.fail("format version " + version + " is newer than this reader (" + ours + "); upgrade scatterlut");
    if (major < 1 || minor < 0)
        r.fail("format version " + version + " is not supported by this reader (" + ours + ")");
    r.major = major;
    // The newest minor version this reader knows for the file's major version: 1.1 was the
    // last of the version-1 mapping.
    const int known_minor = major == static_cast<int>(kExrFormatMajor) ? static_cast<int>(kExrFormatMinor) : 1;

    const uint64_t stored_sum = r.hex(kChecksumPrefix + "header");
    r.hex(kChecksumPrefix + "payload");
    const uint64_t computed_sum = header_checksum(h);
    if (stored_sum != computed_sum)
        r.fail_checksum("header checksum mismatch (stored " + hex64(stored_sum) + ", computed " + hex64(computed_sum) +
               "): the scatterlut.* attributes are corrupt or were edited");

    Table t;
    t.kind = r.text(kPrefix + "kind", kMaxNameBytes);
    const int qv = r.integer(kPrefix + "quantity_version");
    if (qv < 0) r.fail("attribute 'scatterlut.quantity_version' is negative (" + std::to_string(qv) + ")");
    t.quantity_version = static_cast<uint32_t>(qv);
    const std::string storage = r.text(kPrefix + "storage", kMaxNameBytes);
    if (storage == "f16") t.storage = Storage::F16;
    else if (storage == "f32") t.storage = Storage::F32;
    else r.fail("attribute 'scatterlut.storage' = '" + storage + "': expected f16 or f32 in an EXR table");
    const std::string layout = r.text(kPrefix + "layout", kMaxNameBytes);
    if (layout != kLayout) r.fail("attribute 'scatterlut.layout' = '" + layout + "': expected '" + kLayout + "'");

    const int n_axes = r.integer(kPrefix + "axes");
    if (n_axes < 1 || n_axes > static_cast<int>(kMaxAxes))
        r.fail("attribute 'scatterlut.axes' = " + std::to_string(n_axes) + ": expected 1 to " +
               std::to_string(kMaxAxes));
    for (size_t i = 0; i < static_cast<size_t>(n_axes); ++i) {
        Axis a;
        a.name = r.text(axis_key(i, "name"), kMaxNameBytes);
        a.meaning = r.text(axis_key(i, "meaning"), kMaxTextBytes);
        a.map.min = r.real(axis_key(i, "min"));
        a.map.max = r.real(axis_key(i, "max"));
        a.map.scale = r.real(axis_key(i, "scale"));
        a.map.warp = r.integer(axis_key(i, "warp"));
        a.map.count = r.integer(axis_key(i, "count"));
        const std::string wname = r.text(axis_key(i, "warp_name"), kMaxNameBytes);
        const std::string label = "axis " + std::to_string(i) + " ('" + a.name + "')";
        if (a.map.warp < 0 || a.map.warp >= SLUT_WARP_COUNT)
            r.fail(label + ": unknown warp id " + std::to_string(a.map.warp) + " (this reader knows 0 to " +
                   std::to_string(SLUT_WARP_COUNT - 1) + ")");
        if (wname != warp_name(a.map.warp))
            r.fail(label + ": warp id " + std::to_string(a.map.warp) + " is '" + warp_name(a.map.warp) +
                   "' but warp_name says '" + wname + "'");
        if (a.map.count < 2)
            r.fail(label + ": count " + std::to_string(a.map.count) + " is invalid (need 2 <= count <= 2^31-1)");
        if (!std::isfinite(a.map.min) || !std::isfinite(a.map.max) || !std::isfinite(a.map.scale))
            r.fail(label + ": range [" + digits17(a.map.min) + ", " + digits17(a.map.max) + "] / scale " + digits17(a.map.scale) +
                   " is not finite");
        if (!(a.map.min < a.map.max))
            r.fail(label + ": min " + digits17(a.map.min) + " must be less than max " + digits17(a.map.max));
        t.axes.push_back(a);
    }
    long double nodes = 1;
    for (const Axis &a : t.axes) nodes *= static_cast<long double>(a.map.count);
    if (nodes > static_cast<long double>(kMaxNodes)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.0Lf", nodes);
        r.fail(std::string("attributes claim ") + buf + " nodes, more than the limit of 2^31");
    }

    const int n_channels = r.integer(kPrefix + "channels");
    if (n_channels < 1 || n_channels > static_cast<int>(kMaxChannels))
        r.fail("attribute 'scatterlut.channels' = " + std::to_string(n_channels) + ": expected 1 to " +
               std::to_string(kMaxChannels));
    for (size_t i = 0; i < static_cast<size_t>(n_channels); ++i) {
        Channel c;
        c.name = r.text(channel_key(i, "name"), kMaxNameBytes);
        c.meaning = r.text(channel_key(i, "meaning"), kMaxTextBytes);
        const std::string enc = r.text(channel_key(i, "encoding"), kMaxNameBytes);
        if (!encoding_from_string(enc, &c.encoding))
            r.fail("channel " + std::to_string(i) + " ('" + c.name + "'): unknown encoding '" + enc +
                   "' (this reader knows linear, log)");
        if (major >= 2) {
            const std::string exr = r.text(channel_key(i, "exr_channel"), kMaxNameBytes);
            const std::string want = exr_channel_name(static_cast<size_t>(n_channels), i, c.name);
            if (exr != want)
                r.fail("channel " + std::to_string(i) + " ('" + c.name + "'): attribute '" +
                       channel_key(i, "exr_channel") + "' = '" + exr + "', expected '" + want + "'");
            r.exr_channels.push_back(exr);
        } else {
            r.exr_channels.push_back(c.name);
        }
        t.channels.push_back(c);
    }

    Accuracy &ac = t.accuracy;
    ac.integration_max_rel = r.real(kPrefix + "accuracy.integration_max_rel");
    ac.sampling_max_rel = r.real(kPrefix + "accuracy.sampling_max_rel");
    ac.sampling_p99_rel = r.real(kPrefix + "accuracy.sampling_p99_rel");
    ac.sampling_median_rel = r.real(kPrefix + "accuracy.sampling_median_rel");
    ac.storage_max_rel = r.real(kPrefix + "accuracy.storage_max_rel");
    {
        const std::string key = kPrefix + "accuracy.sampling_points";
        const std::string s = r.text(key, 32);
        errno = 0;
        char *end = nullptr;
        const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
        if (s.empty() || s[0] < '0' || s[0] > '9' || *end != '\0' || errno == ERANGE)
            r.fail("attribute '" + key + "' = '" + s + "' is not an unsigned 64-bit decimal");
        ac.sampling_points = v;
    }
    ac.sampling_domain = r.text(kPrefix + "accuracy.sampling_domain", kMaxTextBytes);
    Provenance &pv = t.provenance;
    pv.generator_version = r.text(kPrefix + "provenance.generator_version", kMaxTextBytes);
    pv.command_line = r.text(kPrefix + "provenance.command_line", kMaxLongTextBytes);
    pv.scene = r.text(kPrefix + "provenance.scene", kMaxSceneBytes);
    pv.device = r.text(kPrefix + "provenance.device", kMaxTextBytes);
    pv.created_by = r.text(kPrefix + "provenance.created_by", kMaxTextBytes);
    const Imf::StringVector &extra =
        r.typed<Imf::StringVectorAttribute>(kPrefix + "extra", "stringvector")->value();
    if (extra.size() % 2 != 0) r.fail("attribute 'scatterlut.extra' has an odd number of strings (expected key, value pairs)");
    if (extra.size() / 2 > kMaxExtraEntries) r.fail("attribute 'scatterlut.extra' has more than 1024 entries");
    for (size_t i = 0; i < extra.size(); i += 2) {
        if (extra[i].size() > kMaxNameBytes || extra[i + 1].size() > kMaxLongTextBytes)
            r.fail("attribute 'scatterlut.extra': entry " + std::to_string(i / 2) + " exceeds the size limits");
        if (!t.extra.emplace(extra[i], extra[i + 1]).second)
            r.fail("attribute 'scatterlut.extra': key '" + extra[i] + "' appears twice");
    }

    // Unknown scatterlut.* attributes: skipped from a newer minor version, corrupt otherwise.
    if (minor <= known_minor) {
        for (auto it = h.begin(); it != h.end(); ++it) {
            const std::string key = it.name();
            if (key.compare(0, kPrefix.size(), kPrefix) == 0 && !r.used.count(key))
                r.fail("unknown attribute '" + key + "' (format version " + version + " defines no such attribute)");
        }
    }
    return t;
}

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
void check_exr_value(const ExrReader &r, const std::string &name, const std::string &type, const uint8_t *v,
                     size_t len) {
    const std::string what = "EXR header: attribute '" + name + "' of type " + type + " declares " +
                             std::to_string(len) + " bytes";
    for (const FixedSizeType &f : kFixedSizeTypes)
        if (type == f.name) {
            if (len != f.bytes) r.fail(what + ", but a value of type " + type + " is " + std::to_string(f.bytes) + " bytes");
            return;
        }
    if (type == "string") return; // read as exactly len bytes
    if (type == "floatvector") {
        if (len % 4 != 0) r.fail(what + ", not a multiple of 4 (floats)");
        return;
    }
    if (type == "stringvector") { // {i32 n, n bytes}* up to len
        size_t pos = 0;
        while (pos < len) {
            if (len - pos < 4) r.fail(what + ": a string length at value byte " + std::to_string(pos) + " runs past it");
            const int32_t n = le_i32(v + pos);
            pos += 4;
            if (n < 0 || static_cast<size_t>(n) > len - pos)
                r.fail(what + ": a string at value byte " + std::to_string(pos - 4) + " claims " + std::to_string(n) +
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
            if (!nul) r.fail(what + ": a channel name at value byte " + std::to_string(pos) + " is unterminated or longer than 255 bytes");
            const size_t n = static_cast<size_t>(static_cast<const uint8_t *>(nul) - (v + pos));
            pos += n + 1;
            if (n == 0) break;
            if (len - pos < 16) r.fail(what + ": channel record at value byte " + std::to_string(pos) + " runs past it");
            pos += 16;
        }
        if (pos != len) r.fail(what + ", but its channel list ends after " + std::to_string(pos));
        return;
    }
    if (type == "preview") { // i32 width, i32 height, 4·width·height bytes
        if (len < 8) r.fail(what + ", less than a preview's 8-byte size");
        const int32_t w = le_i32(v), h = le_i32(v + 4);
        if (w < 0 || h < 0 || static_cast<uint64_t>(w) * static_cast<uint64_t>(h) * 4 + 8 != len)
            r.fail(what + ", but a " + std::to_string(w) + " x " + std::to_string(h) + " preview needs " +
                   std::to_string(static_cast<uint64_t>(std::max(w, 0)) * static_cast<uint64_t>(std::max(h, 0)) * 4 + 8));
        return;
    }
    // A type OpenEXR does not know is kept opaque: exactly len bytes. One it knows but we do
    // not (idmanifest, …) could read any amount: scatterlut tables never carry them.
    if (Imf::Attribute::knownType(type.c_str()))
        r.fail("EXR header: attribute '" + name + "' has type " + type +
               ", which scatterlut tables do not use and this reader does not check");
}

// Walks the attribute list (name\0 type\0 i32 size value …, then \0) as OpenEXR will read
// it, checking every size against the value's structure and the bytes that remain.
// Returns the end of the header.
size_t prescan_exr_header(const ExrReader &r, const uint8_t *data, size_t size) {
    Imf::staticInitialize(); // the attribute type registry, for knownType
    size_t pos = 8;
    for (;;) {
        if (pos >= size) r.fail("truncated: the EXR header ends at byte " + std::to_string(size) + " without its terminator");
        if (data[pos] == 0) return pos + 1;
        std::string fields[2];
        for (std::string &f : fields) {
            const size_t limit = std::min<size_t>(256, size - pos);
            const void *nul = std::memchr(data + pos, 0, limit);
            if (!nul) {
                if (limit < 256) r.fail("truncated inside the EXR header at byte " + std::to_string(size));
                r.fail("EXR header: attribute name or type at byte " + std::to_string(pos) + " is longer than 255 bytes");
            }
            f.assign(reinterpret_cast<const char *>(data + pos), static_cast<const uint8_t *>(nul) - (data + pos));
            pos += f.size() + 1;
        }
        if (fields[1].empty()) r.fail("EXR header: attribute '" + fields[0] + "' has an empty type name");
        if (size - pos < 4) r.fail("truncated inside the EXR header at byte " + std::to_string(size));
        const int32_t len = le_i32(data + pos);
        pos += 4;
        if (len < 0 || static_cast<size_t>(len) > size - pos)
            r.fail("truncated or corrupt EXR header: attribute '" + fields[0] + "' claims " + std::to_string(len) +
                   " bytes but only " + std::to_string(size - pos) + " remain");
        check_exr_value(r, fields[0], fields[1], data + pos, static_cast<size_t>(len));
        pos += static_cast<size_t>(len);
        if (pos > kMaxExrHeaderBytes)
            r.fail("EXR header is larger than " + std::to_string(kMaxExrHeaderBytes) + " bytes");
    }
}

} // namespace

Table decode_exr(const uint8_t *data, size_t size, const std::string &name) {
    ExrReader r;
    r.name = name;
    if (data == nullptr || size < 4 || data[0] != 0x76 || data[1] != 0x2f || data[2] != 0x31 || data[3] != 0x01)
        r.fail("not an OpenEXR file (expected magic 76 2f 31 01)");
    if (size < 8) r.fail("truncated: " + std::to_string(size) + " bytes, an OpenEXR file has at least 8");
    const int version = static_cast<int>(uint32_t{data[4]} | uint32_t{data[5]} << 8 | uint32_t{data[6]} << 16 |
                                         uint32_t{data[7]} << 24);
    if (Imf::isMultiPart(version))
        r.fail("is a multi-part EXR; scatterlut tables are single-part scanline images (docs/FORMAT.md)");
    if (Imf::isTiled(version)) r.fail("is a tiled EXR; scatterlut tables are scanline images (docs/FORMAT.md)");
    if (Imf::isNonImage(version)) r.fail("is a deep EXR; scatterlut tables are flat scanline images");
    const size_t header_end = prescan_exr_header(r, data, size);
    try {
        // The header alone first: all checks happen before OpenEXR sizes anything by it.
        Imf::Header hdr;
        {
            MemIStream pre(data, size, name);
            pre.seekg(8);
            int v = version;
            hdr.readFrom(pre, v);
            if (pre.tellg() != header_end) // the pre-scan's promise, kept honest
                r.fail("EXR header: OpenEXR read it to byte " + std::to_string(pre.tellg()) +
                       ", the pre-scan to byte " + std::to_string(header_end));
        }
        r.h = &hdr;
        Table t = decode_exr_header(r, hdr);

        // Image size and channels against the metadata, before allocating pixels.
        const Imath::Box2i dw = hdr.dataWindow();
        const int64_t w = int64_t{dw.max.x} - dw.min.x + 1;
        const int64_t hgt = int64_t{dw.max.y} - dw.min.y + 1;
        const int64_t nodes = static_cast<int64_t>(t.node_count());
        const int64_t want_w = t.axes[0].map.count;
        if (w != want_w || hgt != nodes / want_w)
            r.fail("image is " + std::to_string(w) + " x " + std::to_string(hgt) + " pixels, expected " +
                   std::to_string(want_w) + " x " + std::to_string(nodes / want_w) +
                   " (axis 0 count x product of the other axis counts)");
        const Imf::PixelType type = t.storage == Storage::F16 ? Imf::HALF : Imf::FLOAT;
        const Imf::ChannelList &cl = hdr.channels();
        for (size_t c = 0; c < t.channels.size(); ++c) {
            const std::string &tname = t.channels[c].name, &ename = r.exr_channels[c];
            // From version 2 on the EXR channel (Y, R, …) differs from the table channel: name both.
            const std::string where = ename == tname ? "" : " in EXR channel '" + ename + "'";
            const Imf::Channel *ec = cl.findChannel(ename);
            if (!ec)
                r.fail("missing channel '" + tname + "' (expected " + pixel_type_name(type) + " pixels for storage " +
                       to_string(t.storage) + ")" + where);
            if (ec->type != type)
                r.fail("channel '" + tname + "' has pixel type " + pixel_type_name(ec->type) + ", expected " +
                       pixel_type_name(type) + " (storage " + to_string(t.storage) + ")" + where);
            if (ec->xSampling != 1 || ec->ySampling != 1)
                r.fail("channel '" + tname + "' is subsampled; expected one sample per node" + where);
        }
        for (auto it = cl.begin(); it != cl.end(); ++it) {
            bool known = false;
            for (const std::string &e : r.exr_channels) known = known || e == it.name();
            if (!known) r.fail(std::string("unexpected channel '") + it.name() + "' (not in scatterlut.channel.*)");
        }
        // Plausibility against the real file size: the line-offset table (8 bytes per
        // chunk of ≤ 256 lines) and the pixels (no OpenEXR codec compresses better than
        // ~1:1100; allow 1:4096) must fit what is there.
        const size_t nc = t.channels.size();
        const size_t elem = type == Imf::HALF ? 2 : 4;
        const uint64_t raw = static_cast<uint64_t>(nodes) * nc * elem;
        const uint64_t body = size - header_end;
        if (static_cast<uint64_t>((hgt + 255) / 256) * 8 > body || raw > body * 4096 + 65536)
            r.fail("truncated or corrupt: " + std::to_string(body) + " bytes after the header cannot hold " +
                   std::to_string(hgt) + " lines of " + std::to_string(raw) + " bytes of pixels");

        MemIStream stream(data, size, name);
        Imf::InputFile in(stream);

        // Pixels, then the same little-endian payload bytes as the binary format.
        const size_t n = static_cast<size_t>(nodes) * nc;
        std::vector<uint16_t> half_px;
        std::vector<float> float_px;
        char *base;
        if (type == Imf::HALF) {
            half_px.assign(n, 0);
            base = reinterpret_cast<char *>(half_px.data());
        } else {
            float_px.assign(n, 0.0f);
            base = reinterpret_cast<char *>(float_px.data());
        }
        Imf::FrameBuffer fb;
        for (size_t c = 0; c < nc; ++c)
            fb.insert(r.exr_channels[c], Imf::Slice::Make(type, base + c * elem, in.header().dataWindow(), nc * elem,
                                                           nc * elem * static_cast<size_t>(w)));
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);

        std::vector<uint8_t> payload(n * elem);
        t.values.resize(n);
        for (size_t i = 0; i < n; ++i) {
            uint32_t u;
            if (type == Imf::HALF) {
                u = half_px[i];
                t.values[i] = double_from_f16(half_px[i]);
            } else {
                std::memcpy(&u, &float_px[i], 4);
                t.values[i] = static_cast<double>(float_px[i]);
            }
            for (size_t k = 0; k < elem; ++k) payload[i * elem + k] = static_cast<uint8_t>(u >> (8 * k));
        }
        const uint64_t stored = r.hex(kChecksumPrefix + "payload");
        const uint64_t computed = fnv1a64(payload.data(), payload.size());
        if (stored != computed)
            r.fail_checksum("payload checksum mismatch (stored " + hex64(stored) + ", computed " + hex64(computed) +
                   "): the pixels are corrupt or were edited");
        for (size_t i = 0; i < n; ++i)
            if (!std::isfinite(t.values[i]))
                r.fail("pixel value at " + detail::describe_value(t, i) + " is not finite (" + digits17(t.values[i]) + ")");
        try {
            t.check_consistent();
        } catch (const std::invalid_argument &e) {
            r.fail(std::string("inconsistent table: ") + e.what());
        }
        return t;
    } catch (const LoadError &) {
        throw;
    } catch (const std::exception &e) {
        throw LoadError(name + ": not a readable OpenEXR table: " + e.what());
    }
}

Table load_exr(const std::string &path) {
    const std::vector<uint8_t> bytes = detail::read_file(path);
    return decode_exr(bytes.data(), bytes.size(), path);
}

} // namespace scatterlut
