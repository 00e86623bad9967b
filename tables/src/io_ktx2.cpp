// scatterlut runtime — tables as KTX 2.0 textures (docs/FORMAT.md §6), for engines that
// load GPU texture containers (three.js KTX2Loader, Godot, Bevy, Vulkan tools).
//
// Written against the KTX 2.0 specification (Khronos): an uncompressed texture, one mip
// level, no supercompression, little-endian throughout:
//
//   offset  0  identifier «KTX 20»\r\n\x1A\n (12 bytes)
//          12  vkFormat, typeSize, pixelWidth, pixelHeight, pixelDepth, layerCount,
//              faceCount, levelCount, supercompressionScheme (u32 each)
//          48  dfdByteOffset, dfdByteLength, kvdByteOffset, kvdByteLength (u32 each),
//              sgdByteOffset, sgdByteLength (u64 each)
//          80  level index: byteOffset, byteLength, uncompressedByteLength (u64 each)
//         104  data format descriptor (basic block, one sample per channel)
//              key/value data (sorted by key, each entry padded to 4 bytes)
//              level 0 data (4-byte aligned: lcm(texel block size, 4) for 2 and 4 bytes)
//
// Texel order is x fastest, then y, then z. A 1-D table is a 1-D texture (height 0), 2-D
// a 2-D texture, 3-D a 3-D texture (x = axis 0, y = axis 1, z = axis 2); a 4-D table is a
// 3-D texture with the slices of axis 3 stacked along y: x = i0, y = i1 + c1·i3, z = i2,
// so hardware trilinear filtering covers axes 0–2 inside a slice of axis 3 and the shader
// interpolates axis 3 by hand (two fetches). Depth stays c2 (85 for the default E4 table)
// where stacking along z would exceed common 3-D texture limits (2048).
#include "scatterlut/io.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <numeric>
#include <stdexcept>

#include "io_text.hpp"

