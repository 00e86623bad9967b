// scatterlut generator — the airlight tables' answers for spot lights (docs/SPOT.md),
// measured on the scene's spot geometries (scene_queries.hpp, SpotView: the beam seen from
// inside, from beside and along its axis) against the exact spot airlight. The planner checks
// the chosen table with it against the scene's accepted error (plan_search.cpp); `report`
// shows it per view beside what engines do instead (report_spot.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kinds/table_kind.hpp"
#include "scene_queries.hpp"

namespace scatterlut {

// Relative errors on the radiance of the rays with a finite, positive exact radiance ("lit";
// subnormal radiances, below 2.2e-308 W/(m²·sr) with fewer digits than the errors, left out).
struct SpotViewErrors {
    SpotView view = SpotView::inside;
    size_t rays = 0, lit = 0;
    size_t dark_answered = 0;            // exact 0 (the ray misses the beam) but the table not 0
    std::vector<double> table;           // the table path (spot_airlight_radiance with the table)
    std::vector<double> band_rule;       // the same cuts and band rule with the exact point-light
                                         // radiance: the rule's own error
    std::vector<double> unclipped;       // the whole ray as a point light (exact): no cone at all
    std::vector<double> closest_falloff; // that times f at the ray's closest approach to the light
};

struct SpotMeasurement {
    std::vector<SpotViewErrors> views; // inside, beside, along
    std::vector<SpotQuery> rays;       // every view's rays, in that order (the timings' rays)
    size_t lit() const;
    double table_max() const; // the largest table error over every view (0: no lit ray)
};

// `rays_per_view` rays of each view from `seed`, with their errors; nothing timed. Empty views
// when the scene has no spot light in the served media.
SpotMeasurement measure_spot_lights(const SpotServing &serving, size_t rays_per_view, uint64_t seed);

} // namespace scatterlut
