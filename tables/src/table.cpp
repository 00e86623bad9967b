// scatterlut runtime — names of the enumerations and the consistency check of a Table.
#include "scatterlut/table.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace scatterlut {

const char *to_string(Storage s) {
    switch (s) {
    case Storage::F16: return "f16";
    case Storage::F32: return "f32";
    case Storage::F64: return "f64";
    }
    return "unknown";
}

bool storage_from_string(const std::string &name, Storage *out) {
    for (Storage s : {Storage::F16, Storage::F32, Storage::F64}) {
        if (name == to_string(s)) {
            if (out) *out = s;
            return true;
        }
    }
    return false;
}

size_t storage_bytes(Storage s) {
    switch (s) {
    case Storage::F16: return 2;
    case Storage::F32: return 4;
    case Storage::F64: return 8;
    }
    return 0; // not a Storage: callers check_consistent() first
}

const char *to_string(Encoding e) {
    switch (e) {
    case Encoding::Linear: return "linear";
    case Encoding::Log: return "log";
    }
    return "unknown";
}

bool encoding_from_string(const std::string &name, Encoding *out) {
    for (Encoding e : {Encoding::Linear, Encoding::Log}) {
        if (name == to_string(e)) {
            if (out) *out = e;
            return true;
        }
    }
    return false;
}

const char *warp_name(int warp) {
    switch (warp) {
    case SLUT_WARP_LINEAR: return "linear";
    case SLUT_WARP_LOG: return "log";
    case SLUT_WARP_LOG1P: return "log1p";
    case SLUT_WARP_ASINH_COT: return "asinh_cot";
    case SLUT_WARP_SQRT1P: return "sqrt1p";
    case SLUT_WARP_LOGLIN: return "loglin";
    case SLUT_WARP_NL_QODDS: return "nl_qodds";
    case SLUT_WARP_ASINH_COT_PEAK: return "asinh_cot_peak";
    default: return "unknown";
    }
}

bool warp_from_name(const std::string &name, int *out) {
    for (int w = 0; w < SLUT_WARP_COUNT; ++w) {
        if (name == warp_name(w)) {
            if (out) *out = w;
            return true;
        }
    }
    return false;
}

size_t Table::node_count() const {
    size_t n = 1;
    for (const Axis &a : axes) {
        if (a.map.count <= 0) return 0;
        n *= static_cast<size_t>(a.map.count);
    }
    return n;
}

size_t Table::index(const size_t *node) const {
    size_t flat = 0;
    for (size_t a = axes.size(); a-- > 0;)
        flat = flat * static_cast<size_t>(axes[a].map.count) + node[a];
    return flat * channels.size();
}

namespace {

std::string axis_label(size_t i, const Axis &a) {
    std::ostringstream s;
    s << "axis " << i << " ('" << a.name << "')";
    return s.str();
}

[[noreturn]] void fail(const std::string &what) { throw std::invalid_argument(what); }

std::string num(double x) {
    std::ostringstream s;
    s.precision(17);
    s << x;
    return s.str();
}

} // namespace

