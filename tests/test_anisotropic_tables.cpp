// Anisotropic (Henyey–Greenstein) and coloured media end to end through the command line:
// eval's "phase_g" and per-channel coefficients against the independent references
// (tests/reference/hg_ref.json), bad input, and the extremes (g = ±0.99, γ at 0 and π, one
// channel clear while another is dense) never answering NaN or a negative radiance.
#include <cmath>
#include <fstream>
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

} // namespace
