// Tests of the table files (docs/FORMAT.md): round trips, determinism, storage rounding,
// hostile inputs and atomic writes.
//
// References: IEEE 754 binary16/binary32 (round to nearest, ties to even) checked
// exhaustively over all binary16 numbers and the midpoints between them; the byte
// layout as documented in docs/FORMAT.md, re-implemented here (record walker and
// FNV-1a-64) so that a file built or patched by the test is judged by the document,
// not by the library's own encoder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <system_error>
#include <vector>

#include <dirent.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

#include "scatterlut/io.hpp"
#include "scatterlut/table.hpp"

using namespace scatterlut;
using Bytes = std::vector<uint8_t>;

namespace {

// ------------------------------------------------------------------------------------
// Fixtures: tables with every metadata field set
// ------------------------------------------------------------------------------------

Table make_table(size_t dims, Storage storage) {
    Table t;
    t.kind = kKindAirlightF;
    t.quantity_version = kAirlightFQuantityVersion;
    t.storage = storage;
    struct Spec {
        const char *name, *meaning;
        double min, max, scale;
        int warp, count;
    };
    const Spec spec[4] = {
        {"u", "optical distance sigma_t*D*sin(gamma)", 0.0, 50.0, 0.5, SLUT_WARP_LOG1P, 7},
        {"w", "pi/2 - v", 1e-3, SLUT_PIO2_HI, 0.0, SLUT_WARP_ASINH_COT, 5},
        {"g", "Henyey-Greenstein asymmetry", -0.9, 0.9, 0.0, SLUT_WARP_SQRT1P, 4},
        {"tau", "optical depth", 1e-2, 10.0, 0.0, SLUT_WARP_LOG, 3},
    };
    for (size_t a = 0; a < dims; ++a) {
        Axis ax;
        ax.name = spec[a].name;
        ax.meaning = spec[a].meaning;
        ax.map = slut_axis{spec[a].min, spec[a].max, spec[a].scale, spec[a].warp, spec[a].count};
        t.axes.push_back(ax);
    }
    t.channels.push_back(Channel{"F", "single-scattering integral F(u, v)", Encoding::Linear});
    t.channels.push_back(Channel{"ln_G", "ln of the near-light term", Encoding::Log});
    const size_t nodes = t.node_count();
    for (size_t n = 0; n < nodes; ++n) {
        const double x = static_cast<double>(n) + 0.1234567891234;
        t.values.push_back(0.5 + 60.0 * (0.5 + 0.5 * std::sin(0.37 * x)) + 1e-3 * std::cos(x)); // [0.5, 60.5]
        t.values.push_back(3.0 * std::sin(0.11 * x + 0.3) + 1e-7 * x);                           // ln q
    }
    t.accuracy.integration_max_rel = 3.5e-13;
    t.accuracy.sampling_max_rel = 2.25e-4;
    t.accuracy.sampling_p99_rel = 1.5e-4;
    t.accuracy.sampling_median_rel = 1.0e-5;
    t.accuracy.storage_max_rel = 5.9e-8;
    t.accuracy.sampling_points = 123456789012345ull;
    t.accuracy.sampling_domain = "u in [0, 50], v in [0, pi/2)";
    t.provenance.generator_version = "scatterlut 0.1.0 (test)";
    t.provenance.command_line = "scatterlut bake --scene 'my scene.toml' --out t.slut  # \xc3\xbcnic\xc3\xb6" "de";
    t.provenance.scene = "[medium]\nsigma_t_per_m = 0.1\nphase = \"isotropic\"\n";
    t.provenance.device = "CPU double reference";
    t.provenance.created_by = "scatterlut";
    t.extra["alpha"] = "1";
    t.extra["empty"] = "";
    t.extra["with nul"] = std::string("a\0b\nc", 5);
    return t;
}

void expect_same_metadata(const Table &a, const Table &b) {
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.quantity_version, b.quantity_version);
    EXPECT_EQ(a.storage, b.storage);
    ASSERT_EQ(a.axes.size(), b.axes.size());
    for (size_t i = 0; i < a.axes.size(); ++i) {
        EXPECT_EQ(a.axes[i].name, b.axes[i].name);
        EXPECT_EQ(a.axes[i].meaning, b.axes[i].meaning);
        EXPECT_EQ(a.axes[i].map.min, b.axes[i].map.min); // doubles stored bit-exactly
        EXPECT_EQ(a.axes[i].map.max, b.axes[i].map.max);
        EXPECT_EQ(a.axes[i].map.scale, b.axes[i].map.scale);
        EXPECT_EQ(a.axes[i].map.warp, b.axes[i].map.warp);
        EXPECT_EQ(a.axes[i].map.count, b.axes[i].map.count);
    }
    ASSERT_EQ(a.channels.size(), b.channels.size());
    for (size_t i = 0; i < a.channels.size(); ++i) {
        EXPECT_EQ(a.channels[i].name, b.channels[i].name);
        EXPECT_EQ(a.channels[i].meaning, b.channels[i].meaning);
        EXPECT_EQ(a.channels[i].encoding, b.channels[i].encoding);
    }
    EXPECT_EQ(a.accuracy.integration_max_rel, b.accuracy.integration_max_rel);
    EXPECT_EQ(a.accuracy.sampling_max_rel, b.accuracy.sampling_max_rel);
    EXPECT_EQ(a.accuracy.sampling_p99_rel, b.accuracy.sampling_p99_rel);
    EXPECT_EQ(a.accuracy.sampling_median_rel, b.accuracy.sampling_median_rel);
    EXPECT_EQ(a.accuracy.storage_max_rel, b.accuracy.storage_max_rel);
    EXPECT_EQ(a.accuracy.sampling_points, b.accuracy.sampling_points);
    EXPECT_EQ(a.accuracy.sampling_domain, b.accuracy.sampling_domain);
    EXPECT_EQ(a.provenance.generator_version, b.provenance.generator_version);
    EXPECT_EQ(a.provenance.command_line, b.provenance.command_line);
    EXPECT_EQ(a.provenance.scene, b.provenance.scene);
    EXPECT_EQ(a.provenance.device, b.provenance.device);
    EXPECT_EQ(a.provenance.created_by, b.provenance.created_by);
    EXPECT_EQ(a.extra, b.extra);
}

// The stored number a value must come back as: independent reference roundings
// (float cast for f32; binary16 is validated exhaustively in F16Conversion).
double stored(double v, Storage s) {
    switch (s) {
    case Storage::F16: return double_from_f16(f16_from_double(v));
    case Storage::F32: return static_cast<double>(static_cast<float>(v));
    case Storage::F64: return v;
    }
    return std::nan("");
}

void expect_values_rounded(const Table &original, const Table &loaded) {
    ASSERT_EQ(original.values.size(), loaded.values.size());
    for (size_t i = 0; i < original.values.size(); ++i)
        ASSERT_EQ(loaded.values[i], stored(original.values[i], original.storage)) << "value " << i;
}

// Expects f() to throw LoadError whose message contains `needle`.
template <class F> void expect_load_error(F f, const std::string &needle) {
    try {
        f();
        ADD_FAILURE() << "no LoadError; expected one containing '" << needle << "'";
    } catch (const LoadError &e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
            << "message: " << e.what() << "\nexpected to contain: " << needle;
    }
}

void expect_decode_error(const Bytes &b, const std::string &needle) {
    expect_load_error([&] { decode_binary(b.data(), b.size(), "test.slut"); }, needle);
}

// ------------------------------------------------------------------------------------
// The documented layout, re-implemented (docs/FORMAT.md §2)
// ------------------------------------------------------------------------------------

uint64_t doc_fnv1a64(const uint8_t *p, size_t n, uint64_t h = 0xcbf29ce484222325ull) {
    for (size_t i = 0; i < n; ++i) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}
