// eval's surface quantities (host/src/kinds/surface_runtime.cpp; docs/PHYSICS.md §1.5), run as
// the built executable without tables: "surface" (E_ss) and "surface_specular" (S_n) answer
// "exact" against the mpmath values of tests/reference/surface_ref.json, "table": null (no
// --table given), the direct term and, for "surface", the no-extinction bound; bad
// input is an error line naming the field. With --table of saved surface_G tables (filled by
// quadrature, scatterlut/surface_table.hpp) "table" answers from the table of the query's
// exponent (1 for "surface") where T = σ_t D lies in its domain, null otherwise.
#include <cmath>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "reference_data.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/surface_table.hpp"

namespace {

using slut_test::json_lines;
using slut_test::run_scatterlut;

TEST(SurfaceEval, ExactMatchesTheMpmathReferences) {
    const nlohmann::json file = slut_test::load_json("surface_ref.json");
    std::ostringstream input;
    std::vector<long double> want;
    for (const auto &c : file.at("cases")) {
        nlohmann::json q = {{"quantity", c.at("quantity")}, {"sigma_s", c.at("sigma_s")}, {"sigma_a", c.at("sigma_a")},
                            {"intensity", c.at("intensity")}, {"distance", c.at("distance")}};
        if (c.at("quantity") == "surface") {
            q["theta_s"] = c.at("theta");
        } else {
            q["theta_r"] = c.at("theta");
            q["exponent"] = c.at("exponent");
        }
        input << q.dump() << "\n";
        want.push_back(slut_test::ref_number(c.at("E")));
    }
    const auto r = run_scatterlut("eval", input.str());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = json_lines(r.out);
    ASSERT_EQ(lines.size(), want.size());
    ASSERT_GE(lines.size(), 80u);
    double worst = 0.0;
    for (size_t i = 0; i < lines.size(); ++i) {
        const auto &a = lines[i];
        ASSERT_TRUE(a.contains("exact") && a.at("exact").is_number()) << a.dump();
        const double e = a.at("exact").get<double>(), w = (double)want[i];
        const double err = std::fabs(e - w) / w;
        worst = std::fmax(worst, err);
        EXPECT_LE(err, 1e-12) << a.dump();
        EXPECT_TRUE(a.at("table").is_null()) << a.dump();
        ASSERT_TRUE(a.at("direct").is_number()) << a.dump();
        // The direct term from the query itself: I0 e^{−σ_t D} max(cos θ, 0)^n / D².
        const double st = a.at("sigma_s").get<double>() + a.at("sigma_a").get<double>(), D = a.at("distance").get<double>();
        const bool diffuse = a.at("quantity") == "surface";
        const double theta = a.at(diffuse ? "theta_s" : "theta_r").get<double>();
        const int n = diffuse ? 1 : a.at("exponent").get<int>();
        const double direct = a.at("intensity").get<double>() * std::exp(-st * D) * std::pow(std::fmax(std::cos(theta), 0.0), n) / (D * D);
        EXPECT_NEAR(a.at("direct").get<double>(), direct, 1e-14 * std::fmax(direct, 1e-300)) << a.dump();
        if (diffuse) { // extinction only removes light: the no-extinction closed form bounds E_ss
            ASSERT_TRUE(a.at("no_extinction").is_number()) << a.dump();
            EXPECT_GE(a.at("no_extinction").get<double>(), e) << a.dump();
        }
    }
    RecordProperty("worst_rel_err", std::to_string(worst));
}

TEST(SurfaceEval, BadInputIsAnErrorLineNamingTheField) {
    const std::string base = R"("sigma_s":0.05,"sigma_a":0.01,"intensity":100,"distance":10)";
    const struct {
        std::string line, expect;
    } cases[] = {
        {R"({"quantity":"surface",)" + base + R"(,"theta_s":3.5})", "theta_s"},
        {R"({"quantity":"surface",)" + base + R"(})", "theta_s"},
        {R"({"quantity":"surface_specular",)" + base + R"(,"theta_r":0.3})", "exponent"},
        {R"({"quantity":"surface_specular",)" + base + R"(,"theta_r":0.3,"exponent":2.5})", "exponent"},
        {R"({"quantity":"surface_specular",)" + base + R"(,"theta_r":0.3,"exponent":0})", "exponent"},
        {R"({"quantity":"surface_specular",)" + base + R"(,"theta_r":0.3,"exponent":"20"})", "exponent"},
        {R"({"quantity":"surface_specular",)" + base + R"(,"theta_r":-1,"exponent":20})", "theta_r"},
        {R"({"quantity":"surface","sigma_s":-1,"sigma_a":0.01,"intensity":100,"distance":10,"theta_s":1})", "sigma_s"},
        {R"({"quantity":"surface","sigma_s":0.05,"sigma_a":0.01,"intensity":100,"distance":0,"theta_s":1})", "distance"},
        {R"({"quantity":"surface","phase_g":0.3,)" + base + R"(,"theta_s":1})", "phase_g"},
    };
    std::string input;
    for (const auto &c : cases) input += c.line + "\n";
    const auto r = run_scatterlut("eval", input);
    const auto lines = json_lines(r.out);
    ASSERT_EQ(lines.size(), std::size(cases));
    for (size_t i = 0; i < lines.size(); ++i) {
        ASSERT_TRUE(lines[i].contains("error")) << cases[i].line << " -> " << lines[i].dump();
        EXPECT_NE(lines[i].at("error").get<std::string>().find(cases[i].expect), std::string::npos)
            << cases[i].line << " -> " << lines[i].dump();
        EXPECT_NE(lines[i].at("error").get<std::string>().find("line " + std::to_string(i + 1) + ":"), std::string::npos);
    }
}

TEST(SurfaceEval, LightBelowTheHorizonStillLitAndZeroWithoutScattering) {
    const auto r = run_scatterlut(
        "eval", R"({"quantity":"surface","sigma_s":0.05,"sigma_a":0.01,"intensity":100,"distance":10,"theta_s":3.141592653589793})"
                "\n"
                R"({"quantity":"surface","sigma_s":0,"sigma_a":0.01,"intensity":100,"distance":10,"theta_s":1})"
                "\n");
    const auto lines = json_lines(r.out);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_GT(lines[0].at("exact").get<double>(), 0.0);
    EXPECT_EQ(lines[0].at("direct").get<double>(), 0.0);
    EXPECT_EQ(lines[1].at("exact").get<double>(), 0.0);
}


TEST(SurfaceEval, TableAnswersFromTheTableOfTheQuerysExponent) {
    // A Phong n = 20 table and a diffuse one, both on T ∈ [0, 30]; 48 × 49 nodes: the G_n
    // tables' measured error at this size is below 1e-2 (tests/runtime/test_surface_table.cpp).
    const std::string lobe = slut_test::temp_stem("surface_G_n20") + ".slut";
    const std::string diffuse = slut_test::temp_stem("surface_G_n1") + ".slut";
    scatterlut::save_binary(scatterlut::surface_G_table_by_quadrature(20, 30.0, 48, 49), lobe);
    scatterlut::save_binary(scatterlut::surface_G_table_by_quadrature(1, 30.0, 32, 33), diffuse);
    const auto query = [](const char *quantity, double distance_m, double theta, int exponent) {
        nlohmann::json q = {{"quantity", quantity}, {"sigma_s", 0.3}, {"sigma_a", 0.1}, {"intensity", 50.0},
                            {"distance", distance_m}};
        if (exponent == 0) q["theta_s"] = theta;
        else q["theta_r"] = theta, q["exponent"] = exponent;
        return q.dump() + "\n";
    };
    std::string input;
    const double thetas[] = {0.0, 0.05, 0.3, 1.5707963267948966, 3.141592653589793};
    for (double theta : thetas) input += query("surface_specular", 20.0, theta, 20); // T = 8: the n = 20 table
    input += query("surface_specular", 20.0, 0.3, 1);   // the diffuse table answers S_1
    input += query("surface", 20.0, 0.3, 0);            // and E_ss
    input += query("surface_specular", 20.0, 0.3, 21);  // no table of exponent 21: null
    input += query("surface_specular", 100.0, 0.3, 20); // T = 40 > 30: null
    const auto r = run_scatterlut("eval --table " + lobe + " --table " + diffuse, input);
    std::remove(lobe.c_str());
    std::remove(diffuse.c_str());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = json_lines(r.out);
    ASSERT_EQ(lines.size(), std::size(thetas) + 4);
    for (size_t i = 0; i < std::size(thetas) + 2; ++i) {
        const auto &a = lines[i];
        ASSERT_TRUE(a.at("table").is_number() && a.at("exact").is_number()) << a.dump();
        const double table = a.at("table").get<double>(), exact = a.at("exact").get<double>();
        EXPECT_GT(table, 0.0) << a.dump();
        EXPECT_NEAR(table / exact, 1.0, 1e-2) << a.dump();
    }
    for (size_t i = std::size(thetas) + 2; i < lines.size(); ++i) {
        EXPECT_TRUE(lines[i].at("table").is_null()) << lines[i].dump();
        EXPECT_TRUE(lines[i].at("exact").is_number()) << lines[i].dump();
    }
}

} // namespace
