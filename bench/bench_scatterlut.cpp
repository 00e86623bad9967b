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
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <time.h>
#include <sys/wait.h>

#include "airlight_reference.hpp"
#include "baselines.hpp"
#include "generate_airlight.hpp"
#include "generate_nearlight.hpp"
#include "measure_util.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/nearlight.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_nearlight.h"
}

extern char **environ;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

scatterlut::Device &device() {
    static scatterlut::Device d("");
    return d;
}

// A pause (untimed) between the device run and the baseline, so that the device's worker
// threads are idle again and do not compete with the single-threaded baseline.
void settle(benchmark::State &state) {
    state.PauseTiming();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    state.ResumeTiming();
}

double median(std::vector<double> v) { return scatterlut::percentile(std::move(v), 0.5); }

// Per-round ratios → counters.
void report_rounds(benchmark::State &state, const std::vector<double> &device_s, const std::vector<double> &baseline_s,
                   double cells) {
    std::vector<double> ratio(device_s.size());
    for (size_t k = 0; k < ratio.size(); ++k) ratio[k] = baseline_s[k] / device_s[k];
    state.counters["ratio_median"] = median(ratio);
    state.counters["ratio_min"] = *std::min_element(ratio.begin(), ratio.end());
    state.counters["ratio_max"] = *std::max_element(ratio.begin(), ratio.end());
    state.counters["device_ms"] = 1e3 * median(device_s);
    state.counters["device_cells_per_s"] = cells / median(device_s);
    state.counters["boost_cells_per_s"] = cells / median(baseline_s);
}

// Node indices of a table: uniform random ones plus every corner of the index box.
template <size_t D> std::vector<std::array<int, D>> sample_nodes(const std::array<int, D> &count, int n, uint64_t seed) {
    std::vector<std::array<int, D>> out;
    for (unsigned mask = 0; mask < (1u << D); ++mask) {
        std::array<int, D> c{};
        for (size_t a = 0; a < D; ++a) c[a] = (mask >> a & 1u) ? count[a] - 1 : 0;
        out.push_back(c);
    }
    std::mt19937_64 rng(seed);
    while (static_cast<int>(out.size()) < n) {
        std::array<int, D> c{};
        for (size_t a = 0; a < D; ++a) c[a] = std::uniform_int_distribution<int>(0, count[a] - 1)(rng);
        out.push_back(c);
    }
    return out;
}

// ------------------------------------------------------------------ airlight generation

// The loosest per-piece tolerance that still gives ≤ 1e-13 at every sampled node (Boost's
// |K15 − G7| estimate is pessimistic: 1e-8 gives ~7e-14, 1e-6 already 3e-13; measured on
// 4225 nodes of the 257² table). The counter boost_max_rel shows it holds in each run.
constexpr double kAirlightBoostTol = 1e-8;

