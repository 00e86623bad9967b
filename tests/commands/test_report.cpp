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
#include <stdlib.h>

#include "cli_runner.hpp"

#ifndef SLUT_REPORT_HAVE_EGL
#define SLUT_REPORT_HAVE_EGL 0
#endif
#ifndef SLUT_REQUIRE_SHADER_TESTS
#define SLUT_REQUIRE_SHADER_TESTS 0
#endif

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

// ---------------------------------------------------------------- the GPU section

// The section of report.md from its heading on ("" if absent).
std::string gpu_section(const std::string &dir) {
    const std::string md = read_file(dir + "/report.md");
    const size_t at = md.find("\n## On the GPU: the snippets' tiers\n");
    return at == std::string::npos ? std::string() : md.substr(at);
}

// GPU rows and CPU rows of <table>_gpu.csv files, by name (a GPU tier's name is its tier, made
// unique by its table: "fast airlight_rational").
struct GpuRows {
    std::map<std::string, Row> gpu, cpu;
    void add(const std::string &csv) {
        for (const Row &r : read_csv(csv)) {
            if (r.at("side") == "gpu")
                gpu[r.at("method") + (r.at("table") == "-" ? "" : " " + r.at("table"))] = r;
            else
                cpu[r.at("method")] = r;
        }
    }
};
GpuRows gpu_rows(const std::string &csv) {
    GpuRows out;
    out.add(csv);
    return out;
}

// Whether the section was measured; a report that could not draw at all (no EGL context: the
// section says so before its first table) skips the test (it fails where the build asked for the
// shader tests, SCATTERLUT_REQUIRE_SHADER_TESTS). A table that could not be drawn in a measured
// section (a shader that does not compile, say) is a failure: its rows are missing.
#define SLUT_GPU_SECTION_OR_SKIP(dir)                                                                                  \
    do {                                                                                                               \
        const std::string section = gpu_section(dir);                                                                  \
        ASSERT_FALSE(section.empty()) << (dir) << ": report.md has no GPU section";                                    \
        const size_t not_measured = section.find("**Not measured:**");                                                 \
        if (not_measured != std::string::npos && not_measured < section.find("\n### ")) {                              \
            const std::string why = section.substr(not_measured, section.find('\n', not_measured) - not_measured);     \
            if (SLUT_REPORT_HAVE_EGL && SLUT_REQUIRE_SHADER_TESTS) FAIL() << why;                                      \
            GTEST_SKIP() << why;                                                                                       \
        }                                                                                                              \
    } while (0)

// Every tier of `tiers` of table `table`: finite positive costs, finite errors within the
// scene's accepted error, and the same errors as the C++ runtime on the same table (`cpu_table`,
// its CPU row): the snippet samples as the runtime does, in float (docs/SHADERS.md: ~1e-5).
void expect_tiers(const GpuRows &rows, const std::string &table, const std::vector<std::string> &tiers,
                  const std::string &cpu_table, double accepted) {
    ASSERT_TRUE(rows.cpu.count(cpu_table)) << cpu_table;
    const double cpu_max = num(rows.cpu.at(cpu_table), "max_rel"),
                 cpu_median = num(rows.cpu.at(cpu_table), "median_rel");
    for (const std::string &tier : tiers) {
        const std::string key = tier + " " + table;
        SCOPED_TRACE(key);
        ASSERT_TRUE(rows.gpu.count(key)) << "no GPU row for tier " << tier << " of " << table;
        const Row &r = rows.gpu.at(key);
        EXPECT_EQ(r.at("tier"), tier);
        EXPECT_TRUE(std::isfinite(num(r, "ns")));
        EXPECT_GT(num(r, "ns_per_pixel_frame"), 0.0);
        EXPECT_GT(num(r, "ratio_to_baseline"), 0.0);
        EXPECT_GT(num(r, "queries"), 100.0);
        for (const char *key_rel : {"median_rel", "p99_rel", "max_rel"})
            EXPECT_TRUE(std::isfinite(num(r, key_rel))) << key_rel;
        EXPECT_LE(num(r, "max_rel"), accepted);
        EXPECT_NEAR(num(r, "max_rel"), cpu_max, 0.05 * cpu_max + 2e-5);
        EXPECT_NEAR(num(r, "median_rel"), cpu_median, 0.05 * cpu_median + 2e-5);
    }
}