uint32_t get_u32(const uint8_t *p) { return p[0] | p[1] << 8 | p[2] << 16 | uint32_t{p[3]} << 24; }
uint64_t get_u64(const uint8_t *p) { return get_u32(p) | uint64_t{get_u32(p + 4)} << 32; }
void put_u32(uint8_t *p, uint32_t v) {
    for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
void put_u64(uint8_t *p, uint64_t v) {
    for (int i = 0; i < 8; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
Bytes le_u32(uint32_t v) {
    Bytes b(4);
    put_u32(b.data(), v);
    return b;
}
Bytes le_f64(double d) {
    uint64_t u;
    std::memcpy(&u, &d, 8);
    Bytes b(8);
    put_u64(b.data(), u);
    return b;
}

struct Rec {
    uint32_t tag;
    Bytes value;
};
std::vector<Rec> split(const Bytes &b) {
    std::vector<Rec> out;
    size_t pos = 0;
    while (pos < b.size()) {
        const uint32_t tag = get_u32(&b[pos]), len = get_u32(&b[pos + 4]);
        out.push_back(Rec{tag, Bytes(b.begin() + pos + 8, b.begin() + pos + 8 + len)});
        pos += 8 + len;
    }
    return out;
}
Bytes join(const std::vector<Rec> &recs) {
    Bytes b;
    for (const Rec &r : recs) {
        const Bytes h = le_u32(r.tag), l = le_u32(static_cast<uint32_t>(r.value.size()));
        b.insert(b.end(), h.begin(), h.end());
        b.insert(b.end(), l.begin(), l.end());
        b.insert(b.end(), r.value.begin(), r.value.end());
    }
    return b;
}

struct File {
    uint32_t major, minor;
    std::vector<Rec> header;
    Bytes payload;
};
File parse(const Bytes &b) {
    File f;
    f.major = get_u32(&b[8]);
    f.minor = get_u32(&b[12]);
    const uint64_t hs = get_u64(&b[16]), ps = get_u64(&b[24]);
    f.header = split(Bytes(b.begin() + 48, b.begin() + 48 + static_cast<long>(hs)));
    f.payload = Bytes(b.begin() + 48 + static_cast<long>(hs), b.begin() + 48 + static_cast<long>(hs + ps));
    return f;
}
// Builds a file with correct sizes and checksums, whatever the content.
Bytes build(const File &f) {
    const Bytes h = join(f.header);
    Bytes b(48);
    std::memcpy(b.data(), "SLUTTBL", 8);
    put_u32(&b[8], f.major);
    put_u32(&b[12], f.minor);
    put_u64(&b[16], h.size());
    put_u64(&b[24], f.payload.size());
    put_u64(&b[32], doc_fnv1a64(h.data(), h.size(), doc_fnv1a64(b.data(), 32)));
    put_u64(&b[40], doc_fnv1a64(f.payload.data(), f.payload.size()));
    b.insert(b.end(), h.begin(), h.end());
    b.insert(b.end(), f.payload.begin(), f.payload.end());
    return b;
}
// The n-th record with tag `tag` in a record list.
Rec &nth(std::vector<Rec> &recs, uint32_t tag, size_t n = 0) {
    for (Rec &r : recs)
        if (r.tag == tag && n-- == 0) return r;
    throw std::logic_error("record not found");
}
// Sets field `field` of the n-th nested record `outer` to `value`.
void set_nested(File &f, uint32_t outer, size_t n, uint32_t field, const Bytes &value) {
    Rec &o = nth(f.header, outer, n);
    std::vector<Rec> inner = split(o.value);
    nth(inner, field).value = value;
    o.value = join(inner);
}
constexpr uint32_t kAxisTag = 0x10, kChannelTag = 0x11, kProvenanceTag = 0x21;

// ------------------------------------------------------------------------------------
// Temporary directories
// ------------------------------------------------------------------------------------

struct TempDir {
    std::string path;
    TempDir() {
        std::string tmpl = ::testing::TempDir() + "slut_io_XXXXXX";
        char *p = ::mkdtemp(tmpl.data());
        if (!p) throw std::runtime_error("mkdtemp failed");
        path = p;
    }
    ~TempDir() { std::system(("rm -rf '" + path + "'").c_str()); }
    std::vector<std::string> entries() const {
        std::vector<std::string> out;
        if (DIR *d = ::opendir(path.c_str())) {
            while (dirent *e = ::readdir(d))
                if (std::strcmp(e->d_name, ".") && std::strcmp(e->d_name, "..")) out.push_back(e->d_name);
            ::closedir(d);
        }
        return out;
    }
};

Bytes read_all(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
void write_all(const std::string &path, const Bytes &b) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char *>(b.data()), static_cast<std::streamsize>(b.size()));
}

} // namespace

// ====================================================================================
// table.cpp
// ====================================================================================

TEST(TableNames, RoundTrip) {
    for (Storage s : {Storage::F16, Storage::F32, Storage::F64}) {
        Storage back{};
        ASSERT_TRUE(storage_from_string(to_string(s), &back));
        EXPECT_EQ(back, s);
    }
    EXPECT_EQ(storage_bytes(Storage::F16), 2u);
    EXPECT_EQ(storage_bytes(Storage::F32), 4u);
    EXPECT_EQ(storage_bytes(Storage::F64), 8u);
    for (Encoding e : {Encoding::Linear, Encoding::Log}) {
        Encoding back{};
        ASSERT_TRUE(encoding_from_string(to_string(e), &back));
        EXPECT_EQ(back, e);
    }
    const char *names[] = {"linear", "log", "log1p", "asinh_cot", "sqrt1p", "loglin", "nl_qodds"};
    static_assert(sizeof(names) / sizeof(names[0]) == SLUT_WARP_COUNT, "one name per warp id");
    for (int w = 0; w < SLUT_WARP_COUNT; ++w) {
        EXPECT_STREQ(warp_name(w), names[w]);
        int back = -1;
        ASSERT_TRUE(warp_from_name(names[w], &back));
        EXPECT_EQ(back, w);
    }
    EXPECT_FALSE(warp_from_name("cubic", nullptr));
    EXPECT_FALSE(storage_from_string("f8", nullptr));
    EXPECT_FALSE(encoding_from_string("sqrt", nullptr));
}

TEST(TableIndex, AxisZeroFastestChannelFastestOfAll) {
    const Table t = make_table(3, Storage::F64); // counts 7, 5, 4; 2 channels
    EXPECT_EQ(t.node_count(), 7u * 5u * 4u);
    const size_t node[3] = {2, 3, 1};
    EXPECT_EQ(t.index(node), ((1u * 5u + 3u) * 7u + 2u) * 2u);
    t.check_consistent();
}

TEST(TableCheck, ClearMessages) {
    auto expect = [](Table t, const std::string &needle) {
        try {
            t.check_consistent();
            ADD_FAILURE() << "no exception; expected '" << needle << "'";
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    Table t = make_table(2, Storage::F32);
    { Table u = t; u.values.pop_back(); expect(u, "values holds 69 numbers, expected 70"); }
    { Table u = t; u.axes[0].map.min = 60; expect(u, "min 60 must be less than max 50"); }
    { Table u = t; u.axes[1].map.count = 1; expect(u, "axis 1 ('w'): count 1 is invalid"); }
    { Table u = t; u.axes[0].map.warp = 7; expect(u, "unknown warp id 7"); }
    { Table u = t; u.axes[0].map.scale = 0; expect(u, "warp 'log1p' needs scale > 0"); }
    { Table u = t; u.axes[1].map.min = 0; expect(u, "warp 'asinh_cot' needs min > 0"); }
    { Table u = t; u.axes[0].map.max = INFINITY; expect(u, "is not finite"); }
    { Table u = t; u.values[3] = NAN; expect(u, "value 3 (node (1, 0), channel 'ln_G') is not finite"); }
    { Table u = t; u.channels[1].name = "F"; expect(u, "channel name 'F' appears twice"); }
    { Table u = t; u.axes.clear(); expect(u, "no axes"); }
    { Table u = t; u.axes.resize(9, t.axes[0]); expect(u, "at most 8"); }
}

// ====================================================================================
// Storage rounding
// ====================================================================================

// Reference: IEEE 754 binary16. Every finite half converts back to itself; every
// midpoint between neighbours rounds to the one with an even fraction, and the doubles
// just either side of it to the nearer neighbour. Covers subnormals (h < 0x400), the
// normal/subnormal boundary, and overflow (midpoint 65520 between 65504 and 2^16 → inf).
TEST(F16Conversion, ExhaustiveRoundToNearestEven) {
    for (uint32_t h = 0; h < 0x7c00; ++h) {
        const double v = double_from_f16(static_cast<uint16_t>(h));
        ASSERT_EQ(f16_from_double(v), h) << h;
        ASSERT_EQ(f16_from_double(-v), h | 0x8000u) << h;
        const double next = h + 1 < 0x7c00 ? double_from_f16(static_cast<uint16_t>(h + 1)) : 65536.0;
        const double mid = 0.5 * (v + next); // exact in double
        const uint32_t even = (h & 1u) ? h + 1 : h;
        ASSERT_EQ(f16_from_double(mid), even) << "midpoint above " << h;
        ASSERT_EQ(f16_from_double(std::nextafter(mid, 0.0)), h) << h;
        ASSERT_EQ(f16_from_double(std::nextafter(mid, INFINITY)), h + 1) << h;
    }
    EXPECT_EQ(double_from_f16(0x7bff), 65504.0);
    EXPECT_EQ(double_from_f16(0x0001), std::ldexp(1.0, -24));
    EXPECT_EQ(double_from_f16(0x0400), std::ldexp(1.0, -14));
    EXPECT_EQ(f16_from_double(65520.0), 0x7c00);
    EXPECT_EQ(f16_from_double(1e300), 0x7c00);
    EXPECT_EQ(f16_from_double(-INFINITY), 0xfc00);
    EXPECT_TRUE(std::isnan(double_from_f16(f16_from_double(NAN))));
    EXPECT_EQ(f16_from_double(std::ldexp(1.0, -25)), 0x0000); // tie with 0 → even 0
    EXPECT_EQ(f16_from_double(1e-300), 0x0000);
    EXPECT_EQ(f16_from_double(std::numeric_limits<double>::denorm_min()), 0x0000);
    EXPECT_EQ(f16_from_double(-0.0), 0x8000);
    EXPECT_TRUE(std::isinf(double_from_f16(0x7c00)));
}

TEST(F32Rounding, MatchesFloatCastAndOverflowIsExplicit) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> mant(-1.0, 1.0);
    std::uniform_int_distribution<int> ex(-140, 127);
    for (int i = 0; i < 100000; ++i) {
        const double x = std::ldexp(mant(rng), ex(rng));
        ASSERT_EQ(round_to_storage(x, Storage::F32), static_cast<double>(static_cast<float>(x))) << x;
    }
    const double fmax = FLT_MAX;
    EXPECT_EQ(round_to_storage(std::nextafter(0x1.ffffffp127, 0.0), Storage::F32), fmax);
    EXPECT_TRUE(std::isinf(round_to_storage(0x1.ffffffp127, Storage::F32))); // tie → even (2^128)
    EXPECT_TRUE(std::isinf(round_to_storage(-1e300, Storage::F32)));
}

// Expected: f64 exact (0); f32 relative error ≤ 2^-24 (half an ulp) on linear channels;
// f16 ≤ 2^-11 for values in the normal range. Values spread over many binades reach
// close to the bound, so also check it is not trivially small (> bound/4).
TEST(StorageRounding, MaxRelMatchesHalfUlpBounds) {
    Table t = make_table(2, Storage::F64);
    for (Channel &c : t.channels) c.encoding = Encoding::Linear;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(1.0, 1000.0);
    for (double &v : t.values) v = u(rng);
    EXPECT_EQ(storage_rounding_max_rel(t, Storage::F64), 0.0);
    const double r32 = storage_rounding_max_rel(t, Storage::F32);
    EXPECT_LE(r32, std::ldexp(1.0, -24));
    EXPECT_GT(r32, std::ldexp(1.0, -26));
    const double r16 = storage_rounding_max_rel(t, Storage::F16);
    EXPECT_LE(r16, std::ldexp(1.0, -11));
    EXPECT_GT(r16, std::ldexp(1.0, -13));
    t.values[5] = 1e5; // beyond f16
    EXPECT_TRUE(std::isinf(storage_rounding_max_rel(t, Storage::F16)));
    t.values[5] = NAN;
    EXPECT_THROW(storage_rounding_max_rel(t, Storage::F32), std::invalid_argument);
}

// Log channel: quantity q = exp(stored), so the relative error on q is |exp(r − v) − 1|,
// about |v|·2^-24 for f32, not 2^-24: computed independently here.
TEST(StorageRounding, LogChannelErrorIsOnTheQuantity) {
    Table t = make_table(1, Storage::F64);
    double expected = 0;
    for (size_t i = 0; i < t.values.size(); ++i) {
        const double v = t.values[i];
        const double r = static_cast<double>(static_cast<float>(v));
        const double rel = t.channels[i % 2].encoding == Encoding::Log ? std::fabs(std::exp(r) / std::exp(v) - 1.0)
                                                                       : std::fabs(r - v) / std::fabs(v);
        expected = std::max(expected, rel);
    }
    EXPECT_NEAR(storage_rounding_max_rel(t, Storage::F32), expected, 1e-3 * expected);
}

// Reference: the published FNV-1a-64 test vectors (docs/FORMAT.md §2.5), and the
// test's own implementation from the document, continued over two pieces.
TEST(Checksum, Fnv1a64Vectors) {
    EXPECT_EQ(fnv1a64("", 0), 0xcbf29ce484222325ull);
    EXPECT_EQ(fnv1a64("a", 1), 0xaf63dc4c8601ec8cull);
    EXPECT_EQ(fnv1a64("foobar", 6), 0x85944171f73967e8ull);
    EXPECT_EQ(fnv1a64("bar", 3, fnv1a64("foo", 3)), fnv1a64("foobar", 6));
    const uint8_t bytes[] = {0, 1, 2, 255, 128};
    EXPECT_EQ(fnv1a64(bytes, 5), doc_fnv1a64(bytes, 5));
}

// ====================================================================================
// Binary round trips and determinism
// ====================================================================================

TEST(Binary, RoundTripAllDimensionsAndStorages) {
    for (size_t dims = 1; dims <= 4; ++dims) {
        for (Storage s : {Storage::F16, Storage::F32, Storage::F64}) {
            SCOPED_TRACE(std::to_string(dims) + "-D " + to_string(s));
            const Table t = make_table(dims, s);
            const Bytes b = encode_binary(t);
            const Table back = decode_binary(b.data(), b.size(), "mem");
            expect_same_metadata(t, back);
            expect_values_rounded(t, back);
            // Deterministic, and a loaded table re-encodes to the same bytes.
            EXPECT_EQ(encode_binary(t), b);
            EXPECT_EQ(encode_binary(back), b);
            // Payload 64-byte aligned (FORMAT.md §2.1).
            EXPECT_EQ((48 + get_u64(&b[16])) % 64, 0u);
        }
    }
}

TEST(Binary, SaveLoadFilesByteIdentical) {
    TempDir dir;
    const Table t = make_table(3, Storage::F32);
    save_binary(t, dir.path + "/a.slut");
    save_binary(t, dir.path + "/b.slut");
    EXPECT_EQ(read_all(dir.path + "/a.slut"), read_all(dir.path + "/b.slut"));
    const Table back = load_binary(dir.path + "/a.slut");
    expect_same_metadata(t, back);
    const Table any = load_table(dir.path + "/a.slut");
    expect_values_rounded(t, any);
    EXPECT_EQ(dir.entries().size(), 2u); // no temp files left
}

TEST(Binary, WriterRefusesWhatTheFormatCannotHold) {
    Table t = make_table(2, Storage::F16);
    t.values[0] = 70000.0; // > 65504
    try {
        encode_binary(t);
        ADD_FAILURE();
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("overflows f16"), std::string::npos) << e.what();
    }
    Table u = make_table(1, Storage::F32);
    u.kind = std::string(300, 'k');
    EXPECT_THROW(encode_binary(u), std::invalid_argument);
    Table v = make_table(1, Storage::F32);
    for (int i = 0; i < 16; ++i) v.channels.push_back(Channel{"c" + std::to_string(i), "", Encoding::Linear});
    v.values.assign(v.node_count() * v.channels.size(), 1.0);
    EXPECT_THROW(encode_binary(v), std::invalid_argument);
}

// ====================================================================================
// Binary: hostile inputs
// ====================================================================================

TEST(BinaryHostile, TruncatedAtEveryPrefixLength) {
    for (Storage s : {Storage::F16, Storage::F64}) {
        const Bytes b = encode_binary(make_table(2, s));
        for (size_t n = 0; n < b.size(); ++n) {
            const Bytes prefix(b.begin(), b.begin() + static_cast<long>(n));
            expect_decode_error(prefix, "truncated");
            if (HasFailure()) {
                ADD_FAILURE() << "at prefix length " << n;
                return;
            }
        }
    }
}

TEST(BinaryHostile, WrongMagic) {
    Bytes b = encode_binary(make_table(1, Storage::F32));
    b[3] = 'X';
    expect_decode_error(b, "not a scatterlut binary table: expected magic 53 4c 55 54 54 42 4c 00");
    const Bytes exr = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0, 0, 0};
    expect_decode_error(exr, "an OpenEXR file");
}

