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

#include "scatterlut/spot.hpp"
#include "scatterlut/surface.hpp"

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
// and around a narrow lobe; ~1e-9 relative (measured against surface_G_exact at θ_o = π and
// against a brute-force quadrature over directions of spot_airlight_radiance_exact:
// tests/kernels/test_spot_surface.cpp prints both). 0 for θ_o = 0. Milliseconds (wide lobes)
// to a second (n ~ 1000) per call.
double spot_surface_G_exact(int exponent, const SpotSurfacePoint &q);

// E_ss in W/m² (q.lobe_axis = n): σ_s I0/(4π D) · spot_surface_G_exact(1, q). 0 for σ_s = 0,
// I0 = 0 or θ_o = 0; never NaN.
double spot_surface_irradiance_exact(const SpotSurfacePoint &q);

// S_n in W/m² (q.lobe_axis = ρ): σ_s I0/(4π D) · spot_surface_G_exact(n, q).
double spot_surface_specular_exact(const SpotSurfacePoint &q, int exponent);

} // namespace scatterlut
