#include "svg_plot.hpp"
#include "svg_labels.hpp"

#include "text_format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace scatterlut {
namespace {

// Okabe–Ito: distinguishable with the common colour-vision deficiencies.
constexpr const char *kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                    "#E69F00", "#56B4E9", "#000000", "#F0E442"};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

std::string escape_xml(const std::string &s) {
    std::string out;
    for (char c : s) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

// Pixel coordinate with one decimal: enough for a chart, and stable text.
std::string px(double v) { return fmt("%.1f", v); }

// One axis: the data range mapped to a pixel range, on a linear or log10 scale.
struct Scale {
    bool log = false;
    double lo = 0, hi = 1;     // in data units (log: positive)
    double p0 = 0, p1 = 1;     // pixels of lo and hi

    double t(double v) const { return log ? std::log10(v) : v; }
    double to_px(double v) const {
        const double a = t(lo), b = t(hi);
        return p0 + (p1 - p0) * (t(v) - a) / (b - a);
    }
    bool shows(double v) const { return std::isfinite(v) && (!log || v > 0); }
};

// Expands [lo, hi] to whole decades (log) or to "nice" steps (linear), and returns ticks.
std::vector<double> fit_and_tick(Scale *s) {
    std::vector<double> ticks;
    if (s->log) {
        double a = std::floor(std::log10(s->lo)), b = std::ceil(std::log10(s->hi));
        if (b <= a) b = a + 1;
        s->lo = std::pow(10.0, a);
        s->hi = std::pow(10.0, b);
        const int decades = static_cast<int>(b - a);
        const int step = std::max(1, (decades + 7) / 8); // at most ~8 labelled decades
        for (int k = 0; k <= decades; k += step) ticks.push_back(std::pow(10.0, a + k));
        return ticks;
    }
    if (s->hi <= s->lo) {
        const double pad = s->lo == 0 ? 1.0 : std::fabs(s->lo) * 0.1;
        s->lo -= pad;
        s->hi += pad;
    }
    const double raw = (s->hi - s->lo) / 6.0;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * mag >= raw) {
            step = m * mag;
            break;
        }
    s->lo = std::floor(s->lo / step) * step;
    s->hi = std::ceil(s->hi / step) * step;
    for (double v = s->lo; v <= s->hi + 0.5 * step; v += step) ticks.push_back(std::fabs(v) < 1e-12 * step ? 0.0 : v);
    return ticks;
}

std::string tick_label(const Scale &s, double v) {
    if (s.log) {
        const int e = static_cast<int>(std::lround(std::log10(v)));
        if (e >= 0 && e <= 3) return fmt("%.0f", v);
        return "1e" + std::to_string(e);
    }
    return fmt("%g", v);
}

} // namespace

double text_width_px(const std::string &text, double font_size_px, bool bold) {
    double em = 0;
    for (unsigned char c : text) {
        if ((c & 0xC0) == 0x80) continue; // a UTF-8 continuation byte: the same character
        const bool wide = c == 'm' || c == 'w' || c == 'M' || c == 'W' || c == '%' || c == '@';
        em += wide ? kTextWideAdvanceEm : kTextAdvanceEm;
    }
    return em * font_size_px * (bold ? kTextBoldFactor : 1.0);
}

TextBox text_box(const std::string &text, double x, double y, double font_size_px, TextAnchor anchor, bool bold,
                 bool rotated) {
    const double w = text_width_px(text, font_size_px, bold);
    // Along the text (u, from the anchor point) and across it (v, down from the baseline).
    const double u0 = anchor == TextAnchor::Start ? 0 : anchor == TextAnchor::Middle ? -w / 2 : -w;
    const double v0 = -kTextAscentEm * font_size_px, v1 = kTextDescentEm * font_size_px;
    if (!rotated) return {x + u0, y + v0, x + u0 + w, y + v1};
    // rotate(-90): the text's u axis points up the page, its v axis to the right.
    return {x + v0, y - (u0 + w), x + v1, y - u0};
}

