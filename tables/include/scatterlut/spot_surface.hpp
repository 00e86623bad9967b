// scatterlut runtime — surfaces lit by a spot light through the medium: Sun et al. 2005's
// surface terms (surface.hpp, docs/PHYSICS.md §1.5) for the glTF KHR_lights_punctual spot of
// spot.hpp (docs/SPOT.md, "Surfaces lit by a spot").
//
// Sign conventions: those of surface.hpp (ω a direction FROM THE SURFACE POINT P; n the
// surface's normal, ρ the mirror direction of the view ray) and spot.hpp (θ the angle between
// the spot's axis and the direction FROM THE LIGHT TO THE POINT, f(θ) glTF's falloff, I0 the
// intensity on the axis). With D = |L − P| and L_in(P, ω) the spot's airlight arriving at P
// along the infinite ray from P in direction ω (spot_airlight_radiance_exact, viewer P, s = ∞):
//
//   E_ss = ∫_{n·ω>0} L_in(P, ω) (n·ω) dω        = σ_s I0/(4π D) · G^spot_1     (W/m²)
//   S_n  = ∫_{all ω} L_in(P, ω) max(ω·ρ, 0)^n dω = σ_s I0/(4π D) · G^spot_n     (W/m²)
//
// (S_n not clipped at the horizon, as Sun et al. 2005 and surface.hpp). For θ_i = θ_o = π the
// spot is the point light and G^spot_n = G_n(σ_t D, θ) of surface.hpp.
#pragma once

#include "scatterlut/anisotropic.hpp" // Rgb
#include "scatterlut/spot.hpp"
#include "scatterlut/surface.hpp"
#include "scatterlut/surface_radiance.hpp"

