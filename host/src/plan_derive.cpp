// scatterlut generator — the planner's derivation: which tables a scene calls for, with
// their domains and targets (each kind's add_demand and finish_plan); no device, nothing
// measured.
#include "plan.hpp"

#include <algorithm>
#include <any>
#include <cmath>
#include <string>

#include "text_format.hpp"

extern "C" {
#include "slut_airlight_hg.h"
}

namespace scatterlut {

namespace {

// The largest spacing in g (halving from 0.1) at which ln G̃_g interpolated linearly in g from
// its neighbours g ± h/2 holds `target` at g itself (the worst place between two g nodes),
// over 24 × 12 log-spaced (u, w) in [1e-3, 1e2] × [1e-3, π/2]: what a table with a g axis
// would need around g.
double g_axis_spacing(double g, double target) {
    for (double spacing = 0.1; spacing > 1e-4; spacing *= 0.5) {
        const double h = 0.5 * spacing;
        if (std::fabs(g) + h >= 0.999999) continue;
        double worst = 0;
        for (int i = 0; i < 24 && worst <= target; ++i)
            for (int j = 0; j < 12 && worst <= target; ++j) {
                const double u = 1e-3 * std::pow(1e5, i / 23.0), w = 1e-3 * std::pow(SLUT_PIO2_HI / 1e-3, j / 11.0);
                const double lo = std::log(slut_hg_gs_quadrature(u, w, g - h, 1.0));
                const double hi = std::log(slut_hg_gs_quadrature(u, w, g + h, 1.0));
                const double at = std::log(slut_hg_gs_quadrature(u, w, g, 1.0));
                worst = std::max(worst, std::fabs(std::expm1(0.5 * (lo + hi) - at)));
            }
        if (worst <= target) return spacing;
    }
    return 1e-4;
}

// A per-phase kind (TableKind::per_phase): one table for each distinct g ≠ 0 among the
// scattering media, in the order the media first name it; media that differ only in σ (or
// colour) share their g's table. Directional lights need none (the plan's note says so).
void add_per_phase_tables(const Scene &scene, const TableKind &kind, const AirlightOverrides &overrides,
                          ScenePlan &plan) {
    std::vector<double> phases;
    for (const SceneMedium &m : scene.media)
        if (m.sigma_s_per_m > 0 && !m.isotropic() && std::find(phases.begin(), phases.end(), m.phase_g) == phases.end())
            phases.push_back(m.phase_g);
    std::vector<double> made_for; // the g that got a table of this kind
    for (double g : phases) {
        PlannedTable t;
        t.kind = &kind;
        std::any state;
        for (const SceneMedium &m : scene.media) {
            if (m.sigma_s_per_m == 0 || m.phase_g != g) continue;
            for (const SceneLight &l : scene.lights)
                if (Scene::lights_medium(l, m) && l.type == LightType::Point) kind.add_demand(scene, m, l, state, t);
        }
        if (t.requested_by.empty()) continue;
        kind.finish_plan(scene, state, overrides, t);
        plan.tables.push_back(std::move(t));
        made_for.push_back(g);
    }
    if (made_for.empty()) return;
    const size_t made = made_for.size();
    // One table per g, or one with a g axis over [g_min, g_max]: the g axis needs the spacing
    // at which interpolating in g holds the table's target (measured at every g of the scene;
    // the finest wins), each g node the size of one table.
    const PlannedTable &first = plan.tables.back();
    double spacing = 0.1;
    for (double g : made_for) spacing = std::min(spacing, g_axis_spacing(g, first.target_rel));
    const double lo = *std::min_element(made_for.begin(), made_for.end());
    const double hi = *std::max_element(made_for.begin(), made_for.end());
    const int g_nodes = std::max(2, static_cast<int>(std::ceil((hi - lo) / spacing)) + 1);
    plan.notes.push_back(std::string(kind.name()) + ": one table per phase_g (" + std::to_string(made) +
                         "), not one with a g axis: linear interpolation in g holds the target " +
                         fmt("%.3g", first.target_rel) + " only at a g spacing <= " + fmt("%.3g", spacing) +
                         " (measured at the scene's g" +
                         (std::string(kind.name()).rfind("near_light", 0) == 0
                              ? " on the airlight integral, which the near-light table holds at r = 0"
                              : "") +
                         "; the forward peak of width (1-g)/(1+g) moves with g), so a g "
                         "axis over [" + fmt("%g", lo) + ", " + fmt("%g", hi) + "] would need " +
                         std::to_string(g_nodes) + " g nodes, each the size of one table, against " +
                         std::to_string(made) + " table(s)");
}

// A per-exponent kind (TableKind::per_exponent): one table for each distinct exponent of the
// scene's lit surfaces (ascending), asked by the media whose surfaces need it with the point
// lights that light them.
void add_per_exponent_tables(const Scene &scene, const TableKind &kind, const AirlightOverrides &overrides,
                             ScenePlan &plan) {
    std::vector<int> exponents;
    for (const SceneMedium &m : scene.media)
        if (m.sigma_s_per_m > 0 && m.has_surfaces)
            for (int n : m.surfaces.exponents())
                if (std::find(exponents.begin(), exponents.end(), n) == exponents.end()) exponents.push_back(n);
    std::sort(exponents.begin(), exponents.end());
    for (int n : exponents) {
        PlannedTable t;
        t.kind = &kind;
        t.exponent = n;
        std::any state;
        for (const SceneMedium &m : scene.media) {
            if (m.sigma_s_per_m == 0 || !m.has_surfaces) continue;
            const std::vector<int> e = m.surfaces.exponents();
            if (std::find(e.begin(), e.end(), n) == e.end()) continue;
            for (const SceneLight &l : scene.lights)
                if (Scene::lights_medium(l, m) && l.type == LightType::Point) kind.add_demand(scene, m, l, state, t);
        }
        if (t.requested_by.empty()) continue;
        kind.finish_plan(scene, state, overrides, t);
        plan.tables.push_back(std::move(t));
    }
}

} // namespace

ScenePlan derive_plan(const Scene &scene, Storage storage, const AirlightOverrides &overrides) {
    ScenePlan plan;
    plan.scene = scene;
    plan.storage = storage;
    if (scene.media.empty()) {
        plan.notes.push_back("no medium in the scene: nothing to tabulate");
        return plan;
    }
    // One candidate table per kind, each with its kind's own accumulator over the pairs.
    const std::vector<const TableKind *> &kinds = table_kinds();
    std::vector<PlannedTable> candidates(kinds.size());
    std::vector<std::any> states(kinds.size());
    for (size_t k = 0; k < kinds.size(); ++k) candidates[k].kind = kinds[k];
    for (const SceneMedium &m : scene.media) {
        if (m.sigma_s_per_m == 0) {
            plan.notes.push_back("medium '" + m.name + "': sigma_s = 0, nothing scatters light towards the viewer: no table");
            continue;
        }
        bool lit = false;
        for (const SceneLight &l : scene.lights) {
            if (!Scene::lights_medium(l, m)) continue;
            lit = true;
            if (l.type == LightType::Directional) {
                plan.notes.push_back("medium '" + m.name + "' lit by directional light '" + l.name +
                                     "': the closed form serves (distant light, Gath 2008 eq. 5: L = albedo p L_in "
                                     "(1 - exp(-sigma_t (1+c) s))/(1+c)); no table");
                continue;
            }
            for (size_t k = 0; k < kinds.size(); ++k) kinds[k]->add_demand(scene, m, l, states[k], candidates[k]);
        }
        if (!lit) plan.notes.push_back("medium '" + m.name + "': no light lights it: no table");
    }
    for (size_t k = 0; k < kinds.size(); ++k) {
        if (kinds[k]->per_phase()) {
            add_per_phase_tables(scene, *kinds[k], overrides, plan);
            continue;
        }
        if (kinds[k]->per_exponent()) {
            add_per_exponent_tables(scene, *kinds[k], overrides, plan);
            continue;
        }
        if (candidates[k].requested_by.empty()) continue;
        kinds[k]->finish_plan(scene, states[k], overrides, candidates[k]);
        plan.tables.push_back(std::move(candidates[k]));
    }
    if (plan.tables.empty() && plan.notes.empty()) plan.notes.push_back("no effect needs a table");
    return plan;
}

} // namespace scatterlut
