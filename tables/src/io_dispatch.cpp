// scatterlut runtime — load_table: a table file of either readable format, told by its magic
// number (an OpenEXR file starts with 76 2f 31 01; anything else goes to the binary decoder,
// which names what it found).
#include "scatterlut/io.hpp"

#include <cstring>

#include "io_binary_format.hpp"

namespace scatterlut {

Table load_table(const std::string &path) {
    const std::vector<uint8_t> bytes = detail::read_file(path);
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), binary_format::kExrMagic, 4) == 0)
        return decode_exr(bytes.data(), bytes.size(), path);
    return decode_binary(bytes.data(), bytes.size(), path);
}

} // namespace scatterlut
