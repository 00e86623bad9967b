// The layout checks both airlight runtimes make of a table in their constructors
// (AirlightTable: airlight_F, AirlightHgTable: airlight_Fg; internal, not installed). `what`
// names the table in the messages ("airlight table", "anisotropic airlight table").
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "require.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut::detail {

// Its kind (`not_one`: the message's "not an …" text), quantity version, axes (u, w), channel
// 0 (`channel`, log encoded) and Table::check_consistent.
inline void check_airlight_layout(const Table &t, const char *kind, uint32_t quantity_version, const char *channel,
                                  const std::string &what, const std::string &not_one) {
    require(t.kind == kind, "not " + not_one + " (kind '" + t.kind + "')");
    require(t.quantity_version == quantity_version,
            what + " quantity version " + std::to_string(t.quantity_version) +
                " is not the one this library knows (" + std::to_string(quantity_version) + ")");
    require(t.axes.size() == 2 && t.axes[0].name == "u" && t.axes[1].name == "w", what + " must have axes (u, w)");
    require(!t.channels.empty() && t.channels[0].name == channel && t.channels[0].encoding == Encoding::Log,
            what + " channel 0 must be " + channel + " (log encoded)");
    t.check_consistent();
}

// Its domain: u from 0, w up to π/2 (the viewer's end of every ray).
inline void check_airlight_domain(const Table &t, const std::string &what) {
    require(t.axes[0].map.min == 0.0, what + " u axis must start at 0");
    require(std::fabs(t.axes[1].map.max - 1.5707963267948966) < 1e-12, what + " w axis must end at pi/2");
}

} // namespace scatterlut::detail
