// The anisotropic airlight table (Sun et al. 2005 with a Henyey–Greenstein phase): ln G̃_g(u, w)
// for one g, one table per distinct g among the lit media the viewer is inside (per_phase()).
// Its generator: generate_airlight_hg.cpp (kernels/airlight_Fg.cl); its runtime:
// tables/src/airlight_hg.cpp.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "generate_airlight.hpp"
#include "generate_airlight_hg.hpp"
#include "kinds/derivation.hpp"
#include "measure_util.hpp"
#include "plan.hpp"
#include "scene_queries.hpp"
#include "text_format.hpp"
#include "scatterlut/airlight_hg.hpp"

namespace scatterlut {

const RuntimeKind &airlight_hg_runtime_kind(); // kinds/airlight_hg_runtime.cpp

namespace {

// As the isotropic table: the radiance is a difference of two samples where the second is at
// most half the first, so relative errors ε on both give at most 3ε on the radiance.
constexpr double kRadiancePerTableError = 3.0;

// What the scene's pairs of one g ask: u up to σ_t·D_max (σ_t of the densest channel: the
// dimensionless table serves every channel below it), at the strictest error.
struct Demand {
    double phase_g = 0;
    double u_max = 0;
    double relative_error = HUGE_VAL;
};

const AirlightHgPlan &plan_of(const std::any &plan) { return std::any_cast<const AirlightHgPlan &>(plan); }
AirlightHgPlan &plan_of(std::any &plan) { return std::any_cast<AirlightHgPlan &>(plan); }

// The queries of a table: the query and the g it is for.
struct HgQueries {
    std::vector<AirlightQuery> queries;
    double phase_g = 0;
};
const HgQueries &queries_of(const RadianceQueries &q) { return std::any_cast<const HgQueries &>(q.queries); }

class AirlightHgKind final : public TableKind {
public:
    const RuntimeKind &runtime() const override { return airlight_hg_runtime_kind(); }
    bool per_phase() const override { return true; }

    void add_demand(const Scene &, const SceneMedium &m, const SceneLight &l, std::any &state,
                    PlannedTable &t) const override {
        if (!m.viewer_inside || m.isotropic()) return;
        if (!state.has_value()) state = Demand{};
        Demand &d = std::any_cast<Demand &>(state);
        d.phase_g = m.phase_g;
        const double sigma_t = m.sigma_t_per_m(), d_hi = l.distance_m.max;
        d.u_max = std::max(d.u_max, sigma_t * d_hi);
        d.relative_error = std::min(d.relative_error, m.relative_error);
        t.requested_by.push_back({m.name, l.name,
                                  "viewer inside, phase_g = " + fmt("%g", m.phase_g) + ", light at D <= " +
                                      fmt("%g", d_hi) + " m: u up to sigma_t*D_max = " + fmt("%.4g", sigma_t * d_hi) +
                                      (m.coloured ? " (the densest channel; the others lie below)" : "")});
    }

    void finish_plan(const Scene &, const std::any &state, const AirlightOverrides &, PlannedTable &t) const override {
        const Demand &d = std::any_cast<const Demand &>(state);
        AirlightHgPlan a;
        a.phase_g = d.phase_g;
        t.phase_g = d.phase_g;
        t.stem = airlight_fg_stem(d.phase_g);
        t.target_rel = d.relative_error / kRadiancePerTableError;
        // w_min: where the small-w form holds half the target (g < 0 needs smaller w: the
        // backward peak); u_max: the scene's, raised to where the large-u series holds it.
        a.w_min = airlight_hg_w_min(d.phase_g, t.target_rel);
        if (a.w_min < AirlightHgPlan{}.w_min)
            t.domain_notes.push_back("w_min lowered to " + fmt("%.3g", a.w_min) +
                                     ": above it the small-w form misses the target at g = " + fmt("%g", d.phase_g) +
                                     " (measured)");
        const double onset = airlight_hg_large_u_onset(d.phase_g, t.target_rel, a.w_min);
        a.u_max = std::max(d.u_max, onset);
        if (d.u_max < onset)
            t.domain_notes.push_back("u_max raised from " + fmt("%.3g", d.u_max) + " to " + fmt("%.3g", onset) +
                                     ": from there on the large-u series holds the target at g = " +
                                     fmt("%g", d.phase_g) + " (measured)");
        a.n_u = half_count(a.n_u);
        a.n_w = half_count(a.n_w);
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
        AirlightHgPlan p = plan_of(plan);
        p.integration_tolerance = tolerance;
        return make_airlight_hg_table_layout(p);
    }
    std::vector<double> integrate(Device &device, const Table &layout, double tolerance) const override {
        return integrate_airlight_hg_ln_gs(device, layout, tolerance);
    }
    Table generate(Device &device, const std::any &plan, const Provenance &provenance,
                   const std::function<void(double)> &progress) const override {
        return generate_airlight_hg_table(device, plan_of(plan), provenance, progress);
    }

