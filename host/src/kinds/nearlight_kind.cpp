// The near-light E tables (Gath 2008 §4.2): ln E(T, g, r) for thick media (kind E3, S = ∞)
// and ln E/B(T, g, r, S) for slabs of finite optical thickness (kind E4), and the same with a
// Henyey–Greenstein phase (kinds E3_hg / E4_hg: ln(E_g/ψ_max), the medium's phase_g recorded
// as "phase.g"): one class template, parameterized by its runtime class (NearLightTable or
// NearLightHgTable) and slab / thick, registered four times. Their generator: generate_nearlight.cpp; their runtime:
// tables/src/nearlight.cpp and tables/src/nearlight_hg.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "generate_nearlight.hpp"
#include "kinds/derivation.hpp"
#include "kinds/planned_kind.hpp"
#include "plan.hpp"
#include "scene_queries.hpp"
#include "text_format.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/nearlight_hg.hpp"

extern "C" {
#include "slut_nearlight.h"
}

namespace scatterlut {

namespace {

// Measurements skip E < 1e-6 (generate_nearlight.cpp); so do the search's estimate and the
// report's queries.
constexpr double kEFloor = 1e-6;

// What the scene's pairs ask: T (and for slabs S) ranges, at the strictest error.
struct Demand {
    Span T, S;
    double relative_error = HUGE_VAL;
    double phase_g = 0.0; // anisotropic kinds: the g of the table (its media's)
};

// Runtime: NearLightHgTable for the kinds of the media with g ≠ 0 (E3_hg, E4_hg),
// NearLightTable for the isotropic ones (E3, E4).
template <class Runtime>
class NearLightKind final : public PlannedKind<NearLightKind<Runtime>, NearLightPlan, Runtime, NearLightQuery> {
    using PlannedKind<NearLightKind<Runtime>, NearLightPlan, Runtime, NearLightQuery>::kAnisotropic;

public:
    // For PlannedKind: the generator (generate_nearlight.hpp) and the runtime's answers.
    static constexpr auto layout_of = make_nearlight_table_layout;
    static constexpr auto generate_table = generate_nearlight_table;
    static constexpr double (*measure_integration)(const Runtime &, const std::vector<NodeIndex> &,
                                                   IntegrationReference) = measure_nearlight_integration;
    static constexpr SamplingStats (*measure_sampling)(const Runtime &, int, uint64_t) = measure_nearlight_sampling;
    static std::vector<double> integrate_nodes(Device &device, const Table &layout, double tolerance) {
        return integrate_nearlight_ln_E(device, layout, {}, tolerance);
    }
    // (T, g, r) and, in a 4-D table, S.
    static double lookup(const Runtime &near, const double *p, size_t axes) {
        return near.E(p[0], p[1], p[2], axes == 4 ? p[3] : HUGE_VAL);
    }

    explicit NearLightKind(bool finite_thickness) : finite_(finite_thickness) {}

    const RuntimeKind &runtime() const override { return near_light_runtime_kind(finite_, kAnisotropic); }

    void add_demand(const Scene &scene, const SceneMedium &m, const SceneLight &l, std::any &state,
                    PlannedTable &t) const override {
        if (m.viewer_inside || !(finite_ ? m.has_thickness : m.thick)) return;
        // Isotropic media: the isotropic kinds (today's tables); anisotropic ones: the _hg kind,
        // which the planner asks with the media of one g at a time (per_phase()).
        if (kAnisotropic != !m.isotropic()) return;
        if (!state.has_value()) state = Demand{};
        Demand &d = std::any_cast<Demand &>(state);
        d.phase_g = m.phase_g;
        // A coloured medium: the lower ends from its clearest channel, the upper from its densest
        // (one table serves every channel; a grey medium has sigma_t_lo == sigma_t).
        const double sigma_t = m.sigma_t_per_m(), sigma_t_lo = m.sigma_t_min_per_m();
        const double d_lo = l.distance_m.min, d_hi = l.distance_m.max;
        const std::string T_text = "T = sigma_t*l in [" + fmt("%.4g", sigma_t_lo * d_lo) + ", " +
                                   fmt("%.4g", sigma_t * d_hi) + "]" + (m.coloured ? " (over its channels)" : "");
        d.T.add(sigma_t_lo * d_lo, sigma_t * d_hi);
        d.relative_error = std::min(d.relative_error, m.relative_error);
        if (!finite_) {
            t.requested_by.push_back({m.name, l.name, "thick, seen from outside: " + T_text});
            return;
        }
        // The path inside along the view ray: the thickness, longer by 1/cos at the largest
        // view angle (a slab seen obliquely).
        const double view = scene.view.max_view_angle_deg * SLUT_PI / 180.0;
        const double s_lo = sigma_t_lo * m.thickness_m.min, s_hi = sigma_t * m.thickness_m.max / std::cos(view);
        d.S.add(s_lo, s_hi);
        t.requested_by.push_back({m.name, l.name,
                                  "finite thickness, seen from outside: " + T_text + ", S = sigma_t*s in [" +
                                      fmt("%.4g", s_lo) + ", " + fmt("%.4g", s_hi) + "]"});
    }

