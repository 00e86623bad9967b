// scatterlut runtime, internal — the constants of the binary table format (docs/FORMAT.md §2)
// that its encoder and decoder share, and the magic numbers load_table tells the formats by.
// Not installed.
#pragma once

#include <cstddef>
#include <cstdint>

namespace scatterlut::binary_format {

inline constexpr uint8_t kMagic[8] = {'S', 'L', 'U', 'T', 'T', 'B', 'L', 0};
inline constexpr uint8_t kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01}; // the first 4 bytes of every OpenEXR file
inline constexpr size_t kPreambleBytes = 48;
inline constexpr size_t kPayloadAlign = 64; // the payload's offset in the file is a multiple of this

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

} // namespace scatterlut::binary_format
