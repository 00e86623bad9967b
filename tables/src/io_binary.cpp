// scatterlut runtime — the binary table format (docs/FORMAT.md), storage rounding,
// binary16 conversions, the checksum and atomic file writes.
//
// The decoder treats every byte as hostile: each length is compared with the bytes
// that remain before it is used, nothing is allocated from a header field that has
// not been bounded, and each refusal is a LoadError that names the file and says
// what was expected.
#include "scatterlut/io.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <system_error>

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace scatterlut {

// =====================================================================================
// Checksum, binary16, storage rounding
// =====================================================================================

uint64_t fnv1a64(const void *data, size_t size, uint64_t state) {
    const auto *p = static_cast<const uint8_t *>(data);
    for (size_t i = 0; i < size; ++i) {
        state ^= p[i];
        state *= 0x100000001b3ull;
    }
    return state;
}

// binary16: 1 sign bit, 5 exponent bits (bias 15), 10 fraction bits. Normal numbers
// (1 + f/1024)·2^(e−15) for e = 1…30, subnormals (f/1024)·2^−14 = f·2^−24 for e = 0,
// ±inf / NaN for e = 31. Rounding works on the exact double bits: the kept fraction
// is the top bits of the 53-bit significand, the dropped bits decide the rounding
// (above half: up; exactly half: to even). A carry out of the fraction correctly
// increments the exponent (and 65520 → inf, the largest-normal tie going to even).
uint16_t f16_from_double(double x) {
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const uint16_t sign = static_cast<uint16_t>((bits >> 48) & 0x8000u);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    const uint64_t frac = bits & ((uint64_t{1} << 52) - 1);
    if (biased == 0x7ff) return static_cast<uint16_t>(sign | (frac ? 0x7e00u : 0x7c00u)); // NaN / inf
    const int e = biased - 1023; // x = 1.frac · 2^e for normal doubles
    if (biased == 0 || e < -25) {
        // Double subnormals and anything below 2^−25 (half the smallest subnormal)
        // round to zero; exactly 2^−25 is a tie that goes to the even 0.
        return sign;
    }
    if (e > 15) return static_cast<uint16_t>(sign | 0x7c00u); // ≥ 65536: overflow
    const uint64_t sig = (uint64_t{1} << 52) | frac;         // 53-bit significand
    uint64_t kept;
    int shift; // number of dropped bits
    uint16_t exp_field;
    if (e >= -14) { // normal half: keep 11 significant bits (implicit 1 included)
        shift = 42;
        exp_field = static_cast<uint16_t>((e + 15) << 10);
        kept = (sig >> shift) & 0x3ffu;
    } else { // subnormal half: value = sig·2^(e−52) in units of 2^−24
        shift = 28 - e; // 43 … 53
        exp_field = 0;
        kept = sig >> shift;
    }
    const uint64_t dropped = sig & ((uint64_t{1} << shift) - 1);
    const uint64_t half = uint64_t{1} << (shift - 1);
    uint32_t h = exp_field + static_cast<uint32_t>(kept);
    if (dropped > half || (dropped == half && (kept & 1u))) ++h; // carries into the exponent
    return static_cast<uint16_t>(sign | h);
}

double double_from_f16(uint16_t h) {
    const int e = (h >> 10) & 0x1f;
    const int f = h & 0x3ff;
    double v;
    if (e == 0) v = std::ldexp(static_cast<double>(f), -24);
    else if (e == 31) v = f ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
    else v = std::ldexp(static_cast<double>(1024 + f), e - 25);
    return (h & 0x8000u) ? -v : v;
}

namespace {

// double → float, round to nearest even, with overflow made explicit: a double
// outside the float range is undefined behaviour for static_cast. FLT_MAX = 2^128 − 2^104;
// the midpoint to 2^128 is 2^128 − 2^103 and ties go to the even 2^128 (= inf).
float f32_from_double(double x) {
    if (std::isnan(x)) return std::numeric_limits<float>::quiet_NaN();
    if (std::fabs(x) > static_cast<double>(FLT_MAX)) {
        const double limit = 0x1.ffffffp127; // 2^128 − 2^103
        return static_cast<float>(std::copysign(std::fabs(x) < limit ? static_cast<double>(FLT_MAX)
                                                                     : std::numeric_limits<double>::infinity(),
                                                x));
    }
    return static_cast<float>(x);
}

} // namespace

double round_to_storage(double x, Storage s) {
    switch (s) {
    case Storage::F16: return double_from_f16(f16_from_double(x));
    case Storage::F32: return static_cast<double>(f32_from_double(x));
    case Storage::F64: return x;
    }
    throw std::invalid_argument("round_to_storage: unknown storage id " + std::to_string(static_cast<uint32_t>(s)));
}

namespace detail {

std::string describe_value(const Table &t, size_t i) {
    std::ostringstream s;
    const size_t nc = t.channels.empty() ? 1 : t.channels.size();
    size_t rest = i / nc;
    s << "node (";
    for (size_t a = 0; a < t.axes.size(); ++a) {
        const size_t c = t.axes[a].map.count > 0 ? static_cast<size_t>(t.axes[a].map.count) : 1;
        s << (a ? ", " : "") << rest % c;
        rest /= c;
    }
    s << ")";
    if (i % nc < t.channels.size()) s << ", channel '" << t.channels[i % nc].name << "'";
    return s.str();
}

} // namespace detail

double storage_rounding_max_rel(const Table &t, Storage s) {
    if (storage_bytes(s) == 0)
        throw std::invalid_argument("storage_rounding_max_rel: unknown storage id " +
                                    std::to_string(static_cast<uint32_t>(s)));
    const size_t nc = t.channels.size();
    double worst = 0.0;
    for (size_t i = 0; i < t.values.size(); ++i) {
        const double v = t.values[i];
        if (!std::isfinite(v))
            throw std::invalid_argument("storage_rounding_max_rel: value at " + detail::describe_value(t, i) +
                                        " is not finite");
        const double r = round_to_storage(v, s);
        if (!std::isfinite(r)) return std::numeric_limits<double>::infinity();
        const bool log = nc && t.channels[i % nc].encoding == Encoding::Log;
        double rel;
        if (log) rel = std::fabs(std::expm1(r - v)); // exp(r)/exp(v) − 1, no cancellation
        else if (v == 0.0) rel = 0.0;                // 0 is exact in every storage type
        else rel = std::fabs(r - v) / std::fabs(v);
        if (rel > worst) worst = rel;
    }
    return worst;
}

// =====================================================================================
// Little-endian writing
// =====================================================================================

namespace {

constexpr uint8_t kMagic[8] = {'S', 'L', 'U', 'T', 'T', 'B', 'L', 0};
constexpr uint8_t kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
constexpr size_t kPreambleBytes = 48;
constexpr size_t kPayloadAlign = 64;

// Top-level record tags (docs/FORMAT.md §2.3). Never renumber.
enum : uint32_t {
    kTagPadding = 0x00,
    kTagKind = 0x01,
    kTagQuantityVersion = 0x02,
    kTagStorage = 0x03,
    kTagAxis = 0x10,
    kTagChannel = 0x11,
    kTagAccuracy = 0x20,
    kTagProvenance = 0x21,
    kTagExtra = 0x30,
};
enum : uint32_t { kAxName = 1, kAxMeaning, kAxMin, kAxMax, kAxScale, kAxWarp, kAxCount };
enum : uint32_t { kChName = 1, kChMeaning, kChEncoding };
enum : uint32_t {
    kAcIntegration = 1,
    kAcSamplingMax,
    kAcSamplingP99,
    kAcSamplingMedian,
    kAcStorage,
    kAcSamplingPoints,
    kAcSamplingDomain
};
enum : uint32_t { kPvGenerator = 1, kPvCommandLine, kPvScene, kPvDevice, kPvCreatedBy };
enum : uint32_t { kExKey = 1, kExValue };

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

std::vector<uint8_t> encode_payload(const Table &t) {
    const size_t n = t.values.size();
    const size_t bytes = storage_bytes(t.storage);
    std::vector<uint8_t> out(n * bytes);
    uint8_t *p = out.data();
    for (size_t i = 0; i < n; ++i, p += bytes) {
        const double v = t.values[i];
        if (!std::isfinite(v))
            throw std::invalid_argument("value at " + describe_value(t, i) + " is not finite");
        uint64_t u = 0;
        switch (t.storage) {
        case Storage::F16: {
            const uint16_t h = f16_from_double(v);
            if ((h & 0x7c00u) == 0x7c00u) {
                std::ostringstream s;
                s.precision(17);
                s << "value " << v << " at " << describe_value(t, i)
                  << " overflows f16 (largest finite 65504); store the table as f32";
                throw std::invalid_argument(s.str());
            }
            u = h;
            break;
        }
        case Storage::F32: {
            const float f = f32_from_double(v);
            if (std::isinf(f)) {
                std::ostringstream s;
                s.precision(17);
                s << "value " << v << " at " << describe_value(t, i) << " overflows f32; store the table as f64";
                throw std::invalid_argument(s.str());
            }
            uint32_t w;
            std::memcpy(&w, &f, 4);
            u = w;
            break;
        }
        case Storage::F64: std::memcpy(&u, &v, 8); break;
        }
        for (size_t k = 0; k < bytes; ++k) p[k] = static_cast<uint8_t>(u >> (8 * k));
    }
    return out;
}

} // namespace detail

// =====================================================================================
// Binary encoder
// =====================================================================================

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

// =====================================================================================
// Binary decoder
// =====================================================================================

namespace {

std::string hex64(uint64_t v) {
    char buf[19];
    std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
    return buf;
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

std::string fmt(double x) {
    std::ostringstream s;
    s.precision(17);
    s << x;
    return s.str();
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
               std::to_string(SLUT_WARP_COUNT - 1) + ": linear, log, log1p, asinh_cot, sqrt1p, loglin, nl_qodds)");
    if (a.map.count < 2)
        d.fail(label + ": count " + std::to_string(a.map.count) + " is invalid (need 2 <= count <= 2^31-1)");
    if (!std::isfinite(a.map.min) || !std::isfinite(a.map.max) || !std::isfinite(a.map.scale))
        d.fail(label + ": range [" + fmt(a.map.min) + ", " + fmt(a.map.max) + "] / scale " + fmt(a.map.scale) +
               " is not finite");
    if (!(a.map.min < a.map.max))
        d.fail(label + ": min " + fmt(a.map.min) + " must be less than max " + fmt(a.map.max));
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
            d.fail("payload value at " + detail::describe_value(t, i) + " is not finite (" + fmt(v) + ")");
        t.values[i] = v;
    }

    try {
        t.check_consistent();
    } catch (const std::invalid_argument &e) {
        d.fail(std::string("inconsistent table: ") + e.what());
    }
    return t;
}

// =====================================================================================
// Files
// =====================================================================================

namespace detail {

std::vector<uint8_t> read_file(const std::string &path, uint64_t max_bytes, const char *expected) {
    // O_NONBLOCK: opening a FIFO (or a device) must not wait for a writer; only a regular
    // file is read, and its size is checked before anything is allocated.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) throw LoadError(path + ": cannot open for reading: " + std::strerror(errno));
    struct FdGuard {
        int fd;
        ~FdGuard() { ::close(fd); }
    } guard{fd};
    struct stat st;
    if (::fstat(fd, &st) != 0) throw LoadError(path + ": cannot stat: " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw LoadError(path + ": is a directory, expected " + expected);
    if (!S_ISREG(st.st_mode))
        throw LoadError(path + ": is not a regular file (a FIFO, socket or device), expected " + expected);
    if (static_cast<uint64_t>(st.st_size) > max_bytes)
        throw LoadError(path + ": " + std::to_string(st.st_size) + " bytes, more than the " +
                        std::to_string(max_bytes) + " expected of " + expected);
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    // The size comes from the file system, not from the file's contents.
    std::vector<uint8_t> bytes(static_cast<size_t>(st.st_size));
    size_t got = 0;
    while (got < bytes.size()) {
        const ssize_t r = ::read(fd, bytes.data() + got, bytes.size() - got);
        if (r < 0) {
            if (errno == EINTR) continue;
            throw LoadError(path + ": read error: " + std::strerror(errno));
        }
        if (r == 0) break; // shrank while reading: the decoder reports truncation
        got += static_cast<size_t>(r);
    }
    bytes.resize(got);
    return bytes;
}

std::vector<uint8_t> read_file(const std::string &path) {
    return read_file(path, std::numeric_limits<uint64_t>::max(), "a table file");
}

} // namespace detail

namespace {

// The temporary files of the writes in progress, for remove_temporaries_in_progress (a
// signal handler: it may only read these slots and unlink). A slot is claimed before its
// path is written and published (`ready`) after, so the handler never reads a half-written
// path. More concurrent writes than slots are still atomic, only not cleaned up on a signal.
struct TemporaryFileSlot {
    std::atomic<bool> claimed{false};
    std::atomic<bool> ready{false};
    char path[4096];
};
constexpr int kTemporaryFileSlots = 16;
TemporaryFileSlot g_temporary_files[kTemporaryFileSlots];

TemporaryFileSlot *register_temporary_file(const std::string &path) {
    if (path.size() >= sizeof(TemporaryFileSlot::path)) return nullptr;
    for (TemporaryFileSlot &slot : g_temporary_files) {
        bool expected = false;
        if (!slot.claimed.compare_exchange_strong(expected, true)) continue;
        std::memcpy(slot.path, path.c_str(), path.size() + 1);
        slot.ready.store(true);
        return &slot;
    }
    return nullptr;
}

void release_temporary_file(TemporaryFileSlot *slot) {
    if (!slot) return;
    slot->ready.store(false);
    slot->claimed.store(false);
}

static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs lock-free flags");

} // namespace

void remove_temporaries_in_progress() noexcept {
    for (TemporaryFileSlot &slot : g_temporary_files)
        if (slot.ready.load()) (void)::unlink(slot.path);
}

namespace {

// The directory part of path (the temporary file must be on the same file system).
std::string directory_of(const std::string &path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

// Makes a rename in `dir` durable (best effort: some file systems refuse).
void sync_directory(const std::string &dir) {
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        (void)::fsync(dfd);
        ::close(dfd);
    }
}

struct WrittenTemporary {
    std::string tmp;
    TemporaryFileSlot *slot = nullptr;
};

// Writes bytes to a new hidden temporary beside path, fsyncs and closes it; the temporary is
// registered for remove_temporaries_in_progress until the caller renames or unlinks it and
// releases the slot. On failure nothing is left behind and std::system_error names path.
WrittenTemporary write_temporary(const std::string &path, const std::vector<uint8_t> &bytes) {
    const std::string dir = directory_of(path);
    const size_t slash = path.find_last_of('/');
    const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    if (base.empty() || base == "." || base == "..")
        throw std::system_error(EISDIR, std::generic_category(), path + ": not a file name");

    static std::atomic<unsigned> counter{0};
    // The name is registered before the file exists, so a SIGINT or SIGTERM handler that calls
    // remove_temporaries_in_progress (the scatterlut command's does) removes it at any moment
    // until the rename. (A name taken already carries this PID: a dead process's leftover.)
    std::string tmp;
    TemporaryFileSlot *slot = nullptr;
    int fd = -1;
    for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
        tmp = dir + "/." + base.substr(0, 180) + ".tmp-" + std::to_string(::getpid()) + "-" +
              std::to_string(counter.fetch_add(1));
        slot = register_temporary_file(tmp);
        fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666); // umask applies
        if (fd >= 0) break;
        const int err = errno;
        release_temporary_file(slot);
        if (err != EEXIST)
            throw std::system_error(err, std::generic_category(),
                                    path + ": cannot create a temporary file in '" + dir + "'");
    }
    if (fd < 0)
        throw std::system_error(EEXIST, std::generic_category(),
                                path + ": cannot create a temporary file in '" + dir + "'");

    auto fail = [&](int err, const std::string &what) {
        if (fd >= 0) ::close(fd);
        ::unlink(tmp.c_str());
        release_temporary_file(slot);
        throw std::system_error(err, std::generic_category(), path + ": " + what);
    };
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (w < 0) {
            if (errno == EINTR) continue;
            fail(errno, "write failed (previous file left intact)");
        }
        done += static_cast<size_t>(w);
    }
    if (::fsync(fd) != 0) fail(errno, "fsync failed (previous file left intact)");
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0) fail(errno, "close failed (previous file left intact)");
    return {tmp, slot};
}

} // namespace

