// scatterlut generator — the planner's derivation: which tables a scene calls for, with
// their domains and targets (each kind's add_demand and finish_plan); no device, nothing
// measured.
#include "plan.hpp"

#include <algorithm>
#include <any>
#include <string>

namespace scatterlut {

namespace {

// A per-phase kind (TableKind::per_phase): one table for each distinct g ≠ 0 among the
// scattering media, in the order the media first name it; media that differ only in σ (or
// colour) share their g's table. Directional lights need none (the plan's note says so).
void add_per_phase_tables(const Scene &scene, const TableKind &kind, const AirlightOverrides &overrides,
                          ScenePlan &plan) {
    std::vector<double> phases;
    for (const SceneMedium &m : scene.media)
        if (m.sigma_s_per_m > 0 && !m.isotropic() && std::find(phases.begin(), phases.end(), m.phase_g) == phases.end())
            phases.push_back(m.phase_g);
    size_t made = 0;
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
        ++made;
    }
    if (made > 0)
        plan.notes.push_back(
            std::string(kind.name()) + ": one table per phase_g (" + std::to_string(made) +
            "), not one table with a g axis: the forward peak (width (1-g)/(1+g) in tan xi) moves and narrows with g, "
            "so a g axis would need the finest w spacing of its largest g at every g and enough g nodes to "
            "interpolate across the peak; a table per g keeps each w axis sized to its own g, and a scene has few g's");
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
        if (candidates[k].requested_by.empty()) continue;
        kinds[k]->finish_plan(scene, states[k], overrides, candidates[k]);
        plan.tables.push_back(std::move(candidates[k]));
    }
    if (plan.tables.empty() && plan.notes.empty()) plan.notes.push_back("no effect needs a table");
    return plan;
}

} // namespace scatterlut
