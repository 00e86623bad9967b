// The charts' labels (host/src/svg_plot.cpp): the text-box estimate, the placement that keeps
// labels off each other and inside the plot, the footnotes for labels with no room, and the
// values beyond an axis drawn at its edge. Checked with tests/host/chart_check.hpp, which the
// report's charts are checked with too (tests/commands/test_report_charts.cpp); its own
// findings are checked first, on hand-written SVG.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/chart_check.hpp"
#include "svg_plot.hpp"

namespace {

using scatterlut::Plot;
using scatterlut::PlotSeries;
using scatterlut::TextAnchor;

size_t count(const std::string &s, const std::string &what) {
    size_t n = 0;
    for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
    return n;
}

std::string all_text(const chart_check::Chart &c) {
    std::string s;
    for (const auto &t : c.texts) s += t.content + "\n";
    return s;
}

} // namespace

// The documented advance: 0.64 em a character, 1.0 em for m, w, M, W; bold 1.1x; one UTF-8
// code point is one character. Rotated text (rotate(-90)) reads upwards from its anchor.
TEST(ChartLabels, TextBoxIsTheDocumentedEstimate) {
    EXPECT_DOUBLE_EQ(scatterlut::text_width_px("max", 10), (1.0 + 0.64 + 0.64) * 10);
    EXPECT_DOUBLE_EQ(scatterlut::text_width_px("p99", 10, true), 3 * 0.64 * 10 * 1.1);
    EXPECT_DOUBLE_EQ(scatterlut::text_width_px("σ×", 10), 2 * 0.64 * 10);
    const auto b = scatterlut::text_box("ab", 100, 50, 10, TextAnchor::End);
    EXPECT_DOUBLE_EQ(b.x0, 100 - 12.8);
    EXPECT_DOUBLE_EQ(b.x1, 100);
    EXPECT_DOUBLE_EQ(b.y0, 50 - 7.6);
    EXPECT_DOUBLE_EQ(b.y1, 50 + 2.4);
    const auto r = scatterlut::text_box("ab", 100, 50, 10, TextAnchor::Start, false, true);
    EXPECT_DOUBLE_EQ(r.x0, 100 - 7.6);
    EXPECT_DOUBLE_EQ(r.x1, 100 + 2.4);
    EXPECT_DOUBLE_EQ(r.y0, 50 - 12.8);
    EXPECT_DOUBLE_EQ(r.y1, 50);
    EXPECT_TRUE(scatterlut::boxes_overlap({0, 0, 10, 10}, {9, 9, 20, 20}));
    EXPECT_FALSE(scatterlut::boxes_overlap({0, 0, 10, 10}, {10, 0, 20, 10})) << "touching is not overlapping";
}

// The check finds what it is for: two texts on one spot, a data label across the frame, a
// tick label reaching into the plot, a text over a marker, a marker across the frame.
TEST(ChartLabels, CheckFindsOverlapsAndTextsOutside) {
    const std::string svg =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" height=\"300\" viewBox=\"0 0 400 300\" "
        "font-size=\"12\">\n"
        "<rect class=\"plot-area\" x=\"50.0\" y=\"20.0\" width=\"300.0\" height=\"240.0\"/>\n"
        "<text x=\"100.0\" y=\"100.0\" font-size=\"10\">p99</text>\n"
        "<text x=\"102.0\" y=\"103.0\" font-size=\"10\">max</text>\n"
        "<text x=\"340.0\" y=\"200.0\" font-size=\"10\">far right</text>\n"
        "<text x=\"44.0\" y=\"30.0\" text-anchor=\"end\">1e-2</text>\n"
        "<text x=\"40.0\" y=\"150.0\">a tick too long</text>\n"
        "<text x=\"200.0\" y=\"200.0\" font-size=\"10\">on a dot</text>\n"
        "<circle cx=\"210.0\" cy=\"197.0\" r=\"3.2\"/>\n"
        "<circle cx=\"52.0\" cy=\"250.0\" r=\"3.2\"/>\n"
        "</svg>\n";
    const chart_check::Problems p = chart_check::check(chart_check::parse(svg));
    EXPECT_EQ(p.overlaps.size(), 1u);
    EXPECT_EQ(p.outside.size(), 2u) << "'far right' across the frame, the long tick into the plot";
    EXPECT_EQ(p.over_markers.size(), 1u);
    EXPECT_EQ(p.markers_outside.size(), 1u);
}

