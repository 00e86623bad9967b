// scatterlut runtime, internal — numbers as text for the table codecs (binary, EXR, KTX2):
// checksums as their metadata stores them, and values in messages. Not installed.
#pragma once

#include <cstdint>
#include <cstdio>
#include <sstream>
#include <string>

namespace scatterlut::detail {

// "0x" and 16 lower-case hex digits: a 64-bit checksum as the EXR and KTX2 metadata store it
// (a change here changes the files) and as the loaders' messages show it.
inline std::string hex64(uint64_t v) {
    char buf[19];
    std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// x with 17 significant digits (it reads back as x), for messages.
inline std::string digits17(double x) {
    std::ostringstream s;
    s.precision(17);
    s << x;
    return s.str();
}

} // namespace scatterlut::detail
