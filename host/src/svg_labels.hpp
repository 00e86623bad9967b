// The SVG charts' label placement (svg_plot.cpp's render_svg): data labels where they cover no
// other label and no marker, inside the plot area, else a footnote. Internal to the charts:
// the boxes come from text_box (svg_plot.hpp), the same estimate tests/host/chart_check.hpp
// checks the charts with.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "svg_plot.hpp"

namespace scatterlut {
namespace svg_labels {

// ---------------------------------------------------------------- label placement
// Data labels go where they cover no other label and no marker, inside the plot area (the
// boxes: text_box's estimate): of a list of candidate places around their point, a free one
// nearer its own point than any other if there is one, then crossing the fewest lines, then
// the earliest. Placement order: the vertical, then the horizontal reference lines' captions,
// the markers' labels, the values beyond the axes, the points' labels, the footnotes' numbers.
// A label with no free place goes to the footnotes under the chart.

constexpr double kPointRadius = 3.2;   // a series' point
constexpr double kRingRadius = 8;      // a marker's ring around its point
constexpr double kClippedRadius = 6;   // the triangle of a value beyond the axis, as a disc
constexpr double kLabelGap = 3;        // between a label and its point's marker
constexpr double kLineRoom = 6;        // from a reference line to the plot's frame
constexpr double kEdgeRoom = 10;       // from a point to the plot's frame: its ring fits, and a
                                       // label beside it
constexpr double kBeyondRoom = 2 * kRingRadius + 8; // the same at an end where values beyond
                                                   // the axis are drawn (a ring's width, more)
constexpr double kClearance = 1;       // kept free around labels and markers
constexpr double kPointLabelSize = 10; // font sizes (px)
constexpr double kAxisSize = 12;
constexpr double kTagSize = 9;         // a footnote's number beside its point
constexpr double kFootnoteSize = 11;
constexpr double kFootnoteStep = 15;   // between footnote lines

struct Disc {
    double x = 0, y = 0, r = 0;
};

struct Label {
    std::string text;
    double x = 0, y = 0, size = kAxisSize;
    TextAnchor anchor = TextAnchor::Start;
    bool bold = false, rotated = false;
    std::string colour;
    bool leader = false;              // a line from the point's marker to the label
    double lx0 = 0, ly0 = 0, lx1 = 0, ly1 = 0;

    TextBox box() const { return text_box(text, x, y, size, anchor, bold, rotated); }
};

inline TextBox grown(const TextBox &b, double d) { return {b.x0 - d, b.y0 - d, b.x1 + d, b.y1 + d}; }

inline bool box_meets_disc(const TextBox &b, const Disc &c) {
    const double dx = std::max({b.x0 - c.x, 0.0, c.x - b.x1});
    const double dy = std::max({b.y0 - c.y, 0.0, c.y - b.y1});
    return dx * dx + dy * dy < c.r * c.r;
}

struct Segment {
    double x0, y0, x1, y1;
};

// Whether the segment passes through the box (Liang–Barsky clipping).
inline bool segment_meets_box(const Segment &s, const TextBox &b) {
    double t0 = 0, t1 = 1;
    const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {s.x0 - b.x0, b.x1 - s.x0, s.y0 - b.y0, b.y1 - s.y0};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0) {
            if (q[i] < 0) return false;
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    return true;
}

struct Placer {
    TextBox area;              // the plot area
    std::vector<Disc> markers; // every marker drawn
    std::vector<Segment> lines; // the series' lines and the reference lines: crossed only if need be
    std::vector<Label> placed;