    // g ≥ cos(view + light angle) (the eye and light directions both above the surface),
    // r = μ_l/μ_e ≤ 1/cos(view angle).
    void finish_plan(const Scene &scene, const std::any &state, const AirlightOverrides &,
                     PlannedTable &t) const override {
        const Demand &d = std::any_cast<const Demand &>(state);
        const double view = scene.view.max_view_angle_deg * SLUT_PI / 180.0;
        const double light = scene.view.max_light_angle_deg * SLUT_PI / 180.0;
        NearLightPlan p = default_near_light_plan(finite_);
        const Span Tw = d.T.widened();
        p.T_min = std::max(Tw.lo, 1e-6);
        p.T_max = Tw.hi;
        p.g_min = std::max(p.g_min, std::cos(std::min(SLUT_PI, view + light)));
        p.r_max = 1.0 / std::cos(view);
        if (finite_) {
            const Span Sw = d.S.widened();
            p.S_min = std::max(Sw.lo, 1e-6);
            p.S_max = Sw.hi;
        }
        p.n_T = half_count(p.n_T);
        p.n_g = half_count(p.n_g);
        p.n_r = half_count(p.n_r);
        p.n_S = half_count(p.n_S);
        p.phase_g = d.phase_g;
        if (kAnisotropic) {
            t.phase_g = d.phase_g;
            t.stem = near_light_hg_file_stem(finite_, d.phase_g);
            p.g_max = near_light_hg_g_max(p.phase_g, finite_);
            if (p.g_max < 1.0) {
                if (p.g_min > p.g_max - 0.1) p.g_max = 1.0; // the scene's g lie above: keep them, measured
                else
                    t.domain_notes.push_back("g <= " + fmt("%.3g", p.g_max) + " (phase_g = " + fmt("%.6g", p.phase_g) +
                                             ": its backward peak at g -> 1 is integrated exactly, measured)");
            }
        }
        t.target_rel = d.relative_error;
        t.plan = p;
    }

    const char *target_reason() const override { return "the radiance error: L = sigma_s p I0 sigma_t H E, H exact"; }

    std::vector<int> counts(const std::any &plan) const override {
        const NearLightPlan &p = this->plan_of(plan);
        std::vector<int> c = {p.n_T, p.n_g, p.n_r};
        if (p.finite_thickness) c.push_back(p.n_S);
        return c;
    }
    void set_counts(std::any &plan, const std::vector<int> &c) const override {
        NearLightPlan &p = this->plan_of(plan);
        p.n_T = c[0];
        p.n_g = c[1];
        p.n_r = c[2];
        if (p.finite_thickness) p.n_S = c[3];
    }
    double interpolation_ln_floor() const override { return std::log(kEFloor); }

    RadianceQueries radiance_queries(const Scene &scene, const std::any &plan, size_t count,
                                     uint64_t seed) const override {
        const double phase_g = this->plan_of(plan).phase_g;
        return this->served_queries(
            sample_near_light_queries(scene, finite_, count, seed),
            [phase_g](const NearLightQuery &q) {
                if constexpr (kAnisotropic) return near_light_radiance_exact(q, phase_g);
                else return near_light_radiance_exact(q);
            },
            [](const NearLightQuery &q) { // the attenuation E at least the floor
                const NearLightParams p = near_light_params(q);
                return !p.light_below && slut_nl_E(p.T, p.g, p.r, p.S) >= kEFloor;
            },
            describe_near_light_queries(finite_) + "; queries with E < 1e-6 left out");
    }

    std::vector<RuntimeMethod> runtime_methods(const Table &table, const RadianceQueries &qs) const override {
        const std::vector<NearLightQuery> *q = &this->queries_of(qs);
        if constexpr (kAnisotropic) {
            const double g = NearLightHgTable(table).phase_g();
            return {{"exact", "quadrature per call with the phase (near_light_radiance_exact(q, g))", true,
                     [q, g](size_t k) { return near_light_radiance_exact((*q)[k], g); }},
                    {"table", "one sample of the planned E_g table (NearLightHgTable::radiance)", false,
                     this->table_radiance(table, qs)},
                    {"thin", "thin-medium form times the path's mean phase (near_light_radiance_thin(q, g))", false,
                     [q, g](size_t k) { return near_light_radiance_thin((*q)[k], g); }},
                    {"distant", "distant-light limit, Gath 2008 eq. 5, times the phase at the entry point "
                                "(near_light_radiance_distant(q, g))",
                     false, [q, g](size_t k) { return near_light_radiance_distant((*q)[k], g); }}};
        }
        return {{"exact", "quadrature per call (near_light_radiance_exact)", true,
                 [q](size_t k) { return near_light_radiance_exact((*q)[k]); }},
                {"table", "one sample of the planned E table (NearLightTable::radiance)", false,
                 this->table_radiance(table, qs)},
                {"thin", "thin-medium closed form, Gath 2008 §4.2 (near_light_radiance_thin)", false,
                 [q](size_t k) { return near_light_radiance_thin((*q)[k]); }},
                {"distant", "distant-light limit, Gath 2008 eq. 5 (near_light_radiance_distant)", false,
                 [q](size_t k) { return near_light_radiance_distant((*q)[k]); }}};
    }
    const char *runtime_class() const override { return kAnisotropic ? "NearLightHgTable" : "NearLightTable"; }
    std::string methods_note() const override { return ""; }