    std::vector<NodeIndex> generator_nodes(const Table &table, int nodes, uint64_t seed) const override {
        return airlight_measurement_nodes(table, nodes, seed);
    }
    double integration_error(const RuntimeSampler &sampler, const std::vector<NodeIndex> &nodes,
                             IntegrationReference reference) const override {
        return measure_airlight_hg_integration(sampler.table(), nodes, reference);
    }
    SamplingStats sampling_error(const RuntimeSampler &sampler, int points, uint64_t seed) const override {
        return measure_airlight_hg_sampling(dynamic_cast<const SamplerOf<AirlightHgTable> &>(sampler).runtime, points,
                                            seed);
    }

    RadianceQueries radiance_queries(const Scene &scene, const std::any &plan, size_t count,
                                     uint64_t seed) const override {
        const double g = plan_of(plan).phase_g;
        // The media of this g, one grey copy per channel (so that every channel's σ is queried).
        Scene only = scene;
        only.media.clear();
        for (const SceneMedium &m : scene.media) {
            if (m.phase_g != g || !m.viewer_inside) continue;
            for (int c = 0; c < (m.coloured ? 3 : 1); ++c) {
                SceneMedium one = m;
                one.coloured = false;
                one.sigma_s_per_m = m.sigma_s_rgb_per_m[static_cast<size_t>(c)];
                one.sigma_a_per_m = m.sigma_a_rgb_per_m[static_cast<size_t>(c)];
                if (m.coloured) one.name += "." + std::string(1, "rgb"[c]);
                for (SceneLight &l : only.lights) // lights naming m light its copies
                    if (!l.media.empty() && std::find(l.media.begin(), l.media.end(), m.name) != l.media.end() &&
                        one.name != m.name)
                        l.media.push_back(one.name);
                if (one.sigma_s_per_m > 0.0) only.media.push_back(one);
            }
        }
        std::vector<AirlightQuery> all = sample_airlight_queries(only, count, seed);
        std::vector<double> exact(all.size());
        parallel_for(static_cast<int>(all.size()), [&](int i) {
            exact[static_cast<size_t>(i)] = airlight_radiance_exact(all[static_cast<size_t>(i)], g);
        });
        HgQueries kept;
        kept.phase_g = g;
        RadianceQueries s;
        for (size_t i = 0; i < all.size(); ++i)
            if (std::isfinite(exact[i]) && exact[i] > 0) {
                kept.queries.push_back(all[i]);
                s.exact.push_back(exact[i]);
            }
        s.queries = std::move(kept);
        s.description = describe_airlight_queries() + ", phase_g = " + fmt("%g", g) +
                        ", every colour channel; rays through the light (infinite radiance) left out";
        return s;
    }

    std::vector<RuntimeMethod> runtime_methods(const Table &table, const RadianceQueries &qs) const override {
        const HgQueries *q = &queries_of(qs);
        return {{"exact", "quadrature per call (airlight_radiance_exact with phase_g)", true,
                 [q](size_t k) { return airlight_radiance_exact(q->queries[k], q->phase_g); }},
                {"table", "two samples of the planned F_g table (AirlightHgTable::radiance)", false,
                 table_radiance(table, qs)},
                {"thin", "no extinction along either leg, with the phase (airlight_hg_radiance_thin)", false,
                 [q](size_t k) { return airlight_hg_radiance_thin(q->queries[k], q->phase_g); }},
                {"distant", "distant light, scattering angle gamma along the ray (airlight_hg_radiance_distant)", false,
                 [q](size_t k) { return airlight_hg_radiance_distant(q->queries[k], q->phase_g); }}};
    }
    std::function<double(size_t)> table_radiance(const Table &table, const RadianceQueries &qs) const override {
        auto air = std::make_shared<AirlightHgTable>(table);
        const HgQueries *q = &queries_of(qs);
        return [air, q](size_t k) { return air->radiance(q->queries[k]); };
    }
    std::function<double()> lookup_loop(const Table &table, const std::vector<double> &p, size_t count) const override {
        auto air = std::make_shared<AirlightHgTable>(table);
        const std::vector<double> *params = &p;
        return [air, params, count] {
            const std::vector<double> &pp = *params;
            double sum = 0;
            for (size_t i = 0; i < count; ++i) sum += air->scaled_tail(pp[2 * i], pp[2 * i + 1]);
            return sum;
        };
    }
    const char *runtime_class() const override { return "AirlightHgTable"; }
    std::string methods_note() const override {
        return " With a Henyey-Greenstein phase the closed forms are approximations: thin drops the extinction along "
               "both legs (exact as sigma_t -> 0, an overestimate otherwise); distant keeps the scattering angle at "
               "gamma along the ray and 1/D^2 (Gath 2008 eq. 5 with the phase), fair for a ray much shorter than D.";
    }
};

} // namespace

const TableKind &airlight_hg_table_kind() {
    static const AirlightHgKind kind;
    return kind;
}

} // namespace scatterlut
