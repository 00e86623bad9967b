// `scatterlut generate`'s files as a contract, through
// the executable: the default tables pass `validate` and a 1e-3 relative perturbation with a
// consistent checksum fails it (exit 1); the same command twice writes byte-identical files
// (what `make run` twice must give); a run interrupted by SIGINT or SIGKILL while it writes
// leaves the previous files intact and nothing partial under a final name (and after a
// SIGINT, no temporary file either).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <set>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/inotify.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_runner.hpp"
#include "scatterlut/io.hpp"

namespace {

using Bytes = std::vector<uint8_t>;
using slut_test::run_scatterlut;

const char *const kFiles[] = {"airlight_F.slut",    "airlight_F.exr",    "near_light_E3.slut",
                              "near_light_E3.exr",  "near_light_E4.slut", "near_light_E4.exr",
                              "airlight_rational.slut", "airlight_rational.exr"};

Bytes read_all(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::map<std::string, Bytes> snapshot(const std::string &dir) {
    std::map<std::string, Bytes> out;
    for (const char *f : kFiles) out[f] = read_all(dir + "/" + f);
    return out;
}

std::string fresh_dir(const std::string &tag) {
    const std::string d = slut_test::temp_stem(tag);
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

// The default tables, generated once per test process (`make run` is `generate --out out`).
const std::string &default_dir() {
    static const std::string dir = [] {
        const std::string d = fresh_dir("default_tables");
        const auto r = run_scatterlut("generate --out " + d);
        EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
        return d;
    }();
    return dir;
}

// Starts `scatterlut generate --out DIR ARGS…` and sends `sig` at the first file event in DIR
// (a temporary file created, or any file written or renamed into place), i.e. while it
// writes its first table. Returns the wait status and the name of that first file.
std::pair<int, std::string> generate_interrupted(const std::string &dir, int sig, std::vector<std::string> args) {
    const int in = ::inotify_init1(IN_CLOEXEC);
    if (in < 0) throw std::runtime_error("inotify_init1 failed");
    if (::inotify_add_watch(in, dir.c_str(), IN_CREATE | IN_MODIFY | IN_MOVED_TO | IN_CLOSE_WRITE) < 0)
        throw std::runtime_error("inotify_add_watch failed");
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 1), ::dup2(null, 2);
        args.insert(args.begin(), {SLUT_BINARY, "generate", "--out", dir});
        std::vector<char *> argv;
        for (std::string &a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        ::execv(SLUT_BINARY, argv.data());
        ::_exit(127);
    }
    std::string first;
    pollfd p{in, POLLIN, 0};
    if (::poll(&p, 1, 120000) == 1) {
        alignas(inotify_event) char buf[4096];
        if (::read(in, buf, sizeof buf) > 0) {
            ::kill(pid, sig);
            const auto *e = reinterpret_cast<const inotify_event *>(buf);
            first = e->len ? e->name : "";
        }
    }
    if (first.empty()) ::kill(pid, SIGKILL); // no event within two minutes: fail below
    int status = 0;
    ::waitpid(pid, &status, 0);
    ::close(in);
    return {status, first};
}

} // namespace

// The tables `make run` writes pass `validate`, .slut and .exr alike. Then every stored
// value × 1.001 (ln-encoded channels: + ln 1.001), written by the library so that the
// checksums are consistent and only the accuracy check can catch it: exit 1, for the
// default airlight EXR and the 4-D near-light binary table. (One test: the default tables
// take seconds to generate, once per test process.)
TEST(GeneratedFiles, DefaultTablesPassValidateAndPerturbedFail) {
    std::string files;
    for (const char *f : kFiles) files += " " + default_dir() + "/" + f;
    const auto r = run_scatterlut("validate" + files);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    for (const char *f : kFiles) EXPECT_NE(r.out.find(std::string(f) + ": PASS"), std::string::npos) << f << r.out;

    const std::string dir = fresh_dir("perturbed");
    for (const char *f : {"airlight_F.exr", "near_light_E4.slut"}) {
        scatterlut::Table t = scatterlut::load_table(default_dir() + "/" + f);
        ASSERT_EQ(t.channels[0].encoding, scatterlut::Encoding::Log);
        for (double &v : t.values) v += std::log(1.001);
        const std::string path = dir + "/" + f;
        if (path.compare(path.size() - 4, 4, ".exr") == 0) scatterlut::save_exr(t, path);
        else scatterlut::save_binary(t, path);
        const auto p = run_scatterlut("validate " + path);
        EXPECT_EQ(p.exit_code, 1) << f << "\n" << p.out << p.err;
        EXPECT_NE(p.out.find(path + ": FAIL"), std::string::npos) << p.out;
    }
    std::filesystem::remove_all(dir);
}

// The same command twice, same directory (the command line is recorded in the files, so
// the directory must be the same): byte-identical files, as `make run` twice must give.
TEST(GeneratedFiles, SameCommandTwiceIsByteIdentical) {
    const auto first = snapshot(default_dir());
    for (const auto &[name, bytes] : first) ASSERT_GT(bytes.size(), 1000u) << name;
    const auto r = run_scatterlut("generate --out " + default_dir());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto second = snapshot(default_dir());
    for (const char *f : kFiles) EXPECT_TRUE(first.at(f) == second.at(f)) << f << " differs between two runs";
}

// Interrupted while writing its first table (signal sent at the first file event in the
// directory): every final name still holds the previous run's complete file (or, had the
// rename already happened, a complete new one that loads); the only other entries allowed
// are the writer's hidden temporary files, which a SIGKILL cannot clean up (the command's
// SIGINT handler removes them). The previous files are the default tables; the interrupted
// run makes a smaller airlight table, so the two differ.
TEST(GeneratedFiles, InterruptedRunLeavesThePreviousFiles) {
    for (int sig : {SIGINT, SIGKILL}) {
        SCOPED_TRACE(sig == SIGINT ? "SIGINT" : "SIGKILL");
        const std::string dir = fresh_dir(sig == SIGINT ? "sigint" : "sigkill");
        for (const char *f : kFiles) std::filesystem::copy_file(default_dir() + "/" + f, dir + "/" + f);
        const auto before = snapshot(dir);

        const auto [status, first] = generate_interrupted(dir, sig, {"--n-u", "128", "--n-w", "64"});
        ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status << ", first event '" << first << "'";
        EXPECT_EQ(first.rfind(".airlight_F.slut.tmp-", 0), 0u) << "the first file written is '" << first << "'";

        std::set<std::string> cut; // final names whose temporary file was left
        for (const auto &e : std::filesystem::directory_iterator(dir)) {
            const std::string name = e.path().filename().string();
            if (before.count(name)) continue;
            bool is_temp = false;
            for (const char *f : kFiles)
                if (name.rfind("." + std::string(f) + ".tmp-", 0) == 0) is_temp = true, cut.insert(f);
            EXPECT_TRUE(is_temp) << "unexpected file " << name;
            // SIGINT is handled: the command removes its temporary file before it dies.
            EXPECT_FALSE(is_temp && sig == SIGINT) << "SIGINT left the temporary file " << name;
        }
        const bool temp_left = !cut.empty();
        // Normally the signal lands before the first rename (after a SIGKILL the partial
        // temporary file is left); on a loaded machine the writer may get further (then a
        // complete new file is fine).
        const bool first_replaced = read_all(dir + "/" + kFiles[0]) != before.at(kFiles[0]);
        std::printf("  %s: %s\n", sig == SIGINT ? "SIGINT" : "SIGKILL",
                    first_replaced ? "landed after the first write"
                    : temp_left    ? "cut during the write (temporary file left, final names untouched)"
                                   : "cut during the write (temporary file removed, final names untouched)");
        for (const char *f : kFiles) {
            const Bytes now = read_all(dir + "/" + f);
            if (now == before.at(f)) continue;
            EXPECT_FALSE(cut.count(f)) << f << " replaced although its write was cut";
            EXPECT_NO_THROW(scatterlut::load_table(dir + "/" + f)) << f << " is not the previous file and not a complete one";
        }
        std::filesystem::remove_all(dir);
    }
}
