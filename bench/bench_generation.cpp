// scatterlut benchmarks (bench_scatterlut.cpp): generation on the OpenCL device against a per-cell
// Boost.Math baseline in the same run, in interleaved rounds — the airlight tables (isotropic and
// Henyey–Greenstein) and the near-light tables (isotropic and Henyey–Greenstein).

#include "bench_common.hpp"

namespace {

using namespace slut_bench;

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

} // namespace
