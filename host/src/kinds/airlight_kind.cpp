// The airlight tables (Sun et al. 2005): ln G̃_g(u, w) for a viewer and a point light inside
// a medium, for one Henyey–Greenstein g. One class serves both kinds, parameterised by the
// phase's runtime class: the isotropic F table (airlight_F: the media of g = 0, one table,
// AirlightTable) and the anisotropic F_g tables (airlight_Fg: one table per distinct g ≠ 0,
// per_phase(), AirlightHgTable). Its
// generator: generate_airlight.cpp (kernels/airlight_F.cl); its runtimes:
// tables/src/airlight.cpp (AirlightTable) and tables/src/airlight_hg.cpp (AirlightHgTable).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "generate_airlight.hpp"
#include "kinds/derivation.hpp"
#include "kinds/planned_kind.hpp"
#include "plan.hpp"
#include "scene_queries.hpp"
#include "text_format.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/spot.hpp"

extern "C" {
#include "slut_airlight.h" // slut_F_quadrature: Sun et al. 2005's F for the GPU baseline's table
}

namespace scatterlut {

namespace {

// Sun et al. 2005's plain F(u, v) table as the GPU baseline samples it (bench/shaders/sun2005.glsl,
// the layout of NVIDIA's SDK 10 Rain sample): 64 x 64, u in [0, 10], v in [0, pi/2], linear axes.
constexpr int kSunFCount = 64;
constexpr double kSunFUMax = 10.0;

std::shared_ptr<const GpuTexture> sun2005_f_texture() {
    auto t = std::make_shared<GpuTexture>();
    t->width = t->height = kSunFCount;
    for (int j = 0; j < kSunFCount; ++j)
        for (int i = 0; i < kSunFCount; ++i)
            t->texels.push_back(static_cast<float>(
                slut_F_quadrature(kSunFUMax * i / (kSunFCount - 1), 0.5 * SLUT_PI * j / (kSunFCount - 1))));
    return t;
}

// The airlight radiance is σ_s/(4π)·I0·2e^{−σ_t D}/(D sin γ)·[a − b] with a = w2 G̃_g(u, w2)
// and b = e^{−σ_t Δ} w1 G̃_g(u, w1); the runtime uses this difference only where b ≤ a/2
// (elsewhere the segment's integral). Relative errors ε on both G̃_g samples give
// |δ(a − b)| ≤ ε(a + b) ≤ 3ε(a − b): the table must hold a third of the radiance target.
constexpr double kAirlightRadiancePerTableError = 3.0;

// What the scene's pairs of one g ask: u up to σ_t·D_max (σ_t of the densest channel: the
// dimensionless table serves every channel below it), at the strictest error.
struct Demand {
    double phase_g = 0;
    double u_max = 0;
    double relative_error = HUGE_VAL;
};

// The scene's media of asymmetry g the viewer is inside, one grey copy per colour channel
// (so that every channel's σ is queried); lights that name a coloured medium light its copies.
Scene media_of_phase(const Scene &scene, double g) {
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
            for (SceneLight &l : only.lights)
                if (!l.media.empty() && std::find(l.media.begin(), l.media.end(), m.name) != l.media.end() &&
                    one.name != m.name)
                    l.media.push_back(one.name);
            if (one.sigma_s_per_m > 0.0) only.media.push_back(one);
        }
    }
    return only;
}