TEST(BinaryHostile, ChecksumsCatchFlippedBytes) {
    const Bytes good = encode_binary(make_table(2, Storage::F32));
    Bytes b = good;
    b[b.size() - 5] ^= 0x10; // payload
    expect_decode_error(b, "payload checksum mismatch");
    b = good;
    b[60] ^= 0x01; // inside the header section
    expect_decode_error(b, "header checksum mismatch");
    b = good;
    b[40] ^= 0x01; // the stored payload checksum itself
    expect_decode_error(b, "payload checksum mismatch");
}

TEST(BinaryHostile, HugeNodeCountRefusedBeforeAllocation) {
    File f = parse(encode_binary(make_table(2, Storage::F32)));
    set_nested(f, kAxisTag, 0, 7, le_u32(1000000));
    set_nested(f, kAxisTag, 1, 7, le_u32(1000000)); // 10^12 nodes; payload unchanged
    expect_decode_error(build(f), "header claims 1000000000000 nodes, more than the limit of 2^31");
}

TEST(BinaryHostile, NegativeZeroAndOneCounts) {
    for (int32_t count : {-1, 0, 1, std::numeric_limits<int32_t>::min()}) {
        File f = parse(encode_binary(make_table(2, Storage::F32)));
        set_nested(f, kAxisTag, 1, 7, le_u32(static_cast<uint32_t>(count)));
        expect_decode_error(build(f), "axis 1 ('w'): count " + std::to_string(count) + " is invalid");
    }
}

