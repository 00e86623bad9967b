// The airlight_rational table (kernels/slut_airlight_rational.h): Ĥ(x_m, x_t), the isotropic
// airlight's tail normalised, on rational axes that hardware bilinear filtering serves
// directly (the GPU snippets' fast tier). Planned wherever airlight_F is planned for isotropic
// media (the same pairs: the isotropic kind's add_demand), at the radiance target over
// 2·SLUT_AIRLIGHT_RATIONAL_GAIN − 1. Its generator: generate_airlight_rational.cpp
// (kernels/airlight_rational.cl); its runtime: tables/src/airlight_rational.cpp
// (AirlightRationalTable).
#include <cmath>
#include <string>

#include "generate_airlight.hpp" // airlight_measurement_nodes
#include "generate_airlight_rational.hpp"
#include "kinds/derivation.hpp"
#include "kinds/planned_kind.hpp"
#include "plan.hpp"
#include "scene_queries.hpp"
#include "text_format.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_rational.hpp"

extern "C" {
#include "slut_airlight_rational.h" // SLUT_AIRLIGHT_RATIONAL_GAIN
}

namespace scatterlut {

// Of the isotropic airlight kind (kinds/airlight_kind.cpp), whose pairs this kind serves: the
// strictest relative error its add_demand gathered in `state`, and the scene's isotropic media
// the viewer is inside, one grey copy per colour channel (the report's queries).
double isotropic_airlight_demand_error(const std::any &state);
Scene isotropic_airlight_media(const Scene &scene);

namespace {

// The radiance's relative error per sample's: the tiers take the two samples' difference
// V − F (V = weight2·Ĥ2, F = weight1·Ĥ1) only where F ≤ (1 − 1/G)·V, G = SLUT_AIRLIGHT_RATIONAL_GAIN
// (slut_airlight_rational_radiance; the segment's rule elsewhere), so relative errors ε on
// both samples, of either sign, give |δ(V − F)| ≤ ε (V + F) ≤ (2G − 1) ε (V − F).
constexpr double kRadiancePerSampleError = 2.0 * SLUT_AIRLIGHT_RATIONAL_GAIN - 1.0;

class AirlightRationalKind final
    : public PlannedKind<AirlightRationalKind, AirlightRationalPlan, AirlightRationalTable, AirlightQuery> {
public:
    // For PlannedKind: the generator (generate_airlight_rational.hpp) and the runtime's answers.
    static constexpr auto layout_of = make_airlight_rational_layout;
    static constexpr auto integrate_nodes = integrate_airlight_rational;
    static constexpr auto measurement_nodes = airlight_measurement_nodes; // the corners, then random nodes
    static constexpr auto measure_integration = measure_airlight_rational_integration;
    static constexpr auto measure_sampling = measure_airlight_rational_sampling;
    static Table generate_table(Device &device, const AirlightRationalPlan &plan, const Provenance &provenance,
                                const std::function<void(double)> &progress) {
        return generate_airlight_rational_table(device, plan, provenance, progress);
    }
    static double lookup(const AirlightRationalTable &table, const double *x, size_t) {
        return table.sample(x[0], x[1]);
    }

    const RuntimeKind &runtime() const override { return airlight_rational_runtime_kind(); }

    // The isotropic airlight kind's demand (viewer inside an isotropic medium, a point light),
    // in its own state: this table serves the same pairs. Its "u up to" is what airlight_F
    // needs; the rational axes cover every u and t.
    void add_demand(const Scene &scene, const SceneMedium &m, const SceneLight &l, std::any &state,
                    PlannedTable &t) const override {
        find_table_kind(kKindAirlightF)->add_demand(scene, m, l, state, t);
    }

    void finish_plan(const Scene &, const std::any &state, const AirlightOverrides &, PlannedTable &t) const override {
        AirlightRationalPlan p;
        p.n_m = half_count(p.n_m);
        p.n_t = half_count(p.n_t);
        t.target_rel = isotropic_airlight_demand_error(state) / kRadiancePerSampleError;
        t.plan = p;
    }

    const char *target_reason() const override {
        return "the radiance error over 15: the GPU tiers take the difference of the two ends' samples only where "
               "the far term is at most 7/8 of the viewer's, which amplifies the samples' relative errors at most 15 "
               "times";
    }

    std::vector<int> counts(const std::any &plan) const override { return {plan_of(plan).n_m, plan_of(plan).n_t}; }
    void set_counts(std::any &plan, const std::vector<int> &c) const override {
        AirlightRationalPlan &p = plan_of(plan);
        p.n_m = c[0];
        p.n_t = c[1];
    }

    RadianceQueries radiance_queries(const Scene &scene, const std::any &, size_t count,
                                     uint64_t seed) const override {
        return served_queries(
            sample_airlight_queries(isotropic_airlight_media(scene), count, seed),
            [](const AirlightQuery &q) { return airlight_radiance_exact(q); },
            [](const AirlightQuery &) { return true; }, // every query: the unit square covers every u and t
            describe_airlight_queries() + ", every colour channel; rays through the light (infinite radiance) left out");
    }

    std::vector<RuntimeMethod> runtime_methods(const Table &table, const RadianceQueries &qs) const override {
        const std::vector<AirlightQuery> *q = &queries_of(qs);
        return {{"exact", "quadrature per call (airlight_radiance_exact)", true,
                 [q](size_t k) { return airlight_radiance_exact((*q)[k]); }},
                {"table",
                 "two samples of the planned table, or the short segment's rule where their difference would cancel "
                 "(AirlightRationalTable::radiance)",
                 false, table_radiance(table, qs)}};
    }
    // The airlight snippet's two tiers, which sample this table (the snippet without a tier
    // samples airlight_F: that kind adds it, over the same queries).
    GpuSnippetMethods gpu_methods(const Table &table, const RadianceQueries &qs) const override {
        GpuSnippetMethods g = airlight_gpu_inputs(queries_of(qs), "scatterlut_airlight.glsl");
        const std::string metadata = "SlutAirlightTable slut_planned_table() {\n    return slut_airlight_table(" +
                                     std::to_string(table.axes[0].map.count) + ", " +
                                     std::to_string(table.axes[1].map.count) + ");\n}\n";
        const std::string call =
            "slut_airlight_radiance(slut_table, slut_planned_table(), " + std::string(kAirlightGpuArgs) + ")";
        const auto texture = gpu_table_texture(table);
        g.methods.push_back(
            gpu_tier_method("fast",
                            "SLUT_TIER_FAST: the planned airlight_rational table, one hardware-filtered "
                            "fetch per end of the ray",
                            g.snippet, "sampler2D", texture, metadata, call));
        g.methods.push_back(
            gpu_tier_method("accurate",
                            "SLUT_TIER_ACCURATE: the planned airlight_rational table, four texel fetches "
                            "per end, the bilinear in the shader",
                            g.snippet, "sampler2D", texture, metadata, call));
        return g;
    }
    const char *runtime_class() const override { return "AirlightRationalTable"; }
    const char *independent_reference() const override {
        return "Boost.Math Gauss-Kronrod 61 of H(u,t) over y; Boost.Math expint on the edge x_t = 1";
    }
    std::string methods_note() const override {
        return " The airlight_rational table is what the GPU snippets' tiers sample (docs/SHADERS.md, \"Tiers\": the "
               "fast tier with one hardware-filtered fetch per end of the ray, the accurate one with the bilinear from "
               "four texel fetches), with no exp or log beyond the attenuations. The table method here is their "
               "arithmetic in double: the difference of the two ends' terms (Sun et al. 2005's tail at each end), with "
               "at most 15 times the samples' relative error, or the short segment's corrected trapezoid rule where "
               "that difference would cancel. Stored as f16 the "
               "table's values (0.80 to 1.29) round by up to 2^-11 = 4.9e-4 of themselves: a floor under the f16 "
               "rungs' errors that the f32 table lies far below.";
    }
};

} // namespace

const std::vector<const TableKind *> &airlight_rational_table_kinds() {
    static const AirlightRationalKind kind;
    static const std::vector<const TableKind *> kinds = {&kind};
    return kinds;
}

} // namespace scatterlut