bool boxes_overlap(const TextBox &a, const TextBox &b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

namespace {

using namespace svg_labels;

// A series' point, or a marker's, in pixels; `clipped_x`/`clipped_y` (−1 or +1): the value
// lies beyond that end of the axis (≤ 0 or −∞ on a log axis, ±∞), drawn at the plot's edge.
struct Spot {
    bool drawn = false; // false: NaN, nothing to draw
    double x = 0, y = 0;
    int clipped_x = 0, clipped_y = 0;
    bool clipped() const { return clipped_x != 0 || clipped_y != 0; }
};

// A clipped value sits `radius` + 1 pixels inside the edge it points at.
Spot locate(const Scale &sx, const Scale &sy, const PlotPoint &p, double radius) {
    Spot s;
    if (std::isnan(p.x) || std::isnan(p.y)) return s;
    auto side = [](const Scale &sc, double v) { return sc.shows(v) ? 0 : v > 0 ? 1 : -1; };
    s.clipped_x = side(sx, p.x);
    s.clipped_y = side(sy, p.y);
    const double x_lo = std::min(sx.p0, sx.p1), x_hi = std::max(sx.p0, sx.p1);
    const double y_lo = std::min(sy.p0, sy.p1), y_hi = std::max(sy.p0, sy.p1);
    const double in = radius + 1;
    // Pixels of an axis's low end (−1) or high end (+1).
    s.x = s.clipped_x == 0 ? sx.to_px(p.x) : s.clipped_x < 0 ? sx.p0 + (sx.p1 > sx.p0 ? in : -in)
                                                              : sx.p1 - (sx.p1 > sx.p0 ? in : -in);
    s.y = s.clipped_y == 0 ? sy.to_px(p.y) : s.clipped_y < 0 ? sy.p0 + (sy.p1 > sy.p0 ? in : -in)
                                                              : sy.p1 - (sy.p1 > sy.p0 ? in : -in);
    if (s.clipped()) { // keep the triangle inside the plot along the edge too
        s.x = std::clamp(s.x, x_lo + in, x_hi - in);
        s.y = std::clamp(s.y, y_lo + in, y_hi - in);
    }
    s.drawn = true;
    return s;
}

// The triangle of a clipped value, pointing out of the plot (up, down, left or right).
std::string clipped_triangle(const Spot &s, const Scale &sx, const Scale &sy, const char *colour) {
    const double r = kClippedRadius;
    double ux = 0, uy = 0; // outward, in pixels
    if (s.clipped_y != 0) uy = (s.clipped_y > 0) == (sy.p1 > sy.p0) ? 1 : -1;
    else ux = (s.clipped_x > 0) == (sx.p1 > sx.p0) ? 1 : -1;
    const double tx = s.x + ux * r, ty = s.y + uy * r;              // the tip
    const double bx = s.x - ux * r * 0.5, by = s.y - uy * r * 0.5;  // the base's middle
    const double hx = -uy * r * 0.8, hy = ux * r * 0.8;             // half the base
    return "<polygon class=\"clipped\" points=\"" + px(tx) + "," + px(ty) + " " + px(bx + hx) + "," + px(by + hy) + " " +
           px(bx - hx) + "," + px(by - hy) + "\" fill=\"" + colour + "\"/>\n";
}

// Room to keep between a value and the ends of its axis, in pixels.
struct Room {
    double v, lo, hi;
};

// Moves the ends of `s` out until every value is at least its room inside them, so that no
// marker crosses the plot's frame.
void pad_for_markers(Scale *s, const std::vector<Room> &items) {
    const double length = std::fabs(s->p1 - s->p0);
    double a = s->t(s->lo), b = s->t(s->hi);
    for (int round = 0; round < 20; ++round) {
        bool moved = false;
        for (const Room &r : items) {
            if (!s->shows(r.v)) continue;
            const double t = s->t(r.v), per_px = (b - a) / length;
            if (t - a < r.lo * per_px - 1e-12 * (b - a)) {
                a = t - r.lo * per_px;
                moved = true;
            }
            if (b - t < r.hi * per_px - 1e-12 * (b - a)) {
                b = t + r.hi * per_px;
                moved = true;
            }
        }
        if (!moved) break;
    }
    s->lo = s->log ? std::pow(10.0, a) : a;
    s->hi = s->log ? std::pow(10.0, b) : b;
}

std::string text_element(const Label &l) {
    std::string anchor = l.anchor == TextAnchor::Middle ? " text-anchor=\"middle\""
                         : l.anchor == TextAnchor::End  ? " text-anchor=\"end\""
                                                        : "";
    std::string where = l.rotated ? " transform=\"translate(" + px(l.x) + " " + px(l.y) + ") rotate(-90)\""
                                  : " x=\"" + px(l.x) + "\" y=\"" + px(l.y) + "\"";
    return "<text class=\"label\"" + where + anchor + (l.size != kAxisSize ? " font-size=\"" + fmt("%g", l.size) + "\"" : "") +
           (l.bold ? " font-weight=\"bold\"" : "") + (l.colour.empty() ? "" : " fill=\"" + l.colour + "\"") + ">" +
           escape_xml(l.text) + "</text>\n";
}

} // namespace

std::string render_svg(const Plot &plot, int width_px, int height_px) {
    // Margins; the legend on the right, its texts from 40 px right of the plot area: the
    // picture grows (the plot area keeps its width) where a legend text needs more than 190 px.
    const double left = 78, top = 40, bottom = 58;
    double right = 190;
    for (const auto &s : plot.series) right = std::max(right, 40.0 + text_width_px(s.label, 12) + 10.0);
    width_px += static_cast<int>(std::ceil(right - 190));
    Scale sx, sy;
    sx.log = plot.log_x;
    sy.log = plot.log_y;
    sx.p0 = left;
    sx.p1 = width_px - right;
    sy.p0 = height_px - bottom;
    sy.p1 = top;

    // Data range over everything that is drawn.
    double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
    auto include = [&](const PlotPoint &p) {
        if (!sx.shows(p.x) || !sy.shows(p.y)) return;
        x_lo = std::min(x_lo, p.x);
        x_hi = std::max(x_hi, p.x);
        y_lo = std::min(y_lo, p.y);
        y_hi = std::max(y_hi, p.y);
    };
    for (const auto &s : plot.series)
        for (const auto &p : s.points) include(p);
    for (const auto &m : plot.markers) include(m.at);
    const bool empty = !(x_lo <= x_hi);
    for (const auto &v : plot.vlines)
        if (!empty && sx.shows(v.x)) {
            x_lo = std::min(x_lo, v.x);
            x_hi = std::max(x_hi, v.x);
        }
    for (const auto &h : plot.hlines)
        if (!empty && sy.shows(h.y)) {
            y_lo = std::min(y_lo, h.y);
            y_hi = std::max(y_hi, h.y);
        }

    std::ostringstream head, o; // head: the <svg> element, whose height the footnotes set
    o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    o << "<text x=\"" << px(width_px / 2.0) << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">"
      << escape_xml(plot.title) << "</text>\n";
    auto svg_head = [&](double height) {
        head << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px << "\" height=\"" << height
             << "\" viewBox=\"0 0 " << width_px << " " << height
             << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
        return head.str();
    };
    if (empty) {
        o << "<text x=\"" << px(width_px / 2.0) << "\" y=\"" << px(height_px / 2.0)
          << "\" text-anchor=\"middle\">no data to show</text>\n</svg>\n";
        return svg_head(height_px) + o.str();
    }
    sx.lo = x_lo;
    sx.hi = x_hi;
    sy.lo = y_lo;
    sy.hi = y_hi;
    const std::vector<double> xt = fit_and_tick(&sx), yt = fit_and_tick(&sy);
    {
        // Room inside the frame for every marker, and a reference line apart from the frame:
        // the axes reach a little past their ticks where a point would otherwise sit on the
        // frame; more at an end where values beyond the axis are drawn, so that their
        // triangles keep clear of the points.
        bool beyond_x[2] = {false, false}, beyond_y[2] = {false, false}; // low end, high end
        auto note_beyond = [&](const PlotPoint &p) {
            if (std::isnan(p.x) || std::isnan(p.y)) return;
            if (!sx.shows(p.x)) beyond_x[p.x > 0] = true;
            if (!sy.shows(p.y)) beyond_y[p.y > 0] = true;
        };
        for (const auto &s : plot.series)
            for (const auto &p : s.points) note_beyond(p);
        for (const auto &m : plot.markers) note_beyond(m.at);
        const Room point_x{0, beyond_x[0] ? kBeyondRoom : kEdgeRoom, beyond_x[1] ? kBeyondRoom : kEdgeRoom};
        const Room point_y{0, beyond_y[0] ? kBeyondRoom : kEdgeRoom, beyond_y[1] ? kBeyondRoom : kEdgeRoom};
        std::vector<Room> xs, ys;
        for (const auto &v : plot.vlines) xs.push_back({v.x, kLineRoom, kLineRoom});
        for (const auto &h : plot.hlines) ys.push_back({h.y, kLineRoom, kLineRoom});
        auto add_point = [&](const PlotPoint &p) {
            if (!sx.shows(p.x) || !sy.shows(p.y)) return;
            xs.push_back({p.x, point_x.lo, point_x.hi});
            ys.push_back({p.y, point_y.lo, point_y.hi});
        };
        for (const auto &s : plot.series)
            for (const auto &p : s.points) add_point(p);
        for (const auto &m : plot.markers) add_point(m.at);
        pad_for_markers(&sx, xs);
        pad_for_markers(&sy, ys);
    }

    // Grid, ticks and labels.
    o << "<g stroke=\"#dddddd\" stroke-width=\"1\">\n";
    for (double v : xt)
        o << "<line x1=\"" << px(sx.to_px(v)) << "\" y1=\"" << px(sy.p1) << "\" x2=\"" << px(sx.to_px(v))
          << "\" y2=\"" << px(sy.p0) << "\"/>\n";
    for (double v : yt)
        o << "<line x1=\"" << px(sx.p0) << "\" y1=\"" << px(sy.to_px(v)) << "\" x2=\"" << px(sx.p1) << "\" y2=\""
          << px(sy.to_px(v)) << "\"/>\n";
    o << "</g>\n";
    o << "<rect class=\"plot-area\" x=\"" << px(sx.p0) << "\" y=\"" << px(sy.p1) << "\" width=\"" << px(sx.p1 - sx.p0)
      << "\" height=\"" << px(sy.p0 - sy.p1) << "\" fill=\"none\" stroke=\"#444444\"/>\n";
    for (double v : xt)
        o << "<text x=\"" << px(sx.to_px(v)) << "\" y=\"" << px(sy.p0 + 18) << "\" text-anchor=\"middle\">"
          << escape_xml(tick_label(sx, v)) << "</text>\n";
    for (double v : yt)
        o << "<text x=\"" << px(sx.p0 - 6) << "\" y=\"" << px(sy.to_px(v) + 4) << "\" text-anchor=\"end\">"
          << escape_xml(tick_label(sy, v)) << "</text>\n";
    o << "<text x=\"" << px((sx.p0 + sx.p1) / 2) << "\" y=\"" << px(height_px - 16.0)
      << "\" text-anchor=\"middle\">" << escape_xml(plot.x_label) << "</text>\n";
    o << "<text transform=\"translate(18 " << px((sy.p0 + sy.p1) / 2) << ") rotate(-90)\" text-anchor=\"middle\">"
      << escape_xml(plot.y_label) << "</text>\n";

    // Every marker first (the labels keep clear of them), then the labels in order.
    Placer placer;
    placer.area = {sx.p0, sy.p1, sx.p1, sy.p0};
    std::vector<std::vector<Spot>> spots(plot.series.size());
    for (size_t k = 0; k < plot.series.size(); ++k)
        for (const auto &p : plot.series[k].points) {
            spots[k].push_back(locate(sx, sy, p, kClippedRadius));
            const Spot &s = spots[k].back();
            if (s.drawn) placer.markers.push_back({s.x, s.y, s.clipped() ? kClippedRadius : kPointRadius});
        }
    for (size_t k = 0; k < plot.series.size(); ++k) {
        if (!plot.series[k].line) continue;
        const Spot *prev = nullptr;
        for (const Spot &sp : spots[k]) {
            if (!sp.drawn || sp.clipped()) continue;
            if (prev) placer.lines.push_back({prev->x, prev->y, sp.x, sp.y});
            prev = &sp;
        }
    }
    for (const auto &h : plot.hlines)
        if (sy.shows(h.y)) placer.lines.push_back({sx.p0, sy.to_px(h.y), sx.p1, sy.to_px(h.y)});
    for (const auto &v : plot.vlines)
        if (sx.shows(v.x)) placer.lines.push_back({sx.to_px(v.x), sy.p0, sx.to_px(v.x), sy.p1});
    std::vector<Spot> ring_spots;
    for (const auto &m : plot.markers) {
        ring_spots.push_back(locate(sx, sy, m.at, kRingRadius));
        if (ring_spots.back().drawn) placer.markers.push_back({ring_spots.back().x, ring_spots.back().y, kRingRadius});
    }
    struct Footnote {
        std::string text, colour;
        const Spot *at; // the point it belongs to, or null
        double radius;
    };
    std::vector<Footnote> footnotes;
    auto coords = [](const PlotPoint &p) { return "(" + fmt("%.3g", p.x) + ", " + fmt("%.3g", p.y) + ")"; };
    // A label with no free place: a footnote; its number goes beside the point where that fits,
    // once every label has its place.
    auto footnote = [&](const std::string &text, const std::string &colour, const Spot *at, double r) {
        footnotes.push_back({"[" + std::to_string(footnotes.size() + 1) + "] " + text, colour, at, r});
    };

    const std::string caption_colour = "#555555";
    std::vector<double> hline_px, vline_px;
    for (const auto &v : plot.vlines) {
        if (!sx.shows(v.x)) continue;
        const double x = sx.to_px(v.x);
        vline_px.push_back(x);
        const double asc = kTextAscentEm * kAxisSize, desc = kTextDescentEm * kAxisSize;
        std::vector<Label> c;
        for (const auto &[anchor, y] : {std::pair{TextAnchor::End, sy.p1 + 4}, std::pair{TextAnchor::Start, sy.p0 - 4}})
            for (double base : {x - 3 - desc, x + 3 + asc}) {
                Label l;
                l.text = v.label;
                l.x = base;
                l.y = y;
                l.anchor = anchor;
                l.rotated = true;
                l.colour = caption_colour;
                c.push_back(l);
            }
        if (!placer.place(c)) footnote("the dashed line at " + fmt("%.3g", v.x) + ": " + v.label, caption_colour, nullptr, 0);
    }
    for (const auto &h : plot.hlines) {
        if (!sy.shows(h.y)) continue;
        const double y = sy.to_px(h.y);
        hline_px.push_back(y);
        const double asc = kTextAscentEm * kAxisSize, desc = kTextDescentEm * kAxisSize;
        std::vector<Label> c;
        for (const auto &[anchor, x] : {std::pair{TextAnchor::End, sx.p1 - 4}, std::pair{TextAnchor::Start, sx.p0 + 4},
                                       std::pair{TextAnchor::Middle, (sx.p0 + sx.p1) / 2}})
            for (double base : {y - 3 - desc, y + 3 + asc}) {
                Label l;
                l.text = h.label;
                l.x = x;
                l.y = base;
                l.anchor = anchor;
                l.colour = caption_colour;
                c.push_back(l);
            }
        if (!placer.place(c)) footnote("the dashed line at " + fmt("%.3g", h.y) + ": " + h.label, caption_colour, nullptr, 0);
    }
    for (size_t i = 0; i < plot.markers.size(); ++i) {
        const Spot &s = ring_spots[i];
        if (!s.drawn || plot.markers[i].label.empty()) continue;
        if (!placer.place(around(plot.markers[i].label, s.x, s.y, placer.clear_radius(s.x, s.y, kRingRadius), kAxisSize, true, "", true), s.x, s.y))
            footnote(plot.markers[i].label + " at " + coords(plot.markers[i].at), "#000000", &s, kRingRadius);
    }
    // Values beyond the axes: the value in words beside the triangle.
    for (size_t k = 0; k < plot.series.size(); ++k) {
        const PlotSeries &s = plot.series[k];
        const char *colour = kPalette[k % kPaletteSize];
        for (size_t i = 0; i < s.points.size(); ++i) {
            const Spot &sp = spots[k][i];
            if (!sp.drawn || !sp.clipped()) continue;
            const std::string name = i < s.point_labels.size() ? s.point_labels[i] : "";
            const std::string value = sp.clipped_x == 0 ? fmt("%.3g", s.points[i].y) : coords(s.points[i]);
            const std::string text = name.empty() ? value : name + (sp.clipped_x == 0 ? " = " : " ") + value;
            if (!placer.place(around(text, sp.x, sp.y, placer.clear_radius(sp.x, sp.y, kClippedRadius), kPointLabelSize, false, colour, false), sp.x, sp.y))
                footnote(s.label + ", beyond the axis: " + text, colour, &sp, kClippedRadius);
        }
    }
    for (size_t k = 0; k < plot.series.size(); ++k) {
        const PlotSeries &s = plot.series[k];
        const char *colour = kPalette[k % kPaletteSize];
        std::vector<bool> done(s.points.size(), false);
        for (size_t i = 0; i < s.points.size() && i < s.point_labels.size(); ++i) {
            const Spot &sp = spots[k][i];
            if (done[i] || !sp.drawn || sp.clipped() || s.point_labels[i].empty()) continue;
            // The labels of this series' points drawn on this one (within a pixel), as one.
            std::string text = s.point_labels[i];
            for (size_t j = i + 1; j < s.points.size() && j < s.point_labels.size(); ++j) {
                const Spot &other = spots[k][j];
                if (!done[j] && other.drawn && !other.clipped() && !s.point_labels[j].empty() &&
                    std::hypot(other.x - sp.x, other.y - sp.y) < 1) {
                    text += ", " + s.point_labels[j];
                    done[j] = true;
                }
            }
            if (!placer.place(around(text, sp.x, sp.y, placer.clear_radius(sp.x, sp.y, kPointRadius), kPointLabelSize,
                                     false, colour, false),
                              sp.x, sp.y))
                footnote(s.label + " at " + coords(s.points[i]) + ": " + text, colour, &sp, kPointRadius);
        }
    }

    for (size_t i = 0; i < footnotes.size(); ++i)
        if (const Spot *at = footnotes[i].at)
            placer.place(around("[" + std::to_string(i + 1) + "]", at->x, at->y,
                                placer.clear_radius(at->x, at->y, footnotes[i].radius), kTagSize, false,
                                footnotes[i].colour, false),
                         at->x, at->y);

    // Reference lines, then the series, then the markers, then the labels on top.
    for (double y : hline_px)
        o << "<line x1=\"" << px(sx.p0) << "\" y1=\"" << px(y) << "\" x2=\"" << px(sx.p1) << "\" y2=\"" << px(y)
          << "\" stroke=\"#888888\" stroke-dasharray=\"6 4\"/>\n";
    for (double x : vline_px)
        o << "<line x1=\"" << px(x) << "\" y1=\"" << px(sy.p1) << "\" x2=\"" << px(x) << "\" y2=\"" << px(sy.p0)
          << "\" stroke=\"#888888\" stroke-dasharray=\"6 4\"/>\n";
    for (size_t k = 0; k < plot.series.size(); ++k) {
        const PlotSeries &s = plot.series[k];
        const char *colour = kPalette[k % kPaletteSize];
        std::string path;
        for (const Spot &sp : spots[k]) {
            if (!sp.drawn || sp.clipped()) continue;
            path += (path.empty() ? "M" : " L") + px(sp.x) + " " + px(sp.y);
        }
        if (s.line && !path.empty())
            o << "<path d=\"" << path << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.8\""
              << (s.dashed ? " stroke-dasharray=\"3 3\"" : "") << "/>\n";
        for (const Spot &sp : spots[k]) {
            if (!sp.drawn) continue;
            if (sp.clipped()) o << clipped_triangle(sp, sx, sy, colour);
            else if (s.hollow)
                o << "<circle cx=\"" << px(sp.x) << "\" cy=\"" << px(sp.y) << "\" r=\"" << fmt("%g", kPointRadius)
                  << "\" fill=\"#ffffff\" stroke=\"" << colour << "\" stroke-width=\"1.5\"/>\n";
            else
                o << "<circle cx=\"" << px(sp.x) << "\" cy=\"" << px(sp.y) << "\" r=\"" << fmt("%g", kPointRadius)
                  << "\" fill=\"" << colour << "\"/>\n";
        }
        const double ly = top + 14 + 18.0 * static_cast<double>(k);
        o << "<line x1=\"" << px(sx.p1 + 14) << "\" y1=\"" << px(ly - 4) << "\" x2=\"" << px(sx.p1 + 34) << "\" y2=\""
          << px(ly - 4) << "\" stroke=\"" << colour << "\" stroke-width=\"2.5\""
          << (s.dashed ? " stroke-dasharray=\"3 3\"" : "") << "/>\n";
        o << "<text x=\"" << px(sx.p1 + 40) << "\" y=\"" << px(ly) << "\">" << escape_xml(s.label) << "</text>\n";
    }
    for (const Spot &s : ring_spots)
        if (s.drawn)
            o << "<circle cx=\"" << px(s.x) << "\" cy=\"" << px(s.y) << "\" r=\"" << fmt("%g", kRingRadius)
              << "\" fill=\"none\" stroke=\"#000000\" stroke-width=\"2\"/>\n";
    for (const Label &l : placer.placed) {
        if (l.leader)
            o << "<line class=\"leader\" x1=\"" << px(l.lx0) << "\" y1=\"" << px(l.ly0) << "\" x2=\"" << px(l.lx1)
              << "\" y2=\"" << px(l.ly1) << "\" stroke=\"" << (l.colour.empty() ? "#000000" : l.colour)
              << "\" stroke-width=\"0.8\"/>\n";
        o << text_element(l);
    }
    // The footnotes: under the x axis's title, the picture grown to hold them.
    const double first = height_px + 4.0;
    for (size_t i = 0; i < footnotes.size(); ++i)
        o << "<text class=\"footnote\" x=\"12\" y=\"" << px(first + kFootnoteStep * static_cast<double>(i))
          << "\" font-size=\"" << fmt("%g", kFootnoteSize) << "\" fill=\"" << footnotes[i].colour << "\">"
          << escape_xml(footnotes[i].text) << "</text>\n";
    o << "</svg>\n";
    const double height = footnotes.empty() ? height_px : first + kFootnoteStep * static_cast<double>(footnotes.size() - 1) + 6;
    return svg_head(height) + o.str();
}

std::vector<PlotPoint> pareto_front(std::vector<PlotPoint> points) {
    std::sort(points.begin(), points.end(), [](const PlotPoint &a, const PlotPoint &b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    std::vector<PlotPoint> front;
    for (const PlotPoint &p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
        if (front.empty() || p.y < front.back().y) front.push_back(p);
    }
    return front;
}

} // namespace scatterlut
