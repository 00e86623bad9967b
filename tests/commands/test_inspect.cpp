// `scatterlut inspect`, run as the built executable: the text and JSON descriptions of the
// generated tables.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_runner.hpp"
#include "scatterlut/io.hpp"

namespace {

using Result = slut_test::RunResult;
Result run(const std::string &args) { return slut_test::run_scatterlut(args); }

const std::string &tables_dir() { return slut_test::small_generated_tables_dir(); }

const char *const kStems[] = {"airlight_F", "near_light_E3", "near_light_E4"};

using slut_test::json_lines;

} // namespace

TEST(Inspect, TextAndJson) {
    const std::string &dir = tables_dir();
    const Result r = run("inspect " + dir + "/airlight_F.slut");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("airlight_F"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("format version  1." + std::to_string(scatterlut::kFormatMinor)), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("128 nodes"), std::string::npos) << r.out; // u axis
    EXPECT_NE(r.out.find("64 nodes"), std::string::npos) << r.out;  // w axis
    EXPECT_NE(r.out.find("asinh_cot"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("generate --out"), std::string::npos) << r.out; // command line recorded

    for (const char *ext : {".slut", ".exr"}) {
        const Result j = run("inspect --json " + dir + "/near_light_E4" + ext);
        ASSERT_EQ(j.exit_code, 0) << j.out;
        const auto doc = nlohmann::json::parse(j.out);
        EXPECT_EQ(doc.at("kind"), "near_light_E4");
        ASSERT_EQ(doc.at("axes").size(), 4u);
        EXPECT_EQ(doc.at("axes")[0].at("name"), "T");
        EXPECT_EQ(doc.at("axes")[3].at("name"), "q"); // the slab axis (docs/NEARLIGHT.md)
        EXPECT_EQ(doc.at("axes")[3].at("warp"), "nl_qodds");
        EXPECT_EQ(doc.at("channels")[0].at("name"), "ln_E_over_B");
        EXPECT_EQ(doc.at("channels")[0].at("encoding"), "log");
        // E/B: positive and finite (E ∈ (0, 1], B ≥ e^{−T} ≥ e^{−20}).
        const double lo = doc.at("channels")[0].at("decoded_min"), hi = doc.at("channels")[0].at("decoded_max");
        EXPECT_GT(lo, 0.0);
        EXPECT_LE(hi, std::exp(20.0));
        EXPECT_GE(doc.at("accuracy").at("sampling_max_rel").get<double>(), 0.0);
    }
}