namespace scatterlut {

// A surface point lit by a spot: the medium, the point, the lobe's axis and the light.
struct SpotSurfacePoint {
    double sigma_s_per_m = 0;  // scattering coefficient σ_s, 1/m
    double sigma_a_per_m = 0;  // absorption coefficient σ_a, 1/m
    Vec3 point_m{};            // P (≠ the light's position)
    Vec3 lobe_axis{0, 0, 1};   // n for E_ss, ρ for S_n (need not be unit, ≠ 0)
    SpotLight light;           // position, axis, θ_o ≥ θ_i, I0 on the axis
};

// Throws std::invalid_argument naming the first bad field: σ's, I0, coordinates not finite or
// negative; a zero lobe axis or spot direction; angles outside [0, π] or θ_i > θ_o; P at the light.
void check_spot_surface_point(const SpotSurfacePoint &q);

// G^spot_n (dimensionless, ≥ 0, finite) for an integer n ∈ [1, kSurfaceMaxExponent]: the
// triple integral over the volume around the light (docs/SPOT.md: for each direction ŵ the
// light emits into, at polar angle γ' from the direction light → P and azimuth φ', the ray
// light + d ŵ seen from P at the angle χ from the direction P → light)
//
//   G^spot_n = ∫_0^{2π} dφ' ∫_0^π dγ' f(θ(ŵ)) ∫_0^{π−γ'} e^{−σ_t D s(γ', χ)} max(ℓ·ω, 0)^n dχ,
//   s = (sin χ + sin γ')/sin(γ' + χ)  (the light path (d + r)/D),  ω = ω(φ', χ),  ℓ the lobe axis,
//
// by nested adaptive Gauss–Kronrod: γ' cut where the great circle of φ' crosses the outer and
// inner cones (closed form), φ' where those circles graze the cones, χ where ℓ·ω changes sign
// and around a narrow lobe; ~1e-8 relative (measured against surface_G_exact at θ_o = π and
// against a brute-force quadrature over directions of spot_airlight_radiance_exact:
// tests/kernels/test_spot_surface.cpp prints both). 0 for θ_o = 0. Milliseconds (wide lobes)
// to a second (n ~ 1000) per call.
double spot_surface_G_exact(int exponent, const SpotSurfacePoint &q);

// E_ss in W/m² (q.lobe_axis = n): σ_s I0/(4π D) · spot_surface_G_exact(1, q). 0 for σ_s = 0,
// I0 = 0 or θ_o = 0; never NaN.
double spot_surface_irradiance_exact(const SpotSurfacePoint &q);

// S_n in W/m² (q.lobe_axis = ρ): σ_s I0/(4π D) · spot_surface_G_exact(n, q).
double spot_surface_specular_exact(const SpotSurfacePoint &q, int exponent);

// ---------------------------------------------------------------- what an engine can afford
// A lit surface in physical units as surface_radiance.hpp (the same four terms, material and
// tables), the point light replaced by a spot. θ_P is the spot angle of P (between the spot's
// axis and the direction FROM THE LIGHT TO P), f(θ_P) its falloff (spot_falloff_at_point).
//
//   direct terms    k_d/π E_d, k_s P_d:  the point light's times f(θ_P)  (exact: the lamp sends
//                                         I0 f(θ_P) towards P)
//   scattered terms k_d/π E_ss, k_s S_n: the point light's (G_n(T, θ) from the surface_G tables)
//                                         times a factor F, an approximation (SpotScatterModel):
//     falloff    F = f(θ_P). One multiplication; right only for beams nearly as wide as a point
//                light. Inside a narrow beam it keeps all of the point light's scattered light,
//                which comes from the whole medium around the lamp (several times too bright);
//                outside the beam it drops the glow the beam scatters onto the surface.
//     thin_beam  F = min(1, e^{−T} G^spot_n(T = 0)/G_n(T, θ)), G^spot_n(T = 0) by
//                spot_surface_G_thin. Exact as σ_t D → 0 and while every scattered path through
//                the beam is about D long (σ_t D θ_o small); beyond that too bright. Up to
//                16 × 3 × 6 closed-form evaluations per term.
// docs/SPOT.md ("Surfaces lit by a spot") gives their measured errors and where they fail;
// `scatterlut report` measures both on a scene's spot-lit surfaces.
enum class SpotScatterModel { falloff, thin_beam };

// G^spot_n at zero optical depth (the σ's ignored) by the fixed rule of the thin-beam model: the
// χ integral in closed form, 6-point Gauss–Legendre in γ' on each piece between the cones'
// crossings, 16 azimuths φ' (a full turn, or Gauss–Legendre over the azimuths that meet the
// beam). Within ~1 % of spot_surface_G_exact at σ = 0 where G is not negligible
// (test_spot_surface_radiance prints it).
double spot_surface_G_thin(int exponent, const SpotSurfacePoint &q);

// The thin-beam factor min(1, e^{−σ_t D} spot_surface_G_thin(n, q)/point_G), point_G the point
// light's G_n(σ_t D, θ) (θ_s for n = 1, θ_r otherwise). 0 for point_G = 0.
double spot_surface_thin_factor(int exponent, const SpotSurfacePoint &q, double point_G);

// One surface point, one spot light and the viewer, positions in m (SurfaceLighting with a spot).
struct SpotSurfaceLighting {
    double point_m[3] = {0, 0, 0};  // P
    double normal[3] = {0, 0, 1};   // unit normal n (|n| = 1 within 1e-6), on the viewer's side
    double viewer_m[3] = {0, 0, 1}; // the viewer's position (≠ P)
    SpotLight light;                // position (≠ P), axis, θ_o ≥ θ_i, I0 on the axis
};

// The point light of the same position and on-axis intensity I0 (the lighting whose terms
// spot_surface_radiance scales).
SurfaceLighting point_light_of(const SpotSurfaceLighting &s);

// f(θ_P) ∈ [0, 1]: glTF's falloff of the direction from the light to `point_m`: spot_falloff
// (scatterlut/spot.hpp) for a surface point, which must not sit on the light
// (std::invalid_argument for a bad light or point).
double spot_falloff_at_point(const SpotLight &light, const double point_m[3]);

// The terms as above, W/(m²·sr), G from the tables (SurfaceTables of surface_radiance.hpp; T
// beyond a table's axis by quadrature), the scattered ones by `model`. Throws
// std::invalid_argument as surface_radiance and for a bad spot (angles outside [0, π],
// θ_i > θ_o, a zero axis, I0 not finite or < 0). ≥ 0, never NaN.
SurfaceRadiance spot_surface_radiance(const SurfaceTables &tables, const SpotSurfaceLighting &s, double sigma_s_per_m,
                                      double sigma_a_per_m, const SurfaceMaterial &m,
                                      SpotScatterModel model = SpotScatterModel::thin_beam);

// The reference: the direct terms as above (exact), the scattered ones from the spot's exact
// E_ss and S_n (spot_surface_G_exact with n and ρ; milliseconds to a second per term).
SurfaceRadiance spot_surface_radiance_exact(const SpotSurfaceLighting &s, double sigma_s_per_m, double sigma_a_per_m,
                                            const SurfaceMaterial &m);

// Per colour channel (σ_s, σ_a one value per channel; geometry, light and material shared):
// the total per channel, each the scalar form's.
Rgb spot_surface_radiance_rgb(const SurfaceTables &tables, const SpotSurfaceLighting &s, const Rgb &sigma_s_per_m,
                              const Rgb &sigma_a_per_m, const SurfaceMaterial &m,
                              SpotScatterModel model = SpotScatterModel::thin_beam);
Rgb spot_surface_radiance_exact_rgb(const SpotSurfaceLighting &s, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                                    const SurfaceMaterial &m);

} // namespace scatterlut
