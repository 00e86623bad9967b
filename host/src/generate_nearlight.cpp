#include "generate_nearlight.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "measure_util.hpp"
#include "reference_quadrature.hpp"
#include "table_build.hpp"
#include "scatterlut/io.hpp"

extern "C" {
#include "slut_nearlight.h"
#include "slut_nearlight_hg.h"
}

namespace scatterlut {
namespace {

// What the measurements read of a table, isotropic or anisotropic: the isotropic front-end
// over the stored values, the factor they are scaled by (ψ_max; 1 for the isotropic kinds) and
// the phase (0: the isotropic integral, bit for bit today's measurement).
struct MeasuredTable {
    const NearLightTable &stored;
    const NearLightHgTable *anisotropic = nullptr; // null: the isotropic kinds
    double phase_g = 0.0;
    double node_E(const size_t *node) const { return anisotropic ? anisotropic->node_E(node) : stored.node_E(node); }
    double E(double T, double g, double r, double S) const {
        return anisotropic ? anisotropic->E(T, g, r, S) : stored.E(T, g, r, S);
    }
    // The quadrature E (E_g) at (T, g, r, S), refine 1 (2.5: the finer panel rule).
    double exact(double T, double g, double r, double S, double refine = 1.0) const {
        if (phase_g == 0.0) {
            double E;
            slut_nl_E_lanes(T, g, S, &r, 1, &E, refine);
            return E;
        }
        return slut_hg_nl_E(T, g, r, (S > 1e300) ? HUGE_VAL : S / T, phase_g, refine);
    }
};

MeasuredTable measured(const NearLightTable &t) { return {t, nullptr, 0.0}; }
MeasuredTable measured(const NearLightHgTable &t) { return {t.scaled(), &t, t.phase_g()}; }

} // namespace

NearLightPlan default_near_light_plan(bool finite_thickness) {
    NearLightPlan plan;
    plan.finite_thickness = finite_thickness;
    if (finite_thickness) {
        plan.n_T = 80;
        plan.n_g = 32;
        plan.n_r = 64;
        plan.n_S = 48;
        plan.r_scale = 1e-9;
        plan.g_warp = SLUT_WARP_LOG1P;
        plan.g_scale = 0.02;
    }
    return plan;
}

double near_light_hg_g_max(double phase_g, bool finite_thickness) {
    return (phase_g < -0.5 || (finite_thickness && phase_g <= -0.5)) ? 0.85 : 1.0;
}

Table make_nearlight_table_layout(const NearLightPlan &plan) {
    const bool hg = plan.phase_g != 0.0;
    Table t;
    t.kind = plan.finite_thickness ? (hg ? kKindNearLightE4Hg : kKindNearLightE4)
                                   : (hg ? kKindNearLightE3Hg : kKindNearLightE3);
    t.quantity_version = kNearLightEQuantityVersion;
    t.axes.push_back(make_axis("T", "optical distance sigma_t*l from the entry point to the light", plan.T_min,
                               plan.T_max, plan.T_scale, SLUT_WARP_LOGLIN, plan.n_T));
    t.axes.push_back(make_axis("g", "cosine between the eye direction and the direction to the light", plan.g_min,
                               plan.g_max, plan.g_scale, plan.g_warp, plan.n_g));
    t.axes.push_back(make_axis("r", "mu_l/mu_e, ratio of the light's and the eye's cosines to the normal", 0.0,
                               plan.r_max, plan.r_scale, SLUT_WARP_LOG1P, plan.n_r));
    if (plan.finite_thickness)
        t.axes.push_back(make_axis("q",
                                   "slab S = sigma_t*s in [min, max] by its share q = H(S)/H(inf) of the inverse-square "
                                   "weight: unit coordinate ln(sigma(S)/sigma(min))/ln(sigma(max)/sigma(min)) at each "
                                   "(T, g), sigma = T*(acos g/sqrt(1-g^2))*q/(1-q) (slut_nl_unit_from_S)",
                                   plan.S_min, plan.S_max, 0.0, SLUT_WARP_NL_QODDS, plan.n_S));
    Channel c;
    c.name = plan.finite_thickness ? "ln_E_over_B" : "ln_E";
    c.meaning = plan.finite_thickness
                    ? "ln(E/B): E = N/H, the inverse-square-weighted mean attenuation in (0,1], over the closed-form "
                      "base B = exp(-T) + (1-exp(-T))*E_thin(r, S*T/(S+T)) (slut_nl_E_base)"
                    : "ln of E = N/H, the inverse-square-weighted mean attenuation, in (0,1]";
    c.encoding = Encoding::Log;
    if (hg) {
        check_phase_g(plan.phase_g);
        c.name = plan.finite_thickness ? "ln_E_over_D_B" : "ln_E_over_D";
        c.meaning = std::string("ln(E_g/D") + (plan.finite_thickness ? "/B" : "") +
                    "): E_g = N_g/H, the inverse-square-weighted mean of psi*attenuation, psi = 4*pi*p the "
                    "Henyey-Greenstein phase of asymmetry phase.g, D = slut_hg_nl_divisor: " +
                    (plan.finite_thickness
                         ? std::string("((1+|phase.g|)/(1-|phase.g|))^3 times the attenuation-weighted mean of "
                                       "psi along the path by 16-point Gauss-Legendre in theta")
                         : std::string("psi at the entry point (cos theta = -g), for phase.g < 0 "
                                       "psi_max*(psi0/psi_min)^(1-exp(-T))")) +
                    (plan.finite_thickness ? ", B = slut_nl_E_base (the isotropic slab table's base)" : "");
        t.extra[kExtraPhaseG] = phase_g_text(plan.phase_g);
    }
    t.channels = {c};
    t.storage = plan.storage;
    return t;
}

namespace {

// One near-light kernel over every node of `layout` (axis 0 fastest): the arguments (out, then
// T, g, r node buffers with their counts, the S axis — a thick table passes one layer at
// S = +inf —, the kernel's own `extra` arguments, the refine factor), launched as work-items
// (dim0, g, T padded to a multiple of local_T) in work-groups (local0, 1, local_T), in a few
// slices of g when `progress` is given. The kernel returns at once for T nodes past T_count.
std::vector<double> run_nearlight_kernel(Device &device, const Table &layout, const char *file, const char *name,
                                         const std::function<void(cl::Kernel &, int &)> &extra, size_t dim0,
                                         size_t local0, size_t local_T, const std::function<void(double)> &progress,
                                         double tolerance) {
    const bool finite_thickness = layout.axes.size() == 4;
    const int n_g = layout.axes[1].map.count, n_T = layout.axes[0].map.count;
    cl::Program &program = device.program(file);
    cl::Kernel kernel(program, name);
    std::vector<double> values(layout.node_count());
    const cl::Buffer out = output_buffer(device, values);
    int arg = 0;
    kernel.setArg(arg++, out);
    std::vector<cl::Buffer> node_buffers; // T, g, r: each axis's nodes (slut_axis_node)
    node_buffers.reserve(3);
    for (size_t a = 0; a < 3; ++a) {
        const slut_axis &map = layout.axes[a].map;
        std::vector<double> nodes(static_cast<size_t>(map.count));
        for (int i = 0; i < map.count; ++i) nodes[static_cast<size_t>(i)] = slut_axis_node(&map, i);
        node_buffers.push_back(input_buffer(device, nodes));
        kernel.setArg(arg++, node_buffers.back());
        kernel.setArg(arg++, map.count);
    }
    const double inf = std::numeric_limits<double>::infinity();
    const slut_axis thick = {inf, inf, 0.0, SLUT_WARP_LINEAR, 1};
    set_axis_args(kernel, &arg, finite_thickness ? layout.axes[3].map : thick);
    extra(kernel, arg);
    kernel.setArg(arg++, slut_nl_refine_for_tolerance(tolerance));
    // With a progress callback the launch is cut into a few slices of g (one report each);
    // without one it is a single launch: each slice ends in a wait for its slowest
    // work-items with a core idle.
    const int slices = progress ? std::min(n_g, 8) : 1, per_slice = (n_g + slices - 1) / slices;
    const size_t global_T = (static_cast<size_t>(n_T) + local_T - 1) / local_T * local_T;
    for (int ig0 = 0; ig0 < n_g; ig0 += per_slice) {
        const int count = std::min(per_slice, n_g - ig0);
        device.queue().enqueueNDRangeKernel(kernel, cl::NDRange(0, static_cast<size_t>(ig0), 0),
                                            cl::NDRange(dim0, static_cast<size_t>(count), global_T),
                                            cl::NDRange(local0, 1, local_T));
        if (!progress) continue;
        device.queue().finish();
        progress(static_cast<double>(ig0 + count) / n_g);
    }
    wait_for_output(device, out, values);
    device.kernels_ran(file);
    return values;
}

} // namespace

std::vector<double> integrate_nearlight_ln_E(Device &device, const Table &layout,
                                             const std::function<void(double)> &progress, double tolerance) {
    const bool finite_thickness = layout.axes.size() == 4;
    const int n_T = layout.axes[0].map.count, n_g = layout.axes[1].map.count, n_r = layout.axes[2].map.count;
    const int n_S = finite_thickness ? layout.axes[3].map.count : 1;
    if (layout.kind == kKindNearLightE3Hg || layout.kind == kKindNearLightE4Hg) {
        // kernels/nearlight_Eg.cl: one work-item per (r, g, T) node marching each S node, in
        // work-groups of one r row (its private arrays are SLUT_NLG_MAX_S doubles).
        SLUT_CHECK_LE(n_S, 64); // SLUT_NLG_MAX_S of the kernel
        const double phase_g = table_phase_g(layout);
        return run_nearlight_kernel(
            device, layout, "nearlight_Eg.cl", "nearlight_ln_Eg",
            [phase_g](cl::Kernel &kernel, int &arg) { kernel.setArg(arg++, phase_g); }, static_cast<size_t>(n_r),
            static_cast<size_t>(n_r), 1, progress, tolerance);
    }
    const size_t n = layout.node_count();
    const size_t groups = static_cast<size_t>((n_r + SLUT_NL_MAX_LANES - 1) / SLUT_NL_MAX_LANES);
    // The launch covers every node once: r groups × g × T work-items, each sweeping the S axis.
    SLUT_CHECK_GE(groups * SLUT_NL_MAX_LANES, static_cast<size_t>(n_r));
    SLUT_CHECK_EQ(n, static_cast<size_t>(n_T) * n_g * n_r * n_S);
    SLUT_CHECK_LE(n_S, SLUT_NL_MAX_SWEEP);
    // One work-item per (r group, g, T) sweeps every S node (slut_nl_E_sweep), in work-groups
    // of kNearLightGroupT T nodes: few enough for PoCL's stack (it may keep the private arrays
    // of every work-item of a group on one thread's stack; E alone is SLUT_NL_MAX_SWEEP ×
    // SLUT_NL_MAX_LANES doubles, 8 KiB: its automatic groups of ~2000 overflowed it), enough
    // to take the per-group dispatch out of the kernel's time.
    return run_nearlight_kernel(device, layout, "nearlight_E.cl", "nearlight_ln_E", [](cl::Kernel &, int &) {},
                                groups, 1, static_cast<size_t>(kNearLightGroupT), progress, tolerance);
}

namespace {

template <class Sampler>
Table generate_table(Device &device, const NearLightPlan &plan, const Provenance &provenance,
                     const std::function<void(double)> &progress) {
    Table t = make_nearlight_table_layout(plan);
    begin_generation(t, provenance, plan.integration_tolerance);
    t.values = integrate_nearlight_ln_E(device, t, progress, plan.integration_tolerance);

    t.accuracy.integration_max_rel =
        measure_nearlight_integration(Sampler(t), random_table_nodes(t, 400, 1),
                                      IntegrationReference::FinerPanelRule);
    round_to_table_storage(t);
    const SamplingStats s = measure_nearlight_sampling(Sampler(t), 20000, 2);
    const char *what = plan.phase_g != 0.0 ? "E_g" : "E";
    const char *where = plan.phase_g != 0.0 ? "the attenuation E >= 1e-6" : "E >= 1e-6";
    record_sampling(t, s,
                    plan.finite_thickness
                        ? std::string(what) + " at uniform random unit coordinates of T, g, r and log-uniform S where " + where
                        : std::string(what) + " at uniform random unit coordinates where " + where);
    return t;
}

} // namespace

Table generate_nearlight_table(Device &device, const NearLightPlan &plan, const Provenance &provenance,
                               const std::function<void(double)> &progress) {
    if (plan.phase_g != 0.0) return generate_table<NearLightHgTable>(device, plan, provenance, progress);
    return generate_table<NearLightTable>(device, plan, provenance, progress);
}

namespace {

double integration_error(const MeasuredTable &nl, const std::vector<NodeIndex> &nodes, IntegrationReference reference) {
    std::vector<double> err(nodes.size());
    parallel_for(static_cast<int>(nodes.size()), [&](int k) {
        const NodeIndex &p = nodes[static_cast<size_t>(k)];
        double at[4];
        nl.stored.node_params(p.data(), at); // T, g, r, S
        const double E_ref = reference == IntegrationReference::FinerPanelRule
                                 ? nl.exact(at[0], at[1], at[2], at[3], 2.5)
                                 : reference_near_light_E(at[0], at[1], at[2], at[3], nl.phase_g);
        err[static_cast<size_t>(k)] = std::fabs(nl.node_E(p.data()) - E_ref) / E_ref;
    });
    double worst = 0;
    for (double e : err) worst = std::isnan(e) ? HUGE_VAL : std::max(worst, e);
    return worst;
}

// Relative error of the table at each point where the attenuation E ≥ 1e-6 (points (T, g, r, S)).
SamplingStats sampling_stats(const MeasuredTable &table, const std::vector<std::array<double, 4>> &at) {
    std::vector<double> err(at.size(), -1.0);
    parallel_for(static_cast<int>(at.size()), [&](int k) {
        const auto &p = at[static_cast<size_t>(k)];
        const double exact = table.exact(p[0], p[1], p[2], p[3]);
        const double attenuation = table.phase_g == 0.0 ? exact : slut_nl_E(p[0], p[1], p[2], p[3]);
        if (attenuation >= 1e-6) err[static_cast<size_t>(k)] = std::fabs(table.E(p[0], p[1], p[2], p[3]) - exact) / exact;
    });
    std::vector<double> kept;
    SamplingStats s;
    for (size_t k = 0; k < err.size(); ++k) {
        if (err[k] < 0) continue;
        kept.push_back(err[k]);
        if (err[k] > s.max_rel) {
            s.max_rel = err[k];
            s.worst_u = at[k][0];
            s.worst_w = at[k][1];
            for (int a = 0; a < 4; ++a) s.worst_at[a] = at[k][static_cast<size_t>(a)];
        }
    }
    s.p99_rel = percentile(kept, 0.99);
    s.median_rel = percentile(kept, 0.5);
    s.points = kept.size();
    return s;
}

SamplingStats sampling(const MeasuredTable &table, int points, uint64_t seed) {
    const Table &t = table.stored.table();
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::array<double, 4>> at(static_cast<size_t>(points));
    for (auto &p : at) {
        p[3] = std::numeric_limits<double>::infinity();
        // The slab axis's one-parameter map is LOG in S: slut_param_from_unit gives log-uniform S.
        for (size_t a = 0; a < t.axes.size(); ++a) p[a] = slut_param_from_unit(&t.axes[a].map, unit(rng));
    }
    return sampling_stats(table, at);
}

SamplingStats corners(const MeasuredTable &table, int points, uint64_t seed) {
    const Table &t = table.stored.table();
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto pick = [&](const std::vector<double> &edges, const slut_axis &axis) {
        if (unit(rng) < 0.5) return edges[std::uniform_int_distribution<size_t>(0, edges.size() - 1)(rng)];
        return slut_param_from_unit(&axis, unit(rng));
    };
    const slut_axis &aT = t.axes[0].map, &ag = t.axes[1].map, &ar = t.axes[2].map;
    std::vector<std::array<double, 4>> at(static_cast<size_t>(points));
    for (auto &p : at) {
        p[0] = pick({aT.min, aT.max}, aT);
        p[1] = pick({ag.min, ag.min + 1e-9, 1.0}, ag);
        p[2] = pick({0.0, 1e-12, ar.max}, ar);
        p[3] = std::numeric_limits<double>::infinity();
        if (table.stored.thick_only()) continue;
        const slut_axis &aS = t.axes[3].map;
        std::vector<double> edges = {aS.min, aS.min * (1 + 1e-9), aS.max};
        const double peak = -p[1] * p[0]; // t* = −g·T, the foot of the perpendicular from the light
        for (double f : {1.0 - 1e-3, 1.0, 1.0 + 1e-3})
            if (peak * f > aS.min && peak * f < aS.max) edges.push_back(peak * f);
        p[3] = pick(edges, aS);
    }
    return sampling_stats(table, at);
}

} // namespace

double measure_nearlight_integration(const NearLightTable &table, const std::vector<NodeIndex> &nodes,
                                     IntegrationReference reference) {
    return integration_error(measured(table), nodes, reference);
}
double measure_nearlight_integration(const NearLightHgTable &table, const std::vector<NodeIndex> &nodes,
                                     IntegrationReference reference) {
    return integration_error(measured(table), nodes, reference);
}
SamplingStats measure_nearlight_sampling(const NearLightTable &table, int points, uint64_t seed) {
    return sampling(measured(table), points, seed);
}
SamplingStats measure_nearlight_sampling(const NearLightHgTable &table, int points, uint64_t seed) {
    return sampling(measured(table), points, seed);
}
SamplingStats measure_nearlight_corners(const NearLightTable &table, int points, uint64_t seed) {
    return corners(measured(table), points, seed);
}
SamplingStats measure_nearlight_corners(const NearLightHgTable &table, int points, uint64_t seed) {
    return corners(measured(table), points, seed);
}

} // namespace scatterlut