// fog_street.toml plans airlight_F and airlight_rational (the airlight snippet: no tier on the
// first, fast and accurate on the second, over the same queries, one group) and the surface
// tables of exponents 1 and 50 (the surface snippet, each in every tier). Every tier holds the
// scene's accepted error (0.005) with the C++ runtime's error; the airlight tiers hold the fast
// tier's radiance target of docs/SHADERS.md ("Tiers": sized for 1e-3); Sun et al. 2005's
// two-fetch form on its plain 64 x 64 F table and the engines' closed form are further off.
TEST(Report, GpuSectionDrawsEveryTierOfTheAirlightAndSurfaceTables) {
    SLUT_GPU_SECTION_OR_SKIP(fog_report());
    const GpuRows rows = gpu_rows(fog_report() + "/airlight_F_gpu.csv");
    ASSERT_FALSE(fs::exists(fog_report() + "/airlight_rational_gpu.csv")) << "one group for the airlight snippet";
    GpuRows diffuse = gpu_rows(fog_report() + "/surface_G0_gpu.csv");
    expect_tiers(rows, "airlight_F", {"none"}, "table (airlight_F)", 0.005);
    expect_tiers(rows, "airlight_rational", {"fast", "accurate"}, "table (airlight_rational)", 0.005);
    expect_tiers(diffuse, "surface_G0", {"fast", "accurate", "none"}, "table", 0.005);
    for (const char *tier : {"fast airlight_rational", "accurate airlight_rational", "none airlight_F"}) {
        ASSERT_TRUE(rows.gpu.count(tier)) << tier;
        EXPECT_LE(num(rows.gpu.at(tier), "max_rel"), 1e-3) << tier;
    }
    ASSERT_TRUE(rows.gpu.count("sun2005") && rows.gpu.count("closed"));
    EXPECT_GT(num(rows.gpu.at("sun2005"), "max_rel"), 10 * num(rows.gpu.at("fast airlight_rational"), "max_rel"));
    EXPECT_GT(num(rows.gpu.at("closed"), "median_rel"), 10 * num(rows.gpu.at("fast airlight_rational"), "median_rel"));
    EXPECT_EQ(num(rows.gpu.at("sun2005"), "ratio_to_baseline"), 1.0) << "the airlight's baseline";
    // The Phong table's group: its own file, its own queries' exact S_n.
    expect_tiers(gpu_rows(fog_report() + "/surface_G50_gpu.csv"), "surface_G50", {"fast", "accurate", "none"}, "table",
                 0.005);
    for (const char *svg : {"/airlight_F_gpu.svg", "/surface_G0_gpu.svg", "/surface_G50_gpu.svg"})
        expect_svg(fog_report() + svg);
    const std::string section = gpu_section(fog_report());
    EXPECT_NE(section.find("### airlight_F, airlight_rational (`scatterlut_airlight.glsl`)"), std::string::npos)
        << section;
    EXPECT_NE(section.find("llvmpipe"), std::string::npos) << "the section says what drew";
}

// The near-light tables in every tier of their snippet (candle_wax.toml: E3; forward_near_light.toml:
// E3 and E4 with a Henyey-Greenstein phase), each with the thin-medium form as the baseline.
TEST(Report, GpuSectionDrawsEveryTierOfTheNearLightTables) {
    SLUT_GPU_SECTION_OR_SKIP(candle_report());
    const GpuRows candle = gpu_rows(candle_report() + "/near_light_E3_gpu.csv");
    expect_tiers(candle, "near_light_E3", {"fast", "accurate", "none"}, "table", 0.02);
    ASSERT_TRUE(candle.gpu.count("thin") && candle.gpu.count("fast near_light_E3"));
    EXPECT_EQ(num(candle.gpu.at("thin"), "ratio_to_baseline"), 1.0);
    EXPECT_GT(num(candle.gpu.at("thin"), "max_rel"), 10 * num(candle.gpu.at("fast near_light_E3"), "max_rel"));
    expect_svg(candle_report() + "/near_light_E3_gpu.svg");
    for (const std::string kind : {"near_light_E3_hg_g0.8", "near_light_E4_hg_g0.6"}) {
        expect_tiers(gpu_rows(forward_near_light_report() + "/" + kind + "_gpu.csv"), kind,
                     {"fast", "accurate", "none"}, "table", 0.03);
        expect_svg(forward_near_light_report() + "/" + kind + "_gpu.svg");
    }
}

// Without a GPU measurement the report still succeeds and says why: --no-gpu, and a run where
// EGL offers no surfaceless platform (glvnd finds no vendor library); no GPU files then.
TEST(Report, GpuSectionSaysWhyItWasNotMeasured) {
    const std::string d = slut_test::temp_stem("report_no_gpu");
    const std::string args = "report --scene " + kScenes + "candle_wax.toml --out " + d + " --rounds 1 --queries 200";
    fs::remove_all(d);
    auto r = slut_test::run_scatterlut(args + " --no-gpu");
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    std::string section = gpu_section(d);
    EXPECT_NE(section.find("**Not measured:** the run was given --no-gpu."), std::string::npos) << section;
    EXPECT_NE(section.find("- near_light_E3 (scatterlut_nearlight.glsl)"), std::string::npos) << section;
    EXPECT_FALSE(fs::exists(d + "/near_light_E3_gpu.csv"));

    fs::remove_all(d);
    setenv("__EGL_VENDOR_LIBRARY_FILENAMES", (d + "_no_vendor.json").c_str(), 1); // no EGL driver
    r = slut_test::run_scatterlut(args);
    unsetenv("__EGL_VENDOR_LIBRARY_FILENAMES");
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    section = gpu_section(d);
    const std::string why = SLUT_REPORT_HAVE_EGL ? "**Not measured:** no OpenGL 4.3 context through EGL: "
                                                 : "**Not measured:** this scatterlut was built without the EGL";
    EXPECT_NE(section.find(why), std::string::npos) << section;
    EXPECT_FALSE(fs::exists(d + "/near_light_E3_gpu.csv"));
    fs::remove_all(d);
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
