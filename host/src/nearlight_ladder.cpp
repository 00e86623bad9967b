// nearlight_ladder — the near-light table's sampling error against its size, for
// docs/NEARLIGHT.md: generates one table from a plan given on the command line and prints
// its size, the sampling error at 20000 random points and at 20000 hard-corner points
// (generate_nearlight.hpp), and the generation time.
//
//   nearlight_ladder E3|E4 nT ng nr [nS] [T_scale=..] [g_warp=sqrt1p|log1p] [g_scale=..]
//                    [r_scale=..] [storage=f16|f32|f64]
// Keys left out keep default_near_light_plan's values.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "generate_nearlight.hpp"

using namespace scatterlut;

int main(int argc, char **argv) {
    if (argc < 5 || (std::strcmp(argv[1], "E3") != 0 && std::strcmp(argv[1], "E4") != 0)) {
        std::fprintf(stderr, "usage: %s E3|E4 nT ng nr [nS] [key=value ...]\n", argv[0]);
        return 2;
    }
    const bool finite = std::strcmp(argv[1], "E4") == 0;
    NearLightPlan plan = default_near_light_plan(finite);
    plan.n_T = std::atoi(argv[2]);
    plan.n_g = std::atoi(argv[3]);
    plan.n_r = std::atoi(argv[4]);
    int next = 5;
    if (finite) {
        if (argc < 6) {
            std::fprintf(stderr, "E4 needs nS\n");
            return 2;
        }
        plan.n_S = std::atoi(argv[next++]);
    }
    for (; next < argc; ++next) {
        const std::string kv = argv[next];
        const size_t eq = kv.find('=');
        const std::string key = kv.substr(0, eq), value = eq == std::string::npos ? "" : kv.substr(eq + 1);
        if (key == "T_scale") plan.T_scale = std::atof(value.c_str());
        else if (key == "g_scale") plan.g_scale = std::atof(value.c_str());
        else if (key == "r_scale") plan.r_scale = std::atof(value.c_str());
        else if (key == "g_warp" && (value == "sqrt1p" || value == "log1p"))
            plan.g_warp = value == "sqrt1p" ? SLUT_WARP_SQRT1P : SLUT_WARP_LOG1P;
        else if (key == "storage" && storage_from_string(value, &plan.storage)) {
        } else {
            std::fprintf(stderr, "unknown or bad argument '%s'\n", kv.c_str());
            return 2;
        }
    }
    if (plan.n_T < 2 || plan.n_g < 2 || plan.n_r < 2 || (finite && plan.n_S < 2)) {
        std::fprintf(stderr, "node counts must be >= 2\n");
        return 2;
    }
    Device device("");
    const auto t0 = std::chrono::steady_clock::now();
    const Table t = generate_nearlight_table(device, plan, Provenance{});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const NearLightTable table(t);
    const SamplingStats random = measure_nearlight_sampling(table, 20000, 2); // as the generator's (same seed)
    const SamplingStats corners = measure_nearlight_corners(table, 20000, 3);
    std::printf("%s %d x %d x %d", argv[1], plan.n_T, plan.n_g, plan.n_r);
    if (finite) std::printf(" x %d", plan.n_S);
    std::printf(" %s %.2f MiB (T loglin %g, g %s %g, r log1p %g) %.1f s\n", to_string(plan.storage),
                static_cast<double>(t.node_count() * storage_bytes(plan.storage)) / 1048576.0, plan.T_scale,
                warp_name(plan.g_warp), plan.g_scale, plan.r_scale, seconds);
    for (const auto &[label, st] : {std::pair<const char *, const SamplingStats &>{"random: ", random}, {"corners:", corners}})
        std::printf("  %s max %.3e p99 %.3e median %.2e (%llu points); worst at T=%.5g g=%.6g r=%.4g S=%.5g\n", label,
                    st.max_rel, st.p99_rel, st.median_rel, static_cast<unsigned long long>(st.points), st.worst_at[0],
                    st.worst_at[1], st.worst_at[2], st.worst_at[3]);
    return 0;
}