TEST(BinaryHostile, NonFinitePayloadWithValidChecksum) {
    for (uint32_t bits : {0x7fc00000u, 0x7f800000u, 0xff800000u}) {
        File f = parse(encode_binary(make_table(2, Storage::F32)));
        put_u32(&f.payload[4 * 13], bits); // node (6, 0), channel 1
        expect_decode_error(build(f), "payload value at node (6, 0), channel 'ln_G' is not finite");
    }
    File f = parse(encode_binary(make_table(1, Storage::F16)));
    f.payload[0] = 0x00;
    f.payload[1] = 0x7e; // f16 NaN
    expect_decode_error(build(f), "is not finite (nan)");
}

TEST(BinaryHostile, BadAxisAndEnumerationFields) {
    const File good = parse(encode_binary(make_table(2, Storage::F32)));
    File f = good;
    set_nested(f, kAxisTag, 0, 3, le_f64(NAN));
    expect_decode_error(build(f), "axis 0 ('u'): range [nan, 50] / scale 0.5 is not finite");
    f = good;
    set_nested(f, kAxisTag, 0, 4, le_f64(INFINITY));
    expect_decode_error(build(f), "is not finite");
    f = good;
    set_nested(f, kAxisTag, 0, 3, le_f64(50.0)); // min = max
    expect_decode_error(build(f), "axis 0 ('u'): min 50 must be less than max 50");
    f = good;
    set_nested(f, kAxisTag, 1, 6, le_u32(9));
    expect_decode_error(build(f), "axis 1 ('w'): unknown warp id 9");
    f = good;
    set_nested(f, kChannelTag, 1, 3, le_u32(7));
    expect_decode_error(build(f), "channel 1 ('ln_G'): unknown encoding id 7");
    f = good;
    nth(f.header, 0x03).value = le_u32(4);
    expect_decode_error(build(f), "unknown storage id 4");
    f = good;
    nth(f.header, 0x03).value = le_u32(3); // claims f64, payload holds f32
    expect_decode_error(build(f), "payload is 280 bytes, expected 560");
    f = good;
    set_nested(f, kAxisTag, 1, 3, le_f64(-0.5)); // asinh_cot below 0: check_consistent
    expect_decode_error(build(f), "inconsistent table: axis 1 ('w'): warp 'asinh_cot' needs min > 0");
}

TEST(BinaryHostile, StructuralCorruption) {
    const Bytes good_bytes = encode_binary(make_table(2, Storage::F32));
    const File good = parse(good_bytes);
    File f = good;
    f.header.push_back(f.header[0]); // a second 'kind'
    expect_decode_error(build(f), "field 'kind' appears twice");
    f = good;
    f.header.erase(f.header.begin());
    expect_decode_error(build(f), "required field 'kind' is missing");
    f = good;
    {
        std::vector<Rec> inner = split(nth(f.header, kAxisTag).value);
        inner.pop_back(); // drop 'count'
        nth(f.header, kAxisTag).value = join(inner);
    }
    expect_decode_error(build(f), "axis 0: required field 'count' is missing");
    f = good;
    nth(f.header, 0x02).value = Bytes(3, 0); // quantity_version must be 4 bytes
    expect_decode_error(build(f), "field 'quantity_version' is 3 bytes, expected 4");
    f = good;
    nth(f.header, 0x01).value = Bytes(300, 'k');
    expect_decode_error(build(f), "field 'kind' is 300 bytes, more than the limit 256");
    f = good;
    for (int i = 0; i < 9; ++i) f.header.push_back(nth(f.header, kAxisTag));
    expect_decode_error(build(f), "more than 8 axes");

    // A record whose length runs past the header (checksum recomputed over the lie).
    Bytes b = good_bytes;
    put_u32(&b[48 + 4], 0x7fffffff);
    put_u64(&b[32], doc_fnv1a64(&b[48], get_u64(&b[16]), doc_fnv1a64(b.data(), 32)));
    expect_decode_error(b, "claims 2147483647 bytes but only");

    b = good_bytes;
    put_u64(&b[16], uint64_t{1} << 40);
    expect_decode_error(b, "header size 1099511627776 exceeds the limit");
    b = good_bytes;
    put_u64(&b[24], ~uint64_t{0});
    expect_decode_error(b, "truncated");
    b = good_bytes;
    b.push_back(0);
    expect_decode_error(b, "1 unexpected bytes after the payload");
}

TEST(BinaryHostile, UnknownMajorVersionRefused) {
    Bytes b = encode_binary(make_table(1, Storage::F32));
    put_u32(&b[8], 2);
    put_u32(&b[12], 0);
    expect_decode_error(b, "test.slut: format version 2.0 is newer than this reader (1.x); upgrade scatterlut");
    put_u32(&b[8], 0);
    expect_decode_error(b, "format version 0.0 is older");
}

