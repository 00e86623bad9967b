// Anisotropic (Henyey–Greenstein) and per-channel (RGB) exact single scattering: the airlight
// and the near light of airlight.hpp / nearlight.hpp with the phase
//   p_g(θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}),   g = phase_g ∈ (−1, 1), g > 0 forward,
// θ the angle between the light's propagation direction at the scattering point (from the
// light to the point) and the direction from the point to the viewer (docs/PHYSICS.md §1.4).
// phase_g = 0 is the isotropic radiance of airlight_radiance_exact / near_light_radiance_exact,
// which these functions then call (the same value, bit for bit).
//
// RGB: σ_s and σ_a per channel; the geometry, the intensity and the phase are shared. The
// integrals are dimensionless in σ_t times a length, so each channel is one evaluation of the
// same function (and one table serves every channel).
#pragma once

#include <array>
#include <cstddef>

#include "scatterlut/airlight.hpp"
#include "scatterlut/nearlight.hpp"

namespace scatterlut {

using Rgb = std::array<double, 3>; // one value per colour channel (r, g, b)

// Throws std::invalid_argument unless phase_g is finite and |phase_g| ≤ 0.999999 (the phase is
// a delta function at |g| = 1).
void check_phase_g(double phase_g);

// Airlight radiance in W/(m²·sr) with the phase of phase_g, by quadrature (~1e-13 relative):
// same units, limits and checks as airlight_radiance_exact (+inf through the light, 0 for
// σ_s = 0, I0 = 0 or s = 0; never NaN, never negative).
double airlight_radiance_exact(const AirlightQuery &q, double phase_g);

// Per channel: q supplies the geometry and the intensity (its σ fields are not read),
// sigma_s / sigma_a one coefficient per channel (1/m). A channel with σ_t = 0 (clear) and one
// that is dense are independent evaluations: neither affects the other.
Rgb airlight_radiance_exact_rgb(const AirlightQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                                double phase_g);

// The per-channel form of a one-channel radiance f(Query): f of a copy of q with channel c's
// σ_s and σ_a (1/m), for c = r, g, b; throws std::invalid_argument unless every coefficient
// is finite and ≥ 0. The one loop of every *_rgb entry point.
void check_rgb_coefficients(const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m);
template <class Query, class OneChannel>
Rgb per_channel(const Query &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m, OneChannel f) {
    check_rgb_coefficients(sigma_s_per_m, sigma_a_per_m);
    Rgb out{};
    for (size_t c = 0; c < 3; ++c) {
        Query channel = q;
        channel.sigma_s_per_m = sigma_s_per_m[c];
        channel.sigma_a_per_m = sigma_a_per_m[c];
        out[c] = f(channel);
    }
    return out;
}

// The airlight radiance from the bracket B = (1/sin γ)∫ψ_g(2ξ)e^{−u tan ξ}… of Sun's form
// (slut_hg_airlight_bracket, or the table's two samples): σ_s/(4π)·I0·(2/D)·e^{−τ}·B with
// τ = optical_distance (σ_t·D; 0 for the extinction-free form), through logarithms where the
// plain product would leave the double range. 0 for B ≤ 0 or NaN, +inf for B = +inf.
double airlight_radiance_from_bracket(const AirlightQuery &q, double optical_distance, double B);

// Near-light radiance in W/(m²·sr) with the phase of phase_g (exact quadrature along the
// refracted view ray, ~1e-13 relative): same units, checks, refraction and Fresnel options as
// near_light_radiance_exact; 0 for a light below the plane, never NaN.
double near_light_radiance_exact(const NearLightQuery &q, double phase_g);
Rgb near_light_radiance_exact_rgb(const NearLightQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                                  double phase_g);

} // namespace scatterlut
