// Anisotropic (Henyey–Greenstein) and coloured media end to end through the command line:
// eval's "phase_g" and per-channel coefficients against the independent references
// (tests/reference/hg_ref.json), bad input, and the extremes (g = ±0.99, γ at 0 and π, one
// channel clear while another is dense) never answering NaN or a negative radiance; the
// anisotropic airlight tables a scene with g ≠ 0 gets (plan --json), and their radiance
// through eval against the exact one.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {

using slut_test::json_lines;
using slut_test::run_scatterlut;

nlohmann::json hg_references() {
    std::ifstream in(std::string(SLUT_REFERENCE_DIR) + "/hg_ref.json");
    EXPECT_TRUE(in.good()) << "tests/reference/hg_ref.json";
    return nlohmann::json::parse(in);
}

// The query of a reference case: every field but the reference value L.
nlohmann::json query_of(const nlohmann::json &c) {
    nlohmann::json q = c;
    q.erase("L");
    return q;
}

std::vector<nlohmann::json> eval_lines(const std::vector<nlohmann::json> &queries, const std::string &args = "") {
    std::string input;
    for (const auto &q : queries) input += q.dump() + "\n";
    const slut_test::RunResult r = run_scatterlut("eval" + args, input);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<nlohmann::json> out = json_lines(r.out);
    EXPECT_EQ(out.size(), queries.size());
    return out;
}

// Every reference case (airlight and near light, g from −0.9 to 0.99): eval's exact within
// 1e-9 relative, and the table null (no table given).
TEST(AnisotropicEval, ExactMatchesTheReferences) {
    const nlohmann::json ref = hg_references();
    std::vector<nlohmann::json> queries;
    for (const auto &c : ref["cases"]) queries.push_back(query_of(c));
    ASSERT_GE(queries.size(), 70u);
    const std::vector<nlohmann::json> out = eval_lines(queries);
    double worst = 0;
    for (size_t i = 0; i < out.size() && i < queries.size(); ++i) {
        const double expected = std::stod(ref["cases"][i]["L"].get<std::string>());
        ASSERT_TRUE(out[i].contains("exact") && out[i]["exact"].is_number()) << out[i].dump();
        const double got = out[i]["exact"].get<double>();
        const double rel = std::fabs(got - expected) / expected;
        worst = std::max(worst, rel);
        EXPECT_LE(rel, 1e-9) << out[i].dump();
        EXPECT_TRUE(out[i]["table"].is_null()) << out[i].dump();
        EXPECT_EQ(out[i]["phase_g"], queries[i]["phase_g"]); // echoed
    }
    std::printf("eval exact vs hg_ref.json: max rel %.3g over %zu cases\n", worst, out.size());
}

