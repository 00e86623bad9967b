// scatterlut runtime — what the engine-facing containers (EXR 2.x, KTX2) share.
//
// Real numbers in file metadata are text: the shortest decimal that reads back as the
// same double, so that loaders which skip binary double attributes (three.js's
// EXRLoader) still see every number, and the text reads back exactly.
// std::to_chars / std::from_chars: no locale.
#include "scatterlut/io.hpp"

#include <charconv>
#include <cmath>

namespace scatterlut {

std::string exr_channel_name(size_t count, size_t index, const std::string &table_channel_name) {
    static const char *const kRgba[4] = {"R", "G", "B", "A"};
    if (count == 1) return "Y";
    if (count <= 4 && index < 4) return kRgba[index];
    return table_channel_name;
}

namespace detail {

std::string decimal_text(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buf[64];
    const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, x); // shortest round trip
    return std::string(buf, r.ptr);
}

bool parse_decimal_text(const std::string &s, double *out) {
    if (s.empty()) return false;
    const char *begin = s.data(), *end = s.data() + s.size();
    const std::from_chars_result r = std::from_chars(begin, end, *out);
    return r.ec == std::errc() && r.ptr == end;
}

} // namespace detail
} // namespace scatterlut
