// scatterlut benchmarks (bench_scatterlut.cpp): the runtime's cost per call — the fast math, the
// samplers' lookups, the airlight and near-light radiance (scalar, batch, the scalar call's
// paths) with their errors against the exact radiance, and the closed forms engines use.

#include "bench_common.hpp"

namespace {

using namespace slut_bench;

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

} // namespace