// phase_g absent and phase_g = 0 are the same answer; arrays of 3 give arrays of 3 answers,
// each channel equal to its scalar query; a grey triple equals the number.
TEST(AnisotropicEval, ChannelsAreScalarQueries) {
    const nlohmann::json air = {{"quantity", "airlight"}, {"sigma_s", 0.3}, {"sigma_a", 0.1}, {"intensity", 2},
                                {"distance", 5},          {"gamma", 0.7},   {"length", 12}};
    const nlohmann::json near = {{"quantity", "near_light"}, {"sigma_s", 2.0},
                                 {"sigma_a", 0.5},           {"intensity", 1.0},
                                 {"normal", {0, 0, 1}},      {"eye_dir", {0.2873478855663454, 0, 0.9578262852211513}},
                                 {"light_pos", {0.5, 0.2, 0.01}}, {"length", "inf"}};
    for (const nlohmann::json &base : {air, near}) {
        for (double g : {0.0, 0.85, -0.6}) {
            std::vector<nlohmann::json> qs;
            nlohmann::json q0 = base;
            if (g != 0.0) q0["phase_g"] = g;
            qs.push_back(q0);
            nlohmann::json qz = base;
            qz["phase_g"] = g; // explicit, also 0
            qs.push_back(qz);
            const double ss[3] = {0.3, 1e-3, 4.0}, sa[3] = {0.1, 0.0, 0.2};
            for (int c = 0; c < 3; ++c) {
                nlohmann::json qc = qz;
                qc["sigma_s"] = ss[c];
                qc["sigma_a"] = sa[c];
                qs.push_back(qc);
            }
            nlohmann::json rgb = qz;
            rgb["sigma_s"] = {ss[0], ss[1], ss[2]};
            rgb["sigma_a"] = {sa[0], sa[1], sa[2]};
            qs.push_back(rgb);
            nlohmann::json grey = qz;
            grey["sigma_s"] = {base["sigma_s"], base["sigma_s"], base["sigma_s"]};
            qs.push_back(grey);
            const std::vector<nlohmann::json> out = eval_lines(qs);
            ASSERT_EQ(out.size(), qs.size());
            EXPECT_EQ(out[0]["exact"], out[1]["exact"]) << base["quantity"] << " g=" << g;
            ASSERT_TRUE(out[5]["exact"].is_array()) << out[5].dump();
            ASSERT_EQ(out[5]["exact"].size(), 3u);
            ASSERT_TRUE(out[5]["table"].is_array());
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(out[5]["exact"][c], out[2 + c]["exact"]) << "channel " << c << " g=" << g;
                EXPECT_TRUE(out[5]["table"][c].is_null());
                EXPECT_EQ(out[6]["exact"][c], out[1]["exact"]) << "grey triple, channel " << c;
            }
            if (base["quantity"] == "near_light" && g == 0.0) { // the isotropic closed forms come per channel
                ASSERT_TRUE(out[5]["approx"].is_array()) << out[5].dump();
                ASSERT_TRUE(out[5]["distant"].is_array());
                for (int c = 0; c < 3; ++c) EXPECT_EQ(out[5]["distant"][c], out[2 + c]["distant"]);
            }
        }
    }
}

// Bad input: one error line each, naming the field; processing continues.
TEST(AnisotropicEval, BadInputIsAnErrorLine) {
    const std::string air = R"("quantity":"airlight","intensity":1,"distance":4,"gamma":1,"length":10)";
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"{" + air + R"(,"sigma_s":0.5,"sigma_a":0,"phase_g":1})", "phase_g"},
        {"{" + air + R"(,"sigma_s":0.5,"sigma_a":0,"phase_g":-1.5})", "phase_g"},
        {"{" + air + R"(,"sigma_s":0.5,"sigma_a":0,"phase_g":"forward"})", "phase_g"},
        {"{" + air + R"(,"sigma_s":[0.5,0.2],"sigma_a":0})", "sigma_s"},
        {"{" + air + R"(,"sigma_s":0.5,"sigma_a":[0,0,0,0]})", "sigma_a"},
        {"{" + air + R"(,"sigma_s":[0.5,"x",0.1],"sigma_a":0})", "sigma_s"},
        {"{" + air + R"(,"sigma_s":[0.5,-1,0.1],"sigma_a":0,"phase_g":0.5})", "sigma_s"},
        {R"({"quantity":"F","u":1,"v":0.5,"phase_g":0.5})", "phase_g"},
    };
    std::string input;
    for (const auto &b : bad) input += b.first + "\n";
    input += "{" + air + R"(,"sigma_s":0.5,"sigma_a":0,"phase_g":0.5})" "\n"; // a good line after them
    const slut_test::RunResult r = run_scatterlut("eval", input);
    EXPECT_EQ(r.exit_code, 0) << r.err; // eval answers every line; errors are answer lines
    const std::vector<nlohmann::json> out = json_lines(r.out);
    ASSERT_EQ(out.size(), bad.size() + 1);
    for (size_t i = 0; i < bad.size(); ++i) {
        ASSERT_TRUE(out[i].contains("error")) << bad[i].first << " -> " << out[i].dump();
        EXPECT_NE(out[i]["error"].get<std::string>().find(bad[i].second), std::string::npos) << out[i].dump();
        EXPECT_EQ(out[i]["error"].get<std::string>().rfind("line " + std::to_string(i + 1) + ": ", 0), 0u);
    }
    EXPECT_TRUE(out.back()["exact"].is_number()) << out.back().dump();
}

