#include "preview.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <stdexcept>

#include "scatterlut/sampler.hpp"

extern "C" {
#include "slut_axes.h"
}

namespace scatterlut {
namespace {

// Viridis sampled at entries 0, 16, …, 240 and 255 of matplotlib's 256-entry table
// (_viridis_data, CC0); linear interpolation between samples stays within ~0.005 of the
// full table, below one 8-bit level for most entries.
constexpr std::array<std::array<double, 3>, 17> kViridis = {{
    {0.267004, 0.004874, 0.329415}, {0.282327, 0.094955, 0.417331}, {0.278826, 0.175490, 0.483397},
    {0.258965, 0.251537, 0.524736}, {0.229739, 0.322361, 0.545706}, {0.199430, 0.387607, 0.554642},
    {0.172719, 0.448791, 0.557885}, {0.149039, 0.508051, 0.557250}, {0.127568, 0.566949, 0.550556},
    {0.120638, 0.625828, 0.533488}, {0.157851, 0.683765, 0.501686}, {0.246070, 0.738910, 0.452024},
    {0.369214, 0.788888, 0.382914}, {0.515992, 0.831158, 0.294279}, {0.678489, 0.863742, 0.189503},
    {0.845561, 0.887322, 0.099702}, {0.993248, 0.906157, 0.143936},
}};

// --- layout (image pixels) -------------------------------------------------------------
constexpr int kScale = 2;                            // font pixels → image pixels
constexpr int kCharH = kGlyphHeight * kScale;        // 14
constexpr int kLineH = kLineAdvance * kScale;        // 20
constexpr int kMargin = 16;
constexpr int kPlotW = 512, kPlotH = 384, kStripH = 48; // 2-D plot; 1-D strip
constexpr int kTickLen = 6, kNodeMarkLen = 5, kLabelGap = 6;
constexpr int kBarGap = 28, kBarW = 22;
constexpr int kMaxNodeMarks = 256; // more nodes than this are not marked one by one
const Rgb kInk{25, 25, 25}, kFrame{80, 80, 80}, kMark{150, 150, 150}, kPaper{255, 255, 255};

// --- numbers ---------------------------------------------------------------------------

// %g with `digits` significant digits and a short exponent ("2.5e-7", "1e5").
std::string format_number(double v, int digits) {
    if (v == 0) return "0";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    std::string s = buf;
    const size_t e = s.find('e');
    if (e == std::string::npos) return s;
    std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
    const bool negative = !exponent.empty() && exponent[0] == '-';
    if (!exponent.empty() && (exponent[0] == '-' || exponent[0] == '+')) exponent.erase(0, 1);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    return mantissa + "e" + (negative ? "-" : "") + exponent;
}

// 1, 2 or 5 × 10^k closest above x/… : the step of about `x` that reads well.
double nice_step(double x) {
    const double p = std::pow(10.0, std::floor(std::log10(x)));
    const double f = x / p;
    return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * p;
}

// --- ticks -----------------------------------------------------------------------------
// Where labels go along an axis whose position is a non-linear function of the value (an
// axis warp, or the log of a log-encoded channel): candidates in order of preference (the
// two ends; then for a strongly warped axis 1·10^k; round linear steps; then 5·10^k and
// 2·10^k), each kept if its label does not crowd one already kept. The warp decides
// which round values get room, so a log1p axis is labelled by decades and a linear one by
// even steps, without a case per warp.

using Tick = PreviewTick;

std::vector<Tick> place_ticks(double lo, double hi, const std::function<double(double)> &pos_of,
                              double length_px, const std::function<double(const std::string &)> &extent_px) {
    struct Candidate {
        double value;
        int digits;
    };
    std::vector<Candidate> cand = {{lo, 4}, {hi, 4}};
    const bool warped = std::fabs(pos_of(0.5 * (lo + hi)) - 0.5) > 0.25;
    auto add_powers = [&](double m) {
        for (int k = -30; k <= 30; ++k)
            for (double sign : {1.0, -1.0}) {
                const double v = sign * m * std::pow(10.0, k);
                if (v > lo && v < hi) cand.push_back({v, 3});
            }
    };
    if (lo < 0 && hi > 0) cand.push_back({0.0, 3});
    if (warped) add_powers(1);
    const double step = nice_step((hi - lo) / 5);
    for (double v = std::ceil(lo / step) * step; v < hi; v += step)
        if (v > lo) cand.push_back({std::fabs(v) < step * 1e-9 ? 0.0 : v, 3});
    if (warped) add_powers(5), add_powers(2);

    std::vector<Tick> kept;
    std::vector<double> kept_px, kept_extent;
    for (const Candidate &c : cand) {
        const double pos = pos_of(c.value);
        if (!(pos >= 0 && pos <= 1)) continue;
        const std::string label = format_number(c.value, c.digits);
        const double px = pos * length_px, ext = extent_px(label);
        bool crowded = false;
        for (size_t k = 0; k < kept.size() && !crowded; ++k)
            crowded = std::fabs(px - kept_px[k]) < 0.5 * (ext + kept_extent[k]) + 2 * kLabelGap;
        if (crowded) continue;
        kept.push_back({pos, label});
        kept_px.push_back(px);
        kept_extent.push_back(ext);
    }
    return kept;
}

double text_w(const std::string &s) { return text_width(s, kScale); }
double text_h(const std::string &) { return kCharH; }

std::string axis_title(const Axis &a) {
    std::string s = a.name + "  (" + warp_name(a.map.warp) + " axis";
    if (a.map.warp == SLUT_WARP_LOG1P) s += ", scale " + format_number(a.map.scale, 3);
    return s + ", " + std::to_string(a.map.count) + " nodes)";
}

size_t find_axis(const Table &t, const std::string &name, const char *option) {
    for (size_t i = 0; i < t.axes.size(); ++i)
        if (t.axes[i].name == name) return i;
    std::string names;
    for (const Axis &a : t.axes) names += (names.empty() ? "" : ", ") + a.name;
    throw std::invalid_argument(std::string(option) + ": the table has no axis '" + name + "' (its axes: " + names +
                                ")");
}

std::string trim(const std::string &s) {
    const size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// "NAME=VALUE,NAME=#NODE,…" → (axis, parameter, node or -1).
std::vector<SliceAxis> parse_slice(const Table &t, const std::string &spec) {
    std::vector<SliceAxis> out;
    if (trim(spec).empty()) return out;
    for (size_t start = 0;;) {
        const size_t comma = std::min(spec.find(',', start), spec.size());
        const std::string item = trim(spec.substr(start, comma - start));
        start = comma + 1;
        const size_t eq = item.find('=');
        if (eq == std::string::npos)
            throw std::invalid_argument("--slice '" + item + "': expected NAME=VALUE or NAME=#NODE");
        const size_t axis = find_axis(t, trim(item.substr(0, eq)), "--slice");
        const slut_axis &m = t.axes[axis].map;
        const std::string value = trim(item.substr(eq + 1));
        for (const SliceAxis &s : out)
            if (s.axis == axis) throw std::invalid_argument("--slice: axis '" + t.axes[axis].name + "' given twice");
        SliceAxis s{axis, 0.0, -1};
        char *end = nullptr;
        errno = 0;
        if (!value.empty() && value[0] == '#') {
            const long node = std::strtol(value.c_str() + 1, &end, 10);
            if (value.size() < 2 || *end != '\0' || errno == ERANGE || node < 0 || node >= m.count)
                throw std::invalid_argument("--slice " + item + ": node index must be #0 to #" +
                                            std::to_string(m.count - 1));
            s.node = static_cast<int>(node);
            s.param = slut_axis_node(&m, s.node);
        } else {
            s.param = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0')
                throw std::invalid_argument("--slice " + item + ": '" + value +
                                            "' is not a number (or #NODE for a node index)");
            if (!(s.param >= m.min && s.param <= m.max))
                throw std::invalid_argument("--slice " + item + ": outside the axis range [" +
                                            format_number(m.min, 6) + ", " + format_number(m.max, 6) + "]");
            const double at = slut_unit_from_param(&m, s.param) * (m.count - 1);
            if (std::fabs(at - std::round(at)) < 1e-9) s.node = static_cast<int>(std::lround(at));
        }
        out.push_back(s);
        if (comma == spec.size()) break;
    }
    return out;
}

std::string describe_slice(const Table &t, const std::vector<SliceAxis> &slice) {
    if (slice.empty()) return "slice: none, every node of the table is shown";
    std::string s = "slice: ";
    for (size_t k = 0; k < slice.size(); ++k) {
        const Axis &a = t.axes[slice[k].axis];
        s += (k ? ", " : "") + a.name + " = " + format_number(slice[k].param, 4);
        if (slice[k].node >= 0) {
            s += " (node " + std::to_string(slice[k].node) + " of 0-" + std::to_string(a.map.count - 1) + ")";
        } else {
            int i0;
            double f;
            slut_cell_from_unit(slut_unit_from_param(&a.map, slice[k].param), a.map.count, &i0, &f);
            s += " (between nodes " + std::to_string(i0) + " and " + std::to_string(i0 + 1) + ")";
        }
    }
    return s;
}

} // namespace

Rgb viridis(double t) {
    const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 255.0;
    // Sample k sits at table entry 16k (k < 16) and the last at entry 255.
    size_t k = std::min<size_t>(static_cast<size_t>(x / 16.0), 15);
    const double e0 = 16.0 * static_cast<double>(k), e1 = k == 15 ? 255.0 : e0 + 16.0;
    const double f = (x - e0) / (e1 - e0);
    auto channel = [&](int c) {
        const double v = kViridis[k][c] + f * (kViridis[k + 1][c] - kViridis[k][c]);
        return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
    };
    return {channel(0), channel(1), channel(2)};
}

Preview render_preview(const Table &t, const PreviewRequest &req) {
    Preview p;
    const size_t n_axes = t.axes.size();

    // Channel and axes.
    p.channel = 0;
    if (!req.channel.empty()) {
        p.channel = t.channels.size();
        std::string names;
        for (size_t c = 0; c < t.channels.size(); ++c) {
            if (t.channels[c].name == req.channel) p.channel = c;
            names += (c ? ", " : "") + t.channels[c].name;
        }
        if (p.channel == t.channels.size())
            throw std::invalid_argument("--channel: the table has no channel '" + req.channel + "' (its channels: " +
                                        names + ")");
    }
    if (req.plot_axes.size() > 2) throw std::invalid_argument("--axes: at most two axes (x, y)");
    if (req.plot_axes.empty()) {
        p.x_axis = 0;
        p.y_axis = n_axes >= 2 ? 1 : -1;
    } else {
        p.x_axis = find_axis(t, req.plot_axes[0], "--axes");
        if (req.plot_axes.size() == 2) {
            p.y_axis = static_cast<int>(find_axis(t, req.plot_axes[1], "--axes"));
            if (static_cast<size_t>(p.y_axis) == p.x_axis)
                throw std::invalid_argument("--axes: x and y are both '" + req.plot_axes[0] + "'");
        }
    }
    auto plotted = [&](size_t a) { return a == p.x_axis || (p.y_axis >= 0 && a == static_cast<size_t>(p.y_axis)); };

    // Slice: named axes as asked, the others at their middle node.
    const std::vector<SliceAxis> asked = parse_slice(t, req.slice);
    for (size_t a = 0; a < n_axes; ++a) {
        if (plotted(a)) {
            for (const SliceAxis &s : asked)
                if (s.axis == a)
                    throw std::invalid_argument("--slice: axis '" + t.axes[a].name +
                                                "' is plotted; slice only the other axes");
            continue;
        }
        const int middle = (t.axes[a].map.count - 1) / 2;
        SliceAxis s{a, slut_axis_node(&t.axes[a].map, middle), middle};
        for (const SliceAxis &given : asked)
            if (given.axis == a) s = given;
        p.slice.push_back(s);
    }
    p.slice_text = describe_slice(t, p.slice);

    // Values on the plot grid, through the sampler (stored encoding, multilinear).
    p.plot_w = kPlotW;
    p.plot_h = p.y_axis >= 0 ? kPlotH : kStripH;
    std::vector<double> params(n_axes);
    for (const SliceAxis &s : p.slice) params[s.axis] = s.param;
    const slut_axis &xm = t.axes[p.x_axis].map;
    std::vector<double> grid(static_cast<size_t>(p.plot_w) * static_cast<size_t>(p.plot_h));
    double lo = INFINITY, hi = -INFINITY;
    for (int j = 0; j < p.plot_h; ++j) {
        if (p.y_axis >= 0)
            params[static_cast<size_t>(p.y_axis)] =
                slut_param_from_unit(&t.axes[static_cast<size_t>(p.y_axis)].map, 1.0 - (j + 0.5) / p.plot_h);
        for (int i = 0; i < p.plot_w; ++i) {
            params[p.x_axis] = slut_param_from_unit(&xm, (i + 0.5) / p.plot_w);
            const double v = sample_encoded(t, params.data(), p.channel);
            grid[static_cast<size_t>(j) * static_cast<size_t>(p.plot_w) + static_cast<size_t>(i)] = v;
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    if (!(hi > lo)) { // a constant slice: centre it on the colour bar
        const double d = std::max(std::fabs(lo) * 1e-6, 1e-12);
        lo -= d, hi += d;
    }
    p.value_lo = lo, p.value_hi = hi;

    // Labels first: they decide the margins.
    const Channel &ch = t.channels[p.channel];
    const bool log_channel = ch.encoding == Encoding::Log;
    std::vector<Tick> &x_ticks = p.x_ticks, &y_ticks = p.y_ticks, &bar_ticks = p.bar_ticks;
    x_ticks = place_ticks(
        xm.min, xm.max, [&](double v) { return slut_unit_from_param(&xm, v); }, p.plot_w, text_w);
    if (p.y_axis >= 0) {
        const slut_axis &ym = t.axes[static_cast<size_t>(p.y_axis)].map;
        y_ticks = place_ticks(
            ym.min, ym.max, [&](double v) { return slut_unit_from_param(&ym, v); }, p.plot_h, text_h);
    }
    // The colour bar is linear in the stored value; a log channel is labelled with the
    // quantity exp(stored), so its ticks fall on round quantities.
    bar_ticks =
        log_channel ? place_ticks(
                          std::exp(lo), std::exp(hi), [&](double q) { return (std::log(q) - lo) / (hi - lo); },
                          p.plot_h, text_h)
                    : place_ticks(
                          lo, hi, [&](double v) { return (v - lo) / (hi - lo); }, p.plot_h, text_h);

    const std::string line1 = req.title + "  -  " + t.kind + ", " + to_string(t.storage) + " storage";
    const std::string line2 = "colour: channel " + ch.name +
                              (log_channel ? " (log encoding: colour by " + ch.name + ", bar labelled exp(" +
                                                 ch.name + "))"
                                           : " (linear encoding)");
    const std::string x_title = axis_title(t.axes[p.x_axis]);
    const std::string y_title = p.y_axis >= 0 ? "^ " + axis_title(t.axes[static_cast<size_t>(p.y_axis)]) : "";
    const std::string caption = "grey marks on the top and right edges: table nodes";
    const std::string bar_title = log_channel ? "exp(" + ch.name + ")" : ch.name;

    double y_label_w = 0, bar_label_w = 0;
    for (const Tick &k : y_ticks) y_label_w = std::max(y_label_w, text_w(k.label));
    for (const Tick &k : bar_ticks) bar_label_w = std::max(bar_label_w, text_w(k.label));
    p.plot_x = kMargin + static_cast<int>(y_label_w) + kTickLen + kLabelGap;
    p.plot_y = kMargin + 3 * kLineH + (p.y_axis >= 0 ? kLineH : 0) + kNodeMarkLen;
    const int bar_x = p.plot_x + p.plot_w + kBarGap;
    const int bar_label_x = bar_x + kBarW + kTickLen + kLabelGap;
    int width = std::max(bar_label_x + static_cast<int>(bar_label_w), bar_x + static_cast<int>(text_w(bar_title)));
    for (const std::string &s : {line1, line2, p.slice_text, caption, y_title})
        width = std::max(width, kMargin + static_cast<int>(text_w(s)));
    width += kMargin;
    const int x_labels_y = p.plot_y + p.plot_h + kTickLen + kLabelGap;
    const int x_title_y = x_labels_y + kLineH;
    const int height = x_title_y + 2 * kLineH + kMargin;

    Raster &img = p.image = Raster(width, height, kPaper);
    img.text(kMargin, kMargin, line1, kInk, kScale);
    img.text(kMargin, kMargin + kLineH, line2, kInk, kScale);
    img.text(kMargin, kMargin + 2 * kLineH, p.slice_text, kInk, kScale);
    if (p.y_axis >= 0) img.text(kMargin, kMargin + 3 * kLineH, y_title, kInk, kScale);

    // Plot and frame.
    for (int j = 0; j < p.plot_h; ++j)
        for (int i = 0; i < p.plot_w; ++i) {
            const double v = grid[static_cast<size_t>(j) * static_cast<size_t>(p.plot_w) + static_cast<size_t>(i)];
            img.set(p.plot_x + i, p.plot_y + j, viridis((v - lo) / (hi - lo)));
        }
    auto frame = [&](int x, int y, int w, int h) {
        img.fill(x - 1, y - 1, w + 2, 1, kFrame);
        img.fill(x - 1, y + h, w + 2, 1, kFrame);
        img.fill(x - 1, y - 1, 1, h + 2, kFrame);
        img.fill(x + w, y - 1, 1, h + 2, kFrame);
    };
    frame(p.plot_x, p.plot_y, p.plot_w, p.plot_h);

    // Nodes along the top (x) and right (y) edges.
    auto node_px = [](int count, int i, int length) {
        return static_cast<int>(std::lround(static_cast<double>(i) / (count - 1) * (length - 1)));
    };
    if (xm.count <= kMaxNodeMarks)
        for (int i = 0; i < xm.count; ++i)
            img.fill(p.plot_x + node_px(xm.count, i, p.plot_w), p.plot_y - 1 - kNodeMarkLen, 1, kNodeMarkLen, kMark);
    if (p.y_axis >= 0) {
        const int yc = t.axes[static_cast<size_t>(p.y_axis)].map.count;
        if (yc <= kMaxNodeMarks)
            for (int i = 0; i < yc; ++i)
                img.fill(p.plot_x + p.plot_w + 1, p.plot_y + p.plot_h - 1 - node_px(yc, i, p.plot_h), kNodeMarkLen, 1,
                         kMark);
    }

    // x ticks and labels (centred, kept inside the image), then the x title.
    for (const Tick &k : x_ticks) {
        const int px = p.plot_x + static_cast<int>(std::lround(k.pos * (p.plot_w - 1)));
        img.fill(px, p.plot_y + p.plot_h + 1, 1, kTickLen, kInk);
        const int w = static_cast<int>(text_w(k.label));
        img.text(std::clamp(px - w / 2, 0, width - w), x_labels_y, k.label, kInk, kScale);
    }
    img.text(p.plot_x + (p.plot_w - static_cast<int>(text_w(x_title))) / 2, x_title_y, x_title, kInk, kScale);
    img.text(kMargin, x_title_y + kLineH, caption, kMark, kScale);

    // y ticks and labels (right-aligned).
    for (const Tick &k : y_ticks) {
        const int py = p.plot_y + p.plot_h - 1 - static_cast<int>(std::lround(k.pos * (p.plot_h - 1)));
        img.fill(p.plot_x - 1 - kTickLen, py, kTickLen, 1, kInk);
        img.text(p.plot_x - 1 - kTickLen - kLabelGap - static_cast<int>(text_w(k.label)), py - kCharH / 2, k.label,
                 kInk, kScale);
    }

    // Colour bar: bottom = value_lo, top = value_hi.
    for (int j = 0; j < p.plot_h; ++j)
        img.fill(bar_x, p.plot_y + j, kBarW, 1, viridis(1.0 - (j + 0.5) / p.plot_h));
    frame(bar_x, p.plot_y, kBarW, p.plot_h);
    img.text(bar_x, p.plot_y - kNodeMarkLen - kLineH, bar_title, kInk, kScale);
    for (const Tick &k : bar_ticks) {
        const int py = p.plot_y + p.plot_h - 1 - static_cast<int>(std::lround(k.pos * (p.plot_h - 1)));
        img.fill(bar_x + kBarW + 1, py, kTickLen, 1, kInk);
        img.text(bar_label_x, py - kCharH / 2, k.label, kInk, kScale);
    }
    return p;
}

} // namespace scatterlut
