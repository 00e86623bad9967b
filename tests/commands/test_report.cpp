// `scatterlut report` (host/src/report.cpp) run as the built executable on example scenes
// (its charts: tests/host/test_svg_plot.cpp). The report's numbers are measurements, so the
// checks are the relations a correct measurement must show — each rung meets the tolerance
// it asked for, resolution buys accuracy, f16 costs half the bytes, the planned table holds
// the scene's error, the thin-medium form is wrong for a thick medium — never a time.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using Row = std::map<std::string, std::string>;

const std::string kScenes = std::string(SLUT_SOURCE_DIR) + "/examples/scenes/";

std::string read_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A CSV with a header line, no quoting (the report writes none).
std::vector<Row> read_csv(const std::string &path) {
    std::istringstream in(read_file(path));
    std::string line;
    std::vector<std::string> header;
    std::vector<Row> rows;
    auto split = [](const std::string &s) {
        std::vector<std::string> out;
        std::stringstream ss(s);
        std::string cell;
        while (std::getline(ss, cell, ',')) out.push_back(cell);
        return out;
    };
    if (!std::getline(in, line)) return rows;
    header = split(line);
    while (std::getline(in, line)) {
        const auto cells = split(line);
        EXPECT_EQ(cells.size(), header.size()) << path << ": " << line;
        Row r;
        for (size_t i = 0; i < header.size() && i < cells.size(); ++i) r[header[i]] = cells[i];
        rows.push_back(r);
    }
    return rows;
}

double num(const Row &r, const std::string &key) { return std::stod(r.at(key)); }

void expect_svg(const std::string &path) {
    const std::string s = read_file(path);
    ASSERT_FALSE(s.empty()) << path;
    EXPECT_EQ(s.rfind("<svg", 0), 0u) << path;
    EXPECT_NE(s.find("</svg>\n"), std::string::npos) << path;
    EXPECT_NE(s.find("planned"), std::string::npos) << path << ": the planner's choice must be marked";
    EXPECT_EQ(s.find("nan"), std::string::npos) << path;
}

// One report run per example scene, shared by the tests below (each generates a dozen tables).
std::string run_report(const std::string &scene) {
    const std::string d = slut_test::temp_stem("report_" + scene);
    fs::remove_all(d);
    const auto r = slut_test::run_scatterlut("report --scene " + kScenes + scene + ".toml --out " + d +
                                             " --rounds 1 --queries 800");
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    return d;
}
const std::string &candle_report() {
    static const std::string dir = run_report("candle_wax");
    return dir;
}
const std::string &fog_report() {
    static const std::string dir = run_report("fog_street");
    return dir;
}

const std::string &forward_near_light_report() {
    static const std::string dir = run_report("forward_near_light");
    return dir;
}

// A resolution ladder's planned row, and its coarsest and finest f32 rows (by bytes); null if absent.
struct LadderEnds {
    const Row *planned = nullptr, *coarsest = nullptr, *finest = nullptr;
};
LadderEnds ladder_ends(const std::vector<Row> &rows) {
    LadderEnds e;
    for (const Row &r : rows) {
        if (r.at("planned") == "1") e.planned = &r;
        if (r.at("storage") != "f32") continue;
        if (!e.coarsest || num(r, "bytes") < num(*e.coarsest, "bytes")) e.coarsest = &r;
        if (!e.finest || num(r, "bytes") > num(*e.finest, "bytes")) e.finest = &r;
    }
    return e;
}

void expect_rungs_meet_their_tolerance(const std::string &csv) {
    const auto rows = read_csv(csv);
    ASSERT_GE(rows.size(), 6u) << csv;
    double tightest = 1, tightest_error = 1;
    int planned = 0;
    for (const Row &r : rows) {
        const double tol = num(r, "tolerance"), err = num(r, "max_node_rel_error");
        EXPECT_LE(err, 10 * tol + 1e-14) << csv << ": tolerance " << tol;
        EXPECT_GT(num(r, "generation_ms_median"), 0.0);
        planned += r.at("planned") == "1";
        if (tol < tightest) {
            tightest = tol;
            tightest_error = err;
        }
    }
    EXPECT_EQ(planned, 1) << csv;
    EXPECT_LE(tightest_error, 1e-12) << csv;
}

} // namespace

