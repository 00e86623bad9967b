// scatterlut runtime — the OpenEXR table decoder (docs/FORMAT.md §4; the mapping is described
// in io_exr_format.hpp). It distrusts its input: the raw header is pre-scanned
// (io_exr_prescan.cpp) before OpenEXR reads it, the image size and channels are checked
// against the metadata before any pixel is allocated, and every refusal is a LoadError that
// names the file.
#include "scatterlut/io.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfStringAttribute.h>
#include <ImfStringVectorAttribute.h>

#include "io_exr_format.hpp"
#include "io_text.hpp"

namespace scatterlut {

using namespace exr_format;
using detail::digits17;
using detail::hex64;

namespace {

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


const char *pixel_type_name(Imf::PixelType t) {
    switch (t) {
    case Imf::UINT: return "UINT";
    case Imf::HALF: return "HALF";
    case Imf::FLOAT: return "FLOAT";
    default: return "unknown";
    }
}


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
        const std::string extent = detail::axis_extent_problem(a.map.count, a.map.min, a.map.max, a.map.scale);
        if (!extent.empty()) r.fail(label + ": " + extent);
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
    const size_t header_end = prescan_exr_header(name, data, size);
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
