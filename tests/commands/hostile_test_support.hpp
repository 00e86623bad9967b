// The hostile-input tests' shared harness (tests/commands/test_hostile*.cpp): bounded runs of the
// built executable (killed after 10 s, the peak resident set of the process tree measured),
// temporary directories, the fog street scene's airlight part and its default table.
#pragma once

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_runner.hpp"
#include "scatterlut/io.hpp"

namespace {

namespace fs = std::filesystem;

constexpr int kTimeoutSeconds = 10;
constexpr long kMaxRssKiB = 100 * 1024; // 100 MB

struct Bounded {
    int exit_code = -1;  // -1: killed by a signal (timeout included)
    int signal = 0;
    long max_rss_kib = 0;
    std::string out, err;
};

std::string read_text(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs `sh -c "cd DIR && exec timeout -s KILL 10 SCATTERLUT ARGS"` with `input` on stdin
// (args in shell syntax), waits with wait4 for the peak RSS of the whole tree.
Bounded run_bounded(const std::string &args, const std::string &input = "", const std::string &cwd = ".") {
    static int calls = 0;
    const std::string stem = slut_test::temp_stem("hostile") + "_" + std::to_string(++calls);
    std::ofstream(stem + ".in", std::ios::binary) << input;
    const std::string command = "cd '" + cwd + "' && exec timeout -s KILL " + std::to_string(kTimeoutSeconds) + " " +
                                std::string(SLUT_BINARY) + " " + args + " < '" + stem + ".in' > '" + stem +
                                ".out' 2> '" + stem + ".err'";
    Bounded r;
    const pid_t pid = fork();
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char *>(nullptr));
        _exit(127);
    }
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    r.max_rss_kib = usage.ru_maxrss;
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    else r.signal = WTERMSIG(status);
    if (r.exit_code == 137 || r.exit_code == 124) r.exit_code = -1; // killed by timeout
    r.out = read_text(stem + ".out");
    r.err = read_text(stem + ".err");
    for (const char *ext : {".in", ".out", ".err"}) fs::remove(stem + ext);
    return r;
}

#define EXPECT_BOUNDED(r)                                                                                     \
    do {                                                                                                      \
        EXPECT_NE((r).exit_code, -1) << "killed (timeout " << kTimeoutSeconds << " s or signal " << (r).signal \
                                     << ")\n" << (r).err;                                                     \
        EXPECT_LT((r).max_rss_kib, kMaxRssKiB) << "peak RSS " << (r).max_rss_kib << " KiB";                   \
    } while (0)

bool contains(const std::string &text, const std::string &what) { return text.find(what) != std::string::npos; }

std::vector<nlohmann::json> lines_of(const std::string &text) { return slut_test::json_lines(text); }

std::string tmp_dir(const std::string &tag) {
    const std::string d = slut_test::temp_stem("hostile_" + tag);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// The fog street scene's airlight part (examples/scenes/fog_street.toml without its lit
// surfaces, whose surface tables these tests do not need), written once.
const std::string &airlight_street_scene() {
    static const std::string path = [] {
        const std::string p = slut_test::temp_stem("hostile_street") + ".toml";
        std::ofstream(p) << "name = \"fog street\"\n[accuracy]\nrelative_error = 0.005\n[[medium]]\nname = \"fog\"\n"
                            "sigma_s_per_m = 0.05\nsigma_a_per_m = 0.005\nviewer_inside = true\n[[light]]\nname = \"street lamps\"\n"
                            "type = \"point\"\nintensity_W_per_sr = 300\ndistance_m = [2, 80]\n";
        return p;
    }();
    return path;
}

// A small airlight-only set (that scene at 32 x 16 nodes): quick to write and to validate.
const std::string kSmallSet = "--scene " + airlight_street_scene() + " --n-u 32 --n-w 16 --format both";

// The default airlight table (its declared accuracy is the one users see), generated once.
const std::string &default_airlight() {
    static const std::string path = [] {
        const std::string d = tmp_dir("default");
        const Bounded g = run_bounded("generate --scene " + airlight_street_scene() + " --out " + d +
                                      " --n-u 256 --n-w 128 --format bin");
        EXPECT_EQ(g.exit_code, 0) << g.err;
        return d + "/airlight_F.slut";
    }();
    return path;
}

std::vector<uint8_t> read_bytes(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string write_scene(const std::string &dir, const std::string &name, const std::string &text) {
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    return path;
}

const char *const kFogScene = R"(name = "fog"
[accuracy]
relative_error = 0.01
[[medium]]
name = "fog"
sigma_s_per_m = 0.05
sigma_a_per_m = 0.005
viewer_inside = true
[[light]]
name = "lamp"
type = "point"
intensity_W_per_sr = 300
distance_m = [2, 80]
)";

std::string replace_once(std::string s, const std::string &from, const std::string &to) {
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

} // namespace
