// KTX 2.0 output (docs/FORMAT.md §6): every field of the file read back by a reader
// written here from the KTX 2.0 specification, independent of the writer; the texel data
// equal to the binary payload (packed for 4-D tables); the metadata exact. The
// engine-side check (three.js's KTX2Loader on the default tables) is tests/js.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include <unistd.h>

#include "scatterlut/io.hpp"
#include "scatterlut/table.hpp"

namespace {

using namespace scatterlut;
using Bytes = std::vector<uint8_t>;

uint32_t u32(const Bytes &b, size_t at) {
    return uint32_t{b.at(at)} | uint32_t{b.at(at + 1)} << 8 | uint32_t{b.at(at + 2)} << 16 | uint32_t{b.at(at + 3)} << 24;
}
uint64_t u64(const Bytes &b, size_t at) { return uint64_t{u32(b, at)} | uint64_t{u32(b, at + 4)} << 32; }

// A table with `dims` axes of counts 5, 4, 3, 6 and `channels` channels (distinct values).
Table make_table(size_t dims, size_t channels, Storage storage) {
    Table t;
    t.kind = kKindNearLightE4;
    t.quantity_version = 7;
    t.storage = storage;
    const int counts[5] = {5, 4, 3, 6, 2};
    for (size_t a = 0; a < dims; ++a) {
        Axis ax;
        ax.name = "a" + std::to_string(a);
        ax.meaning = "axis " + std::to_string(a) + " \xce\xbc"; // UTF-8
        ax.map = slut_axis{0.1 * static_cast<double>(a + 1), 1.0 / 3.0 + static_cast<double>(a), 0.1, SLUT_WARP_LINEAR,
                           counts[a]};
        t.axes.push_back(ax);
    }
    for (size_t c = 0; c < channels; ++c)
        t.channels.push_back(Channel{"ch" + std::to_string(c), "channel " + std::to_string(c),
                                     c % 2 ? Encoding::Log : Encoding::Linear});
    for (size_t i = 0; i < t.node_count() * channels; ++i) t.values.push_back(std::sin(0.37 * static_cast<double>(i)) * 3.0);
    t.accuracy.sampling_max_rel = 2.5e-4;
    t.accuracy.sampling_points = 123456789012345ull;
    t.provenance.generator_version = "scatterlut 0.1.0 (test)";
    t.provenance.scene = "[medium]\nsigma_t_per_m = 0.1\n";
    t.extra["plan.target_rel"] = "0.01";
    return t;
}

// The file as the KTX 2.0 specification lays it out, with every structural rule checked.
struct Ktx2 {
    uint32_t vk_format, type_size, width, height, depth, layers, faces, levels, supercompression;
    Bytes dfd;                                // dfdTotalSize and the blocks
    std::vector<std::pair<std::string, Bytes>> kv; // in file order, value bytes as stored
    Bytes level;                              // level 0 data
};

Ktx2 read_ktx2(const Bytes &b, size_t texel_bytes) {
    Ktx2 k{};
    static const uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    EXPECT_EQ(std::memcmp(b.data(), id, 12), 0);
    k.vk_format = u32(b, 12);
    k.type_size = u32(b, 16);
    k.width = u32(b, 20);
    k.height = u32(b, 24);
    k.depth = u32(b, 28);
    k.layers = u32(b, 32);
    k.faces = u32(b, 36);
    k.levels = u32(b, 40);
    k.supercompression = u32(b, 44);
    const uint32_t dfd_at = u32(b, 48), dfd_len = u32(b, 52), kvd_at = u32(b, 56), kvd_len = u32(b, 60);
    EXPECT_EQ(u64(b, 64), 0u); // sgdByteOffset: 0 when there is no global data
    EXPECT_EQ(u64(b, 72), 0u);
    const size_t n_levels = std::max<uint32_t>(1, k.levels);
    EXPECT_EQ(dfd_at, 80 + 24 * n_levels); // the DFD follows the level index
    EXPECT_EQ(u32(b, dfd_at), dfd_len);     // dfdTotalSize
    k.dfd.assign(b.begin() + dfd_at, b.begin() + dfd_at + dfd_len);
    EXPECT_EQ(kvd_at, dfd_at + dfd_len); // key/value data directly after the DFD
    EXPECT_EQ(kvd_at % 4, 0u);
    size_t p = kvd_at;
    while (p < kvd_at + kvd_len) {
        const uint32_t len = u32(b, p);
        EXPECT_GE(len, 2u);
        const std::string key(reinterpret_cast<const char *>(&b[p + 4]));
        EXPECT_LT(key.size(), len);
        k.kv.emplace_back(key, Bytes(b.begin() + static_cast<long>(p + 4 + key.size() + 1),
                                     b.begin() + static_cast<long>(p + 4 + len)));
        p += 4 + len;
        while (p % 4) EXPECT_EQ(b.at(p++), 0) << "valuePadding is zeros";
    }
    EXPECT_EQ(p, kvd_at + kvd_len);
    const uint64_t level_at = u64(b, 80), level_len = u64(b, 88), level_raw = u64(b, 96);
    const size_t align = std::lcm<size_t>(texel_bytes, 4);
    EXPECT_EQ(level_at % align, 0u) << "mipPadding: lcm(texel block size, 4)";
    EXPECT_LT(level_at - p, align);
    for (size_t q = p; q < level_at; ++q) EXPECT_EQ(b[q], 0);
    EXPECT_EQ(level_raw, level_len); // no supercompression
    EXPECT_EQ(level_at + level_len, b.size()); // one level, nothing after it
    k.level.assign(b.begin() + static_cast<long>(level_at), b.end());
    return k;
}

std::string text(const Bytes &v) {
    EXPECT_FALSE(v.empty());
    EXPECT_EQ(v.back(), 0) << "values are NUL-terminated UTF-8";
    return std::string(v.begin(), v.end() - 1);
}

TEST(Ktx2, EveryDimensionAndChannelCount) {
    for (size_t dims = 1; dims <= 4; ++dims)
        for (size_t nc : {1, 2, 3, 4})
            for (Storage s : {Storage::F16, Storage::F32}) {
                SCOPED_TRACE(std::to_string(dims) + "-D, " + std::to_string(nc) + " channels, " + to_string(s));
                const Table t = make_table(dims, nc, s);
                const Bytes b = encode_ktx2(t);
                EXPECT_EQ(encode_ktx2(t), b); // deterministic
                const size_t elem = storage_bytes(s), texel = elem * nc;
                const Ktx2 k = read_ktx2(b, texel);
                const uint32_t want_format[2][4] = {{76, 83, 90, 97}, {100, 103, 106, 109}}; // VkFormat *_SFLOAT
                EXPECT_EQ(k.vk_format, want_format[s == Storage::F32][nc - 1]);
                EXPECT_EQ(k.type_size, elem);
                const uint32_t c[4] = {5, 4, 3, 6};
                EXPECT_EQ(k.width, c[0]);
                EXPECT_EQ(k.height, dims == 1 ? 0u : dims == 4 ? c[1] * c[3] : c[1]);
                EXPECT_EQ(k.depth, dims >= 3 ? c[2] : 0u);
                EXPECT_EQ(k.layers, 0u);
                EXPECT_EQ(k.faces, 1u);
                EXPECT_EQ(k.levels, 1u);
                EXPECT_EQ(k.supercompression, 0u);

                // DFD: one basic block (Khronos Data Format 1.3), RGBSDA, linear, one
                // signed-float sample per channel with bounds −1.0f / 1.0f.
                ASSERT_EQ(k.dfd.size(), 4 + 24 + 16 * nc);
                EXPECT_EQ(u32(k.dfd, 4), 0u);                               // vendor Khronos, type basic
                EXPECT_EQ(u32(k.dfd, 8), 2u | (24u + 16u * nc) << 16);      // version 2, block size
                EXPECT_EQ(u32(k.dfd, 12), 1u | 0u << 8 | 1u << 16 | 0u << 24); // RGBSDA, unspecified, linear, straight
                EXPECT_EQ(u32(k.dfd, 16), 0u);                              // 1×1×1×1 texel blocks
                EXPECT_EQ(u32(k.dfd, 20), texel);                           // bytesPlane0
                EXPECT_EQ(u32(k.dfd, 24), 0u);
                const uint32_t ids[4] = {0, 1, 2, 15};
                for (size_t j = 0; j < nc; ++j) {
                    const size_t at = 28 + 16 * j;
                    EXPECT_EQ(u32(k.dfd, at), (8 * elem * j) | (8 * elem - 1) << 16 | (ids[j] | 0xC0u) << 24);
                    EXPECT_EQ(u32(k.dfd, at + 4), 0u);
                    EXPECT_EQ(u32(k.dfd, at + 8), 0xBF800000u);
                    EXPECT_EQ(u32(k.dfd, at + 12), 0x3F800000u);
                }

                // Texel data: the binary payload, axis 3 stacked along y for a 4-D table.
                const Bytes payload = detail::encode_payload(t);
                ASSERT_EQ(k.level.size(), payload.size());
                if (dims < 4) {
                    EXPECT_EQ(k.level, payload);
                } else {
                    size_t mismatches = 0;
                    for (size_t i3 = 0; i3 < c[3]; ++i3)
                        for (size_t i2 = 0; i2 < c[2]; ++i2)
                            for (size_t i1 = 0; i1 < c[1]; ++i1)
                                for (size_t i0 = 0; i0 < c[0]; ++i0) {
                                    const size_t node = ((i3 * c[2] + i2) * c[1] + i1) * c[0] + i0;
                                    const size_t x = i0, y = i1 + c[1] * i3, z = i2;
                                    const size_t texel_index = (z * (c[1] * c[3]) + y) * c[0] + x;
                                    mismatches += std::memcmp(&k.level[texel_index * texel], &payload[node * texel], texel) != 0;
                                }
                    EXPECT_EQ(mismatches, 0u);
                }

                // Key/value data: sorted, unique, KTXwriter first, every scatterlut.* value text.
                std::map<std::string, std::string> kv;
                for (size_t i = 0; i < k.kv.size(); ++i) {
                    if (i) {
                        EXPECT_LT(k.kv[i - 1].first, k.kv[i].first) << "sorted by code point, unique";
                    }
                    kv[k.kv[i].first] = text(k.kv[i].second);
                }
                EXPECT_EQ(kv.at("KTXwriter"), "scatterlut 0.1.0 (test)");
                EXPECT_EQ(kv.at("scatterlut.kind"), t.kind);
                EXPECT_EQ(kv.at("scatterlut.storage"), to_string(s));
                EXPECT_EQ(kv.at("scatterlut.layout"), dims == 4 ? "packed_4d" : "texture");
                EXPECT_EQ(kv.at("scatterlut.axes"), std::to_string(dims));
                for (size_t a = 0; a < dims; ++a) {
                    const std::string p = "scatterlut.axis." + std::to_string(a) + ".";
                    EXPECT_EQ(kv.at(p + "name"), t.axes[a].name);
                    EXPECT_EQ(kv.at(p + "meaning"), t.axes[a].meaning);
                    double v = 0;
                    ASSERT_TRUE(detail::parse_decimal_text(kv.at(p + "max"), &v));
                    EXPECT_EQ(v, t.axes[a].map.max); // exact: 1/3 + a needs all 17 digits
                    ASSERT_TRUE(detail::parse_decimal_text(kv.at(p + "scale"), &v));
                    EXPECT_EQ(v, t.axes[a].map.scale);
                    EXPECT_EQ(kv.at(p + "warp_name"), "linear");
                    EXPECT_EQ(kv.at(p + "count"), std::to_string(t.axes[a].map.count));
                }
                EXPECT_EQ(kv.at("scatterlut.channels"), std::to_string(nc));
                for (size_t j = 0; j < nc; ++j) {
                    const std::string p = "scatterlut.channel." + std::to_string(j) + ".";
                    EXPECT_EQ(kv.at(p + "name"), t.channels[j].name);
                    EXPECT_EQ(kv.at(p + "encoding"), to_string(t.channels[j].encoding));
                }
                EXPECT_EQ(kv.count("scatterlut.channel." + std::to_string(nc) + ".name"), 0u);
                EXPECT_EQ(kv.at("scatterlut.accuracy.sampling_points"), "123456789012345");
                EXPECT_EQ(kv.at("scatterlut.provenance.scene"), t.provenance.scene);
                EXPECT_EQ(kv.at("scatterlut.extra.plan.target_rel"), "0.01");
                char sum[19];
                std::snprintf(sum, sizeof sum, "0x%016llx",
                              static_cast<unsigned long long>(fnv1a64(payload.data(), payload.size())));
                EXPECT_EQ(kv.at("scatterlut.checksum.payload"), sum);
            }
}

TEST(Ktx2, RefusesWhatItCannotHold) {
    auto refused = [](const Table &t, const std::string &needle) {
        try {
            encode_ktx2(t);
            ADD_FAILURE() << "no exception; expected '" << needle << "'";
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    refused(make_table(2, 1, Storage::F64), "use the binary format for f64 tables");
    refused(make_table(5, 1, Storage::F32), "this table has 5 axes: use the binary format");
    Table wide = make_table(1, 4, Storage::F32);
    wide.channels.push_back(Channel{"ch4", "", Encoding::Linear});
    wide.values.clear();
    for (size_t i = 0; i < wide.node_count() * 5; ++i) wide.values.push_back(1.0);
    refused(wide, "this table has 5: use the binary format");
    Table big = make_table(1, 1, Storage::F16);
    big.values[2] = 70000.0; // beyond binary16
    EXPECT_THROW(encode_ktx2(big), std::invalid_argument);
}

TEST(Ktx2, SaveIsAtomicAndReplaces) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("slut_ktx2_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "t.ktx2").string();
    save_ktx2(make_table(2, 1, Storage::F32), path);
    const Table t = make_table(3, 1, Storage::F16);
    save_ktx2(t, path);
    std::ifstream in(path, std::ios::binary);
    const Bytes got((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(got, encode_ktx2(t));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
    // A table it cannot hold leaves the previous file as it was.
    EXPECT_THROW(save_ktx2(make_table(2, 1, Storage::F64), path), std::invalid_argument);
    std::ifstream again(path, std::ios::binary);
    EXPECT_EQ(Bytes((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>()), got);
    std::filesystem::remove_all(dir);
}

} // namespace
