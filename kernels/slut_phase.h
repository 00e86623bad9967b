/* scatterlut — the Henyey–Greenstein phase function, written once.
 *
 *   p_g(θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}),   g ∈ (−1, 1), 1/sr
 *
 * Sign convention (docs/PHYSICS.md §1.4): θ is the scattering angle between the light's
 * propagation direction at the scattering point (from the light to the point) and the
 * direction from the point to the viewer; g > 0 scatters forward (the glow gathers around a
 * lamp seen through fog), g = 0 is the isotropic p = 1/(4π) of every other formula. The
 * asymmetry is called phase_g / g_hg in the code so that it never clashes with the
 * near-light g = ω·ω_l of kernels/slut_nearlight.h.
 *
 * The functions return ψ_g = 4π p_g (dimensionless, 1 for g = 0), the factor the isotropic
 * formulas are multiplied by. The denominator is written as a sum of non-negative terms,
 *   1 + g² − 2g cos θ = (1 − g)² + 4g sin²(θ/2)   (g ≥ 0)
 *                     = (1 + g)² + 4|g| cos²(θ/2)  (g < 0),
 * so that neither |g| → 1 nor θ → 0 or π loses digits (1 − cos θ from a subtraction would):
 * callers that know sin²(θ/2) and cos²(θ/2) from their geometry pass them directly.
 *
 * Compiled as C++ (host, runtime library, tests) and as OpenCL C; C99, double precision.
 */
#ifndef SLUT_PHASE_H
#define SLUT_PHASE_H

#include "slut_compat.h"

/* ψ_g = 4π p_g from s2 = sin²(θ/2) and c2 = cos²(θ/2) (s2 + c2 = 1; each given with its own
 * relative precision). |g| < 1. */
SLUT_FN double slut_hg_psi_half(double g, double s2, double c2) {
    double q = (g >= 0.0) ? (1.0 - g) * (1.0 - g) + 4.0 * g * s2 : (1.0 + g) * (1.0 + g) - 4.0 * g * c2;
    return (1.0 - g) * (1.0 + g) / (q * sqrt(q));
}

/* ψ_g from cos θ (rounding of 1 ∓ cos θ is that of cos θ itself: use slut_hg_psi_half where
 * the geometry gives the half angle more precisely). */
SLUT_FN double slut_hg_psi(double g, double cos_theta) {
    double c = slut_clamp(cos_theta, -1.0, 1.0);
    return slut_hg_psi_half(g, 0.5 * (1.0 - c), 0.5 * (1.0 + c));
}

/* p_g(θ) in 1/sr. */
SLUT_FN double slut_hg_phase(double g, double cos_theta) { return SLUT_INV_4PI * slut_hg_psi(g, cos_theta); }

/* ψ_g at θ = 0 (forward) and θ = π (backward): (1 + g)/(1 − g)² and (1 − g)/(1 + g)². The
 * largest value is ψ_g(0) for g ≥ 0 and ψ_g(π) for g < 0: (1 + |g|)/(1 − |g|)². */
SLUT_FN double slut_hg_psi_forward(double g) { return (1.0 + g) / ((1.0 - g) * (1.0 - g)); }
SLUT_FN double slut_hg_psi_backward(double g) { return (1.0 - g) / ((1.0 + g) * (1.0 + g)); }
SLUT_FN double slut_hg_psi_max(double g) { return (g >= 0.0) ? slut_hg_psi_forward(g) : slut_hg_psi_backward(g); }

#endif /* SLUT_PHASE_H */