TEST(BinaryHostile, NewerMinorWithUnknownFieldsIsRead) {
    const Table t = make_table(2, Storage::F32);
    File f = parse(encode_binary(t));
    f.minor = kFormatMinor + 1;
    f.header.push_back(Rec{0x7001, Bytes{1, 2, 3, 4, 5}});                       // top level
    nth(f.header, kAxisTag, 1).value = join([&] {                               // nested, in an axis
        std::vector<Rec> inner = split(nth(f.header, kAxisTag, 1).value);
        inner.push_back(Rec{42, le_f64(1.5)});
        return inner;
    }());
    nth(f.header, kProvenanceTag).value.insert(nth(f.header, kProvenanceTag).value.end(), {99, 0, 0, 0, 1, 0, 0, 0, 7});
    const Bytes b = build(f);
    const Table back = decode_binary(b.data(), b.size(), "newer.slut");
    expect_same_metadata(t, back);
    expect_values_rounded(t, back);

    // The same unknown field in a file of this reader's own version is corruption.
    f.minor = kFormatMinor;
    expect_decode_error(build(f), "unknown field tag");
}

// Random mutations of the header with checksums repaired, so that the record parser
// (not the checksum) meets them: every outcome is a table or a LoadError.
TEST(BinaryHostile, FuzzedHeadersNeverCrash) {
    const Bytes good = encode_binary(make_table(3, Storage::F16));
    const uint64_t hs = get_u64(&good[16]);
    std::mt19937 rng(12345);
    int refused = 0;
    for (int iter = 0; iter < 4000; ++iter) {
        Bytes b = good;
        const int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            const size_t at = 48 + rng() % hs;
            switch (rng() % 3) {
            case 0: b[at] ^= static_cast<uint8_t>(1u << (rng() % 8)); break;
            case 1: b[at] = static_cast<uint8_t>(rng()); break;
            default: b[at] = (rng() % 2) ? 0xff : 0x00; break;
            }
        }
        put_u64(&b[32], doc_fnv1a64(&b[48], hs, doc_fnv1a64(b.data(), 32)));
        try {
            decode_binary(b.data(), b.size(), "fuzz");
        } catch (const LoadError &) {
            ++refused;
        }
    }
    EXPECT_GT(refused, 1000);
}

TEST(LoadTable, FileErrors) {
    TempDir dir;
    expect_load_error([&] { load_table(dir.path + "/missing.slut"); }, "cannot open for reading");
    expect_load_error([&] { load_table(dir.path); }, "is a directory");
    write_all(dir.path + "/junk.bin", Bytes{'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd'});
    expect_load_error([&] { load_table(dir.path + "/junk.bin"); }, "junk.bin: not a scatterlut binary table");
    write_all(dir.path + "/empty.slut", Bytes{});
    expect_load_error([&] { load_binary(dir.path + "/empty.slut"); }, "empty.slut: truncated: the file is empty");
}

// ====================================================================================
// Atomic writes
// ====================================================================================

TEST(AtomicWrite, MissingOrInvalidDirectoryThrowsAndLeavesNothing) {
    TempDir dir;
    const Table t = make_table(1, Storage::F32);
    EXPECT_THROW(save_binary(t, dir.path + "/no/such/dir/t.slut"), std::system_error);
    write_all(dir.path + "/plainfile", Bytes{1});
    EXPECT_THROW(save_binary(t, dir.path + "/plainfile/t.slut"), std::system_error);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"plainfile"});
    if (::geteuid() != 0) { // root writes anywhere
        const std::string ro = dir.path + "/ro";
        ASSERT_EQ(::mkdir(ro.c_str(), 0555), 0);
        EXPECT_THROW(save_binary(t, ro + "/t.slut"), std::system_error);
        ::chmod(ro.c_str(), 0755);
    }
}

TEST(AtomicWrite, FailedWriteLeavesPreviousFileIntact) {
    TempDir dir;
    const std::string path = dir.path + "/t.slut";
    const Table small = make_table(1, Storage::F32);
    save_binary(small, path);
    const Bytes before = read_all(path);

    // 1. The table cannot be encoded: nothing is written.
    Table bad = make_table(2, Storage::F16);
    bad.values[0] = 1e6;
    EXPECT_THROW(save_binary(bad, path), std::invalid_argument);
    EXPECT_EQ(read_all(path), before);

    // 2. The write itself fails half-way (file size limit → EFBIG).
    const Table big = make_table(4, Storage::F64); // ~8 KB, beyond the limit below
    ASSERT_GT(encode_binary(big).size(), 4096u + 1024u);
    struct rlimit old_limit;
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old_limit), 0);
    auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    struct rlimit low = old_limit;
    low.rlim_cur = 4096;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &low), 0);
    bool threw = false;
    try {
        save_binary(big, path);
    } catch (const std::system_error &e) {
        threw = true;
        EXPECT_NE(std::string(e.what()).find("previous file left intact"), std::string::npos) << e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old_limit);
    std::signal(SIGXFSZ, old_handler);
    EXPECT_TRUE(threw);
    EXPECT_EQ(read_all(path), before);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"t.slut"}); // temp removed

    // 3. And a successful write replaces it.
    save_binary(big, path);
    EXPECT_EQ(read_all(path), encode_binary(big));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"t.slut"});
}

// ====================================================================================
// EXR
// ====================================================================================

#ifdef SCATTERLUT_HAS_OPENEXR

namespace {

// The channel list attribute of an EXR header (OpenEXR file layout: name\0 type\0 size
// value; chlist = {name\0, i32 pixel type, u8 pLinear, 3 reserved, i32 xs, i32 ys}*, \0).
size_t find_bytes(const Bytes &b, const std::string &needle) {
    auto it = std::search(b.begin(), b.end(), needle.begin(), needle.end());
    if (it == b.end()) throw std::logic_error("not found: " + needle);
    return static_cast<size_t>(it - b.begin());
}
// Offset of the pixel-type field of channel `name` in the chlist.
size_t chlist_type_offset(const Bytes &b, const std::string &name) {
    size_t p = find_bytes(b, std::string("channels\0chlist\0", 16)) + 16 + 4;
    while (b[p] != 0) {
        const std::string n(reinterpret_cast<const char *>(&b[p]));
        p += n.size() + 1;
        if (n == name) return p;
        p += 16;
    }
    throw std::logic_error("channel not found");
}

void expect_exr_error(const Bytes &b, const std::string &needle) {
    expect_load_error([&] { decode_exr(b.data(), b.size(), "test.exr"); }, needle);
}

} // namespace

TEST(Exr, RoundTripAllDimensionsF16F32) {
    ASSERT_TRUE(have_openexr());
    for (size_t dims = 1; dims <= 4; ++dims) {
        for (Storage s : {Storage::F16, Storage::F32}) {
            SCOPED_TRACE(std::to_string(dims) + "-D " + to_string(s));
            const Table t = make_table(dims, s);
            const Bytes b = encode_exr(t);
            const Table back = decode_exr(b.data(), b.size(), "mem.exr");
            expect_same_metadata(t, back);
            expect_values_rounded(t, back);
            EXPECT_EQ(encode_exr(t), b);    // deterministic
            EXPECT_EQ(encode_exr(back), b); // and stable under a round trip
            // Same stored numbers as the binary format.
            const Bytes bin = encode_binary(t);
            const Table from_bin = decode_binary(bin.data(), bin.size(), "mem.slut");
            EXPECT_EQ(from_bin.values, back.values);
        }
    }
}

TEST(Exr, FilesAndDispatchByMagic) {
    TempDir dir;
    const Table t = make_table(3, Storage::F16);
    save_exr(t, dir.path + "/t.exr");
    save_binary(t, dir.path + "/t.slut");
    const Table a = load_table(dir.path + "/t.exr");
    const Table b = load_table(dir.path + "/t.slut");
    EXPECT_EQ(a.values, b.values);
    expect_same_metadata(a, b);
    expect_same_metadata(t, load_exr(dir.path + "/t.exr"));
    expect_load_error([&] { load_binary(dir.path + "/t.exr"); }, "an OpenEXR file: read it with load_table");
    expect_load_error([&] { load_exr(dir.path + "/t.slut"); }, "not an OpenEXR file");
    EXPECT_EQ(dir.entries().size(), 2u);
}

