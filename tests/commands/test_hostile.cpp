// Hostile but fair input through the built `scatterlut` executable, one test (or more) per
// case of the hostile-input review: deep or broken eval lines, NaN options, FIFOs and
// devices as files, empty or blocked output directories, concurrent and interrupted runs,
// physical extremes, corrupt-but-consistent tables, exit codes. Every run is bounded: killed
// after 10 s (timeout -s KILL) and its peak resident set (wait4's ru_maxrss, which covers
// the process tree) held below 100 MB where the case is about memory.
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

const char *kFogScene = R"(name = "fog"
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

// ------------------------------------------------------------------ 1, 2, 14: eval lines

TEST(HostileEval, DeepNestingIsAnErrorLineAndTheStreamGoesOn) {
    const int depth = 100000;
    const std::string deep = "{\"quantity\":\"F\",\"u\":1,\"v\":0.5,\"d\":" + std::string(depth, '[') +
                             std::string(depth, ']') + "}\n";
    const std::string objects = "{\"a\":" + std::string(70, '{') + std::string(70, '}') + "}\n"; // 71 deep
    const std::string inside_string = "{\"quantity\":\"F\",\"u\":1,\"v\":0.5,\"s\":\"" + std::string(1000, '[') + "\"}\n";
    const Bounded r = run_bounded("eval", deep + objects + inside_string + "{\"quantity\":\"F\",\"u\":1,\"v\":0.5}\n");
    EXPECT_BOUNDED(r);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 4u) << r.out.substr(0, 500);
    EXPECT_TRUE(contains(lines[0].value("error", ""), "line 1: nested deeper than 64")) << lines[0];
    EXPECT_TRUE(contains(lines[1].value("error", ""), "line 2: nested deeper than 64")) << lines[1];
    EXPECT_TRUE(lines[2]["exact"].is_number()) << lines[2]; // brackets inside a string do not nest
    EXPECT_TRUE(lines[3]["exact"].is_number()) << lines[3];
}

TEST(HostileEval, InvalidUtf8IsAnErrorLineAndTheStreamGoesOn) {
    const std::string good = "{\"quantity\":\"F\",\"u\":1,\"v\":0.5}\n";
    const std::vector<std::string> bad = {
        "\xff\xfe\n",                                               // the review's line
        "{\"quantity\":\"F\",\"u\":1,\"v\":0.5,\"x\":\"\xc3\x28\"}\n", // broken 2-byte sequence in a string
        "{\"x\":\"\xc0\x80\"}\n",                                   // overlong NUL
        "{\"x\":\"\xed\xa0\x80\"}\n",                               // a UTF-16 surrogate
        "{\"x\":\"\xf5\x80\x80\x80\"}\n",                           // beyond U+10FFFF
        "{\"x\":\"\xe2\x82\"}\n",                                   // truncated
        "\xe2\x82",                                                 // truncated at the end of input
    };
    std::string input;
    for (const std::string &b : bad) input += good + b;
    const Bounded r = run_bounded("eval", input);
    EXPECT_BOUNDED(r);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto lines = lines_of(r.out); // every answer is valid JSON (and so valid UTF-8)
    ASSERT_EQ(lines.size(), 2 * bad.size()) << r.out;
    for (size_t k = 0; k < bad.size(); ++k) {
        EXPECT_TRUE(lines[2 * k]["exact"].is_number()) << lines[2 * k];
        const std::string error = lines[2 * k + 1].value("error", "");
        EXPECT_TRUE(contains(error, "line " + std::to_string(2 * k + 2) + ": not valid UTF-8")) << error;
    }
}

TEST(HostileEval, EveryLineBlankOnesTooGetsExactlyOneAnswer) {
    const std::string q = "{\"quantity\":\"F\",\"u\":1,\"v\":0.5}";
    const Bounded r = run_bounded("eval", q + "\n\n  \t\r\n" + q + "\r\n\n" + q); // last line without '\n'
    EXPECT_BOUNDED(r);
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 6u) << r.out;
    for (int k : {1, 2, 4}) EXPECT_EQ(lines[k].value("error", ""), "line " + std::to_string(k + 1) + ": blank line, expected a JSON object");
    for (int k : {0, 3, 5}) EXPECT_TRUE(lines[k]["exact"].is_number()) << lines[k];
}