// One round: the device integrates every node; the baseline integrates `sample` nodes per
// cell (its time scaled to the whole table). Accuracy: the device at every node against
// the host's independent finer rule (slut_gs_quadrature, refine = 3), device and baseline
// at the sampled nodes against the Boost gauss_kronrod<61> reference
// (tests/airlight_reference.hpp); and the device at every node of a corner table
// (u_max = 500, w_min = 1e-6) against the refine = 3 rule.
void BM_AirlightGeneration(benchmark::State &state) {
    scatterlut::AirlightPlan plan;
    plan.n_u = plan.n_w = static_cast<int>(state.range(0));
    const scatterlut::Table layout = scatterlut::make_airlight_table_layout(plan);
    const slut_axis &au = layout.axes[0].map, &aw = layout.axes[1].map;
    const auto picks = sample_nodes<2>({au.count, aw.count}, 2000, 7);
    std::vector<double> values = scatterlut::integrate_airlight_ln_gs(device(), layout); // warm-up: JIT
    std::vector<double> device_s, baseline_s;
    long evals = 0;
    double baseline_worst = 0, device_worst_sampled = 0;
    for (auto _ : state) {
        auto t0 = Clock::now();
        values = scatterlut::integrate_airlight_ln_gs(device(), layout);
        device_s.push_back(seconds_since(t0));
        settle(state);
        std::vector<double> base(picks.size());
        evals = 0;
        t0 = Clock::now();
        for (size_t k = 0; k < picks.size(); ++k)
            base[k] = slut_bench::scaled_tail(slut_axis_node(&au, picks[k][0]), slut_axis_node(&aw, picks[k][1]),
                                              kAirlightBoostTol, &evals);
        baseline_s.push_back(seconds_since(t0) / static_cast<double>(picks.size()) * static_cast<double>(values.size()));
        if (baseline_worst == 0) { // accuracy once (it does not change between rounds)
            state.PauseTiming();
            for (size_t k = 0; k < picks.size(); ++k) {
                const double u = slut_axis_node(&au, picks[k][0]), w = slut_axis_node(&aw, picks[k][1]);
                const double ref = slut_ref::ref_scaled_tail(u, w);
                baseline_worst = std::max(baseline_worst, std::fabs(base[k] - ref) / ref);
                const double dev = std::exp(values[static_cast<size_t>(picks[k][1]) * au.count + picks[k][0]]);
                device_worst_sampled = std::max(device_worst_sampled, std::fabs(dev - ref) / ref);
            }
            state.ResumeTiming();
        }
    }
    // Device at every node, and at every node of the corner table.
    auto every_node = [](const scatterlut::Table &t, const std::vector<double> &v) {
        const slut_axis &a0 = t.axes[0].map, &a1 = t.axes[1].map;
        std::vector<double> err(static_cast<size_t>(a1.count));
        scatterlut::parallel_for(a1.count, [&](int j) {
            double worst = 0;
            for (int i = 0; i < a0.count; ++i) {
                const double ref = slut_gs_quadrature(slut_axis_node(&a0, i), slut_axis_node(&a1, j), 3.0);
                worst = std::max(worst, std::fabs(std::exp(v[static_cast<size_t>(j) * a0.count + i]) - ref) / ref);
            }
            err[static_cast<size_t>(j)] = worst;
        });
        return *std::max_element(err.begin(), err.end());
    };
    scatterlut::AirlightPlan corner = plan;
    corner.u_max = 500.0;
    corner.w_min = 1e-6;
    const scatterlut::Table corner_layout = scatterlut::make_airlight_table_layout(corner);
    report_rounds(state, device_s, baseline_s, static_cast<double>(values.size()));
    state.counters["device_max_rel"] = every_node(layout, values);
    state.counters["device_max_rel_vs_boost"] = device_worst_sampled;
    state.counters["device_corner_max_rel"] =
        every_node(corner_layout, scatterlut::integrate_airlight_ln_gs(device(), corner_layout));
    state.counters["boost_max_rel"] = baseline_worst;
    state.counters["boost_evals_per_cell"] = static_cast<double>(evals) / static_cast<double>(picks.size());
}
BENCHMARK(BM_AirlightGeneration)->Arg(257)->Arg(1025)->Iterations(7)->Unit(benchmark::kMillisecond);