namespace scatterlut {

using detail::hex64;

namespace {

// Vulkan format numbers (vulkan_core.h, VkFormat), by channel count − 1.
constexpr uint32_t kVkR16Sfloat[4] = {76, 83, 90, 97};   // R16, R16G16, R16G16B16, R16G16B16A16 _SFLOAT
constexpr uint32_t kVkR32Sfloat[4] = {100, 103, 106, 109}; // R32, …, R32G32B32A32 _SFLOAT

// Khronos Data Format Specification, basic descriptor block.
constexpr uint32_t kDfModelRgbsda = 1;
constexpr uint32_t kDfPrimariesUnspecified = 0; // data, not colour: loaders give it no colour space
constexpr uint32_t kDfTransferLinear = 1;
constexpr uint32_t kDfVersion13 = 2;          // versionNumber of Data Format 1.3
constexpr uint8_t kDfSampleFloat = 0x80;      // KHR_DF_SAMPLE_DATATYPE_FLOAT
constexpr uint8_t kDfSampleSigned = 0x40;     // KHR_DF_SAMPLE_DATATYPE_SIGNED
constexpr uint8_t kDfChannelIds[4] = {0, 1, 2, 15}; // R, G, B, A (RGBSDA)
constexpr uint32_t kFloatMinusOne = 0xBF800000u, kFloatOne = 0x3F800000u; // sampleLower/Upper of SFLOAT

const std::string kPrefix = "scatterlut.";

struct Out {
    std::vector<uint8_t> b;
    void u8(uint8_t v) { b.push_back(v); }
    void u16(uint16_t v) { for (int k = 0; k < 2; ++k) b.push_back(static_cast<uint8_t>(v >> (8 * k))); }
    void u32(uint32_t v) { for (int k = 0; k < 4; ++k) b.push_back(static_cast<uint8_t>(v >> (8 * k))); }
    void u64(uint64_t v) { for (int k = 0; k < 8; ++k) b.push_back(static_cast<uint8_t>(v >> (8 * k))); }
    void put_u32(size_t at, uint32_t v) { for (int k = 0; k < 4; ++k) b[at + k] = static_cast<uint8_t>(v >> (8 * k)); }
    void put_u64(size_t at, uint64_t v) { for (int k = 0; k < 8; ++k) b[at + k] = static_cast<uint8_t>(v >> (8 * k)); }
    void pad_to(size_t align) { while (b.size() % align) b.push_back(0); }
};

} // namespace

Ktx2Shape ktx2_shape(const Table &t) {
    const size_t n = t.axes.size();
    if (n < 1 || n > 4)
        throw std::invalid_argument("KTX2 holds 1-D to 3-D textures (a 4-D table packed into 3-D); this table has " +
                                    std::to_string(n) + " axes: use the binary format");
    auto c = [&](size_t i) { return static_cast<uint64_t>(t.axes[i].map.count); };
    Ktx2Shape s;
    s.width = c(0);
    s.height = n >= 2 ? c(1) * (n == 4 ? c(3) : 1) : 0;
    s.depth = n >= 3 ? c(2) : 0;
    if (s.height > UINT32_MAX) throw std::invalid_argument("KTX2: texture height exceeds 2^32 - 1");
    return s;
}

std::vector<uint8_t> encode_ktx2(const Table &t) {
    if (t.storage == Storage::F64)
        throw std::invalid_argument("KTX2 output holds f16 and f32 (R16_SFLOAT, R32_SFLOAT): use the binary format for "
                                    "f64 tables, or storage f32/f16");
    detail::check_limits(t);
    const size_t nc = t.channels.size();
    if (nc > 4)
        throw std::invalid_argument("KTX2 output holds 1 to 4 channels (R to RGBA); this table has " +
                                    std::to_string(nc) + ": use the binary format");
    const Ktx2Shape shape = ktx2_shape(t);
    const std::vector<uint8_t> payload = detail::encode_payload(t); // rounds, refuses overflow
    const uint32_t elem = static_cast<uint32_t>(storage_bytes(t.storage));
    const uint32_t texel = elem * static_cast<uint32_t>(nc);

    // Level data: the payload in texel order. Up to 3 axes it is the payload itself; a 4-D
    // table moves each (i1, i3) row of axis 0 to y = i1 + c1·i3, z = i2.
    std::vector<uint8_t> level;
    if (t.axes.size() == 4) {
        const size_t c0 = static_cast<size_t>(t.axes[0].map.count), c1 = static_cast<size_t>(t.axes[1].map.count);
        const size_t c2 = static_cast<size_t>(t.axes[2].map.count), c3 = static_cast<size_t>(t.axes[3].map.count);
        const size_t row = c0 * texel;
        level.resize(payload.size());
        for (size_t i3 = 0; i3 < c3; ++i3)
            for (size_t i2 = 0; i2 < c2; ++i2)
                for (size_t i1 = 0; i1 < c1; ++i1) {
                    const size_t from = ((i3 * c2 + i2) * c1 + i1) * row;
                    const size_t to = (i2 * (c1 * c3) + (i1 + c1 * i3)) * row;
                    std::memcpy(&level[to], &payload[from], row);
                }
    } else {
        level = payload;
    }

    // Key/value data: the table's metadata as NUL-terminated UTF-8 text, numbers as
    // decimal text, under the names of the EXR attributes (docs/FORMAT.md §4.1, §6).
    std::map<std::string, std::string> kv; // std::map: sorted by key bytes, as KTX2 requires
    const std::string gen = t.provenance.generator_version.empty() ? "scatterlut" : t.provenance.generator_version;
    kv["KTXwriter"] = gen;
    auto put = [&](const std::string &key, const std::string &value) { kv[kPrefix + key] = value; };
    put("format_major", std::to_string(kKtx2FormatMajor));
    put("format_minor", std::to_string(kKtx2FormatMinor));
    put("kind", t.kind);
    put("quantity_version", std::to_string(t.quantity_version));
    put("storage", to_string(t.storage));
    put("layout", t.axes.size() == 4 ? "packed_4d" : "texture");
    put("axes", std::to_string(t.axes.size()));
    for (size_t i = 0; i < t.axes.size(); ++i) {
        const Axis &a = t.axes[i];
        const std::string k = "axis." + std::to_string(i) + ".";
        put(k + "name", a.name);
        put(k + "meaning", a.meaning);
        put(k + "min", detail::decimal_text(a.map.min));
        put(k + "max", detail::decimal_text(a.map.max));
        put(k + "scale", detail::decimal_text(a.map.scale));
        put(k + "warp", std::to_string(a.map.warp));
        put(k + "warp_name", warp_name(a.map.warp));
        put(k + "count", std::to_string(a.map.count));
    }
    put("channels", std::to_string(nc));
    for (size_t j = 0; j < nc; ++j) {
        const std::string k = "channel." + std::to_string(j) + ".";
        put(k + "name", t.channels[j].name);
        put(k + "meaning", t.channels[j].meaning);
        put(k + "encoding", to_string(t.channels[j].encoding));
    }
    const Accuracy &ac = t.accuracy;
    put("accuracy.integration_max_rel", detail::decimal_text(ac.integration_max_rel));
    put("accuracy.sampling_max_rel", detail::decimal_text(ac.sampling_max_rel));
    put("accuracy.sampling_p99_rel", detail::decimal_text(ac.sampling_p99_rel));
    put("accuracy.sampling_median_rel", detail::decimal_text(ac.sampling_median_rel));
    put("accuracy.storage_max_rel", detail::decimal_text(ac.storage_max_rel));
    put("accuracy.sampling_points", std::to_string(ac.sampling_points));
    put("accuracy.sampling_domain", ac.sampling_domain);
    const Provenance &pv = t.provenance;
    put("provenance.generator_version", pv.generator_version);
    put("provenance.command_line", pv.command_line);
    put("provenance.scene", pv.scene);
    put("provenance.device", pv.device);
    put("provenance.created_by", pv.created_by);
    for (const auto &e : t.extra) put("extra." + e.first, e.second);
    put("checksum.payload", hex64(fnv1a64(payload.data(), payload.size())));

    Out o;
    static const uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
    o.b.assign(kIdentifier, kIdentifier + 12);
    o.u32((t.storage == Storage::F16 ? kVkR16Sfloat : kVkR32Sfloat)[nc - 1]); // vkFormat
    o.u32(elem);                                   // typeSize: bytes of the data type
    o.u32(static_cast<uint32_t>(shape.width));     // pixelWidth
    o.u32(static_cast<uint32_t>(shape.height));    // pixelHeight (0: 1-D)
    o.u32(static_cast<uint32_t>(shape.depth));     // pixelDepth (0: not 3-D)
    o.u32(0);                                      // layerCount: not an array
    o.u32(1);                                      // faceCount
    o.u32(1);                                      // levelCount: the base level only
    o.u32(0);                                      // supercompressionScheme: none
    const size_t index_at = o.b.size();            // 48
    for (int k = 0; k < 4; ++k) o.u32(0);          // dfd/kvd offsets and lengths, below
    o.u64(0);                                      // sgdByteOffset: no supercompression global data
    o.u64(0);                                      // sgdByteLength
    const size_t level_index_at = o.b.size();      // 80
    for (int k = 0; k < 3; ++k) o.u64(0);

    // Data format descriptor: total size, then one basic descriptor block.
    const size_t dfd_at = o.b.size();
    const uint32_t block_bytes = 24 + 16 * static_cast<uint32_t>(nc);
    o.u32(4 + block_bytes);                        // dfdTotalSize
    o.u32(0);                                      // vendorId 0 (Khronos) | descriptorType 0 (basic) << 17
    o.u16(static_cast<uint16_t>(kDfVersion13));    // versionNumber
    o.u16(static_cast<uint16_t>(block_bytes));     // descriptorBlockSize
    o.u8(kDfModelRgbsda);                          // colorModel
    o.u8(kDfPrimariesUnspecified);                 // colorPrimaries
    o.u8(kDfTransferLinear);                       // transferFunction
    o.u8(0);                                       // flags: alpha straight
    o.u32(0);                                      // texelBlockDimension0..3 = 0: 1×1×1×1
    o.u8(static_cast<uint8_t>(texel));             // bytesPlane0
    for (int k = 0; k < 7; ++k) o.u8(0);           // bytesPlane1..7
    for (size_t j = 0; j < nc; ++j) {
        o.u16(static_cast<uint16_t>(8 * elem * j)); // bitOffset
        o.u8(static_cast<uint8_t>(8 * elem - 1));   // bitLength − 1
        o.u8(static_cast<uint8_t>(kDfChannelIds[j] | kDfSampleFloat | kDfSampleSigned)); // channelType
        o.u32(0);                                   // samplePosition0..3
        o.u32(kFloatMinusOne);                      // sampleLower: −1.0 (SFLOAT)
        o.u32(kFloatOne);                           // sampleUpper: 1.0
    }
    const size_t dfd_bytes = o.b.size() - dfd_at;

    const size_t kvd_at = o.b.size();
    for (const auto &e : kv) {
        const uint32_t len = static_cast<uint32_t>(e.first.size() + 1 + e.second.size() + 1);
        o.u32(len);                                 // keyAndValueByteLength
        o.b.insert(o.b.end(), e.first.begin(), e.first.end());
        o.u8(0);
        o.b.insert(o.b.end(), e.second.begin(), e.second.end());
        o.u8(0);
        o.pad_to(4);                                // valuePadding
    }
    const size_t kvd_bytes = o.b.size() - kvd_at;
    if (kvd_at + kvd_bytes > UINT32_MAX) throw std::invalid_argument("KTX2: metadata exceed the 32-bit offsets");

    o.pad_to(std::lcm<size_t>(texel, 4)); // mip level padding: lcm(texel block size, 4)
    const size_t level_at = o.b.size();
    o.b.insert(o.b.end(), level.begin(), level.end());

    o.put_u32(index_at + 0, static_cast<uint32_t>(dfd_at));
    o.put_u32(index_at + 4, static_cast<uint32_t>(dfd_bytes));
    o.put_u32(index_at + 8, kvd_bytes ? static_cast<uint32_t>(kvd_at) : 0);
    o.put_u32(index_at + 12, static_cast<uint32_t>(kvd_bytes));
    o.put_u64(level_index_at + 0, level_at);
    o.put_u64(level_index_at + 8, level.size());
    o.put_u64(level_index_at + 16, level.size()); // uncompressedByteLength = byteLength
    return std::move(o.b);
}

void save_ktx2(const Table &table, const std::string &path) { write_file_atomic(path, encode_ktx2(table)); }

} // namespace scatterlut
