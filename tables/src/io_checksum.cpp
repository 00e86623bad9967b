// scatterlut runtime — the checksum of the table files: 64-bit FNV-1a (docs/FORMAT.md §2.5).
#include "scatterlut/io.hpp"

namespace scatterlut {

uint64_t fnv1a64(const void *data, size_t size, uint64_t state) {
    const auto *p = static_cast<const uint8_t *>(data);
    for (size_t i = 0; i < size; ++i) {
        state ^= p[i];
        state *= 0x100000001b3ull;
    }
    return state;
}

} // namespace scatterlut
