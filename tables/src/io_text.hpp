// scatterlut runtime, internal — numbers as text for the table codecs (binary, EXR, KTX2):
// checksums as their metadata stores them, and values in messages. Not installed.
#pragma once

#include <cmath>
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

// What is wrong with an axis's node count, range and warp scale as a file states them, in
// the words of the loaders' messages (after "axis K ('name'): "); "" where nothing is. The
// binary and the EXR decoders check every axis they read with it.
inline std::string axis_extent_problem(int32_t count, double min, double max, double scale) {
    if (count < 2) return "count " + std::to_string(count) + " is invalid (need 2 <= count <= 2^31-1)";
    if (!std::isfinite(min) || !std::isfinite(max) || !std::isfinite(scale))
        return "range [" + digits17(min) + ", " + digits17(max) + "] / scale " + digits17(scale) + " is not finite";
    if (!(min < max)) return "min " + digits17(min) + " must be less than max " + digits17(max);
    return "";
}

} // namespace scatterlut::detail