// The extremes: g = ±0.99, γ at 0 (ray short of the light) and π, one channel clear
// (σ_t = 0) while another is dense: every exact value finite and >= 0.
TEST(AnisotropicEval, ExtremesNeverNaNOrNegative) {
    std::vector<nlohmann::json> qs;
    for (double g : {-0.99, -0.5, 0.0, 0.85, 0.99})
        for (double gamma : {0.0, 1e-9, 1e-4, 1.0, M_PI - 1e-9, M_PI})
            for (double length : {3.0, 1e3}) {
                if (gamma == 0.0 && length >= 5.0) continue; // through the light: diverges (its own note)
                qs.push_back({{"quantity", "airlight"},
                              {"phase_g", g},
                              {"sigma_s", {0.0, 0.2, 50.0}},
                              {"sigma_a", {0.0, 0.0, 30.0}},
                              {"intensity", 1},
                              {"distance", 5},
                              {"gamma", gamma},
                              {"length", length}});
                qs.push_back({{"quantity", "near_light"},
                              {"phase_g", g},
                              {"sigma_s", {1e-12, 0.5, 200.0}},
                              {"sigma_a", {0.0, 0.1, 0.0}},
                              {"intensity", 1},
                              {"normal", {0, 0, 1}},
                              {"eye_dir", {std::sin(gamma / 2), 0, std::cos(gamma / 2)}},
                              {"light_pos", {0.3, 0.0, 0.05}},
                              {"length", length}});
            }
    const std::vector<nlohmann::json> out = eval_lines(qs);
    for (const auto &o : out) {
        ASSERT_TRUE(o.contains("exact") && o["exact"].is_array()) << o.dump();
        for (const auto &v : o["exact"]) {
            ASSERT_TRUE(v.is_number()) << o.dump();
            EXPECT_GE(v.get<double>(), 0.0) << o.dump();
        }
        if (o["quantity"] == "airlight") {
            EXPECT_EQ(o["exact"][0].get<double>(), 0.0) << "clear channel: no scattering";
        }
    }
}

// ------------------------------------------------------------------ the tables
const std::string kForward = std::string(SLUT_SOURCE_DIR) + "/examples/scenes/fog_forward.toml";

// plan --json of the example: exactly one anisotropic airlight table per g (0.85: fog, 0.3:
// the coloured haze), each with its g and its file stem; no isotropic table.
TEST(AnisotropicTables, PlanListsOneTablePerPhase) {
    const slut_test::RunResult r = run_scatterlut("plan --scene " + kForward + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["tables"].size(), 2u) << r.out;
    EXPECT_EQ(j["tables"][0]["kind"], "airlight_Fg");
    EXPECT_EQ(j["tables"][0]["phase_g"], 0.85);
    EXPECT_EQ(j["tables"][0]["file_stem"], "airlight_Fg_g0.85");
    EXPECT_EQ(j["tables"][1]["kind"], "airlight_Fg");
    EXPECT_EQ(j["tables"][1]["phase_g"], 0.3);
    EXPECT_EQ(j["tables"][1]["file_stem"], "airlight_Fg_g0.3");
    for (const auto &t : j["tables"]) {
        EXPECT_TRUE(t["reached"].get<bool>()) << t.dump();
        EXPECT_LE(t["integration_max_rel"].get<double>(), 1e-13);
    }
    // Media that differ only in σ share a table; an isotropic medium beside them keeps its own.
    const std::string base = slut_test::temp_stem("share");
    std::ofstream(base + ".toml") << "[[medium]]\nname = \"a\"\nsigma_s_per_m = 0.1\nsigma_a_per_m = 0\nphase_g = 0.5\n"
                                     "viewer_inside = true\n[[medium]]\nname = \"b\"\nsigma_s_per_m = [0.2, 0.3, 0.9]\n"
                                     "sigma_a_per_m = 0.01\nphase_g = 0.5\nviewer_inside = true\n[[medium]]\nname = \"c\"\n"
                                     "sigma_s_per_m = 0.1\nsigma_a_per_m = 0\nviewer_inside = true\n[[light]]\nname = \"l\"\n"
                                     "type = \"point\"\nintensity_W_per_sr = 1\ndistance_m = [1, 10]\n";
    const slut_test::RunResult s = run_scatterlut("plan --scene " + base + ".toml --json");
    std::filesystem::remove(base + ".toml");
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const nlohmann::json k = nlohmann::json::parse(s.out);
    ASSERT_EQ(k["tables"].size(), 3u) << s.out; // and airlight_rational, for medium c as airlight_F
    EXPECT_EQ(k["tables"][0]["kind"], "airlight_F");
    EXPECT_EQ(k["tables"][0]["phase_g"], 0.0);
    EXPECT_EQ(k["tables"][0]["requested_by"].size(), 1u); // medium c alone
    EXPECT_EQ(k["tables"][1]["file_stem"], "airlight_Fg_g0.5");
    EXPECT_EQ(k["tables"][1]["requested_by"].size(), 2u); // a and b
    EXPECT_EQ(k["tables"][2]["kind"], "airlight_rational");
    EXPECT_EQ(k["tables"][2]["requested_by"].size(), 1u); // medium c alone
    // the densest channel's σ_t = 0.91 times D_max = 10
    EXPECT_NE(k["tables"][1]["requested_by"][1]["need"].get<std::string>().find("u up to sigma_t*D_max = 9.1"),
              std::string::npos);
}

