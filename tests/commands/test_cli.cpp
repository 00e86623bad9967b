// Smoke tests of the `scatterlut` executable: exit codes, files, and eval's JSON lines.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_runner.hpp"
#include "reference_data.hpp"

namespace {

using slut_test::json_lines;
using Result = slut_test::RunResult;
Result run(const std::string &args, const std::string &input = "") { return slut_test::run_scatterlut(args, input); }

std::string out_dir() { return testing::TempDir() + "/slut_cli_tables_" + std::to_string(getpid()); }

} // namespace

TEST(Cli, VersionAndDevices) {
    EXPECT_EQ(run("--version").exit_code, 0);
    const Result devices = run("devices");
    EXPECT_EQ(devices.exit_code, 0);
    EXPECT_NE(devices.out.find("fp64: yes"), std::string::npos) << devices.out;
}

TEST(Cli, BadArgumentsExitNonZero) {
    EXPECT_EQ(run("").exit_code, 2);                          // a subcommand is required
    EXPECT_EQ(run("generate --n-u 3").exit_code, 2);          // out of range
    EXPECT_EQ(run("generate --format png").exit_code, 2);     // not a member
    EXPECT_EQ(run("eval --table /nonexistent.slut").exit_code, 2);
}

// --format ktx2 writes only .ktx2 files (KTX 2.0 identifier first); f64 has no KTX2 form.
TEST(Cli, GenerateKtx2Only) {
    const std::string dir = out_dir() + "_ktx2";
    std::filesystem::remove_all(dir);
    const Result f64 = run("generate --format ktx2 --storage f64 --out " + dir + " --n-u 16 --n-w 16");
    EXPECT_EQ(f64.exit_code, 2);
    EXPECT_NE(f64.err.find("KTX2 output holds no f64"), std::string::npos) << f64.err;
    EXPECT_FALSE(std::filesystem::exists(dir));
    const Result gen = run("generate --format ktx2 --out " + dir + " --n-u 16 --n-w 16");
    ASSERT_EQ(gen.exit_code, 0) << gen.out << gen.err;
    std::vector<std::string> names;
    for (const auto &e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"airlight_F.ktx2", "airlight_rational.ktx2", "manifest.json",
                                               "near_light_E3.ktx2", "near_light_E4.ktx2"}));
    {
        std::ifstream in(dir + "/airlight_F.ktx2", std::ios::binary);
        char id[12] = {};
        in.read(id, 12);
        EXPECT_EQ(std::string(id, 12), std::string("\xabKTX 20\xbb\r\n\x1a\n", 12));
    }
    // The manifest ties the KTX2 files to the run: validate DIR passes, and fails (exit 1)
    // once a byte of one of them changes.
    const Result set = run("validate " + dir);
    EXPECT_EQ(set.exit_code, 0) << set.out << set.err;
    {
        std::fstream f(dir + "/near_light_E3.ktx2", std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(-1, std::ios::end);
        const char last = static_cast<char>(f.get());
        f.seekp(-1, std::ios::end);
        f.put(static_cast<char>(last ^ 0x5a));
    }
    const Result tampered = run("validate " + dir);
    EXPECT_EQ(tampered.exit_code, 1) << tampered.out << tampered.err;
    EXPECT_NE(tampered.out.find("near_light_E3.ktx2"), std::string::npos) << tampered.out;
    std::filesystem::remove_all(dir);
}

TEST(Cli, GenerateThenEval) {
    const std::string dir = out_dir();
    std::filesystem::remove_all(dir);
    const Result gen = run("generate --out " + dir + " --n-u 128 --n-w 64");
    ASSERT_EQ(gen.exit_code, 0) << gen.out;
    ASSERT_TRUE(std::filesystem::exists(dir + "/airlight_F.slut"));
    ASSERT_TRUE(std::filesystem::exists(dir + "/airlight_F.exr"));

    const auto refs = slut_test::load_airlight_refs();
    const auto &c = refs.at(1);
    nlohmann::json air = {{"quantity", "airlight"}, {"sigma_s", c.sigma_s}, {"sigma_a", c.sigma_a},
                          {"intensity", c.intensity}, {"distance", c.distance}, {"gamma", c.gamma},
                          {"length", c.length}};
    const std::string input = nlohmann::json({{"quantity", "F"}, {"u", 0.5}, {"v", 1.0}}).dump() + "\n" +
                              "this is not json\n" + air.dump() + "\n" +
                              R"({"quantity":"airlight","sigma_s":0.3,"sigma_a":0.1,"intensity":1,"distance":5,"gamma":0,"length":"inf"})" "\n" +
                              R"({"quantity":"F","u":-1,"v":1})" "\n" + R"({"quantity":"teapot"})" "\n";
    for (const std::string &table : {dir + "/airlight_F.slut", dir + "/airlight_F.exr"}) {
        const Result r = run("eval --table " + table, input);
        ASSERT_EQ(r.exit_code, 0);
        const auto lines = json_lines(r.out);
        ASSERT_EQ(lines.size(), 6u) << r.out;
        EXPECT_EQ(lines[0]["u"], 0.5); // the query is echoed
        EXPECT_TRUE(lines[0]["exact"].is_number());
        EXPECT_LE(slut_test::rel_err(lines[0]["table"].get<double>(), lines[0]["exact"].get<double>()), 1e-3);
        EXPECT_TRUE(lines[1].contains("error"));
        EXPECT_NE(lines[1]["error"].get<std::string>().find("line 2"), std::string::npos);
        EXPECT_LE(slut_test::rel_err(lines[2]["exact"].get<double>(), c.L), 1e-10);
        EXPECT_LE(slut_test::rel_err(lines[2]["table"].get<double>(), c.L), 1e-3);
        EXPECT_TRUE(lines[3]["exact"].is_null()); // diverges: through the light
        EXPECT_TRUE(lines[3].contains("note"));
        EXPECT_TRUE(lines[4].contains("error"));
        EXPECT_TRUE(lines[5].contains("error"));
    }
    // Without a table, "table" is null.
    const auto lines = json_lines(run("eval", air.dump() + "\n").out);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_TRUE(lines[0]["table"].is_null());
}