TEST(HostileEval, AnOverlongLineIsRefusedUnreadWithBoundedMemory) {
    std::string input = "{\"x\":\"" + std::string(50u << 20, 'a') + "\"}\n"; // 50 MiB on one line
    input += "{\"quantity\":\"F\",\"u\":1,\"v\":0.5}\n";
    input += std::string(3u << 20, ' ') + "\n"; // a long blank line is still too long
    const Bounded r = run_bounded("eval", input);
    EXPECT_BOUNDED(r);
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 3u) << r.out.substr(0, 300);
    EXPECT_EQ(lines[0].value("error", ""), "line 1: longer than 1048576 bytes (not read)");
    EXPECT_TRUE(lines[1]["exact"].is_number());
    EXPECT_EQ(lines[2].value("error", ""), "line 3: longer than 1048576 bytes (not read)");
}

// ------------------------------------------------------------------ 3, 14: options

TEST(HostileOptions, NonFiniteAndNonNumericValuesAreRefusedNamingTheOption) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"plan --u-max nan", "--u-max: expected a finite number, got 'nan'"},
        {"generate --u-max nan", "--u-max: expected a finite number, got 'nan'"},
        {"plan --u-max inf", "--u-max: expected a finite number, got 'inf'"},
        {"plan --u-max 1e999", "--u-max: expected a finite number, got '1e999'"},
        {"plan --u-max -nan", "--u-max: expected a finite number"},
        {"generate --w-min nan", "--w-min: expected a finite number, got 'nan'"},
        {"plan --w-min 0.01x", "--w-min: expected a number, got '0.01x'"},
        {"generate --n-u abc", "--n-u: expected an integer, got 'abc'"},
        {"plan --n-w 8.5", "--n-w: expected an integer, got '8.5'"},
        {"plan --n-u 99999999999", "--n-u: expected an integer of at most 10 digits"},
        {"validate --nodes nan x.slut", "--nodes: expected an integer, got 'nan'"},
        {"report --out /tmp/x --rounds 1e3", "--rounds: expected an integer, got '1e3'"},
        {"generate --out ''", "--out: expected an output directory, got an empty string"},
        {"report --out ''", "--out: expected an output directory, got an empty string"},
        {"frobnicate", "unknown subcommand 'frobnicate' (expected devices, plan, generate, eval, validate, inspect or report"},
    };
    for (const auto &[args, message] : cases) {
        SCOPED_TRACE(args);
        const Bounded r = run_bounded(args);
        EXPECT_BOUNDED(r);
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_TRUE(contains(r.err, message)) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
}

TEST(HostileOptions, AnUnknownDeviceIsAUsageErrorExit2) {
    const std::string dir = tmp_dir("device");
    const Bounded r = run_bounded("generate --device 9:9 --out " + dir + "/set " + kSmallSet);
    EXPECT_BOUNDED(r);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "'9:9': no OpenCL device matches")) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/set")) << "the output directory was created before the device was found";
}

// An empty --out must not fall back to the scene's directory (./out, an unset variable).
TEST(HostileOptions, EmptyOutWritesNothing) {
    const std::string dir = tmp_dir("emptyout");
    const Bounded r = run_bounded(std::string("generate --out \"\" ") + kSmallSet, "", dir);
    EXPECT_BOUNDED(r);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(fs::is_empty(dir)) << "something was written into the working directory";
}

// ------------------------------------------------------------------ 4, 5, 14: what is read

TEST(HostileFiles, DevicesFifosAndDirectoriesAreRefusedWithoutBlocking) {
    const std::string dir = tmp_dir("fifo");
    const std::string fifo = dir + "/f.slut", scene_fifo = dir + "/s.toml";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    ASSERT_EQ(mkfifo(scene_fifo.c_str(), 0600), 0);
    const std::string not_regular = "is not a regular file (a FIFO, socket or device)";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"plan --scene /dev/zero", "/dev/zero: " + not_regular + ", expected a scene file (TOML)"},
        {"generate --scene /dev/zero --out " + dir + "/x", "/dev/zero: " + not_regular},
        {"plan --scene " + scene_fifo, scene_fifo + ": " + not_regular},
        {"validate " + fifo, fifo + ": " + not_regular + ", expected a table file"},
        {"inspect " + fifo, fifo + ": " + not_regular},
        {"eval --table " + fifo, fifo + ": " + not_regular},
        {"validate /dev/zero", "/dev/zero: " + not_regular},
        {"validate /dev/null", "/dev/null: " + not_regular},
    };
    for (const auto &[args, message] : cases) {
        SCOPED_TRACE(args);
        const Bounded r = run_bounded(args);
        EXPECT_BOUNDED(r);
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_TRUE(contains(r.err, message)) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir + "/x"));
}

