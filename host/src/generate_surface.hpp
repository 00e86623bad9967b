// scatterlut generator — the surface tables of Sun et al. 2005 (docs/PHYSICS.md §1.5): G_n(T, θ)
// for one Phong exponent n (n = 1: the diffuse G0), integrated on the OpenCL device
// (kernels/surface_G.cl) and stored as the runtime's SurfaceTable reads it
// (scatterlut/surface_table.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "measurement.hpp"
#include "opencl_device.hpp"
#include "scatterlut/surface_table.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// The integration tolerance of production tables (relative, on G_n): 4 panels of the fixed
// rule per interval (slut_surface_subpanels_for_tolerance), measured ≤ 8.9e-11 against the
// adaptive quadrature (kernels/slut_surface.h).
inline constexpr double kSurfaceIntegrationTolerance = 1e-10;

struct SurfacePlan {
    int exponent = 1;     // Phong exponent n; 1: the diffuse table G0
    double T_max = 30.0;  // σ_t·D, the T axis spans [0, T_max] (log1p, surface_G_T_scale), ≤ kSurfaceGTMaxLimit
    int n_T = 64, n_theta = 65; // node counts; n_theta odd for n = 1 (a node at θ_s = π/2)
    double integration_tolerance = kSurfaceIntegrationTolerance;
    Storage storage = Storage::F32;
};

// The file stem of a table of exponent n: "surface_G0" for n = 1 (Sun et al. 2005's name for
// the diffuse table), "surface_G<n>" otherwise (surface_G20: the Phong lobe of exponent 20).
std::string surface_file_stem(int exponent);

// The Phong exponent a surface_G table holds (1: the diffuse G0; table_surface_exponent).
int surface_table_exponent(const Table &table);

Table make_surface_table_layout(const SurfacePlan &plan);

// The stored channel at every node of `layout` (axis 0 fastest): G_n by the kernel with the
// rule for `tolerance`, encoded on the host. Nothing measured.
std::vector<double> integrate_surface_G(Device &device, const Table &layout, double tolerance);

// Integrated, measured (integration at 100 nodes against surface_G_exact, sampling at 4000
// random points) and rounded to the plan's storage.
Table generate_surface_table(Device &device, const SurfacePlan &plan, const Provenance &provenance);

// Relative error of the decoded G_n at `nodes` against `reference`: the adaptive Gauss–Kronrod
// quadrature of the runtime (surface_G_exact, FinerPanelRule) or Boost.Math's on the physical
// integral (reference_surface_G, IndependentGaussKronrod). +∞ if one is NaN.
double measure_surface_integration(const SurfaceTable &table, const std::vector<NodeIndex> &nodes,
                                   IntegrationReference reference);

// Interpolated G_n at random unit coordinates (T, θ) against the fixed rule with 2 panels per
// interval (≤ 6.1e-9, far below any table's error).
SamplingStats measure_surface_sampling(const SurfaceTable &table, int points, uint64_t seed);

} // namespace scatterlut
