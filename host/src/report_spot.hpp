// scatterlut generator — `report`'s section on spot lights (docs/SPOT.md) for a table that
// answers them: the table path's error per view of the beams (spot_measure.hpp) beside the
// exact spot airlight and what engines do instead, and its cost per call against the same
// rays as point lights.
#pragma once

#include <cstddef>
#include <string>

#include "plan.hpp"

namespace scatterlut {

// The Markdown section ("" when the table serves no spot light of the scene); writes
// <kind>_spot.csv into out_dir.
std::string spot_report_section(const PlannedTable &t, const Scene &scene, size_t rays_per_view, int rounds,
                                 const std::string &out_dir);

} // namespace scatterlut