TEST(HostileFiles, AnOversizedSceneIsRefusedBeforeReading) {
    const std::string dir = tmp_dir("bigscene");
    const std::string path = dir + "/big.toml";
    {
        std::ofstream out(path);
        out << kFogScene << "# " << std::string(10u << 20, 'x') << "\n"; // 10 MB
    }
    const Bounded r = run_bounded("plan --scene " + path);
    EXPECT_BOUNDED(r);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, path + ": 10485")) << r.err;
    EXPECT_TRUE(contains(r.err, "more than the 4194304 expected of a scene file (TOML)")) << r.err;
}

// ------------------------------------------------------------------ 9, 14: scene ranges

TEST(HostileScene, RangesNoTableCanServeAreRefusedAtReadTimeWithFileLineAndKey) {
    const std::string dir = tmp_dir("ranges");
    struct Case {
        std::string from, to, where; // where: "LINE:COL: key 'KEY': expected"
    };
    const std::vector<Case> cases = {
        {"sigma_s_per_m = 0.05", "sigma_s_per_m = 1e300", ":6:17: key 'medium[0].sigma_s_per_m': expected a coefficient in [0, 1e6] (1/m), got 1e+300"},
        {"sigma_a_per_m = 0.005", "sigma_a_per_m = 1e7", ":7:17: key 'medium[0].sigma_a_per_m': expected a coefficient in [0, 1e6]"},
        {"distance_m = [2, 80]", "distance_m = [1e-300, 1e300]", ":13:15: key 'light[0].distance_m[0]': expected a length in [1e-6, 1e6] m, got 1e-300"},
        {"distance_m = [2, 80]", "distance_m = [2, 1e300]", ":13:18: key 'light[0].distance_m[1]': expected a length in [1e-6, 1e6] m, got 1e+300"},
        {"relative_error = 0.01", "relative_error = 1e-30", ":3:18: key 'accuracy.relative_error': expected a relative error on radiance in [1e-9, 0.5]"},
        {"relative_error = 0.01", "relative_error = 0.01\nmax_table_MiB = 1e-9", ":4:17: key 'accuracy.max_table_MiB': expected a size in MiB in [0.01, 4096]"},
        {"intensity_W_per_sr = 300", "intensity_W_per_sr = 1e308", ":12:22: key 'light[0].intensity_W_per_sr': expected a number in (0, 1e30]"},
        {"sigma_s_per_m = 0.05", "sigma_s_per_m = 1e5", ":13:14: key 'light[0].distance_m': expected sigma_t * length <= 1e4 optical depths with medium 'fog'"},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.to);
        const std::string path = write_scene(dir, "s.toml", replace_once(kFogScene, c.from, c.to));
        for (const std::string &cmd : {"plan --scene " + path, "generate --scene " + path + " --out " + dir + "/out"}) {
            const Bounded r = run_bounded(cmd);
            EXPECT_BOUNDED(r);
            EXPECT_EQ(r.exit_code, 2) << r.err;
            EXPECT_TRUE(contains(r.err, path + c.where)) << r.err;
        }
        EXPECT_FALSE(fs::exists(dir + "/out")) << "generate wrote before refusing the scene";
    }
    // A byte 0x01 in a table header (a scene-fuzzer finding that trips an assertion inside
    // toml++ when built with assertions): a syntax error with file:line:col.
    const std::string known = SLUT_SOURCE_DIR "/tests/fuzz/known/scene-toml-assert-1";
    const Bounded syntax = run_bounded("plan --scene " + known);
    EXPECT_BOUNDED(syntax);
    EXPECT_EQ(syntax.exit_code, 2);
    EXPECT_TRUE(contains(syntax.err, known + ":17:3: syntax error: Error while parsing key")) << syntax.err;
    // Non-ASCII outside strings and comments never reaches toml++ (whose classification of
    // some such code points is undefined behaviour: a scene-fuzzer finding); inside a string
    // or a comment it is fine. Invalid UTF-8 is refused with its place.
    const std::vector<std::pair<std::string, std::string>> texts = {
        {"\xef\xbb\xbe" + std::string(kFogScene), ":1:1: syntax error: a non-ASCII character outside a string or comment"},
        {std::string(kFogScene) + "\xc3\xa9 = 1\n", ":14:1: syntax error: a non-ASCII character outside a string or comment"},
        {std::string(kFogScene) + "x =\xe3\x80\x80" "1\n", ":14:4: syntax error: a non-ASCII character"},
        {std::string(kFogScene) + "# \xff\n", ":14:3: syntax error: not valid UTF-8"},
    };
    for (const auto &[text, where] : texts) {
        const std::string path = write_scene(dir, "u.toml", text);
        const Bounded r = run_bounded("plan --scene " + path);
        EXPECT_BOUNDED(r);
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_TRUE(contains(r.err, path + where)) << r.err;
    }
    const std::string unicode = write_scene(
        dir, "unicode.toml",
        "# brouillard \xc3\xa9pais \xe3\x80\x80 \xef\xbb\xbe\n" +
            replace_once(kFogScene, "name = \"fog\"\n[accuracy]", "name = \"caf\xc3\xa9 \xef\xbb\xbe '''\"\n[accuracy]"));
    const Bounded u = run_bounded("plan --scene " + unicode + " --n-u 16 --n-w 8");
    EXPECT_EQ(u.exit_code, 0) << u.err;

    // The bounds themselves are accepted.
    const std::string edge = write_scene(
        dir, "edge.toml",
        replace_once(replace_once(kFogScene, "relative_error = 0.01", "relative_error = 0.5\nmax_table_MiB = 0.01"),
                     "distance_m = [2, 80]", "distance_m = [1e-6, 1e5]"));
    const Bounded ok = run_bounded("plan --scene " + edge + " --n-u 16 --n-w 8");
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