void write_file_atomic(const std::string &path, const std::vector<uint8_t> &bytes) {
    WrittenTemporary t = write_temporary(path, bytes);
    if (::rename(t.tmp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(t.tmp.c_str());
        release_temporary_file(t.slot);
        throw std::system_error(err, std::generic_category(), path + ": cannot rename the temporary file over it");
    }
    release_temporary_file(t.slot);
    sync_directory(directory_of(path));
}

struct AtomicFileSet::Pending {
    std::string path, tmp;
    TemporaryFileSlot *slot = nullptr;
};

AtomicFileSet::AtomicFileSet() = default;

AtomicFileSet::~AtomicFileSet() {
    for (Pending &p : pending_) {
        ::unlink(p.tmp.c_str());
        release_temporary_file(p.slot);
    }
}

void AtomicFileSet::add(const std::string &path, const std::vector<uint8_t> &bytes) {
    pending_.reserve(pending_.size() + 1); // no allocation between the write and the push
    // A final name that is a directory would fail only at its rename, after earlier files
    // of the set were renamed: refused here, while nothing has moved.
    struct stat st;
    if (::lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
        throw std::system_error(EISDIR, std::generic_category(),
                                path + ": is a directory, cannot write the file there (nothing of this set renamed)");
    WrittenTemporary t = write_temporary(path, bytes);
    pending_.push_back(Pending{path, t.tmp, t.slot});
}

void AtomicFileSet::commit() {
    // The renames run with SIGINT, SIGTERM and SIGHUP blocked (this thread): a handler that
    // ends the process must not cut the set in two. A signal that arrives meanwhile is
    // delivered once the last rename is done.
    sigset_t terminating, previous;
    sigemptyset(&terminating);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&terminating, sig);
    pthread_sigmask(SIG_BLOCK, &terminating, &previous);
    struct Restore {
        sigset_t *mask;
        ~Restore() { pthread_sigmask(SIG_SETMASK, mask, nullptr); }
    } restore{&previous};
    std::vector<std::string> dirs;
    dirs.reserve(pending_.size());
    while (!pending_.empty()) {
        Pending &p = pending_.front();
        if (::rename(p.tmp.c_str(), p.path.c_str()) != 0)
            throw std::system_error(errno, std::generic_category(),
                                    p.path + ": cannot rename the temporary file over it (the files before it in "
                                             "the set are renamed already)");
        release_temporary_file(p.slot);
        if (std::find(dirs.begin(), dirs.end(), directory_of(p.path)) == dirs.end()) dirs.push_back(directory_of(p.path));
        pending_.erase(pending_.begin());
    }
    for (const std::string &d : dirs) sync_directory(d);
}

Table load_binary(const std::string &path) {
    const std::vector<uint8_t> bytes = detail::read_file(path);
    return decode_binary(bytes.data(), bytes.size(), path);
}

void save_binary(const Table &table, const std::string &path) { write_file_atomic(path, encode_binary(table)); }

Table load_table(const std::string &path) {
    const std::vector<uint8_t> bytes = detail::read_file(path);
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), kExrMagic, 4) == 0)
        return decode_exr(bytes.data(), bytes.size(), path);
    return decode_binary(bytes.data(), bytes.size(), path);
}

#ifndef SCATTERLUT_HAS_OPENEXR
// Built without OpenEXR: the EXR entry points exist and say so.
namespace {
const char *kNoExr = "this scatterlut library was built without OpenEXR (configure with "
                     "-DSCATTERLUT_WITH_OPENEXR=ON), or use the binary format";
}
bool have_openexr() { return false; }
Table load_exr(const std::string &path) { throw LoadError(path + ": cannot read EXR: " + kNoExr); }
Table decode_exr(const uint8_t *, size_t, const std::string &name) {
    throw LoadError(name + ": cannot read EXR: " + kNoExr);
}
std::vector<uint8_t> encode_exr(const Table &) { throw std::runtime_error(std::string("cannot write EXR: ") + kNoExr); }
void save_exr(const Table &, const std::string &path) {
    throw std::runtime_error(path + ": cannot write EXR: " + kNoExr);
}
#endif

} // namespace scatterlut