void Table::check_consistent() const {
    if (axes.empty()) fail("table has no axes (need 1 to " + std::to_string(kMaxAxes) + ")");
    if (axes.size() > kMaxAxes)
        fail("table has " + std::to_string(axes.size()) + " axes; at most " + std::to_string(kMaxAxes) +
             " are supported");
    for (size_t i = 0; i < axes.size(); ++i) {
        const Axis &ax = axes[i];
        const slut_axis &m = ax.map;
        const std::string label = axis_label(i, ax);
        if (m.count < 2)
            fail(label + ": count " + std::to_string(m.count) + " is invalid (need at least 2 nodes)");
        if (!std::isfinite(m.min) || !std::isfinite(m.max))
            fail(label + ": range [" + num(m.min) + ", " + num(m.max) + "] is not finite");
        if (!(m.min < m.max)) fail(label + ": min " + num(m.min) + " must be less than max " + num(m.max));
        if (!std::isfinite(m.scale)) fail(label + ": scale " + num(m.scale) + " is not finite");
        if (m.warp < 0 || m.warp >= SLUT_WARP_COUNT) fail(label + ": unknown warp id " + std::to_string(m.warp));
        // The warp's own domain, with the message a user can act on.
        switch (m.warp) {
        case SLUT_WARP_LOG:
            if (!(m.min > 0)) fail(label + ": warp 'log' needs min > 0 (min = " + num(m.min) + ")");
            break;
        case SLUT_WARP_LOG1P:
            if (!(m.scale > 0)) fail(label + ": warp 'log1p' needs scale > 0 (scale = " + num(m.scale) + ")");
            break;
        case SLUT_WARP_ASINH_COT:
            if (!(m.min > 0)) fail(label + ": warp 'asinh_cot' needs min > 0 (min = " + num(m.min) + ")");
            break;
        case SLUT_WARP_SQRT1P:
            if (!(m.min >= -1)) fail(label + ": warp 'sqrt1p' needs min >= -1 (min = " + num(m.min) + ")");
            break;
        case SLUT_WARP_LOGLIN:
            if (!(m.min > 0) || !(m.scale > 0))
                fail(label + ": warp 'loglin' needs min > 0 and scale > 0 (min = " + num(m.min) + ", scale = " +
                     num(m.scale) + ")");
            break;
        case SLUT_WARP_NL_QODDS:
            if (!(m.min > 0)) fail(label + ": warp 'nl_qodds' needs min > 0 (min = " + num(m.min) + ")");
            break;
        case SLUT_WARP_ASINH_COT_PEAK:
            if (!(m.min > 0) || !(m.max <= SLUT_PIO2_HI) || !(m.scale > 0))
                fail(label + ": warp 'asinh_cot_peak' needs 0 < min, max <= pi/2 and scale > 0 (min = " + num(m.min) +
                     ", max = " + num(m.max) + ", scale = " + num(m.scale) + ")");
            break;
        default: break;
        }
        // Whatever the warp: g(min) < g(max), both finite, or the unit coordinate is meaningless.
        const double g0 = slut_warp_forward(m.warp, m.min, m.min, m.scale);
        const double g1 = slut_warp_forward(m.warp, m.max, m.min, m.scale);
        if (!std::isfinite(g0) || !std::isfinite(g1) || !(g0 < g1))
            fail(label + ": warp '" + warp_name(m.warp) + "' maps [" + num(m.min) + ", " + num(m.max) + "] to [" +
                 num(g0) + ", " + num(g1) + "], not an increasing finite interval");
    }

    if (channels.empty()) fail("table has no channels");
    std::set<std::string> names;
    for (size_t c = 0; c < channels.size(); ++c) {
        const Channel &ch = channels[c];
        if (ch.name.empty()) fail("channel " + std::to_string(c) + " has an empty name");
        if (!names.insert(ch.name).second) fail("channel name '" + ch.name + "' appears twice");
        if (ch.encoding != Encoding::Linear && ch.encoding != Encoding::Log)
            fail("channel '" + ch.name + "': unknown encoding id " +
                 std::to_string(static_cast<uint32_t>(ch.encoding)));
    }
    if (storage_bytes(storage) == 0)
        fail("unknown storage id " + std::to_string(static_cast<uint32_t>(storage)));

    size_t nodes = 1;
    for (const Axis &ax : axes) {
        const size_t c = static_cast<size_t>(ax.map.count);
        if (nodes > std::numeric_limits<size_t>::max() / c) fail("node count overflows size_t");
        nodes *= c;
    }
    if (nodes > std::numeric_limits<size_t>::max() / channels.size()) fail("value count overflows size_t");
    const size_t expected = nodes * channels.size();
    if (values.size() != expected)
        fail("values holds " + std::to_string(values.size()) + " numbers, expected " + std::to_string(expected) +
             " (" + std::to_string(nodes) + " nodes x " + std::to_string(channels.size()) + " channels)");
    for (size_t i = 0; i < values.size(); ++i) {
        if (std::isfinite(values[i])) continue;
        std::ostringstream s;
        size_t rest = i / channels.size();
        s << "value " << i << " (node (";
        for (size_t a = 0; a < axes.size(); ++a) {
            const size_t c = static_cast<size_t>(axes[a].map.count);
            s << (a ? ", " : "") << rest % c;
            rest /= c;
        }
        s << "), channel '" << channels[i % channels.size()].name << "') is not finite: " << values[i];
        fail(s.str());
    }
}

} // namespace scatterlut
