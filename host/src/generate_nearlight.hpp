// scatterlut generator — the near-light tables: ln E(T, g, r) for thick media (3-D) and
// ln E(T, g, r, S) for slabs of finite optical thickness (4-D), on the OpenCL device.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "measurement.hpp"
#include "opencl_device.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/nearlight_hg.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// The integration tolerance of production tables (relative, on E): refine = 0.63
// (slut_nl_refine_for_tolerance), measured 7.6e-12 at every node of a 64³ E3 table and 5.5e-15
// of a 32³ × 17 E4 one (its panels are cut at every S node) against refine 2.5, and ≤ 1e-10
// at the hard corners (tests NearLightKernel.*). The tables store f32 (6e-8) or f16; the
// 1e-14 of refine = 1 cost E3 ~35 % more quadrature nodes (bench/README.md).
inline constexpr double kNearLightIntegrationTolerance = 1e-11;

// The isotropic near-light kernel's work-group: this many T nodes (work-items, each a whole march)
// per group, the launch's T extent padded to a multiple of it (the kernel returns at once past
// T_count). PoCL runs each work-group as one task of its worker threads; groups of one
// work-item (16384 for E3 64³) cost 3–6 % of the kernel's CPU time in that dispatch
// (bench/README.md, "the node loop's exp, second round"). Values do not depend on it.
inline constexpr int kNearLightGroupT = 8;

struct NearLightPlan {
    bool finite_thickness = false; // false: 3-D (S = ∞); true: 4-D with a slab axis q
    double T_min = 1e-3, T_max = 20.0;  // σ_t·l; loglin axis ln T + T/T_scale: log spacing below
    double T_scale = 1.0;               // T_scale, linear above, where ln E(r = 0) ~ −T falls linearly
    double g_min = -0.99;               // ω·ω_l; below it (grazing view and light) E is integrated exactly
    double g_max = 1.0;                 // below 1 only for strongly backward phases (anisotropic kinds)
    int g_warp = SLUT_WARP_SQRT1P;      // sqrt1p (√(1+g)), or log1p from g_min with g_scale
    double g_scale = 0.0;
    double r_max = 1e3, r_scale = 1e-6; // μ_l/μ_e, log1p axis including r = 0
    double S_min = 1e-3, S_max = 20.0;  // σ_t·s, slab axis q (4-D only); outside: exact
    double integration_tolerance = kNearLightIntegrationTolerance;
    int n_T = 96, n_g = 80, n_r = 64, n_S = 17; // node counts; the defaults: docs/NEARLIGHT.md
    Storage storage = Storage::F32;
    // Henyey–Greenstein g of the medium's phase: 0 gives the isotropic kinds (near_light_E3/E4,
    // unchanged); otherwise the anisotropic kinds near_light_E3_hg/E4_hg (scatterlut/nearlight_hg.hpp),
    // which store ln(E_g/ψ_max) and record g as the extra "phase.g".
    double phase_g = 0.0;
};

// The default plans: the 3-D table (S = ∞), and the 4-D one with r resolved down to 1e-9,
// where thin slabs still see the light through their surface layer, and g in log1p spacing
// from g_min (docs/NEARLIGHT.md).
NearLightPlan default_near_light_plan(bool finite_thickness);

// The largest near-light g an anisotropic table covers. A backward phase (phase_g < −0.5)
// peaks at θ = π, which the view ray reaches for g → 1 (looking away from the light): there E_g
// is the mean of ψ over the last α = acos g of scattering angle and varies with α/α itself,
// which the √(1 + g) axis does not resolve; above g = 0.85 (α < 32°) such tables integrate
// exactly (measured: g = −0.9, 96 × 80 × 64 nodes, 0.6 % max with it, 36 % without; docs/NEARLIGHT.md).
// The slab tables stop there from phase_g ≤ −0.5 on (measured: g = −0.5, the hard corners
// 1.2 % at T = T_max, g = 0.87 with g up to 1).
double near_light_hg_g_max(double phase_g, bool finite_thickness);

Table make_nearlight_table_layout(const NearLightPlan &plan);

// ln E at every node of the layout's axes (axis 0 fastest) on the device; no accuracy
// measurement. progress(fraction done) may be empty.
// `tolerance`: relative, on E (the kernel's refine = slut_nl_refine_for_tolerance).
std::vector<double> integrate_nearlight_ln_E(Device &device, const Table &layout,
                                             const std::function<void(double)> &progress = {},
                                             double tolerance = kNearLightIntegrationTolerance);

Table generate_nearlight_table(Device &device, const NearLightPlan &plan, const Provenance &provenance,
                               const std::function<void(double)> &progress = {});

// Relative error of the decoded E at `nodes` against `reference`: the finer panel rule
// (slut_nl_E_lanes, refine = 2.5) or Boost.Math's Gauss–Kronrod (reference_quadrature.hpp).
double measure_nearlight_integration(const NearLightTable &table, const std::vector<NodeIndex> &nodes,
                                     IntegrationReference reference);

// Interpolated E at random unit coordinates where E ≥ 1e-6, against quadrature (slut_nl_E).
// In a 4-D table S is log-uniform in [S_min, S_max].
SamplingStats measure_nearlight_sampling(const NearLightTable &table, int points, uint64_t seed);

// The same at the hard corners: each parameter, with probability ½, takes one of its edge
// values (T at both ends; g = g_min, g_min + 1e-9, 1; r = 0, 1e-12, r_max; S = S_min,
// S_min·(1 + 1e-9), S_max, and S ≈ −g·T where the slab's far face cuts the 1/ĥ² peak) and
// otherwise a random one as above.
SamplingStats measure_nearlight_corners(const NearLightTable &table, int points, uint64_t seed);

// The same measurements of an anisotropic table: E_g against slut_hg_nl_E (FinerPanelRule:
// refine 2.5) or Boost.Math with the phase; sampling and corners where the attenuation (the
// isotropic E) is ≥ 1e-6.
double measure_nearlight_integration(const NearLightHgTable &table, const std::vector<NodeIndex> &nodes,
                                     IntegrationReference reference);
SamplingStats measure_nearlight_sampling(const NearLightHgTable &table, int points, uint64_t seed);
SamplingStats measure_nearlight_corners(const NearLightHgTable &table, int points, uint64_t seed);

} // namespace scatterlut
