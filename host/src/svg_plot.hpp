// scatterlut generator — small, dependency-free SVG charts for the `report` command:
// x–y series on linear or logarithmic axes, with a legend and labelled markers (the
// planner's choice, a target line). Output is deterministic text (fixed number format),
// so the same measurements give the same file.
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

// The points of `points` that no other point beats in both coordinates (smaller x and
// smaller y are better), sorted by x: the Pareto front of a cost–error trade-off.
std::vector<PlotPoint> pareto_front(std::vector<PlotPoint> points);

// The chart as a standalone SVG document. Points that cannot be shown (non-finite, or
// ≤ 0 on a log axis) are left out; a plot with no showable point says so in its body.
std::string render_svg(const Plot &plot, int width_px = 760, int height_px = 460);

} // namespace scatterlut
