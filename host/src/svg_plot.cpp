#include "svg_plot.hpp"

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

std::string render_svg(const Plot &plot, int width_px, int height_px) {
    const double left = 78, right = 190, top = 40, bottom = 58; // margins; legend on the right
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

    std::ostringstream o;
    o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px << "\" height=\"" << height_px
      << "\" viewBox=\"0 0 " << width_px << " " << height_px << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    o << "<text x=\"" << px(width_px / 2.0) << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">"
      << escape_xml(plot.title) << "</text>\n";
    if (empty) {
        o << "<text x=\"" << px(width_px / 2.0) << "\" y=\"" << px(height_px / 2.0)
          << "\" text-anchor=\"middle\">no data to show</text>\n</svg>\n";
        return o.str();
    }
    sx.lo = x_lo;
    sx.hi = x_hi;
    sy.lo = y_lo;
    sy.hi = y_hi;
    const std::vector<double> xt = fit_and_tick(&sx), yt = fit_and_tick(&sy);

    // Grid, ticks and labels.
    o << "<g stroke=\"#dddddd\" stroke-width=\"1\">\n";
    for (double v : xt)
        o << "<line x1=\"" << px(sx.to_px(v)) << "\" y1=\"" << px(sy.p1) << "\" x2=\"" << px(sx.to_px(v))
          << "\" y2=\"" << px(sy.p0) << "\"/>\n";
    for (double v : yt)
        o << "<line x1=\"" << px(sx.p0) << "\" y1=\"" << px(sy.to_px(v)) << "\" x2=\"" << px(sx.p1) << "\" y2=\""
          << px(sy.to_px(v)) << "\"/>\n";
    o << "</g>\n";
    o << "<rect class=\"plot-area\" x=\"" << px(sx.p0) << "\" y=\"" << px(sy.p1) << "\" width=\"" << px(sx.p1 - sx.p0) << "\" height=\""
      << px(sy.p0 - sy.p1) << "\" fill=\"none\" stroke=\"#444444\"/>\n";
    for (double v : xt)
        o << "<text x=\"" << px(sx.to_px(v)) << "\" y=\"" << px(sy.p0 + 16) << "\" text-anchor=\"middle\">"
          << escape_xml(tick_label(sx, v)) << "</text>\n";
    for (double v : yt)
        o << "<text x=\"" << px(sx.p0 - 6) << "\" y=\"" << px(sy.to_px(v) + 4) << "\" text-anchor=\"end\">"
          << escape_xml(tick_label(sy, v)) << "</text>\n";
    o << "<text x=\"" << px((sx.p0 + sx.p1) / 2) << "\" y=\"" << px(height_px - 16.0)
      << "\" text-anchor=\"middle\">" << escape_xml(plot.x_label) << "</text>\n";
    o << "<text transform=\"translate(18 " << px((sy.p0 + sy.p1) / 2) << ") rotate(-90)\" text-anchor=\"middle\">"
      << escape_xml(plot.y_label) << "</text>\n";

    // Reference lines, then the series, then the markers on top.
    for (const auto &h : plot.hlines) {
        if (!sy.shows(h.y)) continue;
        const double y = sy.to_px(h.y);
        o << "<line x1=\"" << px(sx.p0) << "\" y1=\"" << px(y) << "\" x2=\"" << px(sx.p1) << "\" y2=\"" << px(y)
          << "\" stroke=\"#888888\" stroke-dasharray=\"6 4\"/>\n";
        o << "<text x=\"" << px(sx.p1 - 4) << "\" y=\"" << px(y - 4) << "\" text-anchor=\"end\" fill=\"#555555\">"
          << escape_xml(h.label) << "</text>\n";
    }
    for (const auto &v : plot.vlines) {
        if (!sx.shows(v.x)) continue;
        const double x = sx.to_px(v.x);
        o << "<line x1=\"" << px(x) << "\" y1=\"" << px(sy.p1) << "\" x2=\"" << px(x) << "\" y2=\"" << px(sy.p0)
          << "\" stroke=\"#888888\" stroke-dasharray=\"6 4\"/>\n";
        o << "<text transform=\"translate(" << px(x - 4) << " " << px(sy.p1 + 6) << ") rotate(-90)\" text-anchor=\"end\" "
          << "fill=\"#555555\">" << escape_xml(v.label) << "</text>\n";
    }
    for (size_t k = 0; k < plot.series.size(); ++k) {
        const PlotSeries &s = plot.series[k];
        const char *colour = kPalette[k % kPaletteSize];
        std::string path;
        for (const auto &p : s.points) {
            if (!sx.shows(p.x) || !sy.shows(p.y)) continue;
            path += (path.empty() ? "M" : " L") + px(sx.to_px(p.x)) + " " + px(sy.to_px(p.y));
        }
        if (s.line && !path.empty())
            o << "<path d=\"" << path << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.8\""
              << (s.dashed ? " stroke-dasharray=\"3 3\"" : "") << "/>\n";
        for (size_t i = 0; i < s.points.size(); ++i) {
            const PlotPoint &p = s.points[i];
            if (!sx.shows(p.x) || !sy.shows(p.y)) continue;
            o << "<circle cx=\"" << px(sx.to_px(p.x)) << "\" cy=\"" << px(sy.to_px(p.y)) << "\" r=\"3.2\" fill=\""
              << colour << "\"/>\n";
            if (i < s.point_labels.size() && !s.point_labels[i].empty())
                o << "<text x=\"" << px(sx.to_px(p.x) + 5) << "\" y=\"" << px(sy.to_px(p.y) + 12) << "\" font-size=\"10\" "
                  << "fill=\"" << colour << "\">" << escape_xml(s.point_labels[i]) << "</text>\n";
        }
        const double ly = top + 14 + 18.0 * static_cast<double>(k);
        o << "<line x1=\"" << px(sx.p1 + 14) << "\" y1=\"" << px(ly - 4) << "\" x2=\"" << px(sx.p1 + 34) << "\" y2=\""
          << px(ly - 4) << "\" stroke=\"" << colour << "\" stroke-width=\"2.5\"/>\n";
        o << "<text x=\"" << px(sx.p1 + 40) << "\" y=\"" << px(ly) << "\">" << escape_xml(s.label) << "</text>\n";
    }
    for (const auto &m : plot.markers) {
        if (!sx.shows(m.at.x) || !sy.shows(m.at.y)) continue;
        const double x = sx.to_px(m.at.x), y = sy.to_px(m.at.y);
        o << "<circle cx=\"" << px(x) << "\" cy=\"" << px(y) << "\" r=\"8\" fill=\"none\" stroke=\"#000000\" "
          << "stroke-width=\"2\"/>\n";
        o << "<text x=\"" << px(x + 11) << "\" y=\"" << px(y - 9) << "\" font-weight=\"bold\">" << escape_xml(m.label)
          << "</text>\n";
    }
    o << "</svg>\n";
    return o.str();
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
