// scatterlut runtime — a lit surface in fog in physical units: the radiance a surface point
// sends towards the viewer from one point light, with Sun et al. 2005's surface terms
// (docs/PHYSICS.md §1.5; the geometry and the assembly are kernels/slut_surface_frontend.h,
// shared with the surface shader snippet).
//
// A surface point P in a homogeneous medium with isotropic phase (σ_s, σ_a in 1/m), unit
// normal n on the viewer's side, a point light of intensity I0 (W/sr), a viewer. With
// D = |light − P|, D_v = |viewer − P|, T = σ_t D, θ_s the angle between n and the direction
// FROM P TO THE LIGHT, ρ the mirror direction of the view ray and θ_r the angle between ρ and
// the direction to the light:
//
//   L = e^{−σ_t D_v} [ k_d/π (E_d + E_ss) + k_s (P_d + S_n) ]                    W/(m²·sr)
//   E_d  = I0 e^{−T} max(cos θ_s, 0)/D²            E_ss = σ_s I0/(4π D) · G0(T, θ_s)
//   P_d  = I0 e^{−T} max(cos θ_r, 0)^n/D² (0 if cos θ_s ≤ 0)
//   S_n  = σ_s I0/(4π D) · G_n(T, θ_r)  (the lobe not clipped at the horizon, as Sun et al. 2005)
//
// Phong normalisation: none (Sun et al. 2005's form): k_s is in 1/sr and multiplies the bare
// lobe max(cos θ_r, 0)^n; for an energy-conserving lobe of specular albedo ρ_s pass
// k_s = ρ_s (n + 2)/(2π). k_d is the Lambertian albedo.
//
// Not included: the airlight of the view ray itself (between the viewer and P). The caller
// adds it (AirlightTable::radiance of the same light with length D_v, or the airlight snippet).
// A viewer on the back side (n·(viewer − P) ≤ 0) gets 0.
#pragma once

#include "scatterlut/anisotropic.hpp" // Rgb
#include "scatterlut/surface_table.hpp"

namespace scatterlut {

// One surface point, one point light and the viewer, positions in m.
struct SurfaceLighting {
    double point_m[3] = {0, 0, 0};      // P
    double normal[3] = {0, 0, 1};       // unit normal n (|n| = 1 within 1e-6), on the viewer's side
    double light_m[3] = {0, 0, 1};      // the point light's position (≠ P)
    double viewer_m[3] = {0, 0, 1};     // the viewer's position (≠ P)
    double intensity_W_per_sr = 0;      // I0 ≥ 0
};

// The surface's reflectance: Lambertian albedo k_d plus an unnormalised Phong lobe.
struct SurfaceMaterial {
    double diffuse_albedo = 0;    // k_d ≥ 0 (dimensionless)
    double specular_per_sr = 0;   // k_s ≥ 0, 1/sr (energy-conserving: ρ_s (n + 2)/(2π))
    int phong_exponent = 1;       // n ∈ [1, kSurfaceMaxExponent]
};

// The radiance towards the viewer split into its four terms, W/(m²·sr), each attenuated by
// e^{−σ_t D_v}: k_d/π E_d, k_d/π E_ss, k_s P_d, k_s S_n.
struct SurfaceRadiance {
    double diffuse_direct = 0, diffuse_scattered = 0, specular_direct = 0, specular_scattered = 0;
    double total() const { return diffuse_direct + diffuse_scattered + specular_direct + specular_scattered; }
};

// Throws std::invalid_argument naming the first invalid field: positions finite, |n| = 1
// within 1e-6, the light and the viewer not at P, I0, σ_s, σ_a, k_d, k_s finite and ≥ 0, the
// exponent in [1, kSurfaceMaxExponent].
void check_surface_lighting(const SurfaceLighting &s, double sigma_s_per_m, double sigma_a_per_m,
                            const SurfaceMaterial &m);

// The tables the front-end samples (not owned): diffuse = a surface_G table of exponent 1
// (G0), needed when k_d > 0; specular = a surface_G table whose exponent() is the material's
// n, needed when k_s > 0 (for n = 1 the G0 table serves both). Where T = σ_t D lies beyond a table's T axis the front-end
// integrates that G exactly (surface_G_exact: ~1 ms per call) instead of extrapolating.
struct SurfaceTables {
    const SurfaceTable *diffuse = nullptr;
    const SurfaceTable *specular = nullptr;
};

// L from the tables (grey medium). Throws std::invalid_argument (check_surface_lighting; a
// table missing for a non-zero coefficient; a diffuse table not of exponent 1; a specular
// table of another exponent). ≥ 0, never
// NaN; finite unless I0/D² itself overflows (a light within ~1e-154 m of the point).
SurfaceRadiance surface_radiance(const SurfaceTables &tables, const SurfaceLighting &s, double sigma_s_per_m,
                                 double sigma_a_per_m, const SurfaceMaterial &m);

// L with G0 and G_n by quadrature (surface_G_exact, ~1e-10 relative): the reference of the above.
SurfaceRadiance surface_radiance_exact(const SurfaceLighting &s, double sigma_s_per_m, double sigma_a_per_m,
                                       const SurfaceMaterial &m);

// Per colour channel: σ_s and σ_a one value per channel (1/m); the geometry, I0 and the
// material shared. Each channel is one evaluation of the scalar form (T differs per channel;
// the tables are dimensionless and serve every channel). Returns the total per channel.
Rgb surface_radiance_rgb(const SurfaceTables &tables, const SurfaceLighting &s, const Rgb &sigma_s_per_m,
                         const Rgb &sigma_a_per_m, const SurfaceMaterial &m);
Rgb surface_radiance_exact_rgb(const SurfaceLighting &s, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                               const SurfaceMaterial &m);

} // namespace scatterlut