// One round: the anisotropic airlight table (g = state.range(1)/100) and the isotropic one
// (the one sweep of kernels/airlight_F.cl, the integrand in the host's weights) of the same N×N axes on the
// device, back to back (order alternating between rounds, a pause after each so that the
// device's worker threads are idle again). Each call is timed in process CPU time (every
// thread's, PoCL's workers included: what other jobs on a shared machine take from it counts
// little) and in wall time. Counters: hg_over_iso, the median of the per-round CPU-time ratios
// (the acceptance asks ≤ 2), its quartiles _p25/_p75 and range _min/_max; hg_over_iso_wall,
// the median of the wall-time ratios; hg_ms, iso_ms (CPU-time medians); and the HG table's
// accuracy at 400 nodes against the finer panel rule (refine = 3).
double process_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void BM_AirlightHgGeneration(benchmark::State &state) {
    const int n = static_cast<int>(state.range(0));
    scatterlut::AirlightPlan iso;
    iso.n_u = iso.n_w = n;
    scatterlut::AirlightPlan hg;
    hg.n_u = hg.n_w = n;
    hg.phase_g = static_cast<double>(state.range(1)) / 100.0;
    const scatterlut::Table iso_layout = scatterlut::make_airlight_table_layout(iso);
    scatterlut::Table hg_layout = scatterlut::make_airlight_table_layout(hg);
    scatterlut::integrate_airlight_ln_gs(device(), iso_layout); // warm-up: JIT
    hg_layout.values = scatterlut::integrate_airlight_ln_gs(device(), hg_layout, hg.integration_tolerance);
    std::vector<double> iso_s, hg_s, ratio, ratio_wall;
    int round = 0;
    for (auto _ : state) {
        double cpu[2] = {0, 0}, wall[2] = {0, 0}; // [0] isotropic, [1] anisotropic
        for (int k = 0; k < 2; ++k) {
            const bool hg_now = (k == 0) == (round % 2 == 0);
            const double c0 = process_cpu_seconds();
            const auto t0 = Clock::now();
            if (hg_now) benchmark::DoNotOptimize(scatterlut::integrate_airlight_ln_gs(device(), hg_layout, hg.integration_tolerance));
            else benchmark::DoNotOptimize(scatterlut::integrate_airlight_ln_gs(device(), iso_layout));
            wall[hg_now] = seconds_since(t0);
            cpu[hg_now] = process_cpu_seconds() - c0;
            settle(state);
        }
        iso_s.push_back(cpu[0]);
        hg_s.push_back(cpu[1]);
        ratio.push_back(cpu[1] / cpu[0]);
        ratio_wall.push_back(wall[1] / wall[0]);
        ++round;
    }
    state.counters["hg_over_iso"] = median(ratio);
    state.counters["hg_over_iso_p25"] = scatterlut::percentile(ratio, 0.25);
    state.counters["hg_over_iso_p75"] = scatterlut::percentile(ratio, 0.75);
    state.counters["hg_over_iso_min"] = *std::min_element(ratio.begin(), ratio.end());
    state.counters["hg_over_iso_max"] = *std::max_element(ratio.begin(), ratio.end());
    state.counters["hg_over_iso_wall"] = median(ratio_wall);
    state.counters["hg_ms"] = 1e3 * median(hg_s);
    state.counters["iso_ms"] = 1e3 * median(iso_s);
    state.counters["hg_max_rel"] = scatterlut::measure_airlight_integration(
        hg_layout, scatterlut::airlight_measurement_nodes(hg_layout, 400, 1),
        scatterlut::IntegrationReference::FinerPanelRule);
}
BENCHMARK(BM_AirlightHgGeneration)
    ->Args({257, 85})
    ->Args({257, -50})
    ->Args({513, 85})
    ->Iterations(21)
    ->Unit(benchmark::kMillisecond);

// ------------------------------------------------------------------ near-light generation

// The baseline's cost is set by its break points (each piece costs ≥ 15 evaluations), hardly
// by the tolerance: 1e-9 → 2140 evaluations per E3 cell, 1e-6 → 1630, 1e-4 → 1403, all at
// ≤ 1e-15 against the reference (120 nodes). 1e-6 is the fair middle.
constexpr double kNearLightBoostTol = 1e-6;

// As above for E. Accuracy: device and baseline at the sampled nodes against the
// long-double gauss_kronrod<61> reference (tests/nearlight_reference.hpp).
// The near-light benches' layouts: E3 64³ (range(0) = 3) or E4 32³ × 17 (range(0) = 4).
scatterlut::NearLightPlan bench_near_light_plan(const benchmark::State &state) {
    scatterlut::NearLightPlan plan = scatterlut::default_near_light_plan(state.range(0) == 4);
    plan.n_T = plan.n_g = plan.n_r = plan.finite_thickness ? 32 : 64;
    plan.n_S = 17;
    return plan;
}

