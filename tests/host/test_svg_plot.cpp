// The report's charts (host/src/svg_plot.cpp): the Pareto front of a ladder, log axes that
// leave out what they cannot show, text escaped for SVG.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "svg_plot.hpp"

TEST(SvgPlot, ParetoFrontKeepsTheUndominatedPoints) {
    using scatterlut::PlotPoint;
    const std::vector<PlotPoint> pts = {{1, 5}, {2, 3}, {3, 4}, {4, 1}, {5, 2}, {0.5, 9}};
    const auto front = scatterlut::pareto_front(pts);
    ASSERT_EQ(front.size(), 4u);
    EXPECT_EQ(front[0].x, 0.5);
    EXPECT_EQ(front[1].x, 1);
    EXPECT_EQ(front[2].x, 2);
    EXPECT_EQ(front[3].x, 4);
}

TEST(SvgPlot, LogAxesLeaveOutWhatTheyCannotShow) {
    scatterlut::Plot p;
    p.title = "t <&>";
    p.log_x = p.log_y = true;
    scatterlut::PlotSeries s;
    s.label = "s";
    s.points = {{1, 1e-3}, {10, 1e-5}, {-1, 1}, {100, 0}, {1000, NAN}};
    p.series.push_back(s);
    const std::string svg = scatterlut::render_svg(p);
    EXPECT_NE(svg.find("t &lt;&amp;&gt;"), std::string::npos);
    size_t circles = 0;
    for (size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++circles;
    EXPECT_EQ(circles, 2u) << "only the two positive, finite points";
    EXPECT_NE(svg.find(">1e-5<"), std::string::npos) << "decade ticks";
    scatterlut::Plot empty;
    EXPECT_NE(scatterlut::render_svg(empty).find("no data"), std::string::npos);
}