// Runtime: AirlightHgTable for the kind of the media with g ≠ 0 (airlight_Fg), AirlightTable
// for those with g = 0 (airlight_F).
template <class Runtime>
class AirlightKind final : public PlannedKind<AirlightKind<Runtime>, AirlightPlan, Runtime, AirlightQuery> {
    using PlannedKind<AirlightKind<Runtime>, AirlightPlan, Runtime, AirlightQuery>::kAnisotropic;

public:
    // For PlannedKind: the generator (generate_airlight.hpp) and the runtime's answers.
    static constexpr auto layout_of = make_airlight_table_layout;
    static constexpr auto integrate_nodes = integrate_airlight_ln_gs;
    static constexpr auto generate_table = generate_airlight_table;
    static constexpr auto measurement_nodes = airlight_measurement_nodes; // the corners, then random nodes
    static double measure_integration(const Runtime &air, const std::vector<NodeIndex> &nodes,
                                      IntegrationReference reference) {
        return measure_airlight_integration(air.table(), nodes, reference);
    }
    static SamplingStats measure_sampling(const Runtime &air, int points, uint64_t seed) {
        return measure_airlight_sampling(air.table(), [&air](double u, double w) { return air.scaled_tail(u, w); },
                                         points, seed);
    }
    static double lookup(const Runtime &air, const double *uw, size_t) { return air.scaled_tail(uw[0], uw[1]); }

    const RuntimeKind &runtime() const override { return airlight_runtime_kind(kAnisotropic); }

    void add_demand(const Scene &, const SceneMedium &m, const SceneLight &l, std::any &state,
                    PlannedTable &t) const override {
        if (!m.viewer_inside || m.isotropic() == kAnisotropic) return;
        if (!state.has_value()) state = Demand{};
        Demand &d = std::any_cast<Demand &>(state);
        d.phase_g = m.phase_g;
        const double sigma_t = m.sigma_t_per_m(), d_hi = l.distance_m.max;
        d.u_max = std::max(d.u_max, sigma_t * d_hi);
        d.relative_error = std::min(d.relative_error, m.relative_error);
        t.requested_by.push_back(
            {m.name, l.name,
             "viewer inside, " + (kAnisotropic ? "phase_g = " + fmt("%g", m.phase_g) + ", " : std::string()) +
                 "light at D <= " + fmt("%g", d_hi) + " m: u up to sigma_t*D_max = " + fmt("%.4g", sigma_t * d_hi) +
                 (m.coloured ? " (the densest channel; the others lie below)" : "")});
    }