    // The radius to keep clear around a point at (x, y): its own marker's, or a larger one
    // drawn around it (a marker's ring).
    double clear_radius(double x, double y, double r) const {
        for (const Disc &m : markers)
            if (std::hypot(m.x - x, m.y - y) < m.r) r = std::max(r, m.r + std::hypot(m.x - x, m.y - y));
        return r;
    }
    int lines_crossed(const Label &l) const {
        const TextBox g = grown(l.box(), kClearance);
        int n = 0;
        for (const Segment &s : lines) n += segment_meets_box(s, g);
        return n;
    }
    bool free(const Label &l) const {
        const TextBox b = l.box();
        if (b.x0 < area.x0 + kClearance || b.x1 > area.x1 - kClearance || b.y0 < area.y0 + kClearance ||
            b.y1 > area.y1 - kClearance)
            return false;
        const TextBox g = grown(b, kClearance);
        for (const Label &p : placed)
            if (boxes_overlap(g, p.box()) || (l.leader && segment_meets_box({l.lx0, l.ly0, l.lx1, l.ly1}, p.box())))
                return false;
        for (const Disc &m : markers)
            if (box_meets_disc(g, m)) return false;
        return true;
    }
    // Whether some other marker is nearer the label than its own point at (x, y), so that the
    // reader would take the label for that one's.
    bool nearer_to_another(const Label &l, double x, double y) const {
        if (std::isnan(x)) return false; // a caption: no point of its own
        const TextBox b = l.box();
        auto distance = [&b](double px_, double py_) {
            return std::hypot(std::max({b.x0 - px_, 0.0, px_ - b.x1}), std::max({b.y0 - py_, 0.0, py_ - b.y1}));
        };
        const double own = distance(x, y);
        for (const Disc &m : markers)
            if (std::hypot(m.x - x, m.y - y) > 0.5 && distance(m.x, m.y) < own - 0.5) return true;
        return false;
    }
    // Places the free candidate for the point at (x, y) that is nearer its own point than any
    // other if one is, then crosses the fewest lines, then comes first; false if none is free.
    // A leader line is a line for later labels.
    bool place(const std::vector<Label> &candidates, double x = NAN, double y = NAN) {
        const Label *best = nullptr;
        std::pair<bool, int> best_cost{true, 0};
        for (const Label &c : candidates) {
            if (!free(c)) continue;
            const std::pair<bool, int> cost{nearer_to_another(c, x, y), lines_crossed(c)};
            if (!best || cost < best_cost) {
                best = &c;
                best_cost = cost;
                if (cost == std::pair<bool, int>{false, 0}) break;
            }
        }
        if (!best) return false;
        placed.push_back(*best);
        if (best->leader) lines.push_back({best->lx0, best->ly0, best->lx1, best->ly1});
        return true;
    }
};

// Candidate places for `text` beside a marker of radius r at (x, y), in this order: right,
// left, above, below, the four diagonals, then the eight directions between those; then all
// sixteen further out, with a leader line from the marker to the label. Each place puts the
// label's box at kLabelGap (plus the extra distance) from the marker; a label on the left
// ends there, one on the right starts there (text-anchor), so a text a little wider or
// narrower than its estimate grows away from its point.
inline std::vector<Label> around(const std::string &text, double x, double y, double r, double size, bool bold,
                          const std::string &colour, bool above_right_first) {
    const double asc = kTextAscentEm * size, desc = kTextDescentEm * size;
    const double w = text_width_px(text, size, bold), h = asc + desc;
    constexpr double kPi = 3.14159265358979323846;
    std::vector<double> angles = {0, 180, 90, 270, 315, 45, 225, 135, 337.5, 22.5, 202.5, 157.5, 292.5, 67.5, 247.5, 112.5};
    if (above_right_first) angles.insert(angles.begin(), 45);
    std::vector<Label> out;
    for (double extra : {0.0, 10.0, 20.0, 32.0, 48.0, 72.0}) {
        for (double deg : angles) {
            // Direction on the page (y down): 90° is up.
            const double ux = std::cos(deg * kPi / 180), uy = -std::sin(deg * kPi / 180);
            const double reach = r + kLabelGap + extra;
            // The box's centre along the direction, just far enough for the box to keep `reach`
            // from the point (bisection on the distance, which grows along the ray).
            auto distance = [&](double t) {
                const double cx = t * ux, cy = t * uy;
                return std::hypot(std::max(std::fabs(cx) - w / 2, 0.0), std::max(std::fabs(cy) - h / 2, 0.0));
            };
            double lo = 0, hi = reach + w + h;
            for (int i = 0; i < 40; ++i) (distance((lo + hi) / 2) < reach ? lo : hi) = (lo + hi) / 2;
            const double cx = x + hi * ux, cy = y + hi * uy;
            Label l;
            l.text = text;
            l.size = size;
            l.bold = bold;
            l.colour = colour;
            l.anchor = ux > 0.3 ? TextAnchor::Start : ux < -0.3 ? TextAnchor::End : TextAnchor::Middle;
            l.x = l.anchor == TextAnchor::Start ? cx - w / 2 : l.anchor == TextAnchor::End ? cx + w / 2 : cx;
            l.y = cy + (asc - desc) / 2;
            if (extra > 0) {
                // From the marker's edge to the box's nearest point.
                const TextBox b = l.box();
                const double nx = std::clamp(x, b.x0, b.x1), ny = std::clamp(y, b.y0, b.y1);
                const double len = std::hypot(nx - x, ny - y);
                l.leader = true;
                l.lx0 = x + (nx - x) * r / len;
                l.ly0 = y + (ny - y) * r / len;
                l.lx1 = nx - (nx - x) * 1.0 / len;
                l.ly1 = ny - (ny - y) * 1.0 / len;
            }
            out.push_back(l);
        }
    }
    return out;
}

} // namespace svg_labels
} // namespace scatterlut