void BM_NearLightGeneration(benchmark::State &state) {
    const bool finite = state.range(0) == 4;
    const scatterlut::Table layout = scatterlut::make_nearlight_table_layout(bench_near_light_plan(state));
    const auto &ax = layout.axes;
    const int n_S = finite ? ax[3].map.count : 1;
    const auto picks = sample_nodes<4>({ax[0].map.count, ax[1].map.count, ax[2].map.count, n_S}, 300, 11);
    // The node's (T, g, r, S): S from the slab axis's q map at (T, g) (slut_nl_S_node), as the kernel.
    auto param = [&](const std::array<int, 4> &p, double out[4]) {
        for (size_t a = 0; a < 3; ++a) out[a] = slut_axis_node(&ax[a].map, p[a]);
        out[3] = finite ? slut_nl_S_node(&ax[3].map, out[0], out[1], p[3]) : HUGE_VAL;
    };
    // E at a node from the table's value: ln E (3-D) or ln(E/B) with B = slut_nl_E_base (4-D).
    auto node_E = [&](const std::array<int, 4> &p, double value) {
        double at[4];
        param(p, at);
        return std::exp(value) * (finite ? slut_nl_E_base(at[0], at[2], at[3]) : 1.0);
    };
    auto flat = [&](const std::array<int, 4> &p) {
        size_t node[4] = {static_cast<size_t>(p[0]), static_cast<size_t>(p[1]), static_cast<size_t>(p[2]),
                          static_cast<size_t>(p[3])};
        return layout.index(node);
    };
    std::vector<double> values = scatterlut::integrate_nearlight_ln_E(device(), layout); // warm-up: JIT
    std::vector<double> device_s, baseline_s, ref;
    long evals = 0;
    double baseline_worst = -1, device_worst = 0;
    for (auto _ : state) {
        auto t0 = Clock::now();
        values = scatterlut::integrate_nearlight_ln_E(device(), layout);
        device_s.push_back(seconds_since(t0));
        settle(state);
        std::vector<double> base(picks.size());
        evals = 0;
        t0 = Clock::now();
        for (size_t k = 0; k < picks.size(); ++k) {
            double p[4];
            param(picks[k], p);
            base[k] = slut_bench::nearlight_E(p[0], p[1], p[2], p[3], kNearLightBoostTol, &evals);
        }
        baseline_s.push_back(seconds_since(t0) / static_cast<double>(picks.size()) * static_cast<double>(values.size()));
        if (baseline_worst < 0) {
            state.PauseTiming();
            ref.resize(picks.size());
            scatterlut::parallel_for(static_cast<int>(picks.size()), [&](int k) {
                double p[4];
                param(picks[static_cast<size_t>(k)], p);
                ref[static_cast<size_t>(k)] = static_cast<double>(slut_ref::nearlight_NHE(p[0], p[1], p[2], p[3]).E);
            });
            baseline_worst = 0;
            for (size_t k = 0; k < picks.size(); ++k) {
                baseline_worst = std::max(baseline_worst, std::fabs(base[k] - ref[k]) / ref[k]);
                device_worst = std::max(device_worst, std::fabs(node_E(picks[k], values[flat(picks[k])]) - ref[k]) / ref[k]);
            }
            state.ResumeTiming();
        }
    }
    report_rounds(state, device_s, baseline_s, static_cast<double>(values.size()));
    state.counters["device_max_rel"] = device_worst;
    state.counters["boost_max_rel"] = baseline_worst;
    state.counters["boost_evals_per_cell"] = static_cast<double>(evals) / static_cast<double>(picks.size());
}
BENCHMARK(BM_NearLightGeneration)->Arg(3)->Arg(4)->Iterations(5)->Unit(benchmark::kMillisecond);

