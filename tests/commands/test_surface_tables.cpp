// The surface tables of Sun et al. 2005 as a table kind (host/src/kinds/surface_kind.cpp,
// kernels/surface_G.cl; docs/SCENES.md, docs/FORMAT.md), run as the built executable: `plan
// --json` lists surface_G0 (diffuse) and surface_G<n> (Phong) only for a scene with lit
// surfaces; `generate` writes them and `validate` (Boost.Math's independent quadrature at the
// nodes, new random points) passes; eval's "surface" / "surface_specular" answer "table" from
// them within the scene's accepted error of "exact"; the fixed rule of the kernel (slut_surface_G_fixed)
// meets its integration tolerance against the adaptive quadrature; a hostile scene is refused.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/surface.hpp"

extern "C" {
#include "slut_surface.h"
}

namespace {

using slut_test::RunResult;

// A foggy street: σ_s 0.05, σ_a 0.005 /m, lamps 0.5–20 m from the lit surfaces (T ≤ 1.1),
// diffuse and Phong n = 20, 2 % accepted (small tables: the test stays short).
const char *const kFog = "name = \"street\"\n[accuracy]\nrelative_error = 0.02\n[[medium]]\nname = \"fog\"\n"
                         "sigma_s_per_m = 0.05\nsigma_a_per_m = 0.005\nviewer_inside = true\n";
const char *const kSurfaces = "surfaces = { diffuse = true, phong_exponents = [20], light_distance_m = [0.5, 20] }\n";
const char *const kLamp = "[[light]]\nname = \"lamp\"\ntype = \"point\"\nintensity_W_per_sr = 300\ndistance_m = [2, 80]\n";
constexpr double kAcceptedRel = 0.02;

std::string write_scene(const std::string &tag, const std::string &text) {
    const std::string path = slut_test::temp_stem(tag) + ".toml";
    std::ofstream(path) << text;
    return path;
}

std::set<std::string> stems_of(const nlohmann::json &plan) {
    std::set<std::string> stems;
    for (const auto &t : plan.at("tables")) stems.insert(t.at("file_stem").get<std::string>());
    return stems;
}

TEST(SurfaceTables, PlanListsThemOnlyForAScenesWithSurfaces) {
    const std::string with = write_scene("surf_with", std::string(kFog) + kSurfaces + kLamp);
    const RunResult r = slut_test::run_scatterlut("plan --json --scene " + with);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json plan = nlohmann::json::parse(r.out);
    EXPECT_EQ(stems_of(plan), (std::set<std::string>{"airlight_F", "surface_G0", "surface_G20", "airlight_rational"}));
    for (const auto &t : plan.at("tables")) {
        if (t.at("kind") != "surface_G") continue;
        EXPECT_EQ(t.at("exponent").get<int>(), t.at("file_stem") == "surface_G0" ? 1 : 20);
        EXPECT_TRUE(t.at("reached").get<bool>()) << t.at("verdict");
        EXPECT_LE(t.at("predicted_max_rel").get<double>(), kAcceptedRel);
        EXPECT_LE(t.at("integration_max_rel").get<double>(), 1e-9); // the kernel's rule at tolerance 1e-10
        EXPECT_NEAR(t.at("axes")[0].at("max").get<double>(), 0.055 * 20, 1e-12); // T_max = σ_t·D_max
    }
    const std::string without = write_scene("surf_without", std::string(kFog) + kLamp);
    const RunResult n = slut_test::run_scatterlut("plan --json --scene " + without);
    ASSERT_EQ(n.exit_code, 0) << n.err;
    EXPECT_EQ(stems_of(nlohmann::json::parse(n.out)), (std::set<std::string>{"airlight_F", "airlight_rational"}));
    std::filesystem::remove(with);
    std::filesystem::remove(without);
}

// generate + validate, then eval with the tables: "table" within the scene's error of "exact".
TEST(SurfaceTables, GenerateValidateAndEvalWithinTheScenesError) {
    const std::string scene = write_scene("surf_gen", std::string(kFog) + kSurfaces + kLamp);
    const std::string dir = slut_test::temp_stem("surf_gen_out");
    std::filesystem::remove_all(dir);
    const RunResult gen = slut_test::run_scatterlut("generate --scene " + scene + " --out " + dir + " --format bin");
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
    for (const char *stem : {"surface_G0", "surface_G20"}) {
        const scatterlut::Table t = scatterlut::load_table(dir + "/" + stem + ".slut");
        EXPECT_EQ(t.kind, "surface_G");
        EXPECT_LE(t.accuracy.sampling_max_rel, kAcceptedRel) << stem;
        EXPECT_LE(t.accuracy.integration_max_rel, 1e-9) << stem;
    }
    const RunResult val = slut_test::run_scatterlut("validate --nodes 200 --points 2000 " + dir + "/surface_G0.slut " + dir +
                                                    "/surface_G20.slut");
    EXPECT_EQ(val.exit_code, 0) << val.out << val.err;
    // The node check names the surface kind's own independent reference, not the airlight's.
    EXPECT_NE(val.out.find("exp_sinh along each ray"), std::string::npos) << val.out;
    std::printf("%s", val.out.c_str());

    // Queries over the scene's domain (D ≤ 20 m, every θ), both tables loaded.
    std::ostringstream input;
    const double pi = 3.14159265358979323846;
    int queries = 0;
    for (double D : {0.5, 3.0, 11.0, 20.0})
        for (double theta : {0.0, 0.4, pi / 2, 2.5, pi}) {
            const nlohmann::json base = {{"sigma_s", 0.05}, {"sigma_a", 0.005}, {"intensity", 300.0}, {"distance", D}};
            nlohmann::json diffuse = base, specular = base;
            diffuse["quantity"] = "surface";
            diffuse["theta_s"] = theta;
            specular["quantity"] = "surface_specular";
            specular["theta_r"] = theta;
            specular["exponent"] = 20;
            input << diffuse.dump() << "\n" << specular.dump() << "\n";
            queries += 2;
        }
    const RunResult ev = slut_test::run_scatterlut("eval --table " + dir + "/surface_G0.slut --table " + dir +
                                                   "/surface_G20.slut", input.str());
    ASSERT_EQ(ev.exit_code, 0) << ev.err;
    const auto lines = slut_test::json_lines(ev.out);
    ASSERT_EQ(static_cast<int>(lines.size()), queries);
    double worst = 0;
    for (const auto &a : lines) {
        ASSERT_TRUE(a.at("table").is_number() && a.at("exact").is_number()) << a.dump();
        const double table = a.at("table").get<double>(), exact = a.at("exact").get<double>();
        EXPECT_GT(table, 0.0) << a.dump();
        worst = std::max(worst, std::fabs(table / exact - 1.0));
    }
    EXPECT_LE(worst, kAcceptedRel);
    std::printf("eval table vs exact over %d surface queries: max rel %.3g (accepted %.3g)\n", queries, worst, kAcceptedRel);
    std::filesystem::remove_all(dir);
    std::filesystem::remove(scene);
}

// The kernel's fixed rule at the production tolerance 1e-10 (4 panels per interval) against the
// adaptive Gauss–Kronrod quadrature of the runtime (surface_G_exact, ~1e-10) at the hard places:
// T → 0 and large, θ at 0, π/2, π and past the horizon, narrow lobes (n = 1000).
TEST(SurfaceTables, KernelRuleMeetsItsTolerance) {
    const double pi = 3.14159265358979323846;
    const int subpanels = slut_surface_subpanels_for_tolerance(1e-10);
    double worst = 0;
    for (int n : {1, 2, 50, 1000})
        for (double T : {0.0, 1e-3, 0.7, 3.0, 40.0})
            for (double theta : {0.0, 0.3, pi / 2, 1.9, pi}) {
                const double exact = scatterlut::surface_G_exact(n, T, theta);
                const double fixed = slut_surface_G_fixed(n, T, theta, subpanels);
                ASSERT_TRUE(std::isfinite(fixed) && fixed > 0) << n << " " << T << " " << theta;
                worst = std::max(worst, std::fabs(fixed - exact) / exact);
            }
    // 2e-10: the rule's ~1e-10 plus the adaptive reference's own ~1e-10.
    EXPECT_LE(worst, 2e-10);
    std::printf("fixed rule (%d panels) vs surface_G_exact: max rel %.3g\n", subpanels, worst);
}

// A hostile scene: surfaces in a medium seen from outside, an exponent beyond 1000: exit 2 with
// the file:line and key, before any device work.
TEST(SurfaceTables, HostileScenesRefused) {
    const std::string outside = write_scene(
        "surf_outside", "[[medium]]\nname = \"wax\"\nsigma_s_per_m = 1\nsigma_a_per_m = 0\nviewer_inside = false\n"
                        "thick = true\nsurfaces = { diffuse = true, light_distance_m = [1, 2] }\n" + std::string(kLamp));
    const RunResult a = slut_test::run_scatterlut("plan --scene " + outside, "", true);
    EXPECT_EQ(a.exit_code, 2) << a.out;
    EXPECT_NE(a.out.find(outside + ":7:"), std::string::npos) << a.out;
    EXPECT_NE(a.out.find("key 'medium[0].surfaces': expected no such key"), std::string::npos) << a.out;
    const std::string narrow = write_scene("surf_narrow", std::string(kFog) +
                                                              "surfaces = { phong_exponents = [5000], light_distance_m = [1, 2] }\n" +
                                                              kLamp);
    const RunResult b = slut_test::run_scatterlut("generate --scene " + narrow + " --out " +
                                                      slut_test::temp_stem("surf_narrow_out"), "", true);
    EXPECT_EQ(b.exit_code, 2) << b.out;
    EXPECT_NE(b.out.find("key 'medium[0].surfaces.phong_exponents[0]': expected an integer Phong exponent in [1, 1000], got 5000"),
              std::string::npos) << b.out;
    EXPECT_FALSE(std::filesystem::exists(slut_test::temp_stem("surf_narrow_out")));
    std::filesystem::remove(outside);
    std::filesystem::remove(narrow);
}

} // namespace
