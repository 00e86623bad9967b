// scatterlut generator — the planner: from a scene to the tables it calls for
// (docs/SCENES.md), with domains from the scene's ranges (plan_derive.cpp, each kind's
// add_demand/finish_plan) and resolutions chosen by measurement (plan_search.cpp: generate
// a trial table, measure its sampled error, refine).
#pragma once

#include <any>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "kinds/table_kind.hpp"
#include "opencl_device.hpp"
#include "scene.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// Why a table is in the plan: which medium and which light ask for it, and what they need.
struct TableRequest {
    std::string medium, light;
    std::string need; // e.g. "u up to sigma_t*D_max = 12"
};

// One trial of the resolution search: generated on the device and measured.
struct PlanTrial {
    std::vector<int> counts;         // nodes per axis, in the table's axis order
    size_t bytes = 0;                // payload at the plan's storage
    double sampling_max_rel = 0;     // measured on the trial table (the predicted error if kept)
    double sampling_p99_rel = 0;
    double integration_max_rel = 0;
    double storage_max_rel = 0;      // rounding to the storage type alone (a floor for the sampled error)
    double seconds = 0;              // integration + measurement
};

struct PlannedTable {
    const TableKind *kind = nullptr; // its name() is also the file stem
    std::vector<TableRequest> requested_by;
    std::vector<std::string> domain_notes; // where the domain goes beyond the scene's ranges, and why
    // The kind's own plan (AirlightPlan, NearLightPlan, …): domain and (after the search)
    // resolution. Only the kind reads it; tests reach it with plan_as<P>().
    std::any plan;
    // Target on the table's own quantity (G̃ or E) that gives the scene's radiance error.
    double target_rel = 0;
    bool fixed_resolution = false; // the counts came from the command line: measured, not searched
    std::vector<PlanTrial> trials;
    int chosen = -1;      // the trial whose table is kept
    bool reached = false; // the chosen trial meets target_rel
    std::string verdict;  // one line: how the search ended
    // Spot lights the table answers (airlight tables): the table path's largest relative error
    // on the scene's spot rays (spot_measure.hpp); −1 where the scene has none for it.
    double spot_max_rel = -1;
    Table table;          // the chosen trial's table (after resolve_plan)
    // Per-phase kinds (TableKind::per_phase): the table's g and its file stem; empty stem:
    // the kind's name.
    double phase_g = 0.0;
    std::string stem;
    // Per-exponent kinds (TableKind::per_exponent): the surfaces' exponent the table holds
    // (1: diffuse, n > 1: Phong), set by the planner before add_demand; 0 for the other kinds.
    int exponent = 0;

    const PlanTrial *chosen_trial() const { return chosen >= 0 ? &trials[static_cast<size_t>(chosen)] : nullptr; }
    const char *name() const { return stem.empty() ? kind->name() : stem.c_str(); }
    template <class P> P &plan_as() { return std::any_cast<P &>(plan); }
    template <class P> const P &plan_as() const { return std::any_cast<const P &>(plan); }
};

struct ScenePlan {
    Scene scene;
    Storage storage = Storage::F32;
    std::vector<PlannedTable> tables;
    std::vector<std::string> notes; // effects a closed form serves, media no light reaches, …
    double search_seconds = 0;      // total time of all trials (what generate spends before writing)
};

// Command-line overrides of the airlight table (the historical generate flags).
struct AirlightOverrides {
    std::optional<double> u_max, w_min;
    std::optional<int> n_u, n_w;
};

// A planned table's node counts, in its axis order (u, w / T, g, r[, S]), and "48x40x32".
std::vector<int> counts_of(const PlannedTable &t);
void set_counts(PlannedTable &t, const std::vector<int> &counts);
std::string counts_text(const std::vector<int> &counts, const char *separator = "x");

// Effects → tables with their domains and target errors; no device, nothing measured.
ScenePlan derive_plan(const Scene &scene, Storage storage, const AirlightOverrides &overrides = {});

// Runs the resolution search of every planned table on `device` and keeps each chosen
// table (with `provenance` and plan metadata) in PlannedTable::table.
// progress(label, fraction) may be empty.
void resolve_plan(ScenePlan &plan, Device &device, const Provenance &provenance,
                  const std::function<void(const std::string &, double)> &progress = {});

// Per-axis estimate of the linear-interpolation error of a log-encoded table: the largest
// |v[i−1] − 2 v[i] + v[i+1]| / 8 along each axis (the h²f''/8 bound in the unit coordinate,
// which is relative error for ln-stored values), over node triples whose values all lie at
// or above ln_floor. Exposed for tests.
std::vector<double> axis_interpolation_estimate(const Table &table, double ln_floor);

} // namespace scatterlut
