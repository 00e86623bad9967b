// eval's "spot_airlight" quantity (host/src/kinds/airlight_runtime.cpp, docs/EVAL.md), run as the
// built executable: "exact" is scatterlut::spot_airlight_radiance_exact of the same query (σ as
// numbers or arrays of 3, phase_g, inner_angle defaulting to outer_angle), "table" null without
// tables and, with --table of saved airlight tables (isotropic and g = 0.6, filled by quadrature),
// spot_airlight_radiance from the table of the query's g (null for another g); a ray through the
// lit apex answers null with a note; bad input is an error line naming the field.
#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "airlight_quadrature_table.hpp"
#include "generate_airlight.hpp"
#include "reference_data.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/spot.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_airlight_hg.h"
#include "slut_axes.h"
}

namespace {

using slut_test::json_lines;
using slut_test::run_scatterlut;

nlohmann::json base_line() {
    return {{"quantity", "spot_airlight"}, {"sigma_s", 0.1},          {"sigma_a", 0.05},     {"intensity", 3},
            {"viewer", {0, 0, 0}},         {"view_dir", {1, 0, 0.1}}, {"length", 20},        {"light_pos", {5, 0, 4}},
            {"spot_dir", {0, 0, -1}},      {"outer_angle", 0.6},      {"inner_angle", 0.3}};
}

// The library's query of a line (the test's own parse).
scatterlut::SpotQuery query_of(const nlohmann::json &j) {
    scatterlut::SpotQuery q;
    q.sigma_s_per_m = j.at("sigma_s").is_number() ? j.at("sigma_s").get<double>() : 0.0;
    q.sigma_a_per_m = j.at("sigma_a").get<double>();
    q.light.intensity_W_per_sr = j.at("intensity").get<double>();
    for (int k = 0; k < 3; ++k) {
        q.viewer_m[k] = j.at("viewer")[k].get<double>();
        q.view_dir[k] = j.at("view_dir")[k].get<double>();
        q.light.position_m[k] = j.at("light_pos")[k].get<double>();
        q.light.direction[k] = j.at("spot_dir")[k].get<double>();
    }
    q.length_m = j.at("length").is_string() ? HUGE_VAL : j.at("length").get<double>();
    q.light.outer_angle_rad = j.at("outer_angle").get<double>();
    q.light.inner_angle_rad = j.contains("inner_angle") ? j.at("inner_angle").get<double>() : q.light.outer_angle_rad;
    return q;
}

std::string save_table(double phase_g) {
    const scatterlut::Table t = slut_test::airlight_quadrature_table(phase_g, 128, 64);
    const std::string path = slut_test::temp_stem(phase_g == 0.0 ? "airlight_F" : "airlight_Fg") + ".slut";
    scatterlut::save_binary(t, path);
    return path;
}

std::vector<nlohmann::json> eval(const std::vector<nlohmann::json> &lines, const std::string &args = "") {
    std::ostringstream in;
    for (const auto &l : lines) in << l.dump() << "\n";
    const auto r = run_scatterlut("eval" + args, in.str());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json_lines(r.out);
}

TEST(SpotEval, ExactIsTheLibrarysAndTableNullWithoutTables) {
    std::vector<nlohmann::json> lines;
    nlohmann::json a = base_line();
    lines.push_back(a);
    a.erase("inner_angle"); // hard cone: inner = outer
    a["length"] = "inf";
    lines.push_back(a);
    a = base_line();
    a["phase_g"] = 0.6;
    lines.push_back(a);
    a["sigma_s"] = {0.05, 0.1, 0.2};
    lines.push_back(a);
    const auto out = eval(lines);
    ASSERT_EQ(out.size(), lines.size());
    for (size_t i = 0; i < out.size(); ++i) {
        const double g = lines[i].value("phase_g", 0.0);
        if (lines[i].at("sigma_s").is_array()) {
            ASSERT_TRUE(out[i].at("exact").is_array()) << out[i].dump();
            for (int c = 0; c < 3; ++c) {
                scatterlut::SpotQuery q = query_of(lines[i]);
                q.sigma_s_per_m = lines[i].at("sigma_s")[c].get<double>();
                EXPECT_EQ(out[i].at("exact")[c].get<double>(), scatterlut::spot_airlight_radiance_exact(q, g));
                EXPECT_TRUE(out[i].at("table")[c].is_null());
            }
            continue;
        }
        EXPECT_EQ(out[i].at("exact").get<double>(), scatterlut::spot_airlight_radiance_exact(query_of(lines[i]), g))
            << out[i].dump();
        EXPECT_GT(out[i].at("exact").get<double>(), 0.0);
        EXPECT_TRUE(out[i].at("table").is_null());
    }
}

TEST(SpotEval, TableOfTheQuerysG) {
    const std::string iso = save_table(0.0), hg = save_table(0.6);
    std::vector<nlohmann::json> lines{base_line()};
    nlohmann::json a = base_line();
    a["phase_g"] = 0.6;
    lines.push_back(a);
    a["phase_g"] = 0.3; // no table of this g
    lines.push_back(a);
    const auto out = eval(lines, " --table " + iso + " --table " + hg);
    ASSERT_EQ(out.size(), 3u);
    const scatterlut::AirlightTable iso_table(scatterlut::load_table(iso));
    const scatterlut::AirlightHgTable hg_table(scatterlut::load_table(hg));
    const double want_iso = scatterlut::spot_airlight_radiance(iso_table, query_of(lines[0]));
    const double want_hg = scatterlut::spot_airlight_radiance(hg_table, query_of(lines[1]));
    EXPECT_EQ(out[0].at("table").get<double>(), want_iso) << out[0].dump();
    EXPECT_EQ(out[1].at("table").get<double>(), want_hg) << out[1].dump();
    EXPECT_TRUE(out[2].at("table").is_null()) << out[2].dump();
    // The table's answer near the exact one (the 128 × 64 table's own error, ~1e-3).
    EXPECT_LE(std::fabs(want_iso / out[0].at("exact").get<double>() - 1), 5e-3);
    EXPECT_LE(std::fabs(want_hg / out[1].at("exact").get<double>() - 1), 5e-3);
    std::remove(iso.c_str());
    std::remove(hg.c_str());
}

TEST(SpotEval, ThroughTheLightIsNullWithANote) {
    nlohmann::json a = base_line();
    a["viewer"] = {5, 0, 0};
    a["view_dir"] = {0, 0, 1};
    const auto out = eval({a});
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(out[0].at("exact").is_null()) << out[0].dump();
    EXPECT_NE(out[0].value("note", "").find("passes through the light"), std::string::npos) << out[0].dump();
}

TEST(SpotEval, BadInputNamesTheField) {
    struct Bad {
        const char *field;
        nlohmann::json value;
    };
    const Bad bad[] = {{"view_dir", {0, 0, 0}},       {"spot_dir", {0, 0, 0}},   {"inner_angle", 0.7},
                       {"outer_angle", 3.5},          {"outer_angle", -0.1},     {"inner_angle", "wide"},
                       {"viewer", {1, 2}},            {"light_pos", {1, "a", 2}}, {"length", -1},
                       {"sigma_s", {0.1, 0.2}},       {"phase_g", 1.5},          {"outer_angle", "inf"},
                       {"spot_dir", nullptr}};
    std::vector<nlohmann::json> lines;
    for (const Bad &b : bad) {
        nlohmann::json a = base_line();
        a[b.field] = b.value;
        lines.push_back(a);
    }
    nlohmann::json missing = base_line();
    missing.erase("spot_dir");
    lines.push_back(missing);
    std::ostringstream in;
    for (const auto &l : lines) in << l.dump() << "\n";
    const auto r = run_scatterlut("eval", in.str());
    const auto out = json_lines(r.out);
    ASSERT_EQ(out.size(), lines.size());
    for (size_t i = 0; i < out.size(); ++i) {
        ASSERT_TRUE(out[i].contains("error")) << out[i].dump();
        const std::string field = i < std::size(bad) ? bad[i].field : "spot_dir";
        EXPECT_NE(out[i].at("error").get<std::string>().find(field), std::string::npos) << out[i].dump();
    }
}

} // namespace
