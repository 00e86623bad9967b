// scatterlut runtime — surfaces lit through the medium: the surface terms of Sun et al. 2005
// (docs/PHYSICS.md §1.5). A surface point P inside a homogeneous medium with isotropic
// phase, a point light of intensity I0 at distance D from P, T = σ_t D.
//
// Sign conventions: θ_s is the angle between the surface's unit normal n and the direction
// FROM P TO THE LIGHT (θ_s > π/2: the light is below the surface's horizon); θ_r the angle
// between the mirror direction ρ of the view ray and the direction from P to the light.
//
//   E_ss = ∫_{n·ω>0} L_in(P, ω) (n·ω) dω        = σ_s I0/(4π D) · G_1(T, θ_s)   (W/m²)
//   S_n  = ∫_{all ω} L_in(P, ω) max(ω·ρ, 0)^n dω = σ_s I0/(4π D) · G_n(T, θ_r)   (W/m²)
//
// L_in(P, ω) the airlight arriving at P from direction ω along an infinite ray. S_n is not
// clipped at the surface's horizon (as Sun et al. 2005 define it) and not normalised.
#pragma once

namespace scatterlut {

// One surface query in physical units.
struct SurfaceQuery {
    double sigma_s_per_m = 0;      // scattering coefficient σ_s, 1/m
    double sigma_a_per_m = 0;      // absorption coefficient σ_a, 1/m
    double intensity_W_per_sr = 0; // point light intensity I0
    double distance_m = 0;         // surface point–light distance D (> 0)
    double theta_rad = 0;          // θ_s (irradiance) or θ_r (specular lobe), in [0, π]
};

constexpr int kSurfaceMaxExponent = 10000; // Phong exponents n ∈ [1, kSurfaceMaxExponent]

// Throws std::invalid_argument naming the first invalid field (σ_s, σ_a, I0 finite and ≥ 0,
// D finite and > 0, θ in [0, π]).
void check_surface_query(const SurfaceQuery &q);

// G_n(T, θ) (dimensionless, ≥ 0, finite) for an integer n ∈ [1, kSurfaceMaxExponent]
// (n = 1: the diffuse G0 of Sun et al. 2005), T ≥ 0 finite, θ ∈ [0, π], by adaptive
// Gauss–Kronrod quadrature in γ (~1e-10 relative; break points where the azimuthal kernel
// changes form and around the lobe; γ = γ_1 t² on the first panel). Throws
// std::invalid_argument for inputs outside these ranges.
double surface_G_exact(int exponent, double optical_distance, double theta_rad);

// E_ss in W/m² (scattered irradiance at the surface), by surface_G_exact(1, σ_t D, θ_s).
// 0 for σ_s = 0 or I0 = 0; positive otherwise (also for θ_s ≥ π/2); never NaN.
double surface_irradiance_exact(const SurfaceQuery &q);

// S_n in W/m² (the lobe-weighted incident airlight), by surface_G_exact(n, σ_t D, θ_r).
double surface_specular_exact(const SurfaceQuery &q, int exponent);

// E_ss without extinction, σ_s I0/(2D) · [cos θ_s + E(sin θ_s)] (E the complete elliptic
// integral of the second kind): the exact limit σ_t → 0 (σ_a is ignored), an upper bound otherwise.
double surface_irradiance_no_extinction(const SurfaceQuery &q);

} // namespace scatterlut