TEST(Exr, F64IsRefusedWithAHint) {
    try {
        encode_exr(make_table(2, Storage::F64));
        ADD_FAILURE();
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("use the binary format"), std::string::npos) << e.what();
    }
}

// Table channels F, ln_G are the EXR channels R, G (mapping version 2, docs/FORMAT.md §4).
TEST(ExrHostile, MissingChannel) {
    Bytes b = encode_exr(make_table(2, Storage::F16));
    const size_t type_at = chlist_type_offset(b, "G");
    b[type_at - 2] = 'X'; // rename "G" → "X" in the channel list only
    expect_exr_error(b, "missing channel 'ln_G' (expected HALF pixels for storage f16) in EXR channel 'G'");
}

TEST(ExrHostile, WrongPixelType) {
    Bytes b = encode_exr(make_table(2, Storage::F16));
    put_u32(&b[chlist_type_offset(b, "R")], 2); // FLOAT
    expect_exr_error(b, "channel 'F' has pixel type FLOAT, expected HALF (storage f16) in EXR channel 'R'");
    b = encode_exr(make_table(1, Storage::F32));
    put_u32(&b[chlist_type_offset(b, "G")], 0); // UINT
    expect_exr_error(b, "channel 'ln_G' has pixel type UINT, expected FLOAT");
}

TEST(ExrHostile, EditedAttributesAndVersions) {
    const Bytes good = encode_exr(make_table(2, Storage::F32));
    Bytes b = good;
    b[find_bytes(b, "scatterlut 0.1.0 (test)")] = 'X'; // generator_version edited
    expect_exr_error(b, "header checksum mismatch");
    b = good;
    const size_t major_at = find_bytes(b, std::string("scatterlut.format_major\0int\0", 28)) + 28 + 4;
    put_u32(&b[major_at], kExrFormatMajor + 1);
    expect_exr_error(b, "test.exr: format version " + std::to_string(kExrFormatMajor + 1) + "." +
                            std::to_string(kExrFormatMinor) + " is newer than this reader (" +
                            std::to_string(kExrFormatMajor) + ".x); upgrade scatterlut");
    put_u32(&b[major_at], 0);
    expect_exr_error(b, "test.exr: format version 0." + std::to_string(kExrFormatMinor) + " is not supported");
    b = good;
    const size_t count_at = find_bytes(b, std::string("scatterlut.axis.1.count\0int\0", 28)) + 28 + 4;
    put_u32(&b[count_at], 7);
    expect_exr_error(b, "header checksum mismatch");
}

TEST(ExrHostile, TruncatedAndCorruptNeverCrash) {
    const Bytes good = encode_exr(make_table(2, Storage::F16));
    for (size_t n = 0; n < good.size(); n += (n < 64 ? 1 : 7)) {
        const Bytes prefix(good.begin(), good.begin() + static_cast<long>(n));
        EXPECT_THROW(decode_exr(prefix.data(), prefix.size(), "cut.exr"), LoadError) << n;
    }
    std::mt19937 rng(99);
    for (int i = 0; i < 500; ++i) {
        Bytes b = good;
        b[rng() % b.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
        try {
            decode_exr(b.data(), b.size(), "flip.exr");
        } catch (const LoadError &) {
        }
    }
}

// The header checksum as docs/FORMAT.md §4.1 defines it, recomputed from the file's bytes
// (attribute list: name\0 type\0 i32 size value …, \0) and written into
// scatterlut.checksum.header, so that an edited header is judged by the reader's checks
// rather than by the checksum.
void refresh_exr_header_checksum(Bytes &b) {
    struct Attr {
        std::string name, type;
        size_t value_at, size;
    };
    std::vector<Attr> attrs;
    size_t pos = 8;
    while (b[pos] != 0) {
        Attr a;
        a.name = reinterpret_cast<const char *>(&b[pos]);
        pos += a.name.size() + 1;
        a.type = reinterpret_cast<const char *>(&b[pos]);
        pos += a.type.size() + 1;
        a.size = get_u32(&b[pos]);
        a.value_at = pos + 4;
        pos = a.value_at + a.size;
        attrs.push_back(a);
    }
    std::sort(attrs.begin(), attrs.end(), [](const Attr &x, const Attr &y) { return x.name < y.name; });
    uint64_t h = 0xcbf29ce484222325ull;
    size_t checksum_at = 0;
    for (const Attr &a : attrs) {
        if (a.name == "scatterlut.checksum.header") checksum_at = a.value_at;
        if (a.name.rfind("scatterlut.", 0) != 0 || a.name.rfind("scatterlut.checksum.", 0) == 0) continue;
        const Bytes size = le_u32(static_cast<uint32_t>(a.size));
        h = doc_fnv1a64(reinterpret_cast<const uint8_t *>(a.name.c_str()), a.name.size() + 1, h);
        h = doc_fnv1a64(reinterpret_cast<const uint8_t *>(a.type.c_str()), a.type.size() + 1, h);
        h = doc_fnv1a64(size.data(), 4, h);
        h = doc_fnv1a64(&b[a.value_at], a.size, h);
    }
    char hex[19];
    std::snprintf(hex, sizeof hex, "0x%016llx", static_cast<unsigned long long>(h));
    std::memcpy(&b[checksum_at], hex, 18);
}

// docs/FORMAT.md §2.7 for EXR: a file of a newer minor version with a scatterlut.*
// attribute this reader does not know is read (the attribute skipped); the same attribute
// in a file of this reader's own version is refused. The unknown attribute replaces
// screenWindowWidth (same name length, type float), so no byte moves.
TEST(Exr, NewerMinorWithUnknownAttributesIsRead) {
    const Table t = make_table(2, Storage::F32);
    const Bytes good = encode_exr(t);
    Bytes b = good;
    const size_t at = find_bytes(b, std::string("screenWindowWidth\0float\0", 24));
    std::memcpy(&b[at], "scatterlut.zz_new", 17);
    const std::string minor_attr("scatterlut.format_minor\0int\0", 28);
    put_u32(&b[find_bytes(b, minor_attr) + minor_attr.size() + 4], kExrFormatMinor + 1);
    refresh_exr_header_checksum(b);
    const Table back = decode_exr(b.data(), b.size(), "newer.exr");
    expect_same_metadata(t, back);
    expect_values_rounded(t, back);

    put_u32(&b[find_bytes(b, minor_attr) + minor_attr.size() + 4], kExrFormatMinor);
    refresh_exr_header_checksum(b);
    expect_exr_error(b, "unknown attribute 'scatterlut.zz_new' (format version " + std::to_string(kExrFormatMajor) +
                            "." + std::to_string(kExrFormatMinor) + " defines no such attribute)");
    // And the helper is faithful: refreshing an unedited file changes nothing.
    Bytes same = good;
    refresh_exr_header_checksum(same);
    EXPECT_EQ(same, good);
}


// The attributes of an EXR header as the file lays them out: name → (type, value bytes).
std::map<std::string, std::pair<std::string, Bytes>> exr_attributes(const Bytes &b) {
    std::map<std::string, std::pair<std::string, Bytes>> out;
    size_t pos = 8;
    while (b[pos] != 0) {
        const std::string name = reinterpret_cast<const char *>(&b[pos]);
        pos += name.size() + 1;
        const std::string type = reinterpret_cast<const char *>(&b[pos]);
        pos += type.size() + 1;
        const size_t size = get_u32(&b[pos]);
        pos += 4;
        out[name] = {type, Bytes(b.begin() + static_cast<long>(pos), b.begin() + static_cast<long>(pos + size))};
        pos += size;
    }
    return out;
}

// Mapping version 2 is what engine loaders open: one table channel is the EXR channel Y,
// two to four are R, G, B, A in table order; no attribute is a `double` (three.js's
// EXRLoader skips them): the reals are decimal strings that read back exactly.
TEST(Exr, EngineChannelNamesAndRealsAsText) {
    Table one = make_table(2, Storage::F32);
    one.channels.resize(1);
    one.values.clear();
    for (size_t n = 0; n < one.node_count(); ++n) one.values.push_back(0.25 + 1e-3 * static_cast<double>(n));
    one.axes[0].map.scale = 0.1; // no short binary fraction: the text must carry all 17 digits
    for (const Table &t : {one, make_table(2, Storage::F16)}) {
        const Bytes b = encode_exr(t);
        const auto attrs = exr_attributes(b);
        std::vector<std::string> channels;
        const Bytes &chlist = attrs.at("channels").second;
        for (size_t p = 0; chlist[p] != 0;) {
            channels.emplace_back(reinterpret_cast<const char *>(&chlist[p]));
            p += channels.back().size() + 1 + 16;
        }
        const std::vector<std::string> want =
            t.channels.size() == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"G", "R"}; // EXR sorts
        EXPECT_EQ(channels, want);
        for (size_t c = 0; c < t.channels.size(); ++c) {
            const auto &a = attrs.at("scatterlut.channel." + std::to_string(c) + ".exr_channel");
            EXPECT_EQ(a.first, "string");
            EXPECT_EQ(std::string(a.second.begin(), a.second.end()), exr_channel_name(t.channels.size(), c, ""));
        }
        for (const auto &kv : attrs) EXPECT_NE(kv.second.first, "double") << kv.first;
        const auto &scale = attrs.at("scatterlut.axis.0.scale");
        EXPECT_EQ(scale.first, "string");
        double v = 0;
        ASSERT_TRUE(detail::parse_decimal_text(std::string(scale.second.begin(), scale.second.end()), &v));
        EXPECT_EQ(v, t.axes[0].map.scale);
        EXPECT_EQ(get_u32(&attrs.at("scatterlut.format_major").second[0]), kExrFormatMajor);
        const Table back = decode_exr(b.data(), b.size(), "mem.exr");
        expect_same_metadata(t, back);
        expect_values_rounded(t, back);
    }
    EXPECT_EQ(exr_channel_name(5, 4, "ln_X"), "ln_X"); // beyond RGBA: the table's own names
}