// ------------------------------------------------------------------ 6, 7, 14: the output set

TEST(HostileOutput, AnOutputDirectoryUnderAFileIsAClearUsageError) {
    const std::string dir = tmp_dir("underfile");
    std::ofstream(dir + "/file") << "x";
    const Bounded r = run_bounded("generate --out " + dir + "/file/sub " + kSmallSet);
    EXPECT_BOUNDED(r);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--out '" + dir + "/file/sub': '" + dir + "/file' exists and is not a directory")) << r.err;
}

TEST(HostileOutput, ASecondRunIntoTheSameDirectoryIsRefusedWhileOneHoldsIt) {
    const std::string dir = tmp_dir("lock");
    ASSERT_EQ(run_bounded("generate --out " + dir + " " + kSmallSet).exit_code, 0);
    const auto before = read_bytes(dir + "/airlight_F.slut");
    // This process plays the run in progress: it holds the directory's lock.
    const int fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
    const Bounded r = run_bounded("generate --out " + dir + " --storage f16 " + kSmallSet);
    close(fd);
    EXPECT_BOUNDED(r);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "another scatterlut run is writing '" + dir + "' (it holds the directory's lock); nothing written"))
        << r.err;
    EXPECT_EQ(read_bytes(dir + "/airlight_F.slut"), before);
    // Released: the next run goes ahead.
    EXPECT_EQ(run_bounded("generate --out " + dir + " --storage f16 " + kSmallSet).exit_code, 0);
}

