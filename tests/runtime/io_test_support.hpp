// The table-file tests' shared fixtures (tests/runtime/test_io*.cpp): tables with every metadata
// field set, the checks of a load's error, the byte layout of docs/FORMAT.md re-implemented
// from the document (record walker and FNV-1a-64: a file built or patched by a test is judged
// by the document, not by the library's own encoder), temporary directories and whole-file
// reads and writes, and the EXR header's byte helpers.
#pragma once

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

} // namespace
#endif