// Every rung of the tolerance ladder meets the tolerance it asked for (a factor 10 for the
// rule's error estimate being an estimate, and 1e-14 for the reference's own rounding);
// the tightest rung is at round-off.
TEST(Report, ToleranceRungsMeetTheirTolerance) {
    expect_rungs_meet_their_tolerance(candle_report() + "/near_light_E3_tolerance.csv");
    expect_svg(candle_report() + "/near_light_E3_tolerance.svg");
    expect_rungs_meet_their_tolerance(fog_report() + "/airlight_F_tolerance.csv");
    expect_svg(fog_report() + "/airlight_F_tolerance.svg");
}

// The airlight report: the planned F table holds the fog's accepted error (0.005 in
// fog_street.toml) over the scene's geometries; beside exact and the table the report
// shows the closed forms engines use (no extinction, and × e^{−σ_t D}), which in fog are
// further off than the table: the no-extinction form overestimates (error ≥ the
// attenuated form's, as L ≤ L_0·e^{−σ_t D} ≤ L_0).
TEST(Report, AirlightTableHoldsTheScenesError) {
    const auto res = read_csv(fog_report() + "/airlight_F_resolution.csv");
    bool planned = false;
    for (const Row &r : res)
        if (r.at("planned") == "1") {
            planned = true;
            EXPECT_LE(num(r, "radiance_max_rel"), 0.005);
        }
    EXPECT_TRUE(planned);
    std::map<std::string, Row> m;
    for (const Row &r : read_csv(fog_report() + "/airlight_F_methods.csv")) m[r.at("method")] = r;
    ASSERT_EQ(m.size(), 4u);
    EXPECT_EQ(m.at("exact").at("max_rel"), "reference");
    EXPECT_LE(num(m.at("table"), "max_rel"), 0.005);
    EXPECT_GT(num(m.at("attenuated"), "median_rel"), num(m.at("table"), "median_rel"));
    EXPECT_GE(num(m.at("no_extinction"), "median_rel"), num(m.at("attenuated"), "median_rel"));
    for (const auto &[name, r] : m) EXPECT_GT(num(r, "ns_per_call"), 0.0) << name;
    expect_svg(fog_report() + "/airlight_F_resolution.svg");
    expect_svg(fog_report() + "/airlight_F_methods.svg");
}

// Resolution buys accuracy, f16 halves the bytes, and the planned table holds the scene's
// accepted error (0.02 in candle_wax.toml) on radiance over the scene's own geometries.
TEST(Report, ResolutionLadderBuysAccuracyAndThePlanHoldsTheScenesError) {
    const auto rows = read_csv(candle_report() + "/near_light_E3_resolution.csv");
    ASSERT_GE(rows.size(), 6u);
    std::map<std::string, std::map<std::string, Row>> by_counts; // counts → storage → row
    for (const Row &r : rows) by_counts[r.at("counts")][r.at("storage")] = r;
    const auto [planned, coarsest, finest] = ladder_ends(rows);
    ASSERT_NE(planned, nullptr);
    EXPECT_LE(num(*planned, "radiance_max_rel"), 0.02);
    EXPECT_GT(num(*planned, "queries"), 400.0);
    ASSERT_NE(coarsest, finest);
    EXPECT_LT(num(*finest, "radiance_max_rel"), num(*coarsest, "radiance_max_rel"));
    for (const auto &[counts, st] : by_counts)
        if (st.count("f16") && st.count("f32")) {
            EXPECT_EQ(2 * num(st.at("f16"), "bytes"), num(st.at("f32"), "bytes")) << counts;
            EXPECT_GT(num(st.at("f32"), "ns_per_lookup"), 0.0);
        }
    expect_svg(candle_report() + "/near_light_E3_resolution.svg");
}

// The methods on the same queries: the table holds the scene's error; the thin-medium
// closed form (Gath 2008 §4.2) tends to 0 as S → ∞ (docs/PHYSICS.md §1.3), so on a thick medium it is off by far more.
TEST(Report, MethodsCompareTheTableWithTheClosedForms) {
    const auto rows = read_csv(candle_report() + "/near_light_E3_methods.csv");
    std::map<std::string, Row> m;
    for (const Row &r : rows) m[r.at("method")] = r;
    ASSERT_EQ(m.size(), 4u);
    EXPECT_EQ(m.at("exact").at("max_rel"), "reference");
    EXPECT_LE(num(m.at("table"), "max_rel"), 0.02);
    EXPECT_GT(num(m.at("thin"), "max_rel"), 10 * num(m.at("table"), "max_rel"));
    EXPECT_GT(num(m.at("distant"), "median_rel"), num(m.at("table"), "median_rel"));
    for (const auto &[name, r] : m) EXPECT_GT(num(r, "ns_per_call"), 0.0) << name;
    expect_svg(candle_report() + "/near_light_E3_methods.svg");
    const std::string md = read_file(candle_report() + "/report.md");
    EXPECT_NE(md.find("## near_light_E3"), std::string::npos);
    EXPECT_NE(md.find("candle_wax.toml"), std::string::npos) << "the report names the command that produced it";
    // The closed forms name the paper they come from (docs/PHYSICS.md §1.3).
    EXPECT_NE(md.find("| thin | thin-medium closed form, Gath 2008 §4.2 "), std::string::npos) << md;
    EXPECT_NE(md.find("| distant | distant-light limit, Gath 2008 eq. 5 "), std::string::npos) << md;
}