// The anisotropic near-light tables (kernels/nearlight_Eg.cl, phase_g = range(1)/100) against
// the isotropic ones (kernels/nearlight_E.cl) on the same axes (the layouts of
// BM_NearLightGeneration), in alternating rounds of the same run: iso_ms, hg_ms (medians) and
// hg_over_iso, the median of the per-round ratios [min, max].
void BM_NearLightHgGeneration(benchmark::State &state) {
    scatterlut::NearLightPlan plan = bench_near_light_plan(state);
    const scatterlut::Table iso = scatterlut::make_nearlight_table_layout(plan);
    plan.phase_g = static_cast<double>(state.range(1)) / 100.0;
    const scatterlut::Table hg = scatterlut::make_nearlight_table_layout(plan);
    scatterlut::integrate_nearlight_ln_E(device(), iso); // warm-up: JIT
    scatterlut::integrate_nearlight_ln_E(device(), hg);
    std::vector<double> iso_s, hg_s, ratio;
    for (auto _ : state) {
        const bool hg_first = (iso_s.size() % 2) == 1; // alternate which runs first
        for (int k = 0; k < 2; ++k) {
            const bool run_hg = (k == 0) == hg_first;
            const auto t0 = Clock::now();
            benchmark::DoNotOptimize(scatterlut::integrate_nearlight_ln_E(device(), run_hg ? hg : iso));
            (run_hg ? hg_s : iso_s).push_back(seconds_since(t0));
        }
        ratio.push_back(hg_s.back() / iso_s.back());
    }
    state.counters["iso_ms"] = 1e3 * median(iso_s);
    state.counters["hg_ms"] = 1e3 * median(hg_s);
    state.counters["hg_over_iso"] = median(ratio);
    state.counters["hg_over_iso_min"] = *std::min_element(ratio.begin(), ratio.end());
    state.counters["hg_over_iso_max"] = *std::max_element(ratio.begin(), ratio.end());
}
BENCHMARK(BM_NearLightHgGeneration)
    ->Args({3, 85})
    ->Args({4, 85})
    ->Args({3, -90})
    ->Iterations(5)
    ->Unit(benchmark::kMillisecond);

// ------------------------------------------------------------------ runtime: lookups and radiance

const scatterlut::Table &default_airlight_table() {
    static const scatterlut::Table t = [] {
        scatterlut::AirlightPlan plan;
        scatterlut::Table layout = scatterlut::make_airlight_table_layout(plan);
        layout.values = scatterlut::integrate_airlight_ln_gs(device(), layout);
        for (double &v : layout.values) v = scatterlut::round_to_storage(v, plan.storage);
        return layout;
    }();
    return t;
}

const scatterlut::Table &default_nearlight_table(bool finite) {
    static scatterlut::Table t3, t4;
    scatterlut::Table &t = finite ? t4 : t3;
    if (t.values.empty()) {
        const scatterlut::NearLightPlan plan = scatterlut::default_near_light_plan(finite);
        t = scatterlut::make_nearlight_table_layout(plan);
        t.values = scatterlut::integrate_nearlight_ln_E(device(), t);
        for (double &v : t.values) v = scatterlut::round_to_storage(v, plan.storage);
    }
    return t;
}

constexpr size_t kPoints = 4096; // cycled through; fits in L1/L2 with the query structs

// The runtime's cheaper forms of kernels/slut_fastmath.h against libm's, on the same 4096
// arguments cycled (independent calls: throughput): /0 slut_sincos_half_angle and /1 glibc's
// sincos on h uniform in [0, π/2]; /2 slut_log1p_goldberg and /3 log1p on x = 10^U(−8, 3).
void BM_FastMath(benchmark::State &state) {
    const int which = static_cast<int>(state.range(0));
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> half_angle(0.0, M_PI / 2), decade(-8.0, 3.0);
    std::vector<double> args(kPoints);
    for (double &a : args) a = which < 2 ? half_angle(rng) : std::pow(10.0, decade(rng));
    size_t k = 0;
    for (auto _ : state) {
        const double a = args[k];
        double s = 0.0, c = 0.0;
        if (which == 0) slut_sincos_half_angle(a, &s, &c);
        else if (which == 1) sincos(a, &s, &c);
        else s = which == 2 ? slut_log1p_goldberg(a) : std::log1p(a);
        benchmark::DoNotOptimize(s);
        benchmark::DoNotOptimize(c);
        k = (k + 1) % kPoints;
    }
}
BENCHMARK(BM_FastMath)->DenseRange(0, 3);

void BM_AirlightScaledTail(benchmark::State &state) {
    const scatterlut::AirlightTable table(default_airlight_table());
    const slut_axis &au = table.table().axes[0].map, &aw = table.table().axes[1].map;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<std::pair<double, double>> at(kPoints);
    for (auto &p : at) p = {slut_param_from_unit(&au, unit(rng)), slut_param_from_unit(&aw, unit(rng))};
    size_t k = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(table.scaled_tail(at[k].first, at[k].second));
        k = (k + 1) % kPoints;
    }
}
BENCHMARK(BM_AirlightScaledTail);

