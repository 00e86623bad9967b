#include "generate_airlight_hg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "generate_airlight.hpp" // airlight_measurement_nodes: the same node picks
#include "measure_util.hpp"
#include "reference_quadrature.hpp"
#include "table_build.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/sampler.hpp"

extern "C" {
#include "slut_airlight_hg.h"
}

namespace scatterlut {

Table make_airlight_hg_table_layout(const AirlightHgPlan &plan) {
    check_phase_g(plan.phase_g);
    Table t;
    t.kind = kKindAirlightFg;
    t.quantity_version = kAirlightFgQuantityVersion;
    t.axes = {make_axis("u", "optical distance sigma_t*D*sin(gamma) (dimensionless), first argument of F_g(u,v)", 0.0,
                        plan.u_max, plan.u_scale, SLUT_WARP_LOG1P, plan.n_u),
              make_axis("w", "pi/2 - v (rad), v the second argument of F_g(u,v)", plan.w_min, SLUT_PIO2_HI, 0.0,
                        SLUT_WARP_ASINH_COT, plan.n_w)};
    Channel c;
    c.name = "ln_Gs_g";
    c.meaning = "ln of the scaled tail Gs_g(u,w) = exp(u cot w) * int_{pi/2-w}^{pi/2} psi_g(2x) exp(-u tan x) dx / w, "
                "psi_g = 4 pi p_g (Henyey-Greenstein, g = phase.g), in (0, psi_max]";
    c.encoding = Encoding::Log;
    t.channels = {c};
    t.storage = plan.storage;
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", plan.phase_g);
    t.extra[kPhaseGKey] = text;
    return t;
}

std::vector<double> integrate_airlight_hg_ln_gs(Device &device, const Table &layout, double tolerance) {
    return integrate_airlight_hg_ln_gs_sweep(device, layout, tolerance, table_phase_g(layout));
}

Table generate_airlight_hg_table(Device &device, const AirlightHgPlan &plan, const Provenance &provenance,
                                 const std::function<void(double)> &progress) {
    Table t = make_airlight_hg_table_layout(plan);
    begin_generation(t, provenance, plan.integration_tolerance);
    t.values = integrate_airlight_hg_ln_gs(device, t, plan.integration_tolerance);
    if (progress) progress(1.0);
    t.accuracy.integration_max_rel = measure_airlight_hg_integration(t, airlight_measurement_nodes(t, 400, 1),
                                                                     IntegrationReference::FinerPanelRule);
    t.accuracy.storage_max_rel = storage_rounding_max_rel(t, t.storage);
    for (double &v : t.values) v = round_to_storage(v, t.storage);
    const SamplingStats s = measure_airlight_hg_sampling(AirlightHgTable(t), 20000, 2);
    t.accuracy.sampling_max_rel = s.max_rel;
    t.accuracy.sampling_p99_rel = s.p99_rel;
    t.accuracy.sampling_median_rel = s.median_rel;
    t.accuracy.sampling_points = s.points;
    t.accuracy.sampling_domain = "Gs_g(u,w) at uniform random unit coordinates over the whole table";
    return t;
}

double measure_airlight_hg_integration(const Table &table, const std::vector<NodeIndex> &nodes,
                                       IntegrationReference reference) {
    const double g = table_phase_g(table);
    const slut_axis &au = table.axes[0].map;
    const slut_axis &aw = table.axes[1].map;
    std::vector<double> err(nodes.size());
    parallel_for(static_cast<int>(nodes.size()), [&](int k) {
        const NodeIndex &p = nodes[static_cast<size_t>(k)];
        const double u = slut_axis_node(&au, static_cast<int>(p[0])), w = slut_axis_node(&aw, static_cast<int>(p[1]));
        const double stored = decode(table.channels[0].encoding, table.values[table.index(p.data())]);
        const double exact = reference == IntegrationReference::FinerPanelRule ? slut_hg_gs_quadrature(u, w, g, 3.0)
                                                                                : reference_scaled_tail_hg(u, w, g);
        err[static_cast<size_t>(k)] = std::fabs(stored - exact) / exact;
    });
    double worst = 0;
    for (double e : err) worst = std::isnan(e) ? HUGE_VAL : std::max(worst, e);
    return worst;
}

SamplingStats measure_airlight_hg_sampling(const AirlightHgTable &table, int points, uint64_t seed) {
    const slut_axis &au = table.table().axes[0].map;
    const slut_axis &aw = table.table().axes[1].map;
    const double g = table.phase_g();
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::pair<double, double>> at(static_cast<size_t>(points));
    for (auto &p : at) p = {slut_param_from_unit(&au, unit(rng)), slut_param_from_unit(&aw, unit(rng))};
    std::vector<double> err(at.size());
    parallel_for(points, [&](int k) {
        const auto [u, w] = at[static_cast<size_t>(k)];
        const double exact = slut_hg_gs_quadrature(u, w, g, 1.0);
        err[static_cast<size_t>(k)] = std::fabs(table.scaled_tail(u, w) - exact) / exact;
    });
    SamplingStats s;
    const auto worst = std::max_element(err.begin(), err.end());
    s.max_rel = *worst;
    s.worst_u = at[static_cast<size_t>(worst - err.begin())].first;
    s.worst_w = at[static_cast<size_t>(worst - err.begin())].second;
    s.p99_rel = percentile(err, 0.99);
    s.median_rel = percentile(err, 0.5);
    s.points = err.size();
    return s;
}

double airlight_hg_large_u_onset(double phase_g, double target, double w_min) {
    for (double u = 1.0; u < 1e5; u *= 1.1) {
        double worst = 0;
        for (double uu : {u, 1.3 * u, 2.0 * u})
            for (int i = 0; i < 48 && worst <= 0.5 * target; ++i) {
                const double w = w_min * std::pow(SLUT_PIO2_HI / w_min, i / 47.0);
                const double exact = slut_hg_gs_quadrature(uu, w, phase_g, 1.0);
                worst = std::max(worst, std::fabs(slut_hg_gs_large_u(uu, w, phase_g) - exact) / exact);
            }
        if (worst <= 0.5 * target) return u;
    }
    return 1e5;
}

double airlight_hg_w_min(double phase_g, double target) {
    // Halve w from 1e-3 until the small-w form holds at w and below (checked at w, w/2, w/4).
    for (double w = 1e-3; w > 1e-9; w *= 0.5) {
        double worst = 0;
        for (double ww : {w, 0.5 * w, 0.25 * w})
            for (int i = 0; i < 16; ++i) {
                const double a = 1e-3 * std::pow(1e7, i / 15.0); // a = u·cot w over 1e-3 … 1e4
                const double u = a * std::tan(ww);
                const double exact = slut_hg_gs_quadrature(u, ww, phase_g, 1.0);
                worst = std::max(worst, std::fabs(slut_hg_gs_small_w(ww, a, phase_g) - exact) / exact);
            }
        if (worst <= 0.5 * target) return w;
    }
    return 1e-9;
}

} // namespace scatterlut
