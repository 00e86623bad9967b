// scatterlut runtime — the binary table encoder (docs/FORMAT.md §2) and the format limits
// every encoder (binary, EXR, KTX2) checks a table against before writing it.
#include "scatterlut/io.hpp"

#include <cstring>

#include "io_binary_format.hpp"

namespace scatterlut {

using namespace binary_format;

namespace {

struct Writer {
    std::vector<uint8_t> b;
    void u32(uint32_t v) {
        for (int i = 0; i < 4; ++i) b.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    void u64(uint64_t v) {
        for (int i = 0; i < 8; ++i) b.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    void f64(double v) {
        uint64_t u;
        std::memcpy(&u, &v, 8);
        u64(u);
    }
    void bytes(const void *p, size_t n) {
        const auto *c = static_cast<const uint8_t *>(p);
        b.insert(b.end(), c, c + n);
    }
    // One record: u32 tag, u32 length, value.
    void rec(uint32_t tag, const std::vector<uint8_t> &value) {
        u32(tag);
        u32(static_cast<uint32_t>(value.size()));
        bytes(value.data(), value.size());
    }
    void rec_u32(uint32_t tag, uint32_t v) {
        Writer w;
        w.u32(v);
        rec(tag, w.b);
    }
    void rec_u64(uint32_t tag, uint64_t v) {
        Writer w;
        w.u64(v);
        rec(tag, w.b);
    }
    void rec_f64(uint32_t tag, double v) {
        Writer w;
        w.f64(v);
        rec(tag, w.b);
    }
    void rec_str(uint32_t tag, const std::string &s) {
        u32(tag);
        u32(static_cast<uint32_t>(s.size()));
        bytes(s.data(), s.size());
    }
};

void check_len(const std::string &what, const std::string &s, size_t max) {
    if (s.size() > max)
        throw std::invalid_argument(what + " is " + std::to_string(s.size()) + " bytes; the format allows at most " +
                                    std::to_string(max));
}

} // namespace

namespace detail {

void check_limits(const Table &t) {
    t.check_consistent();
    if (t.channels.size() > kMaxChannels)
        throw std::invalid_argument("table has " + std::to_string(t.channels.size()) +
                                    " channels; the format allows at most " + std::to_string(kMaxChannels));
    if (t.node_count() > kMaxNodes)
        throw std::invalid_argument("table has " + std::to_string(t.node_count()) +
                                    " nodes; the format allows at most 2^31");
    check_len("kind", t.kind, kMaxNameBytes);
    for (size_t i = 0; i < t.axes.size(); ++i) {
        check_len("axis " + std::to_string(i) + " name", t.axes[i].name, kMaxNameBytes);
        check_len("axis " + std::to_string(i) + " meaning", t.axes[i].meaning, kMaxTextBytes);
    }
    for (size_t i = 0; i < t.channels.size(); ++i) {
        check_len("channel " + std::to_string(i) + " name", t.channels[i].name, kMaxNameBytes);
        check_len("channel " + std::to_string(i) + " meaning", t.channels[i].meaning, kMaxTextBytes);
    }
    check_len("accuracy.sampling_domain", t.accuracy.sampling_domain, kMaxTextBytes);
    check_len("provenance.generator_version", t.provenance.generator_version, kMaxTextBytes);
    check_len("provenance.command_line", t.provenance.command_line, kMaxLongTextBytes);
    check_len("provenance.scene", t.provenance.scene, kMaxSceneBytes);
    check_len("provenance.device", t.provenance.device, kMaxTextBytes);
    check_len("provenance.created_by", t.provenance.created_by, kMaxTextBytes);
    if (t.extra.size() > kMaxExtraEntries)
        throw std::invalid_argument("extra has " + std::to_string(t.extra.size()) +
                                    " entries; the format allows at most " + std::to_string(kMaxExtraEntries));
    // All the text together must leave the header (binary or EXR) under 16 MiB; 64 KiB
    // covers the fixed fields and the record / attribute framing.
    size_t text = t.kind.size() + t.accuracy.sampling_domain.size() + t.provenance.generator_version.size() +
                  t.provenance.command_line.size() + t.provenance.scene.size() + t.provenance.device.size() +
                  t.provenance.created_by.size();
    for (const Axis &a : t.axes) text += a.name.size() + a.meaning.size();
    for (const Channel &c : t.channels) text += c.name.size() + c.meaning.size();
    for (const auto &kv : t.extra) {
        check_len("extra key '" + kv.first.substr(0, 64) + "'", kv.first, kMaxNameBytes);
        check_len("extra['" + kv.first + "'] value", kv.second, kMaxLongTextBytes);
        text += kv.first.size() + kv.second.size() + 32;
    }
    if (text > kMaxHeaderBytes - (64u << 10))
        throw std::invalid_argument("the table's metadata total " + std::to_string(text) +
                                    " bytes; the format allows a header of at most 16 MiB");
}

} // namespace detail

std::vector<uint8_t> encode_binary(const Table &t) {
    detail::check_limits(t);
    std::vector<uint8_t> payload = detail::encode_payload(t);

    Writer h; // header section: records in ascending tag order
    h.rec_str(kTagKind, t.kind);
    h.rec_u32(kTagQuantityVersion, t.quantity_version);
    h.rec_u32(kTagStorage, static_cast<uint32_t>(t.storage));
    for (const Axis &a : t.axes) {
        Writer r;
        r.rec_str(kAxName, a.name);
        r.rec_str(kAxMeaning, a.meaning);
        r.rec_f64(kAxMin, a.map.min);
        r.rec_f64(kAxMax, a.map.max);
        r.rec_f64(kAxScale, a.map.scale);
        r.rec_u32(kAxWarp, static_cast<uint32_t>(a.map.warp));
        r.rec_u32(kAxCount, static_cast<uint32_t>(a.map.count)); // i32, ≥ 2 (checked)
        h.rec(kTagAxis, r.b);
    }
    for (const Channel &c : t.channels) {
        Writer r;
        r.rec_str(kChName, c.name);
        r.rec_str(kChMeaning, c.meaning);
        r.rec_u32(kChEncoding, static_cast<uint32_t>(c.encoding));
        h.rec(kTagChannel, r.b);
    }
    {
        const Accuracy &a = t.accuracy;
        Writer r;
        r.rec_f64(kAcIntegration, a.integration_max_rel);
        r.rec_f64(kAcSamplingMax, a.sampling_max_rel);
        r.rec_f64(kAcSamplingP99, a.sampling_p99_rel);
        r.rec_f64(kAcSamplingMedian, a.sampling_median_rel);
        r.rec_f64(kAcStorage, a.storage_max_rel);
        r.rec_u64(kAcSamplingPoints, a.sampling_points);
        r.rec_str(kAcSamplingDomain, a.sampling_domain);
        h.rec(kTagAccuracy, r.b);
    }
    {
        const Provenance &p = t.provenance;
        Writer r;
        r.rec_str(kPvGenerator, p.generator_version);
        r.rec_str(kPvCommandLine, p.command_line);
        r.rec_str(kPvScene, p.scene);
        r.rec_str(kPvDevice, p.device);
        r.rec_str(kPvCreatedBy, p.created_by);
        h.rec(kTagProvenance, r.b);
    }
    for (const auto &kv : t.extra) { // std::map: sorted by key, deterministic
        Writer r;
        r.rec_str(kExKey, kv.first);
        r.rec_str(kExValue, kv.second);
        h.rec(kTagExtra, r.b);
    }
    // Pad so that the payload starts on a 64-byte boundary (mmap / GPU upload friendly).
    const size_t end = kPreambleBytes + h.b.size();
    if (end % kPayloadAlign != 0) {
        size_t pad = kPayloadAlign - end % kPayloadAlign;
        if (pad < 8) pad += kPayloadAlign;
        h.rec(kTagPadding, std::vector<uint8_t>(pad - 8, 0));
    }
    if (h.b.size() > kMaxHeaderBytes)
        throw std::invalid_argument("header is " + std::to_string(h.b.size()) +
                                    " bytes; the format allows at most 16 MiB");

    Writer out;
    out.b.reserve(kPreambleBytes + h.b.size() + payload.size());
    out.bytes(kMagic, 8);
    out.u32(kFormatMajor);
    out.u32(kFormatMinor);
    out.u64(h.b.size());
    out.u64(payload.size());
    const uint64_t header_sum = fnv1a64(h.b.data(), h.b.size(), fnv1a64(out.b.data(), 32));
    out.u64(header_sum);
    out.u64(fnv1a64(payload.data(), payload.size()));
    out.bytes(h.b.data(), h.b.size());
    out.bytes(payload.data(), payload.size());
    return std::move(out.b);
}

void save_binary(const Table &table, const std::string &path) { write_file_atomic(path, encode_binary(table)); }

} // namespace scatterlut