TEST(HostileOutput, ManifestListsTheRunAndValidateDirChecksTheSet) {
    const std::string dir = tmp_dir("manifest");
    ASSERT_EQ(run_bounded("generate --out " + dir + " " + kSmallSet).exit_code, 0);
    const nlohmann::json m = nlohmann::json::parse(read_text(dir + "/manifest.json"));
    EXPECT_EQ(m["manifest"], "scatterlut output set");
    EXPECT_TRUE(contains(m["scene"]["text"].get<std::string>(), "fog street"));
    EXPECT_TRUE(contains(m["command_line"].get<std::string>(), "generate --out " + dir));
    ASSERT_EQ(m["files"].size(), 4u); // airlight_F and airlight_rational, .slut and .exr
    for (const auto &f : m["files"]) {
        const auto bytes = read_bytes(dir + "/" + f["name"].get<std::string>());
        EXPECT_EQ(f["bytes"].get<size_t>(), bytes.size());
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx",
                      static_cast<unsigned long long>(scatterlut::fnv1a64(bytes.data(), bytes.size())));
        EXPECT_EQ(f["fnv1a64"], hex);
        EXPECT_TRUE(f["kind"] == "airlight_F" || f["kind"] == "airlight_rational") << f.dump();
    }
    const Bounded good = run_bounded("validate " + dir);
    EXPECT_EQ(good.exit_code, 0) << good.out << good.err;
    EXPECT_TRUE(contains(good.out, dir + ": one consistent output set (4 file(s) listed in manifest.json)")) << good.out;

    // A file of another run (f16 instead of f32) in the set: exit 1, the file named.
    const std::string other = tmp_dir("manifest_other");
    ASSERT_EQ(run_bounded("generate --out " + other + " --storage f16 " + kSmallSet).exit_code, 0);
    fs::copy_file(other + "/airlight_F.exr", dir + "/airlight_F.exr", fs::copy_options::overwrite_existing);
    const Bounded mixed = run_bounded("validate " + dir);
    EXPECT_EQ(mixed.exit_code, 1) << mixed.out;
    EXPECT_TRUE(contains(mixed.out, "MISMATCH")) << mixed.out;
    EXPECT_TRUE(contains(mixed.err, dir + "/airlight_F.exr: ") && contains(mixed.err, "(not this set's file)")) << mixed.err;
    const Bounded json = run_bounded("validate --json " + dir);
    EXPECT_EQ(json.exit_code, 1);
    EXPECT_EQ(lines_of(json.out).at(0)["status"], "MISMATCH");

    // A stray table file the manifest does not list.
    fs::copy_file(other + "/airlight_F.slut", dir + "/near_light_E3.slut");
    ASSERT_EQ(run_bounded("generate --out " + dir + " " + kSmallSet).exit_code, 0);
    const Bounded stray = run_bounded("validate " + dir);
    EXPECT_EQ(stray.exit_code, 1);
    EXPECT_TRUE(contains(stray.err, dir + "/near_light_E3.slut: a table file the manifest does not list")) << stray.err;

    // No manifest: unreadable input.
    const Bounded none = run_bounded("validate " + tmp_dir("nomanifest"));
    EXPECT_EQ(none.exit_code, 2);
    EXPECT_TRUE(contains(none.err, "manifest.json: cannot open for reading")) << none.err;
}

// An error while the set is being written (here: the third file's name is a directory)
// leaves the previous set whole: nothing is renamed before every file is written.
TEST(HostileOutput, AnErrorBeforeTheRenamesLeavesTheOldSetWhole) {
    const std::string dir = tmp_dir("ioerror");
    ASSERT_EQ(run_bounded("generate --out " + dir + " " + kSmallSet).exit_code, 0);
    const auto slut = read_bytes(dir + "/airlight_F.slut"), manifest = read_bytes(dir + "/manifest.json");
    fs::remove(dir + "/manifest.json");
    fs::create_directory(dir + "/manifest.json"); // the set's last file cannot be written
    const Bounded r = run_bounded("generate --out " + dir + " --storage f16 " + kSmallSet);
    EXPECT_BOUNDED(r);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_TRUE(contains(r.err, dir + "/manifest.json: is a directory")) << r.err;
    EXPECT_EQ(read_bytes(dir + "/airlight_F.slut"), slut); // not renamed
    for (const auto &e : fs::directory_iterator(dir))
        EXPECT_FALSE(contains(e.path().filename().string(), ".tmp-")) << "temporary left: " << e.path();
    fs::remove(dir + "/manifest.json");
    std::ofstream(dir + "/manifest.json", std::ios::binary)
        .write(reinterpret_cast<const char *>(manifest.data()), static_cast<std::streamsize>(manifest.size()));
    EXPECT_EQ(run_bounded("validate " + dir).exit_code, 0);
}