TEST(Exr, DecimalTextReadsBackExactly) {
    for (double x : {0.0, -0.0, 0.1, 1.0 / 3.0, 1e-300, 4.9e-324, 1.7976931348623157e308, -2.5, SLUT_PIO2_HI}) {
        double y = 1;
        ASSERT_TRUE(detail::parse_decimal_text(detail::decimal_text(x), &y)) << detail::decimal_text(x);
        EXPECT_EQ(std::memcmp(&x, &y, sizeof x), 0) << detail::decimal_text(x);
    }
    EXPECT_EQ(detail::decimal_text(0.5), "0.5");
    EXPECT_EQ(detail::decimal_text(1e-5), "1e-05");
    double y;
    for (const char *bad : {"", " 1", "1 ", "1,5", "0x1p3", "+1", "1e", "--1"})
        EXPECT_FALSE(detail::parse_decimal_text(bad, &y)) << bad;
}

// A version-2 file whose channel mapping or real-number text is edited (checksum made
// consistent) is refused with the attribute named.
TEST(ExrHostile, EditedChannelMappingAndRealText) {
    const Bytes good = encode_exr(make_table(2, Storage::F16));
    Bytes b = good;
    const std::string exr_attr("scatterlut.channel.1.exr_channel\0string\0", 40);
    b[find_bytes(b, exr_attr) + exr_attr.size() + 4] = 'B';
    refresh_exr_header_checksum(b);
    expect_exr_error(b, "channel 1 ('ln_G'): attribute 'scatterlut.channel.1.exr_channel' = 'B', expected 'G'");
    b = good;
    const std::string min_attr("scatterlut.axis.0.min\0string\0", 29);
    b[find_bytes(b, min_attr) + min_attr.size() + 4] = 'x'; // "0" → "x"
    refresh_exr_header_checksum(b);
    expect_exr_error(b, "attribute 'scatterlut.axis.0.min' = 'x' is not a decimal number");
}

// Files written by the version-1.1 mapping (channels named after the table's channels,
// `double` attributes; tests/data/exr-format-1.1, written by scatterlut before 2.0 from
// make_table) are still read, with the same metadata and values.
TEST(Exr, ReadsVersion11Files) {
    const std::string dir = std::string(SLUT_SOURCE_DIR) + "/tests/data/exr-format-1.1/";
    for (size_t dims : {2, 4}) {
        const Storage s = dims == 2 ? Storage::F16 : Storage::F32;
        SCOPED_TRACE(std::to_string(dims) + "-D " + to_string(s));
        const Table t = make_table(dims, s);
        const Bytes old = read_all(dir + "make_table_" + std::to_string(dims) + "d_" + to_string(s) + ".exr");
        const auto attrs = exr_attributes(old);
        ASSERT_EQ(get_u32(&attrs.at("scatterlut.format_major").second[0]), 1u);
        ASSERT_EQ(attrs.at("scatterlut.axis.0.min").first, "double");
        const Table back = decode_exr(old.data(), old.size(), "old.exr");
        expect_same_metadata(t, back);
        expect_values_rounded(t, back);
        EXPECT_EQ(back.values, decode_exr(encode_exr(back).data(), encode_exr(back).size(), "new.exr").values);
    }
    // Version-1 messages name the table channel only, as before.
    Bytes b = read_all(dir + "make_table_2d_f16.exr");
    b[chlist_type_offset(b, "ln_G") - 2] = 'X';
    expect_exr_error(b, "missing channel 'ln_G' (expected HALF pixels for storage f16)");
    b = read_all(dir + "make_table_2d_f16.exr");
    put_u32(&b[chlist_type_offset(b, "F")], 2);
    expect_exr_error(b, "channel 'F' has pixel type FLOAT, expected HALF (storage f16)");
    // An unknown scatterlut.* attribute in a 1.1 file is still corruption (1.1 is the
    // newest version-1 mapping), as in NewerMinorWithUnknownAttributesIsRead.
    const size_t at = find_bytes(b, std::string("screenWindowWidth\0float\0", 24));
    b = read_all(dir + "make_table_2d_f16.exr");
    std::memcpy(&b[at], "scatterlut.zz_new", 17);
    refresh_exr_header_checksum(b);
    expect_exr_error(b, "unknown attribute 'scatterlut.zz_new' (format version 1.1 defines no such attribute)");
}

// Attribute sizes that disagree with the value's own structure. OpenEXR reads a value by
// its type (an int is 4 bytes, a chlist runs to its empty name) and never compares with
// the declared size, so such a file would put it out of step with the pre-scan; each is
// refused before OpenEXR reads the header (docs/FORMAT.md §4.2, docs/FUZZING.md).
TEST(ExrHostile, SizeDisagreeingWithTheValueIsRefused) {
    const Bytes good = encode_exr(make_table(2, Storage::F16));
    Bytes b = good;
    const std::string axes_attr("scatterlut.axes\0int\0", 20);
    put_u32(&b[find_bytes(b, axes_attr) + axes_attr.size()], 5);
    expect_exr_error(b, "attribute 'scatterlut.axes' of type int declares 5 bytes, but a value of type int is 4 bytes");
    b = good;
    const size_t chlist_size_at = find_bytes(b, std::string("channels\0chlist\0", 16)) + 16;
    put_u32(&b[chlist_size_at], get_u32(&b[chlist_size_at]) + 40);
    expect_exr_error(b, "attribute 'channels' of type chlist declares");
    expect_exr_error(b, "but its channel list ends after");
    b = good;
    const std::string extra_attr("scatterlut.extra\0stringvector\0", 30);
    const size_t extra_at = find_bytes(b, extra_attr) + extra_attr.size();
    put_u32(&b[extra_at + 4], 0x7fffffff); // the first string's length
    expect_exr_error(b, "attribute 'scatterlut.extra' of type stringvector declares");
    expect_exr_error(b, "a string at value byte 0 claims 2147483647 bytes");
}