// The anisotropic near-light kinds (Henyey–Greenstein phase) on the example that asks for them
// (examples/scenes/forward_near_light.toml: thick skin, g = 0.8; a smoke slab, g = 0.6;
// accepted error 0.03): each kind's tolerance rungs meet their tolerance, its resolution
// ladder has rows whose errors are finite (f16 and f32 at every count) and shrink from the
// coarsest to the finest, the planned row and the table method hold the scene's error, and the
// report's section names the kind.
TEST(Report, AnisotropicNearLightLaddersHoldTheScenesError) {
    const std::string &dir = forward_near_light_report();
    const std::string md = read_file(dir + "/report.md");
    for (const std::string kind : {"near_light_E3_hg_g0.8", "near_light_E4_hg_g0.6"}) {
        SCOPED_TRACE(kind);
        expect_rungs_meet_their_tolerance(dir + "/" + kind + "_tolerance.csv");
        const auto res = read_csv(dir + "/" + kind + "_resolution.csv");
        ASSERT_GE(res.size(), 6u);
        for (const Row &r : res) {
            for (const char *key : {"table_max_rel", "radiance_max_rel", "radiance_p99_rel", "radiance_median_rel"}) {
                EXPECT_TRUE(std::isfinite(num(r, key))) << r.at("counts") << " " << key;
                EXPECT_GT(num(r, key), 0.0) << r.at("counts") << " " << key;
            }
            EXPECT_GT(num(r, "queries"), 400.0);
        }
        const auto [planned, coarsest, finest] = ladder_ends(res);
        ASSERT_NE(planned, nullptr);
        EXPECT_LE(num(*planned, "radiance_max_rel"), 0.03);
        ASSERT_NE(coarsest, finest);
        EXPECT_LT(num(*finest, "radiance_max_rel"), num(*coarsest, "radiance_max_rel"));
        std::map<std::string, Row> m;
        for (const Row &r : read_csv(dir + "/" + kind + "_methods.csv")) m[r.at("method")] = r;
        ASSERT_EQ(m.size(), 4u);
        EXPECT_EQ(m.at("exact").at("max_rel"), "reference");
        EXPECT_TRUE(std::isfinite(num(m.at("table"), "max_rel")));
        EXPECT_LE(num(m.at("table"), "max_rel"), 0.03);
        EXPECT_GT(num(m.at("distant"), "median_rel"), num(m.at("table"), "median_rel"));
        for (const char *chart : {"_tolerance.svg", "_resolution.svg", "_methods.svg"}) expect_svg(dir + "/" + kind + chart);
        EXPECT_NE(md.find("## " + kind), std::string::npos) << md;
    }
    EXPECT_NE(md.find("forward_near_light.toml"), std::string::npos) << "the report names the command that produced it";
}

TEST(Report, SceneWithoutTablesSaysSo) {
    const std::string d = slut_test::temp_stem("report_ocean");
    fs::remove_all(d);
    const auto r = slut_test::run_scatterlut("report --scene " + kScenes + "ocean_sun.toml --out " + d);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const std::string md = read_file(d + "/report.md");
    EXPECT_NE(md.find("no table"), std::string::npos) << md;
    size_t files = 0;
    for (const auto &e : fs::directory_iterator(d)) files += e.is_regular_file();
    EXPECT_EQ(files, 1u) << "only report.md";
}

TEST(Report, BadSceneExits2AndWritesNothing) {
    const std::string bad = slut_test::temp_stem("report_bad") + ".toml";
    std::ofstream(bad) << "[[medium]]\nname = \"fog\"\nsigma_s_per_m = -1\n";
    const std::string d = slut_test::temp_stem("report_bad_out");
    fs::remove_all(d);
    const auto r = slut_test::run_scatterlut("report --scene " + bad + " --out " + d);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(bad + ":3"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(d));
}
