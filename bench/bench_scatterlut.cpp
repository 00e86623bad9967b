// scatterlut benchmarks: generation throughput on the OpenCL device against a
// per-cell Boost.Math baseline in the same run, sampler and radiance cost per call, and
// the whole-process `scatterlut generate` with cold and warm kernel caches.
//
// Speed is only ever a ratio against a baseline measured in the same process, in
// interleaved rounds (a shared machine's speed drifts between rounds; docs/POCL.md): each benchmark
// iteration is one round that times the device and the baseline back to back, and the
// counters report the median and the range of the per-round ratios. Accuracy of both sides
// is reported next to the speed (counters *_max_rel), measured against an independent
// reference, so a ratio is never bought with accuracy. bench/README.md has the figures.
//
// This file: the whole-process `scatterlut generate` and main; generation: bench_generation.cpp;
// the runtime's lookups and radiance: bench_runtime.cpp (bench_common.hpp: what they share).

#include "bench_common.hpp"

extern char **environ;

namespace {

using namespace slut_bench;

// ------------------------------------------------------------------ whole process

// `scatterlut generate` as a child process (the default run, or --scene FILE for each
// examples/scenes/*.toml), under four cache states:
//   cold:          POCL_KERNEL_CACHE=0, SCATTERLUT_PROGRAM_CACHE=0 (every run compiles)
//   ours_only:     POCL_KERNEL_CACHE=0, our binary cache warm (PoCL's cache unavailable)
//   pocl_only:     PoCL's kernel cache warm, ours off
//   warm:          both warm (the normal second run)
// Each state's caches are private directories (XDG_CACHE_HOME), warmed by one untimed run.
// Runs args[0] (an absolute path) with the environment plus env_extra; its exit status.
int run_generate(const std::vector<std::string> &args, const std::vector<std::string> &env_extra) {
    std::vector<std::string> env_s;
    for (char **e = environ; *e; ++e) {
        const std::string kv = *e;
        bool overridden = false;
        for (const std::string &x : env_extra)
            if (kv.compare(0, x.find('=') + 1, x, 0, x.find('=') + 1) == 0) overridden = true;
        if (!overridden) env_s.push_back(kv);
    }
    env_s.insert(env_s.end(), env_extra.begin(), env_extra.end());
    std::vector<char *> argv, envp;
    for (const std::string &a : args) argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    for (std::string &e : env_s) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid;
    if (posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data()) != 0) return -1;
    posix_spawn_file_actions_destroy(&fa);
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Times `args` as a child process under one cache state (see above), after one untimed
// run that fills whichever cache is on; private cache directories under work_dir.
void time_child(benchmark::State &state, const std::vector<std::string> &args, int cache_state,
                const std::filesystem::path &cache_dir) {
    const bool pocl_warm = cache_state >= 2, ours_warm = cache_state == 1 || cache_state == 3;
    const std::vector<std::string> env = {"XDG_CACHE_HOME=" + cache_dir.string(),
                                          std::string("POCL_KERNEL_CACHE=") + (pocl_warm ? "1" : "0"),
                                          std::string("SCATTERLUT_PROGRAM_CACHE=") + (ours_warm ? "1" : "0")};
    if (run_generate(args, env) != 0) {
        state.SkipWithError(("child failed: " + args[0]).c_str());
        return;
    }
    for (auto _ : state) {
        const auto t0 = Clock::now();
        if (run_generate(args, env) != 0) state.SkipWithError(("child failed: " + args[0]).c_str());
        state.SetIterationTime(seconds_since(t0));
    }
}

std::filesystem::path fresh_directory(const std::string &name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("slut_bench_" + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir / "cache");
    return dir;
}

void BM_GenerateProcess(benchmark::State &state, std::string scene, int cache_state) {
    const std::filesystem::path dir = fresh_directory("generate_" + std::to_string(cache_state));
    std::vector<std::string> args = {SLUT_BINARY, "generate", "--out", (dir / "out").string()};
    if (!scene.empty()) {
        args.push_back("--scene");
        args.push_back(scene);
    }
    time_child(state, args, cache_state, dir / "cache");
    std::filesystem::remove_all(dir);
}

// The fixed cost alone: this binary re-run as a child with --slut-fixed-cost (context,
// both programs built, one tiny table of each kind integrated, exit), under the same four
// cache states. This is what a second `generate` saves, without the tables' own work.
const char *g_self = nullptr;

int fixed_cost_child() {
    scatterlut::Device d("");
    scatterlut::AirlightPlan air;
    air.n_u = air.n_w = 16;
    (void)scatterlut::integrate_airlight_ln_gs(d, scatterlut::make_airlight_table_layout(air));
    scatterlut::NearLightPlan nl = scatterlut::default_near_light_plan(false);
    nl.n_T = nl.n_g = nl.n_r = 4;
    (void)scatterlut::integrate_nearlight_ln_E(d, scatterlut::make_nearlight_table_layout(nl));
    return 0;
}

void BM_FixedCost(benchmark::State &state, int cache_state) {
    const std::filesystem::path dir = fresh_directory("fixed_" + std::to_string(cache_state));
    time_child(state, {g_self, "--slut-fixed-cost"}, cache_state, dir / "cache");
    std::filesystem::remove_all(dir);
}

void register_process_benchmarks() {
    std::vector<std::pair<std::string, std::string>> scenes = {{"default", ""}};
    const std::filesystem::path dir = std::filesystem::path(SLUT_SOURCE_DIR) / "examples" / "scenes";
    if (std::filesystem::is_directory(dir))
        for (const auto &e : std::filesystem::directory_iterator(dir))
            if (e.path().extension() == ".toml") scenes.emplace_back(e.path().stem().string(), e.path().string());
    std::sort(scenes.begin() + 1, scenes.end());
    const char *names[] = {"cold", "ours_only", "pocl_only", "warm"};
    for (int c = 0; c < 4; ++c)
        benchmark::RegisterBenchmark((std::string("BM_FixedCost/") + names[c]).c_str(), BM_FixedCost, c)
            ->UseManualTime()
            ->Iterations(5)
            ->Unit(benchmark::kMillisecond);
    for (const auto &[name, path] : scenes)
        for (int c = 0; c < 4; ++c)
            benchmark::RegisterBenchmark(("BM_GenerateProcess/" + name + "/" + names[c]).c_str(), BM_GenerateProcess, path, c)
                ->UseManualTime()
                ->Iterations(3)
                ->Unit(benchmark::kMillisecond);
}

} // namespace

int main(int argc, char **argv) {
    if (argc == 2 && std::string(argv[1]) == "--slut-fixed-cost") return fixed_cost_child();
    static const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
    g_self = self.c_str();
    register_process_benchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
