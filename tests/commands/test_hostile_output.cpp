// Hostile but fair input through the built `scatterlut` executable (test_hostile.cpp): the output
// set — a directory under a file, a second run into a held directory, the manifest and
// `validate --dir`, an error before the renames, interrupts. Part of the test_hostile executable.

#include "hostile_test_support.hpp"

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
