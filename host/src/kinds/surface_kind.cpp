// The surface tables of Sun et al. 2005 (docs/PHYSICS.md §1.5): G_n(T, θ) for lit surfaces inside
// a medium the viewer is in, one table per exponent of the scene's surfaces (per_exponent():
// n = 1 the diffuse G0, file stem surface_G0; n > 1 the Phong lobe, surface_G<n>). E_ss =
// σ_s I0/(4π D) · G_1(T, θ_s) and S_n = σ_s I0/(4π D) · G_n(T, θ_r), T = σ_t D, D the distance
// from the surface point to the light. Its generator: generate_surface.cpp
// (kernels/surface_G.cl); its runtime: tables/src/surface_table.cpp (SurfaceTable).
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "generate_surface.hpp"
#include "kinds/derivation.hpp"
#include "kinds/planned_kind.hpp"
#include "plan.hpp"
#include "scene_queries.hpp"
#include "text_format.hpp"
#include "scatterlut/surface.hpp"
#include "scatterlut/surface_table.hpp"

namespace scatterlut {

namespace {

// What the scene's (medium, light) pairs of one exponent ask: T up to σ_t·D_max (σ_t of the
// densest channel: the dimensionless table serves every channel below it), at the strictest error.
struct Demand {
    double T_max = 0;
    double relative_error = HUGE_VAL;
};

double optical_distance(const SurfaceQuery &q) { return (q.sigma_s_per_m + q.sigma_a_per_m) * q.distance_m; }

// E_ss (n = 1) or S_n (n > 1) in W/m², exact by quadrature and from the table.
double exact_of(const SurfaceQuery &q, int n) {
    return n == 1 ? surface_irradiance_exact(q) : surface_specular_exact(q, n);
}
double table_of(const SurfaceTable &table, const SurfaceQuery &q) {
    return table.exponent() == 1 ? table.irradiance(q) : table.specular(q);
}

class SurfaceKind final : public PlannedKind<SurfaceKind, SurfacePlan, SurfaceTable, SurfaceQuery> {
public:
    // For PlannedKind: the generator (generate_surface.hpp) and the runtime's answers.
    static constexpr auto layout_of = make_surface_table_layout;
    static constexpr auto integrate_nodes = integrate_surface_G;
    static constexpr auto measure_integration = measure_surface_integration;
    static constexpr auto measure_sampling = measure_surface_sampling;
    static Table generate_table(Device &device, const SurfacePlan &plan, const Provenance &provenance,
                                const std::function<void(double)> &) { // no progress to report
        return generate_surface_table(device, plan, provenance);
    }
    static double query_radiance(const SurfaceTable &surface, const SurfaceQuery &q) { return table_of(surface, q); }
    static double lookup(const SurfaceTable &surface, const double *T_theta, size_t) {
        return surface.G(T_theta[0], T_theta[1]);
    }

    const RuntimeKind &runtime() const override { return surface_runtime_kind(); }
    bool per_exponent() const override { return true; }

    void add_demand(const Scene &, const SceneMedium &m, const SceneLight &l, std::any &state,
                    PlannedTable &t) const override {
        if (t.exponent < 1 || !m.viewer_inside || !m.has_surfaces) return;
        if (!state.has_value()) state = Demand{};
        Demand &d = std::any_cast<Demand &>(state);
        const double sigma_t = m.sigma_t_per_m(), d_hi = m.surfaces.light_distance_m.max;
        d.T_max = std::max(d.T_max, sigma_t * d_hi);
        d.relative_error = std::min(d.relative_error, m.relative_error);
        t.requested_by.push_back(
            {m.name, l.name,
             std::string(t.exponent == 1 ? "diffuse surfaces" : "Phong surfaces, n = " + std::to_string(t.exponent)) +
                 " lit from D <= " + fmt("%g", d_hi) + " m: T = sigma_t*D up to " + fmt("%.4g", sigma_t * d_hi) +
                 (m.coloured ? " (the densest channel; the others lie below)" : "")});
    }

    void finish_plan(const Scene &, const std::any &state, const AirlightOverrides &, PlannedTable &t) const override {
        const Demand &d = std::any_cast<const Demand &>(state);
        SurfacePlan p;
        p.exponent = t.exponent;
        p.T_max = d.T_max;
        if (p.T_max > kSurfaceGTMaxLimit) {
            p.T_max = kSurfaceGTMaxLimit;
            t.domain_notes.push_back("T_max lowered from " + fmt("%.4g", d.T_max) + " to " + fmt("%g", kSurfaceGTMaxLimit) +
                                     ": beyond it e^-T underflows towards double's smallest numbers (the runtime "
                                     "integrates exactly there)");
        }
        p.n_T = half_count(p.n_T);
        p.n_theta = half_count(p.n_theta) | 1; // odd (needed for n = 1)
        t.stem = surface_file_stem(t.exponent);
        t.target_rel = d.relative_error;
        t.plan = p;
    }

    const char *target_reason() const override {
        return "the irradiance error: E_ss (or S_n) = sigma_s I0/(4 pi D) G(T, theta), one sample";
    }