void BM_NearLightE(benchmark::State &state) {
    const bool finite = state.range(0) == 4;
    const scatterlut::NearLightTable table(default_nearlight_table(finite));
    const auto &ax = table.table().axes;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<std::array<double, 4>> at(kPoints);
    for (auto &p : at) {
        for (size_t a = 0; a < 3; ++a) p[a] = slut_param_from_unit(&ax[a].map, unit(rng));
        p[3] = finite ? slut_param_from_unit(&ax[3].map, unit(rng)) : HUGE_VAL;
    }
    size_t k = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(table.E(at[k][0], at[k][1], at[k][2], at[k][3]));
        k = (k + 1) % kPoints;
    }
}
BENCHMARK(BM_NearLightE)->Arg(3)->Arg(4);

// Airlight geometries over the table's domain: σ_t D ∈ [1e-3, 10], γ ∈ (0, π), s ∈ [0.01 D, 10 D].
// Arg 0: all of them; 1: only those one θ-panel covers (slut_airlight_theta_fits_one_panel:
// no table sample); 2: only the others (two table samples, or the panel rule where the two
// ends' terms would cancel). The per-path costs say where the time goes.
std::vector<scatterlut::AirlightQuery> airlight_bench_queries(int which) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<scatterlut::AirlightQuery> qs;
    while (qs.size() < kPoints) {
        scatterlut::AirlightQuery q;
        q.sigma_s_per_m = 0.5;
        q.sigma_a_per_m = 0.1;
        q.intensity_W_per_sr = 1.0;
        q.distance_m = std::pow(10.0, -3.0 + 4.0 * unit(rng)) / 0.6;
        q.gamma_rad = 1e-3 + (M_PI - 2e-3) * unit(rng);
        q.length_m = q.distance_m * std::pow(10.0, -2.0 + 3.0 * unit(rng));
        if (which != 0) {
            const slut_airlight_geometry g =
                slut_airlight_setup(q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m,
                                    std::sin(q.gamma_rad), std::cos(q.gamma_rad), q.length_m);
            if ((which == 1) != (slut_airlight_theta_fits_one_panel(g) != 0)) continue;
        }
        qs.push_back(q);
    }
    return qs;
}

// Counters median_rel and max_rel: the relative error of `eval` against airlight_radiance_exact
// on the queries (after the timed loop).
template <class Eval>
void add_airlight_error_counters(benchmark::State &state, const std::vector<scatterlut::AirlightQuery> &qs, Eval eval) {
    std::vector<double> err;
    for (const auto &q : qs) err.push_back(std::fabs(eval(q) / scatterlut::airlight_radiance_exact(q) - 1.0));
    std::sort(err.begin(), err.end());
    state.counters["median_rel"] = err[err.size() / 2];
    state.counters["max_rel"] = err.back();
}

void BM_AirlightRadiance(benchmark::State &state) {
    const scatterlut::AirlightTable table(default_airlight_table());
    const std::vector<scatterlut::AirlightQuery> qs = airlight_bench_queries(static_cast<int>(state.range(0)));
    size_t k = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(table.radiance(qs[k]));
        k = (k + 1) % kPoints;
    }
    add_airlight_error_counters(state, qs, [&table](const scatterlut::AirlightQuery &q) { return table.radiance(q); });
}
BENCHMARK(BM_AirlightRadiance)->Arg(0)->Arg(1)->Arg(2);

// The closed forms engines use instead of the table (Macklin 2010), on BM_AirlightRadiance/0's
// geometries: /0 without extinction, /1 times e^{−σ_t D}. Their error against the exact
// radiance on these geometries is in the counters (median and max relative error), beside
// the table's (BM_AirlightRadiance's counters).
void BM_AirlightClosedForm(benchmark::State &state) {
    const std::vector<scatterlut::AirlightQuery> qs = airlight_bench_queries(0);
    const bool attenuated = state.range(0) == 1;
    auto eval = [attenuated](const scatterlut::AirlightQuery &q) {
        return attenuated ? scatterlut::airlight_radiance_no_extinction_attenuated(q)
                          : scatterlut::airlight_radiance_no_extinction(q);
    };
    size_t k = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(eval(qs[k]));
        k = (k + 1) % kPoints;
    }
    add_airlight_error_counters(state, qs, eval);
}
BENCHMARK(BM_AirlightClosedForm)->Arg(0)->Arg(1);

