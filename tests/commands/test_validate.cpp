// `scatterlut validate`, run as the built executable: exit codes (0 pass, 1 accuracy
// failure, 2 unreadable), the human and JSON outputs.
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
std::string stem() { return slut_test::temp_stem("validate"); }
Result run(const std::string &args) { return slut_test::run_scatterlut(args); }

const std::string &tables_dir() { return slut_test::small_generated_tables_dir(); }

const char *const kStems[] = {"airlight_F", "near_light_E3", "near_light_E4"};

using slut_test::json_lines;

} // namespace

TEST(Validate, GeneratedTablesPass) {
    const std::string &dir = tables_dir();
    std::string files;
    for (const char *s : kStems)
        for (const char *ext : {".slut", ".exr"}) {
            ASSERT_TRUE(std::filesystem::exists(dir + "/" + s + ext)) << s << ext;
            files += " " + dir + "/" + s + ext;
        }
    const Result r = run("validate" + files);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_EQ(r.out.find("FAIL"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("airlight_F.slut: PASS"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("near_light_E4.exr: PASS"), std::string::npos) << r.out;
}

TEST(Validate, JsonOneObjectPerFile) {
    const std::string &dir = tables_dir();
    const Result r = run("validate --json " + dir + "/airlight_F.slut " + dir + "/near_light_E3.exr");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto lines = json_lines(r.out);
    ASSERT_EQ(lines.size(), 2u) << r.out;
    for (const auto &j : lines) {
        EXPECT_TRUE(j.at("pass").get<bool>()) << j.dump();
        EXPECT_GE(j.at("checks").at("nodes").at("count").get<int>(), 200);
        EXPECT_GE(j.at("checks").at("sampling").at("count").get<int>(), 1000); // E < 1e-6 points are dropped
    }
    EXPECT_EQ(lines[0].at("kind"), "airlight_F");
    EXPECT_EQ(lines[1].at("kind"), "near_light_E3");
}

// Values 0.1 % too large, with a consistent checksum (written by the library itself): the
// loader accepts the file, the accuracy check must not.
TEST(Validate, PerturbedValuesFail) {
    const std::string &dir = tables_dir();
    for (const char *s : {"airlight_F", "near_light_E3"}) {
        scatterlut::Table t = scatterlut::load_table(dir + "/" + s + ".slut");
        for (double &v : t.values) v += std::log(1.001); // ln-encoded: quantity × 1.001
        const std::string path = stem() + "_perturbed_" + s + ".slut";
        scatterlut::save_binary(t, path);
        const Result r = run("validate " + path);
        EXPECT_EQ(r.exit_code, 1) << s << "\n" << r.out;
        EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
        const Result j = run("validate --json " + path);
        EXPECT_EQ(j.exit_code, 1);
        EXPECT_FALSE(json_lines(j.out).at(0).at("pass").get<bool>()) << j.out;
        std::filesystem::remove(path);
    }
}

TEST(Validate, TruncatedOrMissingFileExits2) {
    const std::string &dir = tables_dir();
    std::ifstream in(dir + "/airlight_F.slut", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 1000u);
    const std::string path = stem() + "_truncated.slut";
    std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    EXPECT_EQ(run("validate " + path).exit_code, 2);
    // A good file beside it does not hide the bad one.
    EXPECT_EQ(run("validate " + dir + "/airlight_F.slut " + path).exit_code, 2);
    EXPECT_EQ(run("validate " + stem() + "_does_not_exist.slut").exit_code, 2);
    EXPECT_EQ(run("inspect " + path).exit_code, 2);
    EXPECT_EQ(run("validate").exit_code, 2); // a file is required
    std::filesystem::remove(path);
}