// Many points a few pixels apart, each with a label: every label lands clear of the others and
// of every marker, inside the plot, or in a numbered footnote under the chart; none is lost.
TEST(ChartLabels, CrowdedLabelsMoveOrBecomeFootnotes) {
    Plot p;
    p.title = "crowded";
    p.log_x = p.log_y = true;
    for (int k = 0; k < 3; ++k) {
        PlotSeries s;
        s.label = "series " + std::to_string(k);
        for (int i = 0; i < 8; ++i) {
            s.points.push_back({100.0 * (1 + 0.02 * i), 1e-3 * (1 + 0.03 * i + 0.01 * k)});
            s.point_labels.push_back("rung " + std::to_string(k) + "." + std::to_string(i));
        }
        p.series.push_back(s);
    }
    p.series.push_back({"far away", {{1e4, 1}}, {}, true, false});
    p.markers.push_back({{100, 1e-3}, "planned"});
    p.hlines.push_back({1e-3, "accepted error 0.001"});
    const std::string svg = scatterlut::render_svg(p);
    const chart_check::Chart c = chart_check::parse(svg);
    const chart_check::Problems problems = chart_check::check(c);
    for (const auto &s : problems.overlaps) ADD_FAILURE() << s;
    for (const auto &s : problems.outside) ADD_FAILURE() << s;
    for (const auto &s : problems.over_markers) ADD_FAILURE() << s;
    for (const auto &s : problems.markers_outside) ADD_FAILURE() << s;
    const std::string text = all_text(c);
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 8; ++i) {
            const std::string label = "rung " + std::to_string(k) + "." + std::to_string(i);
            EXPECT_NE(text.find(label), std::string::npos) << label;
        }
    EXPECT_NE(text.find("planned"), std::string::npos);
    EXPECT_NE(text.find("accepted error 0.001"), std::string::npos);
    const size_t footnotes = count(svg, "class=\"footnote\"");
    EXPECT_GT(footnotes, 0u) << "24 labels in a few pixels cannot all sit beside their points";
    EXPECT_GT(c.height, 460.0) << "the picture grows to hold its footnotes";
    EXPECT_EQ(count(svg, "<circle"), 25u + 1u) << "every point drawn, and the marker's ring";
}

