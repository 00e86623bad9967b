// Hostile but fair input through the built `scatterlut` executable, one test (or more) per
// case of the hostile-input review: deep or broken eval lines, NaN options, FIFOs and
// devices as files, empty or blocked output directories, concurrent and interrupted runs,
// physical extremes, corrupt-but-consistent tables, exit codes. Every run is bounded: killed
// after 10 s (timeout -s KILL) and its peak resident set (wait4's ru_maxrss, which covers
// the process tree) held below 100 MB where the case is about memory.
//
// This file: eval lines, options, what is read, scene ranges. The output set:
// test_hostile_output.cpp; physical extremes and table files: test_hostile_extremes.cpp (one test
// executable, test_hostile).

#include "hostile_test_support.hpp"

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