// SIGINT and SIGTERM at several moments of a run: the directory afterwards holds one whole
// set (the old or the new), validate DIR passes, and no temporary file is left.
TEST(HostileOutput, InterruptsLeaveOneWholeSet) {
    const std::string dir = tmp_dir("interrupt");
    ASSERT_EQ(run_bounded("generate --out " + dir + " " + kSmallSet).exit_code, 0);
    int k = 0;
    for (int delay_ms : {50, 150, 300, 600, 1000}) {
        for (int sig : {SIGINT, SIGTERM}) {
            SCOPED_TRACE("signal " + std::to_string(sig) + " after " + std::to_string(delay_ms) + " ms");
            const pid_t pid = fork();
            if (pid == 0) {
                const std::string storage = (++k % 2) ? " --storage f16 " : " --storage f32 ";
                const std::string args = std::string(SLUT_BINARY) + " generate --out " + dir + storage + kSmallSet +
                                         " > /dev/null 2>&1";
                execl("/bin/sh", "sh", "-c", ("exec " + args).c_str(), static_cast<char *>(nullptr));
                _exit(127);
            }
            usleep(static_cast<useconds_t>(delay_ms) * 1000);
            kill(pid, sig);
            int status = 0;
            waitpid(pid, &status, 0);
            const Bounded v = run_bounded("validate " + dir);
            EXPECT_EQ(v.exit_code, 0) << v.out << v.err;
            for (const auto &e : fs::directory_iterator(dir))
                EXPECT_FALSE(contains(e.path().filename().string(), ".tmp-")) << "temporary left: " << e.path();
        }
    }
}

// ------------------------------------------------------------------ 8, 10: physical extremes

TEST(HostileExtremes, AirlightGivesTheLimitOrANoteNeverASilentNull) {
    const std::string q = R"({"quantity":"airlight","sigma_a":0,"gamma":1,"length":2,)";
    const std::string input =
        std::string(R"({"quantity":"airlight","sigma_s":1,"sigma_a":4e153,"intensity":1,"distance":2.8e191,"gamma":1.5e-144,"length":"inf"})") + "\n" +
        q + R"("sigma_s":1e300,"intensity":1e308,"distance":1})" + "\n" +      // e^{-1e300}: 0
        q + R"("sigma_s":1e300,"intensity":1e308,"distance":1e-300})" + "\n" + // beyond the double range
        q + R"("sigma_s":1e-300,"intensity":1e-300,"distance":1e-300})" + "\n" +
        R"({"quantity":"near_light","sigma_s":1e300,"sigma_a":0,"intensity":1e308,"normal":[0,0,1],"eye_dir":[0,0.6,0.8],"light_pos":[0.1,0,1],"length":"inf"})" "\n";
    const Bounded r = run_bounded("eval --table " + default_airlight(), input);
    EXPECT_BOUNDED(r);
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 5u) << r.out;
    EXPECT_EQ(lines[0]["exact"], 0.0) << lines[0];
    EXPECT_EQ(lines[0]["table"], 0.0) << lines[0];
    EXPECT_EQ(lines[1]["exact"], 0.0) << lines[1];
    EXPECT_EQ(lines[1]["table"], 0.0) << lines[1];
    EXPECT_TRUE(lines[2]["exact"].is_null());
    EXPECT_TRUE(contains(lines[2].value("note", ""), "null for exact, table: beyond the largest double")) << lines[2];
    EXPECT_TRUE(lines[3]["exact"].is_number()) << lines[3];
    for (const auto &l : lines)
        for (const char *field : {"exact", "table", "approx", "distant"})
            if (l.contains(field) && l[field].is_null() && !(std::string(field) == "table" && l["quantity"] == "near_light")) {
                EXPECT_TRUE(l.contains("note")) << "a silent null: " << l;
            }
    EXPECT_TRUE(lines[4].contains("note")) << lines[4];
}

