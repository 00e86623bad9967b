// scatterlut generator — small, dependency-free SVG charts for the `report` command:
// x–y series on linear or logarithmic axes, with a legend and labelled markers (the
// planner's choice, a target line), the labels placed clear of each other. Output is
// deterministic text (fixed number format), so the same measurements give the same file.
#pragma once

#include <string>
#include <vector>

namespace scatterlut {

struct PlotPoint {
    double x = 0, y = 0;
};

struct PlotSeries {
    std::string label;
    std::vector<PlotPoint> points;       // drawn in the given order
    std::vector<std::string> point_labels; // empty, or one small label per point
    bool line = true;                    // join the points; markers are always drawn
    bool dashed = false;
    bool hollow = false;                 // markers as rings (white inside), to tell one kind of series from another
};

// A point drawn on top of the series, with its label beside it (e.g. "planned").
struct PlotMarker {
    PlotPoint at;
    std::string label;
};

// A horizontal reference line across the plot (e.g. the scene's accepted error).
struct PlotHLine {
    double y = 0;
    std::string label;
};

// A vertical reference line (e.g. the cost of the exact method, whose error is the reference).
struct PlotVLine {
    double x = 0;
    std::string label;
};

struct Plot {
    std::string title;
    std::string x_label, y_label; // with units, e.g. "generation time (ms)"
    bool log_x = false, log_y = false;
    std::vector<PlotSeries> series;
    std::vector<PlotMarker> markers;
    std::vector<PlotHLine> hlines;
    std::vector<PlotVLine> vlines;
};

// ---- The box a line of chart text covers: one estimate for the label placement in
// render_svg and for the tests that check the charts for overlaps (tests/host/chart_check.hpp).
//
// Width: the sum of each character's advance (one UTF-8 code point is one character):
// kTextAdvanceEm of the font size, kTextWideAdvanceEm for the wide letters m, w, M, W, %, @;
// times kTextBoldFactor in bold. These cover DejaVu Sans, the usual "sans-serif" (its digits
// advance 0.636 em, lower case 0.28–0.64 em but m 0.974 em; bold about 1.09x). Height: from
// kTextAscentEm above the baseline (DejaVu's digits and capitals reach 0.73 em, ascenders
// 0.76 em) to kTextDescentEm below it (0.236 em). Pixels, y down, as in the SVG.
constexpr double kTextAdvanceEm = 0.64;
constexpr double kTextWideAdvanceEm = 1.0;
constexpr double kTextBoldFactor = 1.1;
constexpr double kTextAscentEm = 0.76;
constexpr double kTextDescentEm = 0.24;

enum class TextAnchor { Start, Middle, End }; // SVG's text-anchor

struct TextBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0; // left, top, right, bottom
};

double text_width_px(const std::string &text, double font_size_px, bool bold = false);

// The box of `text` drawn at (x, y) (the baseline's anchor point). rotated: the text turned by
// rotate(-90) about (x, y), reading upwards, as the y axis's title and a vertical line's caption.
TextBox text_box(const std::string &text, double x, double y, double font_size_px, TextAnchor anchor,
                 bool bold = false, bool rotated = false);

// Whether the boxes share an area (touching edges do not count).
bool boxes_overlap(const TextBox &a, const TextBox &b);

// The points of `points` that no other point beats in both coordinates (smaller x and
// smaller y are better), sorted by x: the Pareto front of a cost–error trade-off.
std::vector<PlotPoint> pareto_front(std::vector<PlotPoint> points);

// The chart as a standalone SVG document. The axes fit the points and reference lines, with
// room for every marker inside the plot area (<rect class="plot-area">). A value beyond an
// axis (≤ 0 or −∞ on a log axis, ±∞) is a triangle at the plot's edge pointing out, with the
// value written beside it; a NaN is left out. Labels (the points', the markers', the values
// beyond the axes, the reference lines' captions) are placed where they cover no other
// label and no marker, inside the plot area (text_box's estimate): of a list of places around
// their point (right, left, above, below, between those, then further out with a leader
// line), a free one nearer its own point than any other if there is one, then crossing the
// fewest lines, then the earliest. A label with no free place is a numbered footnote under
// the chart (which grows to hold it), its number beside the point where that fits. Labels of
// one series' points that fall on one pixel are one label ("median, p99, max"). A plot with
// no showable point says so in its body.
std::string render_svg(const Plot &plot, int width_px = 760, int height_px = 460);

} // namespace scatterlut
