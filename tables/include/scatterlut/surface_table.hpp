// scatterlut runtime — the surface terms of Sun et al. 2005 from a table: E_ss =
// σ_s I0/(4π D) · G_1(T, θ_s) (diffuse, the G0 of the paper) and S_n = σ_s I0/(4π D) · G_n(T, θ_r)
// (Phong lobe of exponent n), T = σ_t D (scatterlut/surface.hpp has the conventions and the exact
// quadrature, docs/PHYSICS.md §1.5 the derivation, docs/FORMAT.md the layout).
//
// A surface_G table holds one exponent n ∈ [1, kSurfaceMaxExponent] (recorded in `extra` as
// kSurfaceExponentKey) and stores, in one Log channel, the ratio of G_n to a closed-form scale
// (kernels/slut_surface_table.h, slut_surface_G_scale),
//
//   ratio(T, θ) = G_n(T, θ) / (e^{−T} N_n(θ)),   N_1(θ_s) = G_1(0, θ_s) = 2π [cos θ_s + E(sin θ_s)],
//                                                 N_n(θ_r) = the narrow-lobe form of G_n(0, θ_r), n > 1,
//
// on the axes T (log1p warp, scale surface_G_T_scale(n), from 0) × θ on [0, π]:
//  - n = 1: θ_s linear, an odd count so that the kink of G_1 at θ_s = π/2 (sharper as T grows)
//    falls on a node (the 64 × 65 table on T ≤ 30: 5.6e-3 at most);
//  - n > 1: θ_r log1p with scale surface_G_theta_scale(n) = 1/√(n + 1), the lobe's angular width:
//    nodes crowd where the lobe meets the light (tests/runtime/test_surface_table.cpp prints the
//    measured error of each exponent's table).
// The scale removes the e^{−T} fall and the θ shape at T = 0 (exactly for n = 1, to within
// [0.92, 1.16] for n > 1), so bilinear sampling sees only a slow remainder.
#pragma once

#include "scatterlut/surface.hpp"
#include "scatterlut/table.hpp"
#include "scatterlut/sampler.hpp"

namespace scatterlut {

inline constexpr const char *kKindSurfaceG = "surface_G";
inline constexpr uint32_t kSurfaceGQuantityVersion = 1;
inline constexpr double kSurfaceG0TScale = 0.1;  // the T axis's log1p scale (optical depth), n = 1
inline constexpr double kSurfaceGnTScale = 0.02; // the T axis's log1p scale, n > 1
inline constexpr double kSurfaceGTMaxLimit = 700; // T_max at most: e^{−T} stays a normal double
// Table::extra key: the Phong exponent n of the table, a decimal integer (n = 1: the diffuse G0).
inline constexpr const char *kSurfaceExponentKey = "surface.exponent";
// The largest stored ln ratio a table of exponent n > 1 may hold (beyond kLnRoundingSlack): the
// ratio is at most max_θ G_n(0, θ)/N_n(θ), measured 1.156 (n = 2, θ ≈ 0.95; smaller for larger
// n), < e^{0.2} = 1.22 (tests/runtime/test_surface_table.cpp checks n = 2 … 10000 against it).
inline constexpr double kSurfaceGnMaxLnRatio = 0.2;

// The T axis's log1p scale of a G_n table (optical depth): kSurfaceG0TScale for n = 1,
// kSurfaceGnTScale for n > 1 (finer near T = 0, where a narrow lobe facing away from the light
// sees e^{2T} E_2(2T) ≈ 1 + 2T ln 2T).
double surface_G_T_scale(int exponent);
// The θ axis's scale of a G_n table: 1 for n = 1 (linear θ_s), for n > 1 the log1p scale of
// θ_r (radians) 1/√(n + 1), the lobe's width.
double surface_G_theta_scale(int exponent);

// A table of kind surface_G for Phong exponent n ∈ [1, kSurfaceMaxExponent] with its axes and
// channel and no values (T ∈ [0, T_max], T_max in (0, kSurfaceGTMaxLimit]; T_count ≥ 2;
// theta_count ≥ 3, odd for n = 1). Throws std::invalid_argument.
Table surface_G_layout(int exponent, double T_max, int T_count, int theta_count);

// The stored channel at a node (T, θ): ln(G / slut_surface_G_scale(n, T, θ)) from G = G_n(T, θ).
double surface_G_encode(int exponent, double optical_distance, double theta_rad, double G);

// The layout filled on the CPU by surface_G_exact (~1e-10) at every node: the reference
// table the tests and a device kernel's output are checked against. Storage F64.
Table surface_G_table_by_quadrature(int exponent, double T_max, int T_count, int theta_count);

// The exponent a table records (kSurfaceExponentKey): an integer in [1, kSurfaceMaxExponent]
// written as such, else std::invalid_argument naming the key and the text.
int table_surface_exponent(const Table &table);

// The diffuse case n = 1 (the G0 of Sun et al. 2005): the functions above with exponent 1.
Table surface_G0_layout(double T_max, int T_count, int theta_count);
double surface_G0_encode(double optical_distance, double theta_rad, double g0);
Table surface_G0_table_by_quadrature(double T_max, int T_count, int theta_count);

// Samples G_n, and E_ss (n = 1) or S_n, from a surface_G table (checked on construction: kind,
// version, exponent, the axes and channel of that exponent, stored values finite and within
// the ratio's physical range; std::invalid_argument otherwise). Thread-safe.
class SurfaceTable {
public:
    explicit SurfaceTable(Table table);
    const Table &table() const { return table_; }
    int exponent() const { return exponent_; }
    double T_max() const { return table_.axes[0].map.max; }
    // G_n(T, θ) of the table's exponent for T ∈ [0, T_max], θ ∈ [0, π] (std::invalid_argument
    // outside, naming the parameter): non-negative (positive unless it underflows), finite.
    double G(double optical_distance, double theta_rad) const;
    // G(T, θ_s) of a diffuse table (std::invalid_argument unless exponent() == 1).
    double G0(double optical_distance, double theta_rad) const;
    // E_ss in W/m² (check_surface_query; q.theta_rad is θ_s; T = (σ_s + σ_a) D must lie in the
    // table's domain; exponent() must be 1).
    double irradiance(const SurfaceQuery &q) const;
    // S_n in W/m² for n = exponent() (as surface_specular_exact(q, n); q.theta_rad is θ_r; T
    // must lie in the table's domain).
    double specular(const SurfaceQuery &q) const;

private:
    Table table_;
    SamplerCache cache_;
    int exponent_ = 1;
};

} // namespace scatterlut
