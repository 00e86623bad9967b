// scatterlut generator — the anisotropic airlight table: ln G̃_g(u, w) for one
// Henyey–Greenstein g on the OpenCL device (kernels/airlight_Fg.cl), then its accuracy
// measured against quadrature on the host. Axes as the isotropic table (generate_airlight.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "measurement.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

struct AirlightHgPlan {
    double phase_g = 0.85; // the table's g (≠ 0), recorded as extra "phase.g"
    double u_max = 64.0;   // largest σ_t·D·sin γ; beyond it the large-u series (the planner measures its onset)
    double u_scale = 1e-7; // LOG1P warp scale
    double w_min = 1e-3;   // smallest w = π/2 − v; below it the three-term small-w form
    double integration_tolerance = 1e-13; // relative, on G̃_g (the sweep's panels at 1e-4 of it); measured
    int n_u = 512;
    int n_w = 256;
    Storage storage = Storage::F32;
};

// A table with the plan's axes, its g in extra "phase.g", and no values yet.
Table make_airlight_hg_table_layout(const AirlightHgPlan &plan);

// ln G̃_g at every node of the layout (axis 0 fastest), on the device; g from the layout:
// the sweep of kernels/airlight_Fg.cl (its panels held to 1e-4 of `tolerance`, as the
// isotropic table's; generate_airlight.cpp).
std::vector<double> integrate_airlight_hg_ln_gs(Device &device, const Table &layout, double tolerance);

// Integrates every node on the device and measures the table's accuracy on the host.
Table generate_airlight_hg_table(Device &device, const AirlightHgPlan &plan, const Provenance &provenance,
                                 const std::function<void(double)> &progress = {});

// Relative error of the decoded G̃_g at `nodes` against `reference`: the finer panel rule
// (slut_hg_gs_quadrature, refine = 3) or Boost.Math's Gauss–Kronrod (reference_quadrature.hpp).
double measure_airlight_hg_integration(const Table &table, const std::vector<NodeIndex> &nodes,
                                       IntegrationReference reference);

// Relative error of interpolated G̃_g at `points` uniformly random off-node points (unit
// coordinates of both axes) against quadrature.
SamplingStats measure_airlight_hg_sampling(const AirlightHgTable &table, int points, uint64_t seed);

// The smallest u from which on the large-u series of G̃_g (slut_hg_gs_large_u) holds half of
// `target` against quadrature at u, 1.3u and 2u on 48 log-spaced w in [w_min, π/2]; 1e5 at most.
double airlight_hg_large_u_onset(double phase_g, double target, double w_min);

// The largest w_min (≤ 1e-3) at which the small-w form of G̃_g holds half of `target`:
// for g ≥ 0 its truncation is ≤ tan⁶w; for g < 0 ≈ 2.2 (κ tan²w)³, κ = ((1 − g)/(1 + g))²
// (kernels/slut_airlight_hg.h), checked against quadrature at 16 u.
double airlight_hg_w_min(double phase_g, double target);

} // namespace scatterlut
