// scatterlut generator — the airlight table: ln G̃(u, w) on the OpenCL device, then its
// accuracy measured against the shared quadrature on the host.
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
    double u_max = 64.0;   // largest σ_t·D·sin γ in the table; beyond it the large-u series
    double u_scale = 1e-7; // LOG1P warp scale: log spacing in u above ~u_scale
    double w_min = 1e-3;   // smallest w = π/2 − v in the table; below it the small-w form
    double integration_tolerance = kAirlightIntegrationTolerance;
    int n_u = 512;
    int n_w = 256;
    Storage storage = Storage::F32;
};

// A table with the plan's axes and no values yet.
Table make_airlight_table_layout(const AirlightPlan &plan);

// ln G̃ at every node of the layout's axes (axis 0 fastest), integrated on the device by
// the sweep of kernels/airlight_F.cl; no accuracy measurement.
// `tolerance`: relative, on G̃; each panel is held to 1e-4 of it (generate_airlight.cpp).
std::vector<double> integrate_airlight_ln_gs(Device &device, const Table &layout,
                                             double tolerance = kAirlightIntegrationTolerance);

// The same sweep with the Henyey–Greenstein integrand of asymmetry phase_g ≠ 0
// (kernels/airlight_Fg.cl; no large-u series): ln G̃_g at every node of `layout` (the rows
// u = 0 by the same recurrence at u = 0, on the host).
std::vector<double> integrate_airlight_hg_ln_gs_sweep(Device &device, const Table &layout, double tolerance,
                                                      double phase_g);

// Integrates every node on the device and measures the table's accuracy on the host.
// progress(fraction done) may be empty.
Table generate_airlight_table(Device &device, const AirlightPlan &plan, const Provenance &provenance,
                              const std::function<void(double)> &progress = {});

// The generator's nodes for its integration-error measurement: the four corners, then
// random nodes from `seed` up to `nodes`.
std::vector<NodeIndex> airlight_measurement_nodes(const Table &table, int nodes, uint64_t seed);

// Relative error of the decoded G̃ at `nodes` against `reference`: the finer panel rule
// (slut_gs_quadrature, refine = 3) or Boost.Math's Gauss–Kronrod (reference_quadrature.hpp).
double measure_airlight_integration(const Table &table, const std::vector<NodeIndex> &nodes,
                                    IntegrationReference reference);

// Relative error of interpolated G̃ at `points` uniformly random off-node points (in the
// unit coordinates of both axes) against quadrature.
SamplingStats measure_airlight_sampling(const AirlightTable &table, int points, uint64_t seed);

} // namespace scatterlut
