// Runs the built `scatterlut` executable from a test: exit code and stdout.
#pragma once

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

namespace slut_test {

struct RunResult {
    int exit_code;
    std::string out;
    std::string err; // stderr
};

// A per-process prefix for temporary files: ctest runs tests as parallel processes.
inline std::string temp_stem(const std::string &tag) {
    return testing::TempDir() + "/slut_" + tag + "_" + std::to_string(getpid());
}

// Runs SLUT_BINARY with `args` (shell syntax) and `input` on stdin; captures stdout and
// stderr (with_stderr: stderr also appended to out, for tests that read both as one text).
inline RunResult run_scatterlut(const std::string &args, const std::string &input = "", bool with_stderr = false) {
    static int calls = 0;
    const std::string stem = temp_stem("run") + "_" + std::to_string(++calls);
    std::ofstream(stem + ".in") << input;
    const std::string command = std::string(SLUT_BINARY) + " " + args + " < " + stem + ".in 2>" + stem + ".err";
    FILE *pipe = popen(command.c_str(), "r");
    std::string out;
    char buffer[4096];
    size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    const int status = pclose(pipe);
    std::ifstream err_file(stem + ".err", std::ios::binary);
    std::stringstream err;
    err << err_file.rdbuf();
    if (with_stderr) out += err.str();
    std::filesystem::remove(stem + ".in");
    std::filesystem::remove(stem + ".err");
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out, err.str()};
}

inline std::vector<nlohmann::json> json_lines(const std::string &text) {
    std::vector<nlohmann::json> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) out.push_back(nlohmann::json::parse(line));
    return out;
}

// The default scene's tables at a small airlight resolution (--n-u 128 --n-w 64), generated
// once per test process into a temporary folder; a failed generate fails the calling test.
inline const std::string &small_generated_tables_dir() {
    static const std::string dir = [] {
        const std::string d = temp_stem("tables") + "_tables";
        std::filesystem::remove_all(d);
        const RunResult gen = run_scatterlut("generate --out " + d + " --n-u 128 --n-w 64");
        EXPECT_EQ(gen.exit_code, 0) << gen.out;
        return d;
    }();
    return dir;
}

} // namespace slut_test
