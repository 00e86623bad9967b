/* scatterlut — the near-light closed forms that need no table: the distant light (Gath 2008
 * eq. 5) and the thin-medium approximation of E (Gath 2008 §4.2).
 *
 * Symbols: kernels/slut_nearlight.h and docs/PHYSICS.md §1.2–§1.3. Compiled as OpenCL C
 * (the E4 kernel's value base), as C++ and, whole, as GLSL/HLSL in float (the near-light
 * snippet's closed forms); written in the shared subset (kernels/slut_compat.h).
 */
#ifndef SLUT_NEARLIGHT_APPROX_H
#define SLUT_NEARLIGHT_APPROX_H

#include "slut_compat.h"
#include "slut_nearlight_closed.h" /* slut_nl_H (slut_nl_N_thin) */

/* ------------------------------------------------------------------ closed forms (no table) */

/* Distant-light attenuation integral ∫_0^S e^{−(1+c)t} dt = (1 − e^{−(1+c)S})/(1+c), c = 1/r
 * (Gath 2008 eq. 5; docs/PHYSICS.md §1.2–§1.3). Written with r: 1/(1+c) = r/(1+r), (1+c)S = S(1+r)/r, and
 * −expm1 for small exponents. Limits: r = 0 → 0; r = ∞ → 1 − e^{−S}; S = ∞ → r/(1+r);
 * S = 0 → 0. This is also the T → ∞ limit of T²·N(T, g, r, S). */
SLUT_FN double slut_distant_light_factor(double r, double S) {
    SLUT_CHECK_GE(r, 0.0);
    SLUT_CHECK_GE(S, 0.0);
    if (!(S > 0.0) || !(r > 0.0)) return 0.0;
    if (r > SLUT_INFINITE_ABOVE) return -expm1(-S);
    double frac = r / (1.0 + r);
    if (S > SLUT_INFINITE_ABOVE) return frac;
    return frac * -expm1(-S / frac);
}

/* Distant light (sun over an ocean; Gath 2008 eq. 5), W/(m²·sr):
 *   L = Λ/(4π) · L_in · (1 − e^{−σ_t (1+c) s})/(1+c),  c = μ_e/μ_l,  Λ = σ_s/σ_t,
 * L_in the beam's irradiance at normal incidence (W/m²; docs/PHYSICS.md §1.3), μ_e = ω·n of the viewer,
 * μ_l = ω_l·n of the light (0 for a light at or below the horizon), s in m (+∞ = thick). */
SLUT_FN double slut_distant_light_radiance(double sigma_s_per_m, double sigma_a_per_m, double L_in,
                                           double mu_e, double mu_l, double length_m) {
    double sigma_t = sigma_s_per_m + sigma_a_per_m;
    if (!(mu_e > 0.0) || !(mu_l > 0.0) || !(sigma_s_per_m > 0.0) || !(length_m > 0.0)) return 0.0;
    double S = (length_m > SLUT_INFINITE_ABOVE) ? SLUT_HUGE_VAL : sigma_t * length_m;
    return (sigma_s_per_m / sigma_t) * SLUT_INV_4PI * L_in * slut_distant_light_factor(mu_l / mu_e, S);
}

/* Thin-medium approximation of E (Gath 2008 §4.2; docs/PHYSICS.md §1.3): the distant-light attenuation
 * averaged over the path, E ≈ (1 − e^{−x})/x, x = (1+c)S = S(1+r)/r. Limits: x → 0 gives 1
 * (also S = 0), S = ∞ or r = 0 (S > 0) gives 0 — the approximation is wrong for thick media
 * and as r → 0 (docs/PHYSICS.md §1.3); it never returns NaN. */
/* Its two steps for 0 < S < ∞ as expressions of variables r (≥ 0), S and x, written once for
 * a scalar and for the table kernel's lane vector of r (OpenCL C's ?: selects per element
 * where the condition is a lane comparison; S is a scalar): x = (1 + c)S (r = ∞: S, r = 0: ∞),
 * then (1 − e^{−x})/x: 1 below SLUT_TINY, 1/x above 40 (e^{−x} < 5e-18: 1 − e^{−x} rounds to 1,
 * the same value without expm1; also x = ∞: 0). */
#define SLUT_NL_THIN_X(r, S) (((r) > SLUT_INFINITE_ABOVE) ? (S) : (S) * ((1.0 + (r)) / (r)))
#define SLUT_NL_THIN_NEEDS_EXPM1(x) ((x) >= SLUT_TINY && (x) <= 40.0)
#define SLUT_NL_THIN_OF_X_WITHOUT_EXPM1(x) (((x) < SLUT_TINY) ? 1.0 : 1.0 / (x)) /* x outside [TINY, 40] */
/* The second step given em = expm1(−x) (the caller's: the table kernel's lane expm1), one divide. */
#define SLUT_NL_THIN_OF_X_GIVEN(x, em) (((x) < SLUT_TINY) ? 1.0 : (SLUT_NL_THIN_NEEDS_EXPM1(x) ? -(em) : 1.0) / (x))
#define SLUT_NL_THIN_OF_X(x) SLUT_NL_THIN_OF_X_GIVEN(x, expm1(-(x)))
SLUT_FN double slut_nl_E_thin(double r, double S) {
    SLUT_CHECK_GE(r, 0.0);
    SLUT_CHECK_GE(S, 0.0);
    if (!(S > 0.0)) return 1.0;
    if (!(r > 0.0) || S > SLUT_INFINITE_ABOVE) return 0.0;
    double x = SLUT_NL_THIN_X(r, S);
    return SLUT_NL_THIN_OF_X(x);
}


/* N ≈ H(T, g, S)·(1 − e^{−(1+c)S})/((1+c)S): closed-form H times slut_nl_E_thin. */
SLUT_FN double slut_nl_N_thin(double T, double g, double r, double S) {
    double H = slut_nl_H(T, g, S);
    if (!(H > 0.0)) return 0.0;
    double E = slut_nl_E_thin(r, S);
    if (!SLUT_ISFINITE(H)) return (E > 0.0) ? SLUT_HUGE_VAL : 0.0;
    return H * E;
}

#endif /* SLUT_NEARLIGHT_APPROX_H */
