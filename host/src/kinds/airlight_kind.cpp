// The airlight F table (Sun et al. 2005): ln G̃(u, w) for a viewer and a point light inside
// a medium. Its generator: generate_airlight.cpp; its runtime: tables/src/airlight.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "generate_airlight.hpp"
#include "kinds/derivation.hpp"
#include "measure_util.hpp"
#include "plan.hpp"
#include "scene_queries.hpp"
#include "text_format.hpp"
#include "scatterlut/airlight.hpp"

extern "C" {
#include "slut_airlight.h"
}

namespace scatterlut {

const RuntimeKind &airlight_runtime_kind(); // kinds/airlight_runtime.cpp

namespace {

// The airlight radiance is σ_s p I0 · 2/(D sin γ) · [a − b] with a = e^{−σ_t D}(π/2 − v2) G̃(A1, v2)
// and b = e^{−σ_t(s+d(s))}(π/2 − v1) G̃(A1, v1); the runtime uses this difference only where
// b ≤ a/2 (slut_airlight_from_gs; elsewhere the θ-integral). Relative errors ε on both G̃
// samples give |δ(a − b)| ≤ ε(a + b) ≤ 3ε(a − b): the table must hold a third of the
// radiance target.
constexpr double kAirlightRadiancePerTableError = 3.0;

// The smallest u from which on the runtime's large-u series (slut_gs_large_u, used beyond
// the table's u_max) holds half of `target`, measured against the quadrature at u, 1.3u and
// 2u on 48 log-spaced w in [w_min, π/2] (its error falls with u like k!/u^k at the
// smallest term). The airlight table must reach at least this u.
double large_u_series_onset(double target, double w_min) {
    for (double u = 1.0; u < 1e4; u *= 1.05) {
        double worst = 0;
        for (double uu : {u, 1.3 * u, 2.0 * u})
            for (int i = 0; i < 48; ++i) {
                const double w = w_min * std::pow(SLUT_PIO2_HI / w_min, i / 47.0);
                const double exact = slut_gs_quadrature(uu, w, 1.0);
                worst = std::max(worst, std::fabs(slut_gs_large_u(uu, w) - exact) / exact);
            }
        if (worst <= 0.5 * target) return u;
    }
    return 1e4;
}

// What the scene's pairs ask: u up to σ_t·D_max, at the strictest error.
struct Demand {
    double u_max = 0;
    double relative_error = HUGE_VAL;
};

const AirlightPlan &plan_of(const std::any &plan) { return std::any_cast<const AirlightPlan &>(plan); }
AirlightPlan &plan_of(std::any &plan) { return std::any_cast<AirlightPlan &>(plan); }
const std::vector<AirlightQuery> &queries_of(const RadianceQueries &q) {
    return std::any_cast<const std::vector<AirlightQuery> &>(q.queries);
}

class AirlightKind final : public TableKind {
public:
    const RuntimeKind &runtime() const override { return airlight_runtime_kind(); }

    void add_demand(const Scene &, const SceneMedium &m, const SceneLight &l, std::any &state,
                    PlannedTable &t) const override {
        if (!m.viewer_inside || !m.isotropic()) return; // g ≠ 0: the anisotropic kind's (airlight_hg_kind.cpp)
        if (!state.has_value()) state = Demand{};
        Demand &d = std::any_cast<Demand &>(state);
        const double sigma_t = m.sigma_t_per_m(), d_hi = l.distance_m.max;
        d.u_max = std::max(d.u_max, sigma_t * d_hi);
        d.relative_error = std::min(d.relative_error, m.relative_error);
        t.requested_by.push_back({m.name, l.name,
                                  "viewer inside, light at D <= " + fmt("%g", d_hi) +
                                      " m: u up to sigma_t*D_max = " + fmt("%.4g", sigma_t * d_hi)});
    }

    void finish_plan(const Scene &, const std::any &state, const AirlightOverrides &overrides,
                     PlannedTable &t) const override {
        const Demand &d = std::any_cast<const Demand &>(state);
        AirlightPlan a;
        t.target_rel = d.relative_error / kAirlightRadiancePerTableError;
        if (overrides.w_min) a.w_min = *overrides.w_min;
        // u up to σ_t·D_max, and at least to where the large-u series takes over at the target.
        const double onset = large_u_series_onset(t.target_rel, a.w_min);
        a.u_max = std::max(d.u_max, onset);
        if (d.u_max < onset)
            t.domain_notes.push_back("u_max raised from " + fmt("%.3g", d.u_max) + " to " + fmt("%.3g", onset) +
                                     ": from there on the large-u series holds the target (measured)");
        if (overrides.u_max) a.u_max = *overrides.u_max;
        a.n_u = half_count(a.n_u);
        a.n_w = half_count(a.n_w);
        if (overrides.n_u || overrides.n_w) {
            t.fixed_resolution = true;
            a.n_u = overrides.n_u.value_or(AirlightPlan{}.n_u);
            a.n_w = overrides.n_w.value_or(AirlightPlan{}.n_w);
        }
        t.plan = a;
    }

