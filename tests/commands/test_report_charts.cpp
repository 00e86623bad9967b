// `scatterlut report`'s charts read as a person reads them (the ladders' and the GPU
// section's): on every example scene (examples/scenes/*.toml, one test each) the report is
// run as the built executable and every
// SVG it writes is checked with tests/host/chart_check.hpp: no text over another text or over
// a marker, no data label or marker outside the plot area, the axes' and legend's texts
// inside the picture. The labels' boxes are the generator's own estimate (text_box in
// host/src/svg_plot.hpp). The report runs with one timing round and 800 queries (the
// cheapest run that still fills every chart: one to two minutes for all seven scenes on 2
// cores, most of it fog_street).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "host/chart_check.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kScenes = std::string(SLUT_SOURCE_DIR) + "/examples/scenes/";

std::vector<std::string> example_scenes() {
    std::vector<std::string> names;
    for (const auto &e : fs::directory_iterator(kScenes))
        if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string read_file(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every data row's field `k` (0: the first) of a CSV (the report writes no quoting).
std::vector<std::string> column(const fs::path &csv, size_t k = 0) {
    std::vector<std::string> out;
    std::istringstream in(read_file(csv));
    std::string line;
    std::getline(in, line); // header
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string field;
        for (size_t i = 0; i <= k && std::getline(fields, field, ','); ++i) {
        }
        out.push_back(field);
    }
    return out;
}

class ReportCharts : public testing::TestWithParam<std::string> {};

TEST_P(ReportCharts, NoLabelOverAnotherNorOutsideThePlot) {
    const std::string scene = GetParam();
    const std::string dir = slut_test::temp_stem("charts_" + scene);
    fs::remove_all(dir);
    const auto run = slut_test::run_scatterlut("report --scene " + kScenes + scene + ".toml --out " + dir +
                                               " --rounds 1 --queries 800");
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    ASSERT_TRUE(fs::exists(fs::path(dir) / "report.md"));

    std::vector<fs::path> svgs;
    for (const auto &e : fs::directory_iterator(dir))
        if (e.path().extension() == ".svg") svgs.push_back(e.path());
    std::sort(svgs.begin(), svgs.end());
    size_t overlaps = 0, outside = 0, over_markers = 0, markers_outside = 0;
    for (const fs::path &svg : svgs) {
        SCOPED_TRACE(svg.filename().string());
        const std::string text = read_file(svg);
        const chart_check::Chart chart = chart_check::parse(text);
        ASSERT_TRUE(chart.has_plot_area);
        ASSERT_GT(chart.width, 0.0);
        const chart_check::Problems p = chart_check::check(chart);
        for (const auto &s : p.overlaps) ADD_FAILURE() << "texts over each other: " << s << " (in " << dir << ")";
        for (const auto &s : p.outside) ADD_FAILURE() << "text outside its place: " << s;
        for (const auto &s : p.over_markers) ADD_FAILURE() << "text over a marker: " << s;
        for (const auto &s : p.markers_outside) ADD_FAILURE() << "marker outside the plot area: " << s;
        overlaps += p.overlaps.size();
        outside += p.outside.size();
        over_markers += p.over_markers.size();
        markers_outside += p.markers_outside.size();

        // The content stays: every rung's node counts and every method are named on its chart
        // (beside its point, or in the footnotes under the chart).
        const std::string name = svg.filename().string();
        const fs::path stem = svg.parent_path() / svg.stem();
        std::string all_text;
        for (const auto &t : chart.texts) all_text += t.content + "\n";
        if (name.size() > 15 && name.substr(name.size() - 15) == "_resolution.svg") {
            const fs::path csv = stem.string() + ".csv";
            for (const std::string &counts : column(csv)) EXPECT_NE(all_text.find(counts), std::string::npos) << counts;
        }
        if (name.size() > 12 && name.substr(name.size() - 12) == "_methods.svg") {
            const fs::path csv = stem.string() + ".csv";
            for (const std::string &method : column(csv)) EXPECT_NE(all_text.find(method), std::string::npos) << method;
        }
        // The GPU section's chart (<table>_gpu.svg): every CPU method and GPU row of its CSV.
        if (name.size() > 8 && name.substr(name.size() - 8) == "_gpu.svg") {
            const fs::path csv = stem.string() + ".csv";
            const std::vector<std::string> sides = column(csv, 0), methods = column(csv, 1);
            ASSERT_EQ(sides.size(), methods.size());
            for (size_t i = 0; i < methods.size(); ++i)
                EXPECT_NE(all_text.find(methods[i] == "exact" ? "CPU exact"
                                                              : (sides[i] == "gpu" ? "GPU " : "CPU ") + methods[i]),
                          std::string::npos)
                    << sides[i] << " " << methods[i];
        }
        EXPECT_NE(all_text.find("planned"), std::string::npos);
    }
    std::cout << scene << ": " << svgs.size() << " charts; texts over each other " << overlaps
              << ", texts outside their place " << outside << ", texts over markers " << over_markers
              << ", markers outside the plot " << markers_outside << "\n";
    if (!HasFailure()) fs::remove_all(dir); // else kept, to be looked at
}

INSTANTIATE_TEST_SUITE_P(ExampleScenes, ReportCharts, testing::ValuesIn(example_scenes()),
                         [](const testing::TestParamInfo<std::string> &scene) { return scene.param; });

} // namespace
