// scatterlut generator — the airlight tables: ln G̃_g(u, w) on the OpenCL device for one
// Henyey–Greenstein g (g = 0: the isotropic table airlight_F, exactly as before the phase
// existed; g ≠ 0: airlight_Fg, its g recorded in the file), then their accuracy measured
// against the shared quadrature on the host. One code path for every g.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "measurement.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// Domain and resolution of an airlight table. The defaults hold the default scene's
// accuracy (docs/AIRLIGHT.md gives the measurements behind them).
// The integration tolerance of production tables (relative, on G̃): the sweep's panels at
// 1e-17; what it reaches is ~1e-15–6e-14 (measured by every generate and by `report`).
inline constexpr double kAirlightIntegrationTolerance = 1e-13;

struct AirlightPlan {
    double phase_g = 0.0;  // Henyey–Greenstein g: 0 the isotropic kind airlight_F, else airlight_Fg
    double u_max = 64.0;   // largest σ_t·D·sin γ in the table; beyond it the large-u series
    double u_scale = 1e-7; // LOG1P warp scale: log spacing in u above ~u_scale
    double w_min = 1e-3;   // smallest w = π/2 − v in the table; below it the small-w form
    double integration_tolerance = kAirlightIntegrationTolerance;
    int n_u = 512;
    int n_w = 256;
    Storage storage = Storage::F32;
};

// A table with the plan's axes (and, for g ≠ 0, its g in extra "phase.g") and no values yet.
Table make_airlight_table_layout(const AirlightPlan &plan);

// The scale s of the w axis's ASINH_COT_PEAK warp for g > 0 (kernels/slut_axes.h: log spacing
// in v = π/2 − w down to s, linear below): half the forward peak's width (1 − g)/(1 + g) in
// tan ξ (the distance of k_g's singularities from the real axis, generate_airlight.cpp), the
// best of 1/8 … 2 times that width by the sampling error against node count (docs/AIRLIGHT.md);
// 0 for g ≤ 0, whose w axis is ASINH_COT (the isotropic table's, bit for bit at g = 0).
double airlight_w_peak_scale(double phase_g);

// The Henyey–Greenstein g of an airlight table of either kind: 0 for airlight_F, the recorded
// "phase.g" for airlight_Fg (throws std::invalid_argument when that is missing or bad).
double airlight_table_phase_g(const Table &table);

// ln G̃_g at every node of the layout's axes (axis 0 fastest), g from the layout, integrated
// on the device by the sweep of kernels/airlight_F.cl; no accuracy measurement.
// `tolerance`: relative, on G̃_g; each panel is held to 1e-4 of it (generate_airlight.cpp).
std::vector<double> integrate_airlight_ln_gs(Device &device, const Table &layout,
                                             double tolerance = kAirlightIntegrationTolerance);

// Integrates every node on the device and measures the table's accuracy on the host.
// progress(fraction done) may be empty.
Table generate_airlight_table(Device &device, const AirlightPlan &plan, const Provenance &provenance,
                              const std::function<void(double)> &progress = {});

// The generator's nodes for its integration-error measurement: the four corners, then
// random nodes from `seed` up to `nodes`.
std::vector<NodeIndex> airlight_measurement_nodes(const Table &table, int nodes, uint64_t seed);

// Relative error of the decoded G̃_g at `nodes` against `reference`: the finer panel rule
// (slut_hg_gs_quadrature, refine = 3) or Boost.Math's Gauss–Kronrod (reference_quadrature.hpp).
double measure_airlight_integration(const Table &table, const std::vector<NodeIndex> &nodes,
                                    IntegrationReference reference);

// The runtime's G̃_g(u, w) of a table (AirlightTable::scaled_tail, AirlightHgTable::scaled_tail).
using AirlightScaledTail = std::function<double(double u, double w)>;

// Relative error of interpolated G̃_g (`scaled_tail`, the runtime of `table`) at `points`
// uniformly random off-node points (in the unit coordinates of both axes) against quadrature.
SamplingStats measure_airlight_sampling(const Table &table, const AirlightScaledTail &scaled_tail, int points,
                                        uint64_t seed);

// The smallest u from which on the large-u series of G̃_g (slut_hg_gs_large_u; g = 0:
// slut_gs_large_u) holds half of `target` against quadrature at u, 1.3u and 2u on 48
// log-spaced w in [w_min, π/2] (its error falls with u like k!/u^k at the smallest term);
// 1e5 at most. An airlight table must reach at least this u.
double airlight_large_u_onset(double phase_g, double target, double w_min);

// The largest w_min (≤ 1e-3) at which the small-w form of G̃_g holds half of `target`:
// for g ≥ 0 its truncation is ≤ tan⁶w (g = 0: tan⁴w); for g < 0 ≈ 2.2 (κ tan²w)³,
// κ = ((1 − g)/(1 + g))² (kernels/slut_airlight_hg.h), checked against quadrature at 16 u.
double airlight_small_w_min(double phase_g, double target);

} // namespace scatterlut
