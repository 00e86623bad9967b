// scatterlut runtime — the binary table decoder (docs/FORMAT.md §2).
//
// The decoder treats every byte as hostile: each length is compared with the bytes
// that remain before it is used, nothing is allocated from a header field that has
// not been bounded, and each refusal is a LoadError that names the file and says
// what was expected.
#include "scatterlut/io.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "io_binary_format.hpp"
#include "io_text.hpp"

namespace scatterlut {

using namespace binary_format;
using detail::digits17;
using detail::hex64;

namespace {

uint32_t rd_u32(const uint8_t *p) {
    return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}
uint64_t rd_u64(const uint8_t *p) { return uint64_t{rd_u32(p)} | uint64_t{rd_u32(p + 4)} << 32; }
double rd_f64(const uint8_t *p) {
    const uint64_t u = rd_u64(p);
    double d;
    std::memcpy(&d, &u, 8);
    return d;
}

std::string hex_bytes(const uint8_t *p, size_t n) {
    std::string s;
    char buf[4];
    for (size_t i = 0; i < n; ++i) {
        std::snprintf(buf, sizeof buf, "%s%02x", i ? " " : "", p[i]);
        s += buf;
    }
    return s;
}

struct Decoder {
    std::string name;
    uint32_t major = 0, minor = 0;
    const uint8_t *base = nullptr; // start of the file, for offsets in messages

    [[noreturn]] void fail(const std::string &what) const { throw LoadError(name + ": " + what); }
    [[noreturn]] void fail_checksum(const std::string &what) const { throw ChecksumError(name + ": " + what); }

    // Visits the records of [p, p + n): f(tag, value, length, offset_in_file).
    template <class F> void records(const uint8_t *p, size_t n, const std::string &where, F f) const {
        size_t pos = 0;
        while (pos < n) {
            const size_t off = static_cast<size_t>(p + pos - base);
            if (n - pos < 8)
                fail(where + ": record at offset " + std::to_string(off) + " is truncated (" +
                     std::to_string(n - pos) + " bytes left, a record header needs 8)");
            const uint32_t tag = rd_u32(p + pos);
            const uint32_t len = rd_u32(p + pos + 4);
            if (len > n - pos - 8)
                fail(where + ": record at offset " + std::to_string(off) + " (tag " + std::to_string(tag) +
                     ") claims " + std::to_string(len) + " bytes but only " + std::to_string(n - pos - 8) +
                     " remain");
            if (tag != kTagPadding) f(tag, p + pos + 8, static_cast<size_t>(len), off);
            pos += 8 + static_cast<size_t>(len);
        }
    }

    // A tag this reader does not know: skipped in a newer-minor file, corrupt otherwise.
    void unknown(uint32_t tag, const std::string &where, size_t off) const {
        if (minor > kFormatMinor) return;
        fail(where + ": unknown field tag " + std::to_string(tag) + " at offset " + std::to_string(off) +
             " (format version " + std::to_string(major) + "." + std::to_string(minor) +
             " defines no such field; the file is corrupt)");
    }

    void once(uint64_t *seen, uint32_t tag, const std::string &where, const char *field) const {
        const uint64_t bit = uint64_t{1} << tag;
        if (*seen & bit) fail(where + ": field '" + field + "' appears twice");
        *seen |= bit;
    }