// Near-light geometries: light 0.1–10 m from the entry point above the plane, view
// directions over the upper hemisphere, thick (3-D table) or slabs of 1 mm – 10 m (4-D).
std::vector<scatterlut::NearLightQuery> near_light_bench_queries(bool finite) {
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> unit(0, 1);
    auto hemisphere = [&](double out[3]) {
        const double z = 0.05 + 0.95 * unit(rng), phi = 2 * M_PI * unit(rng), s = std::sqrt(1 - z * z);
        out[0] = s * std::cos(phi);
        out[1] = s * std::sin(phi);
        out[2] = z;
    };
    std::vector<scatterlut::NearLightQuery> qs(kPoints);
    for (auto &q : qs) {
        q.sigma_s_per_m = 0.8;
        q.sigma_a_per_m = 0.2;
        q.intensity_W_per_sr = 1.0;
        hemisphere(q.eye_dir);
        double l[3];
        hemisphere(l);
        const double dist = std::pow(10.0, -1.0 + 2.0 * unit(rng));
        for (int i = 0; i < 3; ++i) q.light_rel_m[i] = dist * l[i];
        q.length_m = finite ? std::pow(10.0, -3.0 + 4.0 * unit(rng)) : HUGE_VAL;
    }
    return qs;
}

void BM_NearLightRadiance(benchmark::State &state) {
    const bool finite = state.range(0) == 4;
    const scatterlut::NearLightTable table(default_nearlight_table(finite));
    const std::vector<scatterlut::NearLightQuery> qs = near_light_bench_queries(finite);
    size_t k = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(table.radiance(qs[k]));
        k = (k + 1) % kPoints;
    }
}
BENCHMARK(BM_NearLightRadiance)->Arg(3)->Arg(4);

// The batch radiance (AirlightTable::radiance and NearLightTable::radiance over spans) against
// the scalar call and, for the airlight, the closed form × e^{−σ_t D} engines use, on the
// geometries of BM_AirlightRadiance/0 (arg 0) and BM_NearLightRadiance/3, /4 (args 3, 4). One
// iteration is one round: the 4096 queries through each method back to back (thread CPU
// time, so that other processes on the cores do not count), the order rotating per round.
// Counters: ns per query of each (medians over the rounds), and the medians [min, max] of
// the per-round ratios scalar/batch and closed form/batch (> 1: the batch is faster).
double thread_cpu_seconds() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void BM_RadianceBatch(benchmark::State &state) {
    const int which = static_cast<int>(state.range(0));
    std::vector<std::function<double()>> methods; // each runs all kPoints queries, returns a checksum
    std::vector<double> out(kPoints);
    std::unique_ptr<scatterlut::AirlightTable> air;
    std::unique_ptr<scatterlut::NearLightTable> near;
    std::vector<scatterlut::AirlightQuery> air_qs;
    std::vector<scatterlut::NearLightQuery> near_qs;
    if (which == 0) {
        air = std::make_unique<scatterlut::AirlightTable>(default_airlight_table());
        air_qs = airlight_bench_queries(0);
        methods.push_back([&] {
            double sum = 0;
            for (const auto &q : air_qs) sum += air->radiance(q);
            return sum;
        });
        methods.push_back([&] {
            air->radiance(air_qs.data(), air_qs.size(), out.data());
            return out[0] + out[kPoints - 1];
        });
        methods.push_back([&] {
            double sum = 0;
            for (const auto &q : air_qs) sum += scatterlut::airlight_radiance_no_extinction_attenuated(q);
            return sum;
        });
    } else {
        near = std::make_unique<scatterlut::NearLightTable>(default_nearlight_table(which == 4));
        near_qs = near_light_bench_queries(which == 4);
        methods.push_back([&] {
            double sum = 0;
            for (const auto &q : near_qs) sum += near->radiance(q);
            return sum;
        });
        methods.push_back([&] {
            near->radiance(near_qs.data(), near_qs.size(), out.data());
            return out[0] + out[kPoints - 1];
        });
    }
    std::vector<std::vector<double>> seconds(methods.size());
    size_t round = 0;
    for (auto _ : state) {
        for (size_t m = 0; m < methods.size(); ++m) {
            const size_t k = (m + round) % methods.size();
            const double t0 = thread_cpu_seconds();
            benchmark::DoNotOptimize(methods[k]());
            seconds[k].push_back(thread_cpu_seconds() - t0);
        }
        ++round;
    }
    const char *names[] = {"scalar", "batch", "closed_form_att"};
    for (size_t m = 0; m < methods.size(); ++m)
        state.counters[std::string(names[m]) + "_ns"] = 1e9 * median(seconds[m]) / static_cast<double>(kPoints);
    for (size_t m = 0; m < methods.size(); ++m) {
        if (m == 1) continue;
        std::vector<double> ratio(seconds[1].size());
        for (size_t k = 0; k < ratio.size(); ++k) ratio[k] = seconds[m][k] / seconds[1][k];
        const std::string name = std::string(names[m]) + "_over_batch";
        state.counters[name] = median(ratio);
        state.counters[name + "_min"] = *std::min_element(ratio.begin(), ratio.end());
        state.counters[name + "_max"] = *std::max_element(ratio.begin(), ratio.end());
    }
}
BENCHMARK(BM_RadianceBatch)->Arg(0)->Arg(3)->Arg(4)->Iterations(200)->Unit(benchmark::kMillisecond);