TEST(HostileExtremes, AirlightTableAtNanometreAndSmallerDistances) {
    std::string input;
    for (double D : {1e-170, 1e-200, 1e-9, 1e160})
        for (double gamma : {0.13, 0.69, 2.0, 3.0960635525811138, 3.1415891386690555})
            for (double s_over_D : {0.1, 1.0, 4.0, 1e3, 1e6}) {
                const double sigma_s = D > 1.0 ? 1.0 / D : 20.0; // the review's 20/m; sigma D = 1 at 1e160 m
                input += nlohmann::json({{"quantity", "airlight"}, {"sigma_s", sigma_s}, {"sigma_a", 0.0},
                                         {"intensity", 1.0}, {"distance", D}, {"gamma", gamma},
                                         {"length", s_over_D * D}})
                             .dump() +
                         "\n";
            }
    const Bounded r = run_bounded("eval --table " + default_airlight(), input);
    EXPECT_BOUNDED(r);
    for (const auto &l : lines_of(r.out)) {
        ASSERT_TRUE(l["exact"].is_number() && l["table"].is_number()) << l;
        const double exact = l["exact"].get<double>(), table = l["table"].get<double>();
        EXPECT_LE(std::fabs(table - exact), 1e-3 * exact) << l;
    }
}

// ------------------------------------------------------------------ 13: F at small v

TEST(HostileExtremes, TableFKeepsTheDeclaredAccuracyForEveryV) {
    const Bounded info = run_bounded("inspect --json " + default_airlight());
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const double declared = nlohmann::json::parse(info.out)["accuracy"]["sampling_max_rel"].get<double>();
    ASSERT_GT(declared, 0.0);
    std::string input;
    for (double u : {0.0, 1e-6, 0.5, 1.0, 2.0, 5.0, 30.0, 200.0})
        for (double v : {1e-300, 1e-124, 1e-10, 1e-5, 1e-3, 0.01, 0.03, 0.1, 0.3, 0.7, 1.0, 1.4, 1.57})
            input += nlohmann::json({{"quantity", "F"}, {"u", u}, {"v", v}}).dump() + "\n";
    const Bounded r = run_bounded("eval --table " + default_airlight(), input);
    EXPECT_BOUNDED(r);
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 8u * 13u);
    for (const auto &l : lines) {
        ASSERT_TRUE(l["exact"].is_number() && l["table"].is_number()) << l;
        const double exact = l["exact"].get<double>(), table = l["table"].get<double>();
        ASSERT_GT(exact, 0.0) << l;
        EXPECT_LE(std::fabs(table - exact) / exact, declared) << l;
    }
}

// ------------------------------------------------------------------ 11, 12: table files

// A table whose stored logarithms are absurd but finite, with consistent checksums: the
// runtime refuses it at load, naming the node (exit 2), instead of answering null.
TEST(HostileTables, AbsurdButConsistentValuesAreRefusedNamingTheNode) {
    const std::string dir = tmp_dir("absurd");
    scatterlut::Table t = scatterlut::load_table(default_airlight());
    const size_t n_u = static_cast<size_t>(t.axes[0].map.count);
    t.values[3 * n_u + 7] = 3e38; // node (7, 3)
    const std::string path = dir + "/absurd.slut";
    scatterlut::save_binary(t, path);
    for (const std::string &cmd : {"validate " + path, "eval --table " + path}) {
        const Bounded r = run_bounded(cmd, "{\"quantity\":\"F\",\"u\":1,\"v\":0.5}\n");
        EXPECT_BOUNDED(r);
        EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
        EXPECT_TRUE(contains(r.err, "ln G~ = ") && contains(r.err, "at node (7, 3), channel 'ln_Gs' is outside the quantity's range"))
            << r.err;
    }
    t.values[3 * n_u + 7] = 1e-2; // ln G~ > 0: G~ > 1, still refused
    scatterlut::save_binary(t, path);
    EXPECT_EQ(run_bounded("validate " + path).exit_code, 2);
}

TEST(HostileTables, PayloadChecksumMismatchExits1) {
    const std::string dir = tmp_dir("checksum");
    auto bytes = read_bytes(default_airlight());
    bytes[bytes.size() - 5] ^= 0x10;
    const std::string path = dir + "/flipped.slut";
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char *>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    const Bounded v = run_bounded("validate " + path);
    EXPECT_EQ(v.exit_code, 1) << v.out << v.err;
    EXPECT_TRUE(contains(v.out, path + ": FAIL")) << v.out;
    EXPECT_TRUE(contains(v.err, path + ": payload checksum mismatch")) << v.err;
    EXPECT_EQ(run_bounded("inspect " + path).exit_code, 1);
    EXPECT_EQ(run_bounded("eval --table " + path).exit_code, 1);
}