    void need_len(size_t len, size_t want, const std::string &where, const char *field) const {
        if (len != want)
            fail(where + ": field '" + field + "' is " + std::to_string(len) + " bytes, expected " +
                 std::to_string(want));
    }
    uint32_t u32(const uint8_t *v, size_t len, const std::string &where, const char *field) const {
        need_len(len, 4, where, field);
        return rd_u32(v);
    }
    uint64_t u64(const uint8_t *v, size_t len, const std::string &where, const char *field) const {
        need_len(len, 8, where, field);
        return rd_u64(v);
    }
    double f64(const uint8_t *v, size_t len, const std::string &where, const char *field) const {
        need_len(len, 8, where, field);
        return rd_f64(v);
    }
    std::string str(const uint8_t *v, size_t len, size_t max, const std::string &where, const char *field) const {
        if (len > max)
            fail(where + ": field '" + field + "' is " + std::to_string(len) + " bytes, more than the limit " +
                 std::to_string(max));
        return std::string(reinterpret_cast<const char *>(v), len);
    }
    void require(uint64_t seen, uint64_t want, const std::string &where,
                 std::initializer_list<std::pair<uint32_t, const char *>> fields) const {
        for (const auto &f : fields)
            if ((want & (uint64_t{1} << f.first)) && !(seen & (uint64_t{1} << f.first)))
                fail(where + ": required field '" + f.second + "' is missing");
    }
};

Axis parse_axis(const Decoder &d, const uint8_t *p, size_t n, size_t index) {
    const std::string where = "axis " + std::to_string(index);
    Axis a;
    uint64_t seen = 0;
    bool warp_ok = true;
    uint32_t warp = 0;
    d.records(p, n, where, [&](uint32_t tag, const uint8_t *v, size_t len, size_t off) {
        switch (tag) {
        case kAxName: d.once(&seen, tag, where, "name"); a.name = d.str(v, len, kMaxNameBytes, where, "name"); break;
        case kAxMeaning:
            d.once(&seen, tag, where, "meaning");
            a.meaning = d.str(v, len, kMaxTextBytes, where, "meaning");
            break;
        case kAxMin: d.once(&seen, tag, where, "min"); a.map.min = d.f64(v, len, where, "min"); break;
        case kAxMax: d.once(&seen, tag, where, "max"); a.map.max = d.f64(v, len, where, "max"); break;
        case kAxScale: d.once(&seen, tag, where, "scale"); a.map.scale = d.f64(v, len, where, "scale"); break;
        case kAxWarp:
            d.once(&seen, tag, where, "warp");
            warp = d.u32(v, len, where, "warp");
            warp_ok = warp < SLUT_WARP_COUNT;
            a.map.warp = warp_ok ? static_cast<int>(warp) : 0;
            break;
        case kAxCount:
            d.once(&seen, tag, where, "count");
            a.map.count = static_cast<int32_t>(d.u32(v, len, where, "count")); // two's complement i32
            break;
        default: d.unknown(tag, where, off);
        }
    });
    d.require(seen, ~uint64_t{0}, where,
              {{kAxName, "name"}, {kAxMeaning, "meaning"}, {kAxMin, "min"}, {kAxMax, "max"},
               {kAxScale, "scale"}, {kAxWarp, "warp"}, {kAxCount, "count"}});
    const std::string label = where + " ('" + a.name + "')";
    if (!warp_ok)
        d.fail(label + ": unknown warp id " + std::to_string(warp) + " (this reader knows 0 to " +
               std::to_string(SLUT_WARP_COUNT - 1) + ": linear, log, log1p, asinh_cot, sqrt1p, loglin, nl_qodds, asinh_cot_peak)");
    const std::string extent = detail::axis_extent_problem(a.map.count, a.map.min, a.map.max, a.map.scale);
    if (!extent.empty()) d.fail(label + ": " + extent);
    return a;
}

Channel parse_channel(const Decoder &d, const uint8_t *p, size_t n, size_t index) {
    const std::string where = "channel " + std::to_string(index);
    Channel c;
    uint64_t seen = 0;
    uint32_t enc = 0;
    d.records(p, n, where, [&](uint32_t tag, const uint8_t *v, size_t len, size_t off) {
        switch (tag) {
        case kChName: d.once(&seen, tag, where, "name"); c.name = d.str(v, len, kMaxNameBytes, where, "name"); break;
        case kChMeaning:
            d.once(&seen, tag, where, "meaning");
            c.meaning = d.str(v, len, kMaxTextBytes, where, "meaning");
            break;
        case kChEncoding: d.once(&seen, tag, where, "encoding"); enc = d.u32(v, len, where, "encoding"); break;
        default: d.unknown(tag, where, off);
        }
    });
    d.require(seen, ~uint64_t{0}, where, {{kChName, "name"}, {kChMeaning, "meaning"}, {kChEncoding, "encoding"}});
    if (enc != static_cast<uint32_t>(Encoding::Linear) && enc != static_cast<uint32_t>(Encoding::Log))
        d.fail(where + " ('" + c.name + "'): unknown encoding id " + std::to_string(enc) +
               " (this reader knows 0 = linear, 1 = log)");
    c.encoding = static_cast<Encoding>(enc);
    return c;
}

void parse_accuracy(const Decoder &d, const uint8_t *p, size_t n, Accuracy *a) {
    const std::string where = "accuracy";
    uint64_t seen = 0;
    d.records(p, n, where, [&](uint32_t tag, const uint8_t *v, size_t len, size_t off) {
        switch (tag) {
        case kAcIntegration:
            d.once(&seen, tag, where, "integration_max_rel");
            a->integration_max_rel = d.f64(v, len, where, "integration_max_rel");
            break;
        case kAcSamplingMax:
            d.once(&seen, tag, where, "sampling_max_rel");
            a->sampling_max_rel = d.f64(v, len, where, "sampling_max_rel");
            break;
        case kAcSamplingP99:
            d.once(&seen, tag, where, "sampling_p99_rel");
            a->sampling_p99_rel = d.f64(v, len, where, "sampling_p99_rel");
            break;
        case kAcSamplingMedian:
            d.once(&seen, tag, where, "sampling_median_rel");
            a->sampling_median_rel = d.f64(v, len, where, "sampling_median_rel");
            break;
        case kAcStorage:
            d.once(&seen, tag, where, "storage_max_rel");
            a->storage_max_rel = d.f64(v, len, where, "storage_max_rel");
            break;
        case kAcSamplingPoints:
            d.once(&seen, tag, where, "sampling_points");
            a->sampling_points = d.u64(v, len, where, "sampling_points");
            break;
        case kAcSamplingDomain:
            d.once(&seen, tag, where, "sampling_domain");
            a->sampling_domain = d.str(v, len, kMaxTextBytes, where, "sampling_domain");
            break;
        default: d.unknown(tag, where, off);
        }
    });
    d.require(seen, ~uint64_t{0}, where,
              {{kAcIntegration, "integration_max_rel"}, {kAcSamplingMax, "sampling_max_rel"},
               {kAcSamplingP99, "sampling_p99_rel"}, {kAcSamplingMedian, "sampling_median_rel"},
               {kAcStorage, "storage_max_rel"}, {kAcSamplingPoints, "sampling_points"},
               {kAcSamplingDomain, "sampling_domain"}});
}

void parse_provenance(const Decoder &d, const uint8_t *p, size_t n, Provenance *pv) {
    const std::string where = "provenance";
    uint64_t seen = 0;
    d.records(p, n, where, [&](uint32_t tag, const uint8_t *v, size_t len, size_t off) {
        switch (tag) {
        case kPvGenerator:
            d.once(&seen, tag, where, "generator_version");
            pv->generator_version = d.str(v, len, kMaxTextBytes, where, "generator_version");
            break;
        case kPvCommandLine:
            d.once(&seen, tag, where, "command_line");
            pv->command_line = d.str(v, len, kMaxLongTextBytes, where, "command_line");
            break;
        case kPvScene:
            d.once(&seen, tag, where, "scene");
            pv->scene = d.str(v, len, kMaxSceneBytes, where, "scene");
            break;
        case kPvDevice:
            d.once(&seen, tag, where, "device");
            pv->device = d.str(v, len, kMaxTextBytes, where, "device");
            break;
        case kPvCreatedBy:
            d.once(&seen, tag, where, "created_by");
            pv->created_by = d.str(v, len, kMaxTextBytes, where, "created_by");
            break;
        default: d.unknown(tag, where, off);
        }
    });
    d.require(seen, ~uint64_t{0}, where,
              {{kPvGenerator, "generator_version"}, {kPvCommandLine, "command_line"}, {kPvScene, "scene"},
               {kPvDevice, "device"}, {kPvCreatedBy, "created_by"}});
}

} // namespace

Table decode_binary(const uint8_t *data, size_t size, const std::string &name) {
    Decoder d;
    d.name = name;
    d.base = data;
    if (size == 0 || data == nullptr)
        d.fail("truncated: the file is empty (a scatterlut binary table starts with a 48-byte preamble)");

    // Magic: a shorter prefix of the right magic is a truncated file, anything else is not ours.
    const size_t m = size < 8 ? size : 8;
    if (std::memcmp(data, kMagic, m) != 0) {
        std::string msg = "not a scatterlut binary table: expected magic 53 4c 55 54 54 42 4c 00 (\"SLUTTBL\\0\"), found " +
                          hex_bytes(data, m);
        if (size >= 4 && std::memcmp(data, kExrMagic, 4) == 0)
            msg += " (an OpenEXR file: read it with load_table or load_exr)";
        d.fail(msg);
    }
    if (size < kPreambleBytes)
        d.fail("truncated: " + std::to_string(size) + " bytes, but the preamble alone is " +
               std::to_string(kPreambleBytes));

    // Version first: everything after offset 16 may change with the major version.
    d.major = rd_u32(data + 8);
    d.minor = rd_u32(data + 12);
    const std::string version = std::to_string(d.major) + "." + std::to_string(d.minor);
    const std::string ours = std::to_string(kFormatMajor) + ".x";
    if (d.major > kFormatMajor)
        d.fail("format version " + version + " is newer than this reader (" + ours + "); upgrade scatterlut");
    if (d.major < kFormatMajor)
        d.fail("format version " + version + " is older than this reader supports (" + ours + ")");

    const uint64_t header_size = rd_u64(data + 16);
    const uint64_t payload_size = rd_u64(data + 24);
    const uint64_t header_sum = rd_u64(data + 32);
    const uint64_t payload_sum = rd_u64(data + 40);
    if (header_size > kMaxHeaderBytes)
        d.fail("header size " + std::to_string(header_size) + " exceeds the limit of " +
               std::to_string(kMaxHeaderBytes) + " bytes (16 MiB)");
    const uint64_t after_header = kPreambleBytes + header_size;
    if (payload_size > std::numeric_limits<uint64_t>::max() - after_header || after_header + payload_size > size)
        d.fail("truncated: " + std::to_string(size) + " bytes, but the preamble announces a " +
               std::to_string(header_size) + "-byte header and a " + std::to_string(payload_size) +
               "-byte payload (" + (payload_size > std::numeric_limits<uint64_t>::max() - after_header
                                        ? std::string("overflow")
                                        : std::to_string(after_header + payload_size)) +
               " bytes in all)");
    if (after_header + payload_size < size)
        d.fail(std::to_string(size - after_header - payload_size) +
               " unexpected bytes after the payload (the preamble announces " +
               std::to_string(after_header + payload_size) + " bytes in all)");

    const uint8_t *hdr = data + kPreambleBytes;
    const size_t hdr_n = static_cast<size_t>(header_size);
    const uint64_t computed_header_sum = fnv1a64(hdr, hdr_n, fnv1a64(data, 32));
    if (computed_header_sum != header_sum)
        d.fail_checksum("header checksum mismatch (stored " + hex64(header_sum) + ", computed " + hex64(computed_header_sum) +
               "): the file is corrupt");

    // --- header records ---
    Table t;
    t.provenance.created_by.clear();
    uint64_t seen = 0;
    uint32_t storage_id = 0;
    d.records(hdr, hdr_n, "header", [&](uint32_t tag, const uint8_t *v, size_t len, size_t off) {
        switch (tag) {
        case kTagKind: d.once(&seen, tag, "header", "kind"); t.kind = d.str(v, len, kMaxNameBytes, "header", "kind"); break;
        case kTagQuantityVersion:
            d.once(&seen, tag, "header", "quantity_version");
            t.quantity_version = d.u32(v, len, "header", "quantity_version");
            break;
        case kTagStorage: d.once(&seen, tag, "header", "storage"); storage_id = d.u32(v, len, "header", "storage"); break;
        case kTagAxis:
            if (t.axes.size() == kMaxAxes)
                d.fail("header: more than " + std::to_string(kMaxAxes) + " axes (the format allows at most " +
                       std::to_string(kMaxAxes) + ")");
            t.axes.push_back(parse_axis(d, v, len, t.axes.size()));
            break;
        case kTagChannel:
            if (t.channels.size() == kMaxChannels)
                d.fail("header: more than " + std::to_string(kMaxChannels) + " channels (the format allows at most " +
                       std::to_string(kMaxChannels) + ")");
            t.channels.push_back(parse_channel(d, v, len, t.channels.size()));
            break;
        case kTagAccuracy: d.once(&seen, tag, "header", "accuracy"); parse_accuracy(d, v, len, &t.accuracy); break;
        case kTagProvenance:
            d.once(&seen, tag, "header", "provenance");
            parse_provenance(d, v, len, &t.provenance);
            break;
        case kTagExtra: {
            if (t.extra.size() == kMaxExtraEntries)
                d.fail("header: more than " + std::to_string(kMaxExtraEntries) + " extra entries");
            const std::string where = "extra entry " + std::to_string(t.extra.size());
            uint64_t s = 0;
            std::string key, value;
            d.records(v, len, where, [&](uint32_t tg, const uint8_t *vv, size_t ll, size_t oo) {
                switch (tg) {
                case kExKey: d.once(&s, tg, where, "key"); key = d.str(vv, ll, kMaxNameBytes, where, "key"); break;
                case kExValue:
                    d.once(&s, tg, where, "value");
                    value = d.str(vv, ll, kMaxLongTextBytes, where, "value");
                    break;
                default: d.unknown(tg, where, oo);
                }
            });
            d.require(s, ~uint64_t{0}, where, {{kExKey, "key"}, {kExValue, "value"}});
            if (!t.extra.emplace(std::move(key), std::move(value)).second)
                d.fail(where + ": key appears twice");
            break;
        }
        default: d.unknown(tag, "header", off);
        }
    });
    d.require(seen, ~uint64_t{0}, "header",
              {{kTagKind, "kind"}, {kTagQuantityVersion, "quantity_version"}, {kTagStorage, "storage"},
               {kTagAccuracy, "accuracy"}, {kTagProvenance, "provenance"}});
    if (t.axes.empty()) d.fail("header: the table has no axis");
    if (t.channels.empty()) d.fail("header: the table has no channel");
    if (storage_id < 1 || storage_id > 3)
        d.fail("header: unknown storage id " + std::to_string(storage_id) + " (this reader knows 1 = f16, 2 = f32, 3 = f64)");
    t.storage = static_cast<Storage>(storage_id);

    // --- sizes, before anything is allocated ---
    uint64_t nodes = 1;
    long double nodes_ld = 1; // for the message when the product exceeds 64 bits
    for (const Axis &a : t.axes) nodes_ld *= static_cast<long double>(a.map.count);
    if (nodes_ld > static_cast<long double>(kMaxNodes)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.0Lf", nodes_ld);
        d.fail(std::string("header claims ") + buf + " nodes, more than the limit of 2^31 = " +
               std::to_string(kMaxNodes));
    }
    for (const Axis &a : t.axes) nodes *= static_cast<uint64_t>(a.map.count);
    const uint64_t n_values = nodes * t.channels.size();
    const uint64_t expected_payload = n_values * storage_bytes(t.storage);
    if (payload_size != expected_payload)
        d.fail("payload is " + std::to_string(payload_size) + " bytes, expected " + std::to_string(expected_payload) +
               " (" + std::to_string(nodes) + " nodes x " + std::to_string(t.channels.size()) + " channels x " +
               std::to_string(storage_bytes(t.storage)) + " bytes of " + to_string(t.storage) + ")");

    const uint8_t *pl = data + after_header;
    const uint64_t computed_payload_sum = fnv1a64(pl, static_cast<size_t>(payload_size));
    if (computed_payload_sum != payload_sum)
        d.fail_checksum("payload checksum mismatch (stored " + hex64(payload_sum) + ", computed " +
               hex64(computed_payload_sum) + "): the file is corrupt");

    // --- payload ---
    t.values.resize(static_cast<size_t>(n_values));
    const size_t bytes = storage_bytes(t.storage);
    for (size_t i = 0; i < t.values.size(); ++i) {
        const uint8_t *p = pl + i * bytes;
        double v = 0;
        switch (t.storage) {
        case Storage::F16: v = double_from_f16(static_cast<uint16_t>(p[0] | p[1] << 8)); break;
        case Storage::F32: {
            const uint32_t w = rd_u32(p);
            float f;
            std::memcpy(&f, &w, 4);
            v = static_cast<double>(f);
            break;
        }
        case Storage::F64: v = rd_f64(p); break;
        }
        if (!std::isfinite(v))
            d.fail("payload value at " + detail::describe_value(t, i) + " is not finite (" + digits17(v) + ")");
        t.values[i] = v;
    }

    try {
        t.check_consistent();
    } catch (const std::invalid_argument &e) {
        d.fail(std::string("inconsistent table: ") + e.what());
    }
    return t;
}

Table load_binary(const std::string &path) {
    const std::vector<uint8_t> bytes = detail::read_file(path);
    return decode_binary(bytes.data(), bytes.size(), path);
}

} // namespace scatterlut