// generate the example, then eval random scene queries (every channel, both g) with the
// tables: within the scene's accepted error (0.01) wherever the attenuation e^{−σ_t D} ≥ 1e-6;
// a query of another g, or an isotropic one, gets "table": null.
TEST(AnisotropicTables, TableRadianceWithinTheScenesError) {
    const std::string dir = slut_test::temp_stem("fogfwd");
    std::filesystem::remove_all(dir);
    const slut_test::RunResult gen = run_scatterlut("generate --scene " + kForward + " --out " + dir + " --format bin");
    ASSERT_EQ(gen.exit_code, 0) << gen.out << gen.err;
    ASSERT_TRUE(std::filesystem::exists(dir + "/airlight_Fg_g0.85.slut"));
    ASSERT_TRUE(std::filesystem::exists(dir + "/airlight_Fg_g0.3.slut"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/airlight_F.slut"));
    const slut_test::RunResult info = run_scatterlut("inspect " + dir + "/airlight_Fg_g0.85.slut --json");
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("\"phase.g\""), std::string::npos) << info.out;

    std::mt19937_64 rng(15);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<nlohmann::json> qs;
    for (int k = 0; k < 600; ++k) {
        const bool fog = k % 2 == 0;
        const double D = 2.0 * std::pow(40.0, unit(rng)); // [2, 80] m
        const double gamma = std::acos(1.0 - 2.0 * unit(rng));
        nlohmann::json length = D * std::exp(std::log(1e-3) + unit(rng) * std::log(1e4));
        if (k % 5 == 4) length = "inf";
        if (gamma < 1e-6) continue;
        nlohmann::json q = {{"quantity", "airlight"}, {"intensity", 300}, {"distance", D}, {"gamma", gamma},
                            {"length", length}};
        if (fog) {
            q["phase_g"] = 0.85;
            q["sigma_s"] = 0.05;
            q["sigma_a"] = 0.002;
        } else {
            q["phase_g"] = 0.3;
            q["sigma_s"] = {0.004, 0.007, 0.012};
            q["sigma_a"] = {0.001, 0.001, 0.001};
        }
        qs.push_back(q);
    }
    const size_t checked = qs.size();
    nlohmann::json other = qs[0];
    other["phase_g"] = 0.5; // no table of this g
    qs.push_back(other);
    nlohmann::json iso = qs[0];
    iso.erase("phase_g"); // isotropic: no airlight_F table given
    qs.push_back(iso);
    const std::vector<nlohmann::json> out =
        eval_lines(qs, " --table " + dir + "/airlight_Fg_g0.85.slut --table " + dir + "/airlight_Fg_g0.3.slut");
    ASSERT_EQ(out.size(), qs.size());
    double worst = 0;
    int compared = 0;
    for (size_t i = 0; i < checked; ++i) {
        const nlohmann::json &o = out[i];
        ASSERT_TRUE(o.contains("exact")) << o.dump();
        const bool rgb = o["exact"].is_array();
        for (int c = 0; c < (rgb ? 3 : 1); ++c) {
            const nlohmann::json e = rgb ? o["exact"][c] : o["exact"], t = rgb ? o["table"][c] : o["table"];
            ASSERT_TRUE(e.is_number() && t.is_number()) << o.dump();
            const double ss = rgb ? qs[i]["sigma_s"][c].get<double>() : qs[i]["sigma_s"].get<double>();
            const double sa = rgb ? qs[i]["sigma_a"][c].get<double>() : qs[i]["sigma_a"].get<double>();
            EXPECT_GE(t.get<double>(), 0.0);
            if (std::exp(-(ss + sa) * qs[i]["distance"].get<double>()) < 1e-6 || !(e.get<double>() > 0)) continue;
            const double rel = std::fabs(t.get<double>() - e.get<double>()) / e.get<double>();
            worst = std::max(worst, rel);
            ++compared;
            EXPECT_LE(rel, 0.01) << o.dump();
        }
    }
    EXPECT_GT(compared, 800);
    std::printf("table radiance vs exact: max rel %.3g over %d channel values (accepts 0.01)\n", worst, compared);
    EXPECT_TRUE(out[checked]["table"].is_null()) << out[checked].dump();
    EXPECT_TRUE(out[checked + 1]["table"].is_null()) << out[checked + 1].dump();
    std::filesystem::remove_all(dir);
}

// The forward peak at g = 0.99: the scene's table (its w axis warped onto the peak,
// asinh_cot_peak) passes validate (its own independent Boost rule and off-node points), and
// its radiance through eval is within the scene's accepted error (0.01) of anisotropic.hpp's
// exact radiance wherever e^{−σ_t D} ≥ 1e-6: random rays, half of them within 6° of the lamp
// (γ from 1e-4 to 0.1 rad, where the glow lies), lengths short of, across and beyond it.
TEST(AnisotropicTables, ForwardPeakTablePassesValidateAndMeetsTheScenesError) {
    const std::string base = slut_test::temp_stem("gpeak");
    std::filesystem::remove_all(base + "_out");
    std::ofstream(base + ".toml") << "[accuracy]\nrelative_error = 0.01\n[[medium]]\nname = \"fog\"\n"
                                     "sigma_s_per_m = 0.05\nsigma_a_per_m = 0.002\nphase_g = 0.99\nviewer_inside = true\n"
                                     "[[light]]\nname = \"lamp\"\ntype = \"point\"\nintensity_W_per_sr = 300\n"
                                     "distance_m = [2, 80]\n";
    const slut_test::RunResult gen =
        run_scatterlut("generate --scene " + base + ".toml --out " + base + "_out --format bin");
    ASSERT_EQ(gen.exit_code, 0) << gen.out << gen.err;
    const std::string table = base + "_out/airlight_Fg_g0.99.slut";
    const slut_test::RunResult info = run_scatterlut("inspect " + table + " --json");
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("asinh_cot_peak"), std::string::npos) << info.out;
    const slut_test::RunResult check = run_scatterlut("validate " + table);
    EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
    EXPECT_NE(check.out.find("PASS"), std::string::npos) << check.out;
    EXPECT_EQ(check.out.find("FAIL"), std::string::npos) << check.out;

    std::mt19937_64 rng(16);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<nlohmann::json> qs;
    for (int k = 0; k < 800; ++k) {
        const double D = 2.0 * std::pow(40.0, unit(rng)); // [2, 80] m
        const double gamma = k % 2 == 0 ? 1e-4 * std::pow(1e3, unit(rng)) : std::acos(1.0 - 2.0 * unit(rng));
        nlohmann::json length = D * std::exp(std::log(1e-3) + unit(rng) * std::log(1e4));
        if (k % 5 == 4) length = "inf";
        if (gamma < 1e-6) continue;
        qs.push_back({{"quantity", "airlight"}, {"phase_g", 0.99}, {"sigma_s", 0.05}, {"sigma_a", 0.002},
                      {"intensity", 300}, {"distance", D}, {"gamma", gamma}, {"length", length}});
    }
    const std::vector<nlohmann::json> out = eval_lines(qs, " --table " + table);
    ASSERT_EQ(out.size(), qs.size());
    double worst = 0;
    int compared = 0;
    for (size_t i = 0; i < out.size(); ++i) {
        const nlohmann::json &o = out[i];
        ASSERT_TRUE(o["exact"].is_number() && o["table"].is_number()) << o.dump();
        const double e = o["exact"].get<double>(), t = o["table"].get<double>();
        EXPECT_GE(t, 0.0) << o.dump();
        if (std::exp(-0.052 * qs[i]["distance"].get<double>()) < 1e-6 || !(e > 0)) continue;
        const double rel = std::fabs(t - e) / e;
        worst = std::max(worst, rel);
        ++compared;
        EXPECT_LE(rel, 0.01) << o.dump();
    }
    EXPECT_GT(compared, 700);
    std::printf("g = 0.99: table radiance vs exact max rel %.3g over %d queries (accepts 0.01)\n", worst, compared);
    std::filesystem::remove_all(base + "_out");
    std::filesystem::remove(base + ".toml");
}