    // The near-light snippet (the HG one for an anisotropic table) in every tier, and its
    // closed forms (no table) as the GPU baselines.
    GpuSnippetMethods gpu_methods(const Table &table, const RadianceQueries &qs) const override {
        const std::vector<NearLightQuery> &queries = this->queries_of(qs);
        GpuSnippetMethods g =
            near_light_gpu_inputs(queries, kAnisotropic ? "scatterlut_nearlight_hg.glsl" : "scatterlut_nearlight.glsl");
        std::string axes;
        for (const Axis &a : table.axes) axes += (axes.empty() ? "" : ", ") + glsl_axis(a);
        std::string base =
            std::string(finite_ ? "slut_near_light_table_e4(" : "slut_near_light_table_e3(") + axes + ")";
        std::string phase_g, type = "SlutNearLightTable", radiance = "slut_near_light_radiance",
                             closed = "slut_near_light_radiance_";
        if constexpr (kAnisotropic) {
            phase_g = glsl_float(NearLightHgTable(table).phase_g());
            base = "slut_near_light_hg_table(" + base + ", " + phase_g + ")";
            type = "SlutNearLightHgTable";
            radiance = "slut_near_light_hg_radiance";
            closed = "slut_near_light_hg_radiance_";
        }
        const std::string metadata = type + " slut_planned_table() {\n    return " + base + ";\n}\n";
        const std::string args = kNearLightGpuArgs;
        const std::string call = radiance + "(slut_table, slut_planned_table(), " + args + ")";
        const auto texture = gpu_table_texture(table);
        const std::string fetches =
            finite_ ? "two trilinear filtered fetches (E4: the two layers)" : "one trilinear filtered fetch";
        g.methods.push_back(
            gpu_tier_method("fast", "SLUT_TIER_FAST: " + fetches, g.snippet, "sampler3D", texture, metadata, call));
        g.methods.push_back(gpu_tier_method("accurate",
                                            "SLUT_TIER_ACCURATE: texel fetches, the trilinear in the shader", g.snippet,
                                            "sampler3D", texture, metadata, call));
        g.methods.push_back(gpu_tier_method("none",
                                            std::string("no tier (as accurate): texel fetches, as ") + runtime_class(),
                                            g.snippet, "sampler3D", texture, metadata, call));
        for (const char *form : {"thin", "distant"}) {
            GpuMethod m;
            m.name = form;
            m.what = std::string(form[0] == 't' ? "thin-medium closed form, Gath 2008 §4.2"
                                                : "distant-light limit, Gath 2008 eq. 5") +
                     (kAnisotropic ? ", with the phase" : "") + " (" + closed + form + ", no table)";
            m.source = g.snippet;
            m.call = closed + form + "(" + (kAnisotropic ? phase_g + ", " : std::string()) + args + ")";
            g.methods.push_back(m);
        }
        g.baseline = "thin";
        // Where the table does not cover a query the C++ runtime integrates E exactly and a
        // shader clamps to the table's edge (docs/SHADERS.md, "Outside the table's domain").
        const Runtime runtime(table);
        size_t outside = 0;
        for (const NearLightQuery &q : queries) {
            const NearLightParams p = near_light_params(q);
            outside += !runtime.covers(p.T, p.g, p.r, p.S);
        }
        if (outside > 0)
            g.notes.push_back(std::to_string(outside) + " of the " + std::to_string(queries.size()) +
                              " queries lie outside the table's axes: there the shader returns E at the table's edge "
                              "(the C++ runtime integrates exactly)");
        return g;
    }

private:
    bool finite_;
};

} // namespace

const std::vector<const TableKind *> &near_light_table_kinds() {
    static const NearLightKind<NearLightTable> thick(false), slab(true);
    static const NearLightKind<NearLightHgTable> thick_hg(false), slab_hg(true);
    static const std::vector<const TableKind *> kinds = {&thick, &slab, &thick_hg, &slab_hg};
    return kinds;
}

} // namespace scatterlut
