// scatterlut generator — one number formatted with printf's `format` into a string (the
// text of plans, reports, plots and verdicts).
#pragma once

#include <cstdio>
#include <string>

namespace scatterlut {

inline std::string fmt(const char *format, double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, x);
    return buf;
}

} // namespace scatterlut