    std::vector<int> counts(const std::any &plan) const override { return {plan_of(plan).n_T, plan_of(plan).n_theta}; }
    void set_counts(std::any &plan, const std::vector<int> &c) const override {
        SurfacePlan &p = plan_of(plan);
        p.n_T = c[0];
        p.n_theta = p.exponent == 1 ? std::max(3, c[1] | 1) : std::max(3, c[1]); // n = 1: a node at theta_s = pi/2
    }

    RadianceQueries radiance_queries(const Scene &scene, const std::any &plan, size_t count,
                                     uint64_t seed) const override {
        const int n = plan_of(plan).exponent;
        const double T_max = plan_of(plan).T_max;
        return served_queries(
            sample_surface_queries(scene, n, count, seed), [n](const SurfaceQuery &q) { return exact_of(q, n); },
            [T_max](const SurfaceQuery &q) { return optical_distance(q) <= T_max; },
            std::string(n == 1 ? "scattered irradiance E_ss (W/m^2)" : "specular lobe S_n (W/m^2)") +
                " of the scene's lit surfaces: every medium with surfaces and point light lighting it, every "
                "colour channel, the light at D log-uniform over surfaces.light_distance_m, theta uniform in "
                "[0, pi]; queries beyond the table's T_max left out");
    }

    std::vector<RuntimeMethod> runtime_methods(const Table &table, const RadianceQueries &qs) const override {
        const std::vector<SurfaceQuery> *q = &queries_of(qs);
        const int n = surface_table_exponent(table);
        std::vector<RuntimeMethod> m = {
            {"exact", n == 1 ? "adaptive quadrature per call (surface_irradiance_exact)"
                             : "adaptive quadrature per call (surface_specular_exact)",
             true, [q, n](size_t k) { return exact_of((*q)[k], n); }},
            {"table", n == 1 ? "one sample of the planned table (SurfaceTable::irradiance)"
                             : "one sample of the planned table (SurfaceTable::specular)",
             false, table_radiance(table, qs)}};
        if (n == 1) {
            m.push_back({"no_extinction", "closed form without extinction (surface_irradiance_no_extinction)", false,
                         [q](size_t k) { return surface_irradiance_no_extinction((*q)[k]); }});
            m.push_back({"attenuated", "the same times e^(-sigma_t D), an engine fudge", false, [q](size_t k) {
                             return surface_irradiance_no_extinction((*q)[k]) * std::exp(-optical_distance((*q)[k]));
                         }});
        }
        return m;
    }
    // The surface snippet in every tier: E_ss (or S_n) as SurfaceTable::specular forms it, the
    // snippet's scale sigma_s I0/(4 pi D) (slut_surface_scattered_scale) times its G_n. The
    // snippet has no closed form of its own: no GPU baseline; the costs are ratios to no tier.
    GpuSnippetMethods gpu_methods(const Table &table, const RadianceQueries &qs) const override {
        GpuSnippetMethods g = surface_gpu_inputs(queries_of(qs), "scatterlut_surface.glsl");
        const std::string metadata = "SlutSurfaceTable slut_planned_table() {\n    return slut_surface_table(" +
                                     glsl_axis(table.axes[0]) + ", " + glsl_axis(table.axes[1]) + ", " +
                                     std::to_string(surface_table_exponent(table)) + ", 0);\n}\n";
        // sigma_s in0.x, sigma_a in0.y, I0 in0.z, D in0.w, theta in1.x; T = sigma_t D.
        const std::string call = "slut_surface_scattered_scale(in0.x, in0.z, in0.w) * slut_surface_G(slut_table, "
                                 "slut_planned_table(), (in0.x + in0.y) * in0.w, in1.x)";
        const auto texture = gpu_table_texture(table);
        g.methods.push_back(gpu_tier_method("fast", "SLUT_TIER_FAST: one hardware-filtered fetch", g.snippet,
                                            "sampler2D", texture, metadata, call));
        g.methods.push_back(gpu_tier_method("accurate", "SLUT_TIER_ACCURATE: texel fetches, the bilinear in the shader",
                                            g.snippet, "sampler2D", texture, metadata, call));
        g.methods.push_back(gpu_tier_method("none", "no tier (as accurate): texel fetches, as SurfaceTable", g.snippet,
                                            "sampler2D", texture, metadata, call));
        g.baseline = "none";
        return g;
    }
    const char *runtime_class() const override { return "SurfaceTable"; }
    const char *independent_reference() const override {
        return "Boost.Math Gauss-Kronrod 31 over gamma, exp_sinh along each ray";
    }
    std::string methods_note() const override {
        return " The surface tables answer irradiance (W/m^2), not radiance: E_ss, the airlight a surface point "
               "receives over its hemisphere (Sun et al. 2005). no_extinction is its exact limit sigma_t -> 0 "
               "(sigma_s I0/(2D) [cos theta_s + E(sin theta_s)], an upper bound otherwise); attenuated multiplies it "
               "by e^(-sigma_t D), which ignores that scattered light reaches the surface over shorter paths. A Phong "
               "table (exponent n > 1) answers S_n, the lobe-weighted incident airlight, which has no closed form here.";
    }
};

} // namespace

const std::vector<const TableKind *> &surface_table_kinds() {
    static const SurfaceKind kind;
    static const std::vector<const TableKind *> kinds = {&kind};
    return kinds;
}

} // namespace scatterlut