// A value an axis cannot show (0 or −∞ on a log axis, ±∞) is a triangle at the plot's edge
// with its value beside it, not a point outside the plot; NaN is left out.
TEST(ChartLabels, ValuesBeyondTheAxisAreDrawnAtTheEdge) {
    const double inf = std::numeric_limits<double>::infinity();
    Plot p;
    p.log_x = p.log_y = true;
    PlotSeries s;
    s.label = "method";
    s.points = {{10, 1e-3}, {10, 1e-1}, {10, 0}, {10, inf}, {-5, 1e-2}, {10, NAN}};
    s.point_labels = {"median", "p99", "best", "max", "", "nan"};
    s.line = false;
    p.series.push_back(s);
    p.series.push_back({"other", {{100, 1e-2}}, {}, true, false});
    p.markers.push_back({{10, inf}, "planned"});
    const std::string svg = scatterlut::render_svg(p);
    const chart_check::Chart c = chart_check::parse(svg);
    const chart_check::Problems problems = chart_check::check(c);
    EXPECT_EQ(problems.total(), 0u) << svg;
    ASSERT_EQ(c.polygons.size(), 3u) << "0 and ∞ on the y axis, −5 on the x axis";
    EXPECT_EQ(count(svg, "class=\"clipped\""), 3u);
    // The triangles' tips touch the edges they point at: bottom, top, left.
    auto tip_at = [&](double x, double y) {
        for (const auto &poly : c.polygons)
            if (std::fabs(poly[0].first - x) < 0.06 || std::fabs(poly[0].second - y) < 0.06) return true;
        return false;
    };
    EXPECT_TRUE(tip_at(NAN, c.plot_area.y1 - 1));
    EXPECT_TRUE(tip_at(NAN, c.plot_area.y0 + 1));
    EXPECT_TRUE(tip_at(c.plot_area.x0 + 1, NAN));
    const std::string text = all_text(c);
    EXPECT_NE(text.find("best = 0"), std::string::npos) << text;
    EXPECT_NE(text.find("max = inf"), std::string::npos) << text;
    EXPECT_NE(text.find("(-5, 0.01)"), std::string::npos) << text;
    EXPECT_EQ(text.find("nan"), std::string::npos) << "a NaN is left out";
    EXPECT_EQ(count(svg, "<circle"), 2u + 1u + 1u) << "median, p99, the other series' point, the ring";
}

// Points on the axes' ends (whole decades) and reference lines there: the axes make room, so
// that the markers' discs and rings lie inside the frame and the lines apart from it.
TEST(ChartLabels, MarkersOnTheAxisEndsStayInside) {
    Plot p;
    p.log_x = p.log_y = true;
    PlotSeries s;
    s.label = "rungs";
    s.points = {{1, 1e-15}, {10, 1e-12}, {100, 1e-9}};
    s.point_labels = {"tol 1e-13", "tol 1e-11", "tol 1e-9"};
    p.series.push_back(s);
    p.markers.push_back({{1, 1e-15}, "planned"});
    p.hlines.push_back({1e-9, "accepted"});
    const std::string svg = scatterlut::render_svg(p);
    const chart_check::Chart c = chart_check::parse(svg);
    const chart_check::Problems problems = chart_check::check(c);
    EXPECT_EQ(problems.total(), 0u) << svg;
    for (const auto &m : c.circles) {
        EXPECT_GE(m.cx - m.r, c.plot_area.x0 + 1);
        EXPECT_LE(m.cy + m.r, c.plot_area.y1 - 1);
    }
    EXPECT_NE(svg.find(">1e-15<"), std::string::npos) << "the decade ticks stay";
}

// The legend's texts stay inside the picture however long (the picture grows, the plot area
// keeps its width: the same chart with short labels keeps its size), and a hollow series
// (the report's GPU rows) draws its markers as rings, with a dashed line in the legend.
TEST(ChartLabels, LongLegendTextsWidenThePictureAndHollowSeriesAreRings) {
    Plot p;
    p.x_label = "x";
    p.y_label = "y";
    PlotSeries cpu, gpu;
    cpu.label = "CPU short";
    cpu.points = {{1, 1}, {2, 2}};
    gpu.label = "GPU a legend text much longer than the 150 px a legend had";
    gpu.points = {{1, 2}, {2, 3}};
    gpu.hollow = gpu.dashed = true;
    p.series = {cpu, gpu};
    const std::string svg = scatterlut::render_svg(p);
    const chart_check::Chart c = chart_check::parse(svg);
    EXPECT_GT(c.width, 760.0);
    EXPECT_EQ(chart_check::check(c).total(), 0u) << svg;
    EXPECT_EQ(count(svg, "fill=\"#ffffff\" stroke="), 2u) << "the hollow series' two rings";
    EXPECT_EQ(count(svg, "stroke-dasharray=\"3 3\""), 2u) << "its line and its legend";
    p.series[1].label = "GPU short";
    EXPECT_EQ(chart_check::parse(scatterlut::render_svg(p)).width, 760.0);
}