// Tables at g = ±0.99 (a loose error keeps the g = 0.99 table small): the radiance through
// them at γ → 0 and π, one channel clear while another is dense, is finite and >= 0.
TEST(AnisotropicTables, ExtremeTablesNeverNaNOrNegative) {
    for (double g : {0.99, -0.99}) {
        const std::string base = slut_test::temp_stem(g > 0 ? "gplus" : "gminus");
        std::filesystem::remove_all(base + "_out");
        std::ofstream(base + ".toml") << "[accuracy]\nrelative_error = 0.1\n[[medium]]\nname = \"m\"\n"
                                         "sigma_s_per_m = [0.0, 0.5, 5.0]\nsigma_a_per_m = [0.0, 0.01, 1.0]\nphase_g = "
                                      << g
                                      << "\nviewer_inside = true\n[[light]]\nname = \"l\"\ntype = \"point\"\n"
                                         "intensity_W_per_sr = 1\ndistance_m = [0.5, 20]\n";
        const slut_test::RunResult gen =
            run_scatterlut("generate --scene " + base + ".toml --out " + base + "_out --format bin");
        ASSERT_EQ(gen.exit_code, 0) << gen.out << gen.err;
        std::vector<nlohmann::json> qs;
        for (double gamma : {0.0, 1e-12, 1e-7, 1e-3, 1.0, 2.0, M_PI - 1e-7, M_PI - 1e-12, M_PI})
            for (double D : {0.5, 5.0, 20.0})
                for (nlohmann::json length : {nlohmann::json(1e-3), nlohmann::json(0.4), nlohmann::json(3.0),
                                              nlohmann::json(100.0), nlohmann::json("inf")}) {
                    if (gamma == 0.0 && (length.is_string() || length.get<double>() >= D)) continue; // through the light
                    qs.push_back({{"quantity", "airlight"},
                                  {"phase_g", g},
                                  {"sigma_s", {0.0, 0.5, 5.0}},
                                  {"sigma_a", {0.0, 0.01, 1.0}},
                                  {"intensity", 1},
                                  {"distance", D},
                                  {"gamma", gamma},
                                  {"length", length}});
                }
        std::string stem = base + "_out/airlight_Fg_g" + (g > 0 ? "0.99" : "-0.99") + ".slut";
        const std::vector<nlohmann::json> out = eval_lines(qs, " --table " + stem);
        ASSERT_EQ(out.size(), qs.size());
        double worst = 0;
        for (const auto &o : out) {
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(o["table"][c].is_number()) << o.dump();
                ASSERT_TRUE(o["exact"][c].is_number()) << o.dump();
                EXPECT_GE(o["table"][c].get<double>(), 0.0) << o.dump();
                const double e = o["exact"][c].get<double>(), t = o["table"][c].get<double>();
                if (e > 0 && std::exp(-(o["sigma_s"][c].get<double>() + o["sigma_a"][c].get<double>()) *
                                      o["distance"].get<double>()) >= 1e-6)
                    worst = std::max(worst, std::fabs(t - e) / e);
            }
            EXPECT_EQ(o["table"][0].get<double>(), 0.0) << "the clear channel scatters nothing";
        }
        EXPECT_LE(worst, 0.1) << "g = " << g;
        std::printf("g = %g: table vs exact max rel %.3g over %zu extreme queries (accepts 0.1)\n", g, worst, out.size());
        std::filesystem::remove_all(base + "_out");
        std::filesystem::remove(base + ".toml");
    }
}

} // namespace
