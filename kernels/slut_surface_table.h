/* scatterlut — the closed forms a surface_G table's decode needs (Sun et al. 2005's surface
 * terms, docs/PHYSICS.md §1.5; the table layout in docs/FORMAT.md).
 *
 * C99 / OpenCL C / C++ in double, and the shader subset in float (SLUT_SHADER: docs/SHADERS.md
 * "One source"). A surface_G table of Phong exponent n stores, in one Log channel,
 *
 *   ln( G_n(T, θ) / slut_surface_G_scale(n, T, θ) ),   slut_surface_G_scale = e^{−T} · N_n(θ),
 *
 * T = σ_t D (optical distance from the surface point to the light) and θ the angle between the
 * surface normal (n = 1, θ_s) or the mirror direction ρ (n > 1, θ_r) and the direction FROM THE
 * SURFACE POINT TO THE LIGHT. N_n(θ) takes out the e^{−T} fall and the θ shape of G_n at T = 0,
 * so that the bilinear sampler sees a slow remainder:
 *   - n = 1: N_1(θ_s) = G_1(0, θ_s) = 2π [cos θ_s + E(sin θ_s)] exactly (the ratio is 1 at T = 0);
 *   - n > 1: N_n(θ) = π √(2π/m) · e^{−x} I_0(x) · θ (π − θ)/sin θ,   m = n + 1, x = m θ²/4,
 *     a narrow-lobe form (docs/PHYSICS.md §1.5): within G_n(0, θ)/N_n(θ) ∈ [0.92, 1.16] for
 *     every n ≥ 2 and θ (measured: tests/runtime/test_surface_table.cpp).
 * Both bound G_n from above to within that factor: G_n(T, θ) ≤ e^{−T} G_n(0, θ) (extinction only
 * removes light), so the stored ln ratio is ≤ 0 for n = 1 and ≤ ln 1.16 for n > 1.
 */
#ifndef SLUT_SURFACE_TABLE_H
#define SLUT_SURFACE_TABLE_H

#include "slut_compat.h"

/* slut_ellint_2 stops once the AGM's c is below this fraction of a: the next term, ~(c/a)⁴/16
 * of the sum, is then below the working precision. */
#ifdef SLUT_SHADER
#  define SLUT_AGM_CONVERGED 1e-4
#else
#  define SLUT_AGM_CONVERGED 1e-9
#endif

/* Complete elliptic integral of the second kind E(k) = ∫_0^{π/2} √(1 − k² sin²φ) dφ from
 * k' = √(1 − k²) (given, so that k → 1 keeps its precision), by the arithmetic–geometric mean:
 * E = π/(2 M(1, k')) · (1 − Σ_{j≥0} 2^{j−1} c_j²), c_0 = k, c_{j+1} = (a_j − b_j)/2.
 * E(1) = 1 (k' = 0) is returned as such. ~1e-16 relative in double (tests: ≤ 1e-14 against
 * Boost's ellint_2). */
SLUT_FN double slut_ellint_2(double k, double k_comp) {
    if (k_comp <= 0.0) return 1.0;
    double a = 1.0, b = k_comp, sum = 0.5 * k * k, power = 0.5;
    for (int j = 0; j < 64; ++j) {
        double c = 0.5 * (a - b);
        double a_next = 0.5 * (a + b);
        b = sqrt(a * b);
        a = a_next;
        power *= 2.0;
        sum += power * c * c;
        /* Quadratic convergence: the next c would be ~c²/(4a), whose term is negligible.
         * (Iterating on would add 2^j times the rounding residue of a − b.) */
        if (fabs(c) < SLUT_AGM_CONVERGED * a) break;
    }
    return SLUT_PI / (2.0 * a) * (1.0 - sum);
}

/* G_1(0, θ_s) = 2π [cos θ_s + E(sin θ_s)]: the diffuse term without extinction (σ_t → 0). */
SLUT_FN double slut_surface_G0_no_extinction(double theta_s) {
    double c = cos(theta_s), s = sin(theta_s);
    return 2.0 * SLUT_PI * (c + slut_ellint_2(s, fabs(c)));
}

