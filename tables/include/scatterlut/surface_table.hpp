// scatterlut runtime — the diffuse surface term of Sun et al. 2005 from a table: E_ss =
// σ_s I0/(4π D) · G0(T, θ_s), T = σ_t D (scatterlut/surface.hpp has the conventions and
// the exact quadrature, docs/PHYSICS.md §1.5 the derivation).
//
// The table stores, in one Log channel, the ratio of G0 to its closed-form scale,
//
//   ratio(T, θ_s) = G0(T, θ_s) / (e^{−T} · G0(0, θ_s)),   G0(0, θ_s) = 2π [cos θ_s + E(sin θ_s)],
//
// (ratio = 1 at T = 0, slowly falling to ~0.005 at T = 100), on the axes T (log1p warp, scale
// kSurfaceG0TScale, from 0) × θ_s (linear on [0, π], an odd count so that the kink of G0
// at θ_s = π/2, sharper as T grows, falls on a node). The ratio removes the e^{−T} fall and
// the θ_s shape at T = 0 exactly, so bilinear sampling sees only its slow remainder (the
// 64 × 65 table on T ≤ 30: tests/runtime/test_surface_table.cpp prints its measured error).
#pragma once

#include "scatterlut/surface.hpp"
#include "scatterlut/table.hpp"
#include "scatterlut/sampler.hpp"

namespace scatterlut {

inline constexpr const char *kKindSurfaceG = "surface_G";
inline constexpr uint32_t kSurfaceGQuantityVersion = 1;
inline constexpr double kSurfaceG0TScale = 0.1; // the T axis's log1p scale (optical depth)

// A table of kind surface_G with the G0 axes and channel and no values (T ∈ [0, T_max],
// T_max finite > 0; T_count ≥ 2; theta_count odd ≥ 3). Throws std::invalid_argument.
Table surface_G0_layout(double T_max, int T_count, int theta_count);

// The stored channel at a node (T, θ_s): ln(G0 / (e^{−T} G0(0, θ_s))) from G0 = g0.
double surface_G0_encode(double optical_distance, double theta_rad, double g0);

// The layout filled on the CPU by surface_G_exact (~1e-10) at every node: the reference
// table the tests and a device kernel's output are checked against. Storage F64.
Table surface_G0_table_by_quadrature(double T_max, int T_count, int theta_count);

// Samples G0 and E_ss from a surface_G table (checked on construction: kind, version,
// axes, channel, finite stored values; std::invalid_argument otherwise). Thread-safe.
class SurfaceTable {
public:
    explicit SurfaceTable(Table table);
    const Table &table() const { return table_; }
    double T_max() const { return table_.axes[0].map.max; }
    // G0(T, θ_s) for T ∈ [0, T_max], θ_s ∈ [0, π] (std::invalid_argument outside, naming
    // the parameter): positive, finite.
    double G0(double optical_distance, double theta_rad) const;
    // E_ss in W/m² (check_surface_query; T = (σ_s + σ_a) D must lie in the table's domain).
    double irradiance(const SurfaceQuery &q) const;

private:
    Table table_;
    SamplerCache cache_;
};

} // namespace scatterlut
