// scatterlut generator — the airlight_rational table (kernels/slut_airlight_rational.h): Ĥ(x_m, x_t),
// the airlight's tail H(u, t) normalised by N = t + 2/π + u (1 + t²), on the unit square of
// rational coordinates x_m = (m/(m + K))^{1/4}, m = u (1 + t), and x_t = t/(1 + t), integrated node
// by node on the OpenCL device (kernels/airlight_rational.cl) and stored as the runtime's
// AirlightRationalTable reads it (scatterlut/airlight_rational.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "measurement.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight_rational.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// The integration tolerance recorded for the table (relative, on Ĥ): the node function's rule
// (slut_w_gs_quadrature at refine = 1: 16-point Gauss–Legendre panels, ≤ 1e-13 per panel) is
// fixed, not chosen by a tolerance; what it reaches is measured by every generate (against
// refine = 3) and validate (against Boost.Math).
inline constexpr double kAirlightRationalIntegrationTolerance = 1e-12;

struct AirlightRationalPlan {
    int n_m = 256; // nodes on x_m (axis 0, the texture's width)
    int n_t = 256; // nodes on x_t (axis 1, its height)
    double integration_tolerance = kAirlightRationalIntegrationTolerance;
    Storage storage = Storage::F32;
};

// A table with the plan's two linear unit axes and its channel, no values.
Table make_airlight_rational_layout(const AirlightRationalPlan &plan);

// Ĥ at every node of `layout` (axis 0 fastest) by the kernel; nothing measured. The rule is
// fixed: `tolerance` does not change it.
std::vector<double> integrate_airlight_rational(Device &device, const Table &layout, double tolerance);

// Integrated, measured (integration at the corners and 396 random nodes against refine = 3;
// sampling at 20000 uniform random unit coordinates) and rounded to the plan's storage.
// progress(fraction done) may be empty.
Table generate_airlight_rational_table(Device &device, const AirlightRationalPlan &plan,
                                       const Provenance &provenance,
                                       const std::function<void(double)> &progress = {});

// Ĥ at unit coordinates by an independent rule: m from x_m by bisection on the axis's map
// (slut_airlight_rational_x_m, not the node function's inverse), then Boost.Math's Gauss–Kronrod
// of H(u, t) over y (reference_scaled_tail, long double), Boost.Math's expint on the edge
// x_t = 1 (e^m E_2(m)·(1 + m)), 1 on the edge x_m = 1.
double reference_airlight_rational(double x_m, double x_t);

// Relative error of the stored (decoded) Ĥ at `nodes` against `reference`: the node function
// at refine = 3 (FinerPanelRule) or reference_airlight_rational (IndependentGaussKronrod).
// +∞ if one is NaN.
double measure_airlight_rational_integration(const AirlightRationalTable &table, const std::vector<NodeIndex> &nodes,
                                             IntegrationReference reference);

// Relative error of the sampled Ĥ (AirlightRationalTable::sample) at `points` uniformly random
// unit coordinates against the node function (refine = 1). worst_u, worst_w: x_m, x_t of the
// largest.
SamplingStats measure_airlight_rational_sampling(const AirlightRationalTable &table, int points, uint64_t seed);

} // namespace scatterlut