// The fuzzer's finding tests/fuzz/known/exr-oom-1 (3041 bytes): its chlist claims 2327
// bytes and holds 23; OpenEXR 3.1 read on into the declared value and met a "string"
// whose size field was four bytes of text, 2.0 GB, and allocated it before failing.
// Decoded here in a child process whose address space is capped at its current size
// + 256 MiB: such an allocation fails there (std::bad_alloc, a different outcome), so
// this test fails if any allocation sized by an unchecked field comes back.
TEST(ExrHostile, FuzzFindingExrOomRefusedWithBoundedMemory) {
    const Bytes file = read_all(std::string(SLUT_SOURCE_DIR) + "/tests/fuzz/known/exr-oom-1");
    ASSERT_EQ(file.size(), 3041u);
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::close(fds[0]);
        auto report = [&](int code, const std::string &what) {
            if (::write(fds[1], what.data(), what.size()) < 0) code = 9;
            ::_exit(code);
        };
        std::ifstream status("/proc/self/status");
        std::string line;
        unsigned long long vm_kib = 0;
        while (std::getline(status, line))
            if (line.rfind("VmSize:", 0) == 0) vm_kib = std::strtoull(line.c_str() + 7, nullptr, 10);
        if (vm_kib == 0) report(5, "no VmSize in /proc/self/status");
        struct rlimit cap;
        cap.rlim_cur = cap.rlim_max = (vm_kib << 10) + (256ull << 20);
        if (::setrlimit(RLIMIT_AS, &cap) != 0) report(6, "setrlimit failed");
        try {
            decode_exr(file.data(), file.size(), "exr-oom-1");
            report(2, "decoded without error");
        } catch (const LoadError &e) {
            report(0, e.what());
        } catch (const std::bad_alloc &) {
            report(3, "std::bad_alloc: an allocation beyond the 256 MiB cap");
        } catch (const std::exception &e) {
            report(4, std::string("not a LoadError: ") + e.what());
        }
    }
    ::close(fds[1]);
    std::string message;
    char buf[512];
    ssize_t n;
    while ((n = ::read(fds[0], buf, sizeof buf)) > 0) message.append(buf, static_cast<size_t>(n));
    ::close(fds[0]);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "child died: signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 0) << message;
    EXPECT_NE(message.find("exr-oom-1: EXR header: attribute 'channels' of type chlist declares 2327 bytes, but its "
                           "channel list ends after 23"),
              std::string::npos)
        << message;
}

#else

TEST(Exr, BuiltWithoutOpenExr) {
    EXPECT_FALSE(have_openexr());
    const Bytes b = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
    expect_load_error([&] { decode_exr(b.data(), b.size(), "x.exr"); }, "built without OpenEXR");
    EXPECT_THROW(encode_exr(make_table(1, Storage::F32)), std::runtime_error);
}

#endif

// ====================================================================================
// The command line on hostile files: `validate` and `inspect` exit 2 with the reason
// ====================================================================================

namespace {

struct Corruption {
    const char *name; // file name in the temp dir; the extension picks the format
    Bytes bytes;
    std::string message; // what the reason must say (after the file name)
    int exit_code = 2;   // 1 for a checksum failure: the file was read, and is corrupt
};

std::vector<Corruption> corruptions() {
    std::vector<Corruption> out;
    const Bytes good = encode_binary(make_table(2, Storage::F32));
    out.push_back({"truncated.slut", Bytes(good.begin(), good.begin() + static_cast<long>(good.size() / 2)),
                   "truncated"});
    Bytes b = good;
    b[3] = 'X';
    out.push_back({"magic.slut", b, "not a scatterlut binary table: expected magic 53 4c 55 54 54 42 4c 00"});
    b = good;
    b[b.size() - 5] ^= 0x10;
    out.push_back({"flipped.slut", b, "payload checksum mismatch", 1});
    File f = parse(good);
    set_nested(f, kAxisTag, 0, 7, le_u32(1000000));
    set_nested(f, kAxisTag, 1, 7, le_u32(1000000));
    out.push_back({"huge.slut", build(f), "header claims 1000000000000 nodes, more than the limit of 2^31"});
    f = parse(good);
    set_nested(f, kAxisTag, 1, 7, le_u32(static_cast<uint32_t>(-5)));
    out.push_back({"negative.slut", build(f), "axis 1 ('w'): count -5 is invalid"});
    f = parse(good);
    put_u32(&f.payload[4 * 13], 0x7fc00000u); // NaN, checksum consistent
    out.push_back({"nan.slut", build(f), "payload value at node (6, 0), channel 'ln_G' is not finite (nan)"});
    f = parse(good);
    put_u32(&f.payload[0], 0xff800000u); // −inf
    out.push_back({"inf.slut", build(f), "payload value at node (0, 0), channel 'F' is not finite (-inf)"});
    b = good;
    put_u32(&b[8], 2);
    out.push_back({"major.slut", b,
                   "format version 2." + std::to_string(kFormatMinor) + " is newer than this reader (1.x); upgrade scatterlut"});
#ifdef SCATTERLUT_HAS_OPENEXR
    const Bytes exr = encode_exr(make_table(2, Storage::F16));
    b = exr;
    b[chlist_type_offset(b, "G") - 2] = 'X';
    out.push_back({"nochannel.exr", b, "missing channel 'ln_G' (expected HALF pixels for storage f16) in EXR channel 'G'"});
    b = exr;
    put_u32(&b[chlist_type_offset(b, "R")], 2);
    out.push_back({"type.exr", b, "channel 'F' has pixel type FLOAT, expected HALF (storage f16) in EXR channel 'R'"});
    out.push_back({"exr-oom-1.exr", read_all(std::string(SLUT_SOURCE_DIR) + "/tests/fuzz/known/exr-oom-1"),
                   "EXR header: attribute 'channels' of type chlist declares 2327 bytes"});
#endif
    return out;
}

} // namespace

// Each corruption of docs/FORMAT.md §2.6/§4.2 through the executable: exit 2 from
// `validate` (text and --json) and `inspect` (exit 1 and FAIL for a checksum mismatch: a
// file read but corrupt), the reason on stderr as "scatterlut: FILE:
// reason", and validate's report naming the file UNREADABLE.
TEST(CliHostile, ValidateAndInspectExit2WithTheReason) {
    TempDir dir;
    for (const Corruption &c : corruptions()) {
        SCOPED_TRACE(c.name);
        const std::string path = dir.path + "/" + c.name;
        write_all(path, c.bytes);
        const std::string reason = path + ": " + c.message;
        const char *status = c.exit_code == 1 ? "FAIL" : "UNREADABLE";
        const auto v = slut_test::run_scatterlut("validate " + path);
        EXPECT_EQ(v.exit_code, c.exit_code) << v.out << v.err;
        EXPECT_NE(v.err.find(reason), std::string::npos) << v.err;
        EXPECT_NE(v.out.find(path + ": " + status), std::string::npos) << v.out;
        const auto j = slut_test::run_scatterlut("validate --json " + path);
        EXPECT_EQ(j.exit_code, c.exit_code);
        const nlohmann::json doc = nlohmann::json::parse(j.out);
        EXPECT_EQ(doc.at("status"), status);
        EXPECT_NE(doc.at("message").get<std::string>().find(reason), std::string::npos) << j.out;
        const auto i = slut_test::run_scatterlut("inspect " + path);
        EXPECT_EQ(i.exit_code, c.exit_code) << i.out;
        EXPECT_NE(i.err.find("scatterlut: " + reason), std::string::npos) << i.err;
        EXPECT_TRUE(i.out.empty()) << i.out;
    }
}
