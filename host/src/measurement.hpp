// scatterlut generator — what the accuracy measurements of every table kind report, and
// which reference an integration-error measurement compares the nodes with.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "scatterlut/table.hpp"

namespace scatterlut {

// Relative error of interpolated values at random off-node points against quadrature.
struct SamplingStats {
    double max_rel = 0, p99_rel = 0, median_rel = 0;
    uint64_t points = 0;
    double worst_u = 0, worst_w = 0;   // where max_rel occurs (the first two parameters)
    double worst_at[4] = {0, 0, 0, 0}; // near-light tables: (T, g, r, S) of max_rel
};

// A node of a table: its index along each axis.
using NodeIndex = std::array<size_t, kMaxAxes>;

// The reference an integration-error measurement compares the nodes with.
enum class IntegrationReference {
    // The kernels' own panel rules with a finer refinement (kernels/slut_*.h): what
    // `generate` and `report` measure with (the declared accuracy.integration_max_rel).
    FinerPanelRule,
    // Boost.Math adaptive 61-point Gauss–Kronrod of the physical integral (in long double),
    // sharing no rule with the kernels: what `validate` re-measures with
    // (reference_quadrature.hpp).
    IndependentGaussKronrod,
};

} // namespace scatterlut