    void finish_plan(const Scene &, const std::any &state, const AirlightOverrides &overrides,
                     PlannedTable &t) const override {
        const Demand &d = std::any_cast<const Demand &>(state);
        const double g = d.phase_g;
        const std::string at_g = kAnisotropic ? " at g = " + fmt("%g", g) : "";
        AirlightPlan a;
        a.phase_g = g;
        if (kAnisotropic) {
            t.phase_g = g;
            t.stem = airlight_fg_stem(g);
        }
        t.target_rel = d.relative_error / kAirlightRadiancePerTableError;
        // w_min: where the small-w form holds half the target (g < 0 needs smaller w: the
        // backward peak); u_max: the scene's, raised to where the large-u series holds it.
        a.w_min = overrides.w_min ? *overrides.w_min : airlight_small_w_min(g, t.target_rel);
        if (a.w_min < AirlightPlan{}.w_min && !overrides.w_min)
            t.domain_notes.push_back("w_min lowered to " + fmt("%.3g", a.w_min) +
                                     ": above it the small-w form misses the target" + at_g + " (measured)");
        const double onset = airlight_large_u_onset(g, t.target_rel, a.w_min);
        a.u_max = std::max(d.u_max, onset);
        if (d.u_max < onset)
            t.domain_notes.push_back("u_max raised from " + fmt("%.3g", d.u_max) + " to " + fmt("%.3g", onset) +
                                     ": from there on the large-u series holds the target" + at_g + " (measured)");
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

    std::vector<int> counts(const std::any &plan) const override {
        const AirlightPlan &p = this->plan_of(plan);
        return {p.n_u, p.n_w};
    }
    void set_counts(std::any &plan, const std::vector<int> &c) const override {
        AirlightPlan &p = this->plan_of(plan);
        p.n_u = c[0];
        p.n_w = c[1];
    }

    RadianceQueries radiance_queries(const Scene &scene, const std::any &plan, size_t count,
                                     uint64_t seed) const override {
        const double g = this->plan_of(plan).phase_g;
        return this->served_queries(
            sample_airlight_queries(media_of_phase(scene, g), count, seed),
            [g](const AirlightQuery &q) { return airlight_radiance_exact(q, g); },
            [](const AirlightQuery &) { return true; }, // every query: the table spans the scene's u
            describe_airlight_queries() + (kAnisotropic ? ", phase_g = " + fmt("%g", g) : std::string()) +
                ", every colour channel; rays through the light (infinite radiance) left out");
    }

    std::vector<RuntimeMethod> runtime_methods(const Table &table, const RadianceQueries &qs) const override {
        const std::vector<AirlightQuery> *q = &this->queries_of(qs);
        const double g = airlight_table_phase_g(table);
        std::vector<RuntimeMethod> m = {
            {"exact", "quadrature per call (airlight_radiance_exact with phase_g)", true,
             [q, g](size_t k) { return airlight_radiance_exact((*q)[k], g); }},
            {"table", std::string("two samples of the planned table (") + runtime_class() + "::radiance)", false,
             this->table_radiance(table, qs)}};
        if (kAnisotropic) { // the closed forms with the phase
            m.push_back({"thin", "no extinction along either leg, with the phase (airlight_hg_radiance_thin)", false,
                         [q, g](size_t k) { return airlight_hg_radiance_thin((*q)[k], g); }});
            m.push_back({"distant",
                         "distant light, scattering angle gamma along the ray (airlight_hg_radiance_distant)", false,
                         [q, g](size_t k) { return airlight_hg_radiance_distant((*q)[k], g); }});
        } else { // the isotropic closed forms engines use
            m.push_back({"no_extinction", "closed form without extinction, Macklin 2010 (airlight_radiance_no_extinction)",
                         false, [q](size_t k) { return airlight_radiance_no_extinction((*q)[k]); }});
            m.push_back({"attenuated",
                         "the same times e^(-sigma_t D), an engine fudge (airlight_radiance_no_extinction_attenuated)",
                         false, [q](size_t k) { return airlight_radiance_no_extinction_attenuated((*q)[k]); }});
        }
        return m;
    }
    // The isotropic table: the airlight snippet without a tier (the airlight_F table as
    // AirlightTable samples it; its tiers sample the airlight_rational table, whose kind adds
    // them) and the per-pixel forms engines use. The anisotropic table: the HG snippet in every
    // tier and its closed forms with the phase.
    GpuSnippetMethods gpu_methods(const Table &table, const RadianceQueries &qs) const override {
        const std::string args = kAirlightGpuArgs;
        if (!kAnisotropic) {
            GpuSnippetMethods g = airlight_gpu_inputs(this->queries_of(qs), "scatterlut_airlight.glsl");
            const std::string metadata =
                "SlutAirlightTable slut_planned_table() {\n    SlutAirlightTable t;\n    t.u = " +
                glsl_axis(table.axes[0]) + ";\n    t.w = " + glsl_axis(table.axes[1]) + ";\n    return t;\n}\n";
            g.methods.push_back(
                gpu_tier_method("none", "no tier: the planned airlight_F table, texel fetches (as AirlightTable)",
                                g.snippet, "sampler2D", gpu_table_texture(table), metadata,
                                "slut_airlight_radiance(slut_table, slut_planned_table(), " + args + ")"));
            GpuMethod sun;
            sun.name = "sun2005";
            sun.what = "Sun et al. 2005's two-fetch form on a plain 64x64 F(u, v) table (u <= 10, linear axes, "
                       "bench/shaders/sun2005.glsl)";
            sun.source = "sun2005.glsl";
            sun.call = "sun2005(" + args + ")";
            sun.texture = sun2005_f_texture();
            sun.uniforms = {{"f_u_max", static_cast<float>(kSunFUMax)}};
            GpuMethod closed;
            closed.name = "closed";
            closed.what =
                "closed form without extinction times e^(-sigma_t D), Macklin 2010 (bench/shaders/closed_form.glsl; "
                "an infinite ray as 1e30 m: the form takes a finite length)";
            closed.source = "closed_form.glsl";
            closed.call = "closed_form_attenuated(in0.x, in0.y, in0.z, in0.w, in1.x, in1.y, min(in1.z, 1e30))";
            g.methods.push_back(sun);
            g.methods.push_back(closed);
            g.baseline = "sun2005";
            return g;
        }
        GpuSnippetMethods g = airlight_gpu_inputs(this->queries_of(qs), "scatterlut_airlight_hg.glsl");
        const std::string phase_g = glsl_float(airlight_table_phase_g(table));
        const std::string metadata = "SlutAirlightHgTable slut_planned_table() {\n    return slut_airlight_hg_table(" +
                                     glsl_axis(table.axes[0]) + ", " + glsl_axis(table.axes[1]) + ", " + phase_g +
                                     ");\n}\n";
        const std::string call = "slut_airlight_hg_radiance(slut_table, slut_planned_table(), " + args + ")";
        const auto texture = gpu_table_texture(table);
        g.methods.push_back(gpu_tier_method("fast", "SLUT_TIER_FAST: one hardware-filtered fetch per sample", g.snippet,
                                            "sampler2D", texture, metadata, call));
        g.methods.push_back(gpu_tier_method("accurate", "SLUT_TIER_ACCURATE: texel fetches, the bilinear in the shader",
                                            g.snippet, "sampler2D", texture, metadata, call));
        g.methods.push_back(gpu_tier_method("none", "no tier (as accurate): texel fetches, as AirlightHgTable",
                                            g.snippet, "sampler2D", texture, metadata, call));
        for (const char *form : {"thin", "distant"}) {
            GpuMethod m;
            m.name = form;
            m.what = std::string("the snippet's closed form with the phase, no table (slut_airlight_hg_radiance_") +
                     form + ")";
            m.source = g.snippet;
            m.call = std::string("slut_airlight_hg_radiance_") + form + "(" + args + ", " + phase_g + ")";
            g.methods.push_back(m);
        }
        g.baseline = "thin";
        return g;
    }
    const char *runtime_class() const override { return kAnisotropic ? "AirlightHgTable" : "AirlightTable"; }
    // Spots are served by the point light's table: the ray cut by the cone (docs/SPOT.md).
    std::optional<SpotServing> spot_serving(const Scene &scene, const std::any &plan,
                                            const Table &table) const override {
        const double g = this->plan_of(plan).phase_g;
        auto runtime = std::make_shared<Runtime>(table);
        return SpotServing{media_of_phase(scene, g), g,
                           [runtime](const SpotQuery &q) { return spot_airlight_radiance(*runtime, q); }};
    }
    std::string methods_note() const override {
        if (kAnisotropic)
            return " With a Henyey-Greenstein phase the closed forms are approximations: thin drops the extinction "
                   "along both legs (exact as sigma_t -> 0, an overestimate otherwise); distant keeps the scattering "
                   "angle at gamma along the ray and 1/D^2 (Gath 2008 eq. 5 with the phase), fair for a ray much "
                   "shorter than D.";
        return " The thin-medium form (Gath 2008 §4.2) and the distant-light limit (Gath 2008 eq. 5) are near-light "
               "methods (a light outside the medium); for a viewer and a light inside the medium the alternatives to "
               "the table are the closed forms engines use (Macklin 2010): no_extinction drops the attenuation along "
               "both legs of the light path, attenuated applies e^(-sigma_t D) to the whole ray.";
    }
};

} // namespace

// What the airlight_rational kind (kinds/airlight_rational_kind.cpp), which serves the pairs
// the isotropic kind serves, reuses of it: the strictest relative error in its add_demand's
// state, and the media its report queries (media_of_phase at g = 0).
double isotropic_airlight_demand_error(const std::any &state) {
    return std::any_cast<const Demand &>(state).relative_error;
}
Scene isotropic_airlight_media(const Scene &scene) { return media_of_phase(scene, 0.0); }

const std::vector<const TableKind *> &airlight_table_kinds() {
    static const AirlightKind<AirlightTable> isotropic;
    static const AirlightKind<AirlightHgTable> anisotropic;
    static const std::vector<const TableKind *> kinds = {&isotropic, &anisotropic};
    return kinds;
}

} // namespace scatterlut
