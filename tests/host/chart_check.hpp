// Checks a chart written by render_svg (host/src/svg_plot.cpp) the way a reader looks at it:
// no text drawn over another text or over a marker, no data label or marker outside the plot
// area. Each text's box is the generator's own estimate (scatterlut::text_box: the advance per
// character documented in svg_plot.hpp), so the check and the placement agree on what a
// label covers; the SVG is read with a few regular expressions (render_svg's output is one
// element per line, attributes in double quotes).
//
// What "inside" means for each text:
// - A data label (class="label", or any text whose anchor point lies inside the plot area:
//   point labels, marker labels, reference lines' captions, clipped values) lies wholly
//   inside the plot area, the <rect class="plot-area">.
// - Every other text (the title, tick labels, axis titles, the legend, the footnotes) sits
//   around the plot: wholly inside the SVG's viewBox and outside the plot area (touching
//   its edge is allowed).
// Markers (<circle>, and the <polygon> of a value beyond the axis) lie wholly inside the plot
// area. Lines (series, grid, reference and leader lines) may cross texts.
#pragma once

#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "svg_plot.hpp"

namespace chart_check {

struct Text {
    std::string content; // XML entities decoded
    std::string css_class;
    double x = 0, y = 0, font_size = 12;
    scatterlut::TextAnchor anchor = scatterlut::TextAnchor::Start;
    bool bold = false, rotated = false;
    scatterlut::TextBox box;
};

struct Circle {
    double cx = 0, cy = 0, r = 0;
};

struct Chart {
    double width = 0, height = 0;   // the viewBox (its origin is 0 0)
    scatterlut::TextBox plot_area;  // the <rect class="plot-area">
    bool has_plot_area = false;
    std::vector<Text> texts;
    std::vector<Circle> circles;
    std::vector<std::vector<std::pair<double, double>>> polygons;
};

inline std::string attribute(const std::string &element, const std::string &name) {
    const std::regex re("\\s" + name + "=\"([^\"]*)\"");
    std::smatch m;
    return std::regex_search(element, m, re) ? m[1].str() : std::string();
}

inline double number_attribute(const std::string &element, const std::string &name, double fallback) {
    const std::string v = attribute(element, name);
    return v.empty() ? fallback : std::stod(v);
}

inline std::string decode_xml(const std::string &s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] != '&') {
            out += s[i];
            continue;
        }
        const size_t semi = s.find(';', i);
        const std::string entity = s.substr(i + 1, semi - i - 1);
        if (entity == "amp") out += '&';
        else if (entity == "lt") out += '<';
        else if (entity == "gt") out += '>';
        else if (entity == "quot") out += '"';
        else if (entity == "apos") out += '\'';
        else out += '?'; // a numeric reference: one character
        i = semi;
    }
    return out;
}

inline Chart parse(const std::string &svg) {
    Chart c;
    std::smatch m;
    double default_font = 12;
    if (std::regex_search(svg, m, std::regex("<svg[^>]*>"))) {
        const std::string root = m[0].str();
        default_font = number_attribute(root, "font-size", 12);
        std::smatch vb;
        const std::string box = attribute(root, "viewBox");
        if (std::regex_match(box, vb, std::regex("0 0 ([0-9.]+) ([0-9.]+)"))) {
            c.width = std::stod(vb[1].str());
            c.height = std::stod(vb[2].str());
        }
    }
    const std::regex rect_re("<rect[^>]*class=\"plot-area\"[^>]*>");
    if (std::regex_search(svg, m, rect_re)) {
        const std::string e = m[0].str();
        const double x = number_attribute(e, "x", 0), y = number_attribute(e, "y", 0);
        c.plot_area = {x, y, x + number_attribute(e, "width", 0), y + number_attribute(e, "height", 0)};
        c.has_plot_area = true;
    }
    const std::regex text_re("(<text[^>]*>)([^<]*)</text>");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), text_re); it != std::sregex_iterator(); ++it) {
        const std::string e = (*it)[1].str();
        Text t;
        t.content = decode_xml((*it)[2].str());
        t.css_class = attribute(e, "class");
        t.font_size = number_attribute(e, "font-size", default_font);
        const std::string anchor = attribute(e, "text-anchor");
        t.anchor = anchor == "middle" ? scatterlut::TextAnchor::Middle
                   : anchor == "end"  ? scatterlut::TextAnchor::End
                                      : scatterlut::TextAnchor::Start;
        t.bold = attribute(e, "font-weight") == "bold";
        const std::string transform = attribute(e, "transform");
        std::smatch tm;
        if (std::regex_match(transform, tm, std::regex("translate\\(([-0-9.]+) ([-0-9.]+)\\) rotate\\(-90\\)"))) {
            t.x = std::stod(tm[1].str());
            t.y = std::stod(tm[2].str());
            t.rotated = true;
        } else {
            t.x = number_attribute(e, "x", 0);
            t.y = number_attribute(e, "y", 0);
        }
        t.box = scatterlut::text_box(t.content, t.x, t.y, t.font_size, t.anchor, t.bold, t.rotated);
        c.texts.push_back(t);
    }
    const std::regex circle_re("<circle[^>]*>");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle_re); it != std::sregex_iterator(); ++it) {
        const std::string e = (*it)[0].str();
        c.circles.push_back({number_attribute(e, "cx", 0), number_attribute(e, "cy", 0), number_attribute(e, "r", 0)});
    }
    const std::regex polygon_re("<polygon[^>]*>");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polygon_re); it != std::sregex_iterator(); ++it) {
        std::vector<std::pair<double, double>> pts;
        const std::string list = attribute((*it)[0].str(), "points");
        const std::regex pair_re("([-0-9.]+),([-0-9.]+)");
        for (auto p = std::sregex_iterator(list.begin(), list.end(), pair_re); p != std::sregex_iterator(); ++p)
            pts.push_back({std::stod((*p)[1].str()), std::stod((*p)[2].str())});
        c.polygons.push_back(pts);
    }
    return c;
}