// The scalar airlight radiance against the portable path it takes on CPUs without AVX2 + FMA
// (scatterlut::detail::airlight_radiance_portable: the scalar call before its vector path), in
// one process, on the geometries of BM_AirlightRadiance/N (arg N). One iteration is one round:
// the 4096 queries through each, back to back in alternating order, thread CPU time. Counters:
// ns per query of each (medians over the rounds) and portable_over_scalar, the median [min,
// max] of the per-round ratios (> 1: the scalar call's vector path is faster).
void BM_AirlightScalarPaths(benchmark::State &state) {
    const scatterlut::AirlightTable table(default_airlight_table());
    const std::vector<scatterlut::AirlightQuery> qs = airlight_bench_queries(static_cast<int>(state.range(0)));
    const std::function<double()> methods[2] = {
        [&] {
            double sum = 0;
            for (const auto &q : qs) sum += table.radiance(q);
            return sum;
        },
        [&] {
            double sum = 0;
            for (const auto &q : qs) sum += scatterlut::detail::airlight_radiance_portable(table, q);
            return sum;
        }};
    std::vector<double> seconds[2];
    size_t round = 0;
    for (auto _ : state) {
        for (size_t m = 0; m < 2; ++m) {
            const size_t k = (m + round) % 2;
            const double t0 = thread_cpu_seconds();
            benchmark::DoNotOptimize(methods[k]());
            seconds[k].push_back(thread_cpu_seconds() - t0);
        }
        ++round;
    }
    state.counters["scalar_ns"] = 1e9 * median(seconds[0]) / static_cast<double>(kPoints);
    state.counters["portable_ns"] = 1e9 * median(seconds[1]) / static_cast<double>(kPoints);
    std::vector<double> ratio(seconds[0].size());
    for (size_t k = 0; k < ratio.size(); ++k) ratio[k] = seconds[1][k] / seconds[0][k];
    state.counters["portable_over_scalar"] = median(ratio);
    state.counters["portable_over_scalar_min"] = *std::min_element(ratio.begin(), ratio.end());
    state.counters["portable_over_scalar_max"] = *std::max_element(ratio.begin(), ratio.end());
}
BENCHMARK(BM_AirlightScalarPaths)->Arg(0)->Arg(1)->Arg(2)->Iterations(200)->Unit(benchmark::kMillisecond);

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