/* e^{−x} I_0(x) for x ≥ 0 (I_0 the modified Bessel function of the first kind), by Abramowitz &
 * Stegun 9.8.1 (x < 3.75, |ε| < 1.6e-7 relative on I_0) and 9.8.2 (x ≥ 3.75, |ε| < 1.9e-7 on
 * √x e^{−x} I_0(x)). Only a smooth scale for the table's ratio (encode and decode share it), so
 * this precision, and the ~3e-7 step at x = 3.75, are ample. */
SLUT_FN double slut_bessel_i0_scaled(double x) {
    if (x < 3.75) {
        double t = x / 3.75;
        double t2 = t * t;
        double i0 = 1.0 + t2 * (3.5156229 + t2 * (3.0899424 + t2 * (1.2067492 +
                    t2 * (0.2659732 + t2 * (0.0360768 + t2 * 0.0045813)))));
        return exp(-x) * i0;
    }
    {
        double r = 3.75 / x;
        double p = 0.39894228 + r * (0.01328592 + r * (0.00225319 + r * (-0.00157565 + r * (0.00916281 +
                   r * (-0.02057706 + r * (0.02635537 + r * (-0.01647633 + r * 0.00392377)))))));
        return p / sqrt(x);
    }
}

/* t / sin t for t ∈ [0, π/2] (1 at t = 0). */
SLUT_FN double slut_surface_t_over_sin(double t) {
    return t < 1e-4 ? 1.0 + t * t / 6.0 : t / sin(t);
}

/* N_n(θ) for an integer n ≥ 2, θ ∈ [0, π] (clamped): the narrow-lobe form of G_n(0, θ).
 * Derivation (docs/PHYSICS.md §1.5): at T = 0 the incident airlight is A(0, γ) = (π − γ)/sin γ
 * ≈ π/γ near the light; the lobe max(ω·ρ, 0)^n, of integral 2π/m, is nearly a Gaussian of
 * variance 1/m per axis in the plane tangent at ρ, where the light sits at distance θ; the mean
 * of 1/γ over it is that of 1/R for a Rice variable, √(π m/2) e^{−x} I_0(x), x = m θ²/4 (→ 1/θ for
 * θ ≫ 1/√m). Replacing π/θ by A(0, θ) keeps the far-lobe limit G_n → (2π/m) A(0, θ) exact:
 *   N_n(θ) = (2π/m) · √(π m/2) e^{−x} I_0(x) · θ (π − θ)/sin θ   (θ (π − θ)/sin θ = π at 0 and π).
 * Positive and finite for every n and θ; falls like 1/(m θ) away from the light. */
SLUT_FN double slut_surface_Gn_lobe_scale(int exponent, double theta) {
    double th = slut_clamp(theta, 0.0, SLUT_PI);
    double m = SLUT_DOUBLE(exponent + 1);
    /* θ (π − θ)/sin θ with both ends finite: (π − θ)·[θ/sin θ] below π/2, θ·[t/sin t], t = π − θ, above. */
    double t = (2.0 * SLUT_PIO2_HI - th) + 2.0 * SLUT_PIO2_LO;
    double w = th <= 0.5 * SLUT_PI ? t * slut_surface_t_over_sin(th) : th * slut_surface_t_over_sin(t);
    return SLUT_PI * sqrt(2.0 * SLUT_PI / m) * slut_bessel_i0_scaled(0.25 * m * th * th) * w;
}

/* The scale a surface_G table of exponent n ≥ 1 divides G_n by (the stored channel is
 * ln(G_n / scale)): e^{−T} G_1(0, θ) for n = 1, e^{−T} N_n(θ) for n > 1. T ≥ 0, θ ∈ [0, π].
 * Underflows to 0 for T > ~745 in double (the tables end at T ≤ 700) and for T > ~87 in float
 * (the shaders: e^{−87} ≈ 1.6e-38, light that is gone against anything else in the frame). */
SLUT_FN double slut_surface_G_scale(int exponent, double optical_distance, double theta) {
    double shape = exponent == 1 ? slut_surface_G0_no_extinction(slut_clamp(theta, 0.0, SLUT_PI))
                                 : slut_surface_Gn_lobe_scale(exponent, theta);
    return exp(-optical_distance) * shape;
}

#endif /* SLUT_SURFACE_TABLE_H */