// Coordinates are written with one decimal: a box may reach this far past an edge.
constexpr double kRounding = 0.051;

inline bool inside(const scatterlut::TextBox &b, const scatterlut::TextBox &area) {
    return b.x0 >= area.x0 - kRounding && b.x1 <= area.x1 + kRounding && b.y0 >= area.y0 - kRounding &&
           b.y1 <= area.y1 + kRounding;
}

inline bool point_inside(double x, double y, const scatterlut::TextBox &area) {
    return x > area.x0 && x < area.x1 && y > area.y0 && y < area.y1;
}

inline bool box_meets_circle(const scatterlut::TextBox &b, const Circle &c) {
    const double dx = std::max({b.x0 - c.cx, 0.0, c.cx - b.x1});
    const double dy = std::max({b.y0 - c.cy, 0.0, c.cy - b.y1});
    return dx * dx + dy * dy < c.r * c.r;
}

inline bool is_data_label(const Chart &c, const Text &t) {
    return t.css_class == "label" || (c.has_plot_area && point_inside(t.x, t.y, c.plot_area));
}

// Each problem in words, one per entry; the kinds counted apart.
struct Problems {
    std::vector<std::string> overlaps;        // two texts over each other
    std::vector<std::string> outside;         // a text outside where it belongs
    std::vector<std::string> over_markers;    // a text over a marker
    std::vector<std::string> markers_outside; // a marker outside the plot area
    size_t total() const { return overlaps.size() + outside.size() + over_markers.size() + markers_outside.size(); }
};

inline std::string describe(const Text &t) {
    return "'" + t.content + "' at (" + std::to_string(t.x) + ", " + std::to_string(t.y) + ")";
}

inline Problems check(const Chart &c) {
    Problems p;
    if (!c.has_plot_area) {
        p.outside.push_back("no <rect class=\"plot-area\">");
        return p;
    }
    const scatterlut::TextBox view{0, 0, c.width, c.height};
    for (size_t i = 0; i < c.texts.size(); ++i) {
        const Text &t = c.texts[i];
        for (size_t j = i + 1; j < c.texts.size(); ++j)
            if (scatterlut::boxes_overlap(t.box, c.texts[j].box))
                p.overlaps.push_back(describe(t) + " and " + describe(c.texts[j]));
        if (is_data_label(c, t)) {
            if (!inside(t.box, c.plot_area)) p.outside.push_back(describe(t) + ": a data label beyond the plot area");
        } else {
            scatterlut::TextBox shrunk = c.plot_area; // touching the frame is allowed
            shrunk.x0 += kRounding;
            shrunk.y0 += kRounding;
            shrunk.x1 -= kRounding;
            shrunk.y1 -= kRounding;
            if (!inside(t.box, view)) p.outside.push_back(describe(t) + ": beyond the viewBox");
            else if (scatterlut::boxes_overlap(t.box, shrunk))
                p.outside.push_back(describe(t) + ": reaches into the plot area");
        }
        for (const Circle &m : c.circles)
            if (box_meets_circle(t.box, m))
                p.over_markers.push_back(describe(t) + " over the marker at (" + std::to_string(m.cx) + ", " +
                                         std::to_string(m.cy) + ")");
    }
    const scatterlut::TextBox &a = c.plot_area;
    for (const Circle &m : c.circles)
        if (!inside({m.cx - m.r, m.cy - m.r, m.cx + m.r, m.cy + m.r}, a))
            p.markers_outside.push_back("the circle at (" + std::to_string(m.cx) + ", " + std::to_string(m.cy) +
                                        ") r " + std::to_string(m.r));
    for (const auto &poly : c.polygons)
        for (const auto &[x, y] : poly)
            if (!inside({x, y, x, y}, a)) {
                p.markers_outside.push_back("a polygon's corner (" + std::to_string(x) + ", " + std::to_string(y) + ")");
                break;
            }
    return p;
}

} // namespace chart_check