    const char *target_reason() const override {
        return "a third of the radiance error: the airlight is a difference of two samples";
    }

    std::vector<int> counts(const std::any &plan) const override { return {plan_of(plan).n_u, plan_of(plan).n_w}; }
    void set_counts(std::any &plan, const std::vector<int> &c) const override {
        plan_of(plan).n_u = c[0];
        plan_of(plan).n_w = c[1];
    }
    void set_storage(std::any &plan, Storage storage) const override { plan_of(plan).storage = storage; }
    double integration_tolerance(const std::any &plan) const override { return plan_of(plan).integration_tolerance; }
    double interpolation_ln_floor() const override { return -HUGE_VAL; }

    Table layout(const std::any &plan, double tolerance) const override {
        AirlightPlan p = plan_of(plan);
        p.integration_tolerance = tolerance;
        return make_airlight_table_layout(p);
    }
    std::vector<double> integrate(Device &device, const Table &layout, double tolerance) const override {
        return integrate_airlight_ln_gs(device, layout, tolerance);
    }
    Table generate(Device &device, const std::any &plan, const Provenance &provenance,
                   const std::function<void(double)> &progress) const override {
        return generate_airlight_table(device, plan_of(plan), provenance, progress);
    }

    std::vector<NodeIndex> generator_nodes(const Table &table, int nodes, uint64_t seed) const override {
        return airlight_measurement_nodes(table, nodes, seed);
    }
    double integration_error(const RuntimeSampler &sampler, const std::vector<NodeIndex> &nodes,
                             IntegrationReference reference) const override {
        return measure_airlight_integration(sampler.table(), nodes, reference);
    }
    SamplingStats sampling_error(const RuntimeSampler &sampler, int points, uint64_t seed) const override {
        return measure_airlight_sampling(dynamic_cast<const SamplerOf<AirlightTable> &>(sampler).runtime, points, seed);
    }

    RadianceQueries radiance_queries(const Scene &scene, const std::any &, size_t count,
                                     uint64_t seed) const override {
        std::vector<AirlightQuery> all = sample_airlight_queries(scene, count, seed), kept;
        std::vector<double> exact(all.size());
        parallel_for(static_cast<int>(all.size()),
                     [&](int i) { exact[static_cast<size_t>(i)] = airlight_radiance_exact(all[static_cast<size_t>(i)]); });
        RadianceQueries s;
        for (size_t i = 0; i < all.size(); ++i)
            if (std::isfinite(exact[i]) && exact[i] > 0) {
                kept.push_back(all[i]);
                s.exact.push_back(exact[i]);
            }
        s.queries = std::move(kept);
        s.description = describe_airlight_queries() + "; rays through the light (infinite radiance) left out";
        return s;
    }

    std::vector<RuntimeMethod> runtime_methods(const Table &table, const RadianceQueries &qs) const override {
        const std::vector<AirlightQuery> *q = &queries_of(qs);
        return {{"exact", "quadrature per call (airlight_radiance_exact)", true,
                 [q](size_t k) { return airlight_radiance_exact((*q)[k]); }},
                {"table", "two samples of the planned F table (AirlightTable::radiance)", false, table_radiance(table, qs)},
                {"no_extinction", "closed form without extinction, Macklin 2010 (airlight_radiance_no_extinction)", false,
                 [q](size_t k) { return airlight_radiance_no_extinction((*q)[k]); }},
                {"attenuated",
                 "the same times e^(-sigma_t D), an engine fudge (airlight_radiance_no_extinction_attenuated)", false,
                 [q](size_t k) { return airlight_radiance_no_extinction_attenuated((*q)[k]); }}};
    }
    std::function<double(size_t)> table_radiance(const Table &table, const RadianceQueries &qs) const override {
        auto air = std::make_shared<AirlightTable>(table);
        const std::vector<AirlightQuery> *q = &queries_of(qs);
        return [air, q](size_t k) { return air->radiance((*q)[k]); };
    }
    std::function<double()> lookup_loop(const Table &table, const std::vector<double> &p, size_t count) const override {
        auto air = std::make_shared<AirlightTable>(table);
        const std::vector<double> *params = &p;
        return [air, params, count] {
            const std::vector<double> &pp = *params;
            double sum = 0;
            for (size_t i = 0; i < count; ++i) sum += air->scaled_tail(pp[2 * i], pp[2 * i + 1]);
            return sum;
        };
    }
    const char *runtime_class() const override { return "AirlightTable"; }
    std::string methods_note() const override {
        return " The thin-medium form (Gath 2008 §4.2) and the distant-light limit (Gath 2008 eq. 5) are near-light "
               "methods (a light outside the medium); for a viewer and a light inside the medium the alternatives to "
               "the table are the closed forms engines use (Macklin 2010): no_extinction drops the attenuation along "
               "both legs of the light path, attenuated applies e^(-sigma_t D) to the whole ray.";
    }

};

} // namespace

const TableKind &airlight_table_kind() {
    static const AirlightKind kind;
    return kind;
}

} // namespace scatterlut
