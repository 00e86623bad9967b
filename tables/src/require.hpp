// The runtime library's argument check (internal; not installed): throws
// std::invalid_argument(message) unless `ok`. Two overloads so that the hot paths (radiance
// checks every query) pass literal messages without building a std::string.
#pragma once

#include <stdexcept>
#include <string>

namespace scatterlut::detail {

inline void require(bool ok, const char *message) {
    if (!ok) throw std::invalid_argument(message);
}

inline void require(bool ok, const std::string &message) {
    if (!ok) throw std::invalid_argument(message);
}

} // namespace scatterlut::detail
