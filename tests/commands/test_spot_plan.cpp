// Spot lights in `plan` and `report` (host/src/plan_search.cpp's check, report_spot.cpp;
// docs/SPOT.md): the planner measures the airlight table's answers for the scene's spots
// (the ray cut at the cone, the falloff band by parts) against the scene's error and says so;
// the report shows them per view of the beams beside what engines do instead.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
const std::string kScenes = std::string(SLUT_SOURCE_DIR) + "/examples/scenes/";

const nlohmann::json *table_of(const nlohmann::json &plan, const std::string &stem) {
    for (const auto &t : plan.at("tables"))
        if (t.at("file_stem") == stem) return &t;
    return nullptr;
}

std::string read_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The planned airlight_F table answers the spots of examples/scenes/fog_spots.toml within its
// accepted error (0.005), measured; a scene without spots has no such check.
TEST(SpotPlan, PlannerMeasuresTheSpotsAgainstTheScenesError) {
    const slut_test::RunResult r = slut_test::run_scatterlut("plan --json --scene " + kScenes + "fog_spots.toml");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json plan = nlohmann::json::parse(r.out);
    const nlohmann::json *f = table_of(plan, "airlight_F");
    ASSERT_NE(f, nullptr);
    ASSERT_TRUE(f->contains("spot_max_rel")) << f->dump();
    const double spot = f->at("spot_max_rel").get<double>();
    EXPECT_GT(spot, 0.0);
    EXPECT_LE(spot, 0.005);
    EXPECT_TRUE(f->at("reached").get<bool>());
    EXPECT_NE(f->at("verdict").get<std::string>().find("spot lights: measured"), std::string::npos) << f->at("verdict");
    // The rational table (the GPU tiers') is not the C++ spot path's: no check there.
    if (const nlohmann::json *rat = table_of(plan, "airlight_rational")) {
        EXPECT_FALSE(rat->contains("spot_max_rel"));
    }

    const slut_test::RunResult s = slut_test::run_scatterlut("plan --json --scene " + kScenes + "fog_street.toml");
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const nlohmann::json street = nlohmann::json::parse(s.out);
    ASSERT_NE(table_of(street, "airlight_F"), nullptr);
    EXPECT_FALSE(table_of(street, "airlight_F")->contains("spot_max_rel"));
}

// report's spot section: per view (inside, beside, along) the table path within the scene's
// error, the band rule alone far inside it, no ray that misses the beams answered with light,
// and the unclipped point light (NVIDIA's Rain sample) far off beside the beams.
TEST(SpotPlan, ReportShowsTheSpotsPerView) {
    const std::string d = slut_test::temp_stem("report_spots");
    fs::remove_all(d);
    const slut_test::RunResult r = slut_test::run_scatterlut("report --scene " + kScenes + "fog_spots.toml --out " + d +
                                                             " --rounds 1 --queries 800");
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_NE(read_file(d + "/report.md").find("### Spot lights"), std::string::npos);
    std::istringstream csv(read_file(d + "/airlight_F_spot.csv"));
    std::string line;
    ASSERT_TRUE(std::getline(csv, line));
    EXPECT_EQ(line, "view,rays,lit,misses_answered_nonzero,method,median,p90,p99,max");
    std::map<std::string, std::map<std::string, std::vector<double>>> rows; // view → method → numbers
    while (std::getline(csv, line)) {
        std::stringstream ss(line);
        std::vector<std::string> c;
        for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
        ASSERT_EQ(c.size(), 9u) << line;
        std::vector<double> v;
        for (size_t i : {1u, 2u, 3u, 5u, 6u, 7u, 8u}) v.push_back(std::stod(c[i]));
        rows[c[0]][c[4]] = v; // rays, lit, misses answered, median, p90, p99, max
    }
    ASSERT_EQ(rows.size(), 3u);
    for (const char *view : {"inside", "beside", "along"}) {
        ASSERT_EQ(rows[view].size(), 4u) << view;
        const auto &table = rows[view]["table"];
        EXPECT_EQ(table[0], 200.0) << view;
        EXPECT_GT(table[1], 50.0) << view << ": lit rays";
        EXPECT_EQ(table[2], 0.0) << view << ": rays missing the beams answered with light";
        EXPECT_LE(table[6], 0.005) << view;
        EXPECT_LE(rows[view]["band_rule"][6], 1e-4) << view;
        for (double x : table) EXPECT_TRUE(std::isfinite(x)) << view;
    }
    EXPECT_GT(rows["beside"]["unclipped"][3], 1.0); // median: the light outside the beam counted
}

} // namespace
