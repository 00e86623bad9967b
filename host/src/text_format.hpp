// scatterlut generator — small text helpers: one number formatted with printf's `format`
// into a string (the text of plans, reports, plots and verdicts), a 64-bit value as 16
// lower-case hex digits (checksums, cache keys).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace scatterlut {

inline std::string fmt(const char *format, double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, x);
    return buf;
}

inline std::string hex64(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

} // namespace scatterlut
