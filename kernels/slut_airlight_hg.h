/* scatterlut — the airlight of Sun et al. 2005 with a Henyey–Greenstein phase, written once.
 *
 * Derivation and conventions: docs/PHYSICS.md §1.4. With the phase the airlight is
 *
 *   L = σ_s I0 ∫_0^s p_g(θ(x)) e^{−σ_t (x + d(x))} / d(x)² dx,
 *   cos θ(x) = (D cos γ − x)/d(x)      (θ between the light's propagation direction at the
 *                                        point and the direction from the point to the viewer)
 *
 * (γ, D, s, d(x) as in kernels/slut_airlight.h). In Sun's substitution the scattering angle
 * is exactly θ = 2ξ, so the airlight keeps its 2-D form with
 *
 *   F_g(u, v) = ∫_0^v ψ_g(2ξ) e^{−u tan ξ} dξ,        ψ_g = 4π p_g (kernels/slut_phase.h)
 *   G̃_g(u, w) = e^{u cot w} ∫_{π/2−w}^{π/2} ψ_g(2ξ) e^{−u tan ξ} dξ / w
 *
 * and L = σ_s/(4π)·I0·2e^{−σ_t D}/(D sin γ)·[w2 G̃_g(u, w2) − e^{−σ_t Δ} w1 G̃_g(u, w1)] with the
 * u, w1, w2, Δ of the isotropic case. g = 0 gives ψ = 1 and today's F, G̃; every function
 * here hands g = 0 to the isotropic one of kernels/slut_airlight.h, so that case is today's
 * path, bit for bit.
 *
 * One integral serves them all. With t = tan ξ, dξ = dt/(1 + t²) and
 *   ψ_g(2ξ)/(1 + t²) = (1 − g²)·√(1 + t²) / ((1 − g)² + (1 + g)² t²)^{3/2}
 * (both terms of the denominator ≥ 0 for every g: no cancellation as |g| → 1), and after
 * scaling t = λ(τ̂ + z) by λ = max(1, tan v) (so that nothing over- or underflows as v → π/2):
 *
 *   K_g(û, τ̂, ε̂, Z) = ∫_0^Z e^{−û z} k_g(τ̂ + z) dz,
 *   k_g(T) = (1 − g²)·r / Q^{3/2},   r = √(ε̂² + T²),   Q = (1 − g)² ε̂² + (1 + g)² T²,
 *
 * with û = λu, τ̂ = tan v/λ, ε̂ = 1/λ (one of τ̂, ε̂ is 1). Then
 *   w·G̃_g(u, w) = K_g(λu, τ̂, ε̂, ∞)/λ,    F_g(u, v) = K_g(u, 0, 1, tan v),
 * and the bracket of the radiance (the segment's integral) is K_g over the segment
 * (slut_airlight_hg_bracket.h).
 * For g = 0, k_0(T) = 1/(ε̂² + T²): the isotropic integrand.
 *
 * Compiled as C++ by the runtime library and the tests, as OpenCL C by kernels/airlight_Fg.cl
 * (double precision), and whole, a third time, as GLSL/HLSL in float for the anisotropic
 * airlight snippet (docs/SHADERS.md; kernels/slut_compat.h lists the subset that keeps to:
 * structs by value, precision-dependent thresholds as SLUT_* macros, every math call mapped).
 * The generator's quadratures of F_g and G̃_g sit in an `#ifndef SLUT_SHADER` block
 * (slut_airlight_hg_integral.h).
 *
 * The parts, each included here (and each includable by itself), in the order the GPU
 * snippets concatenate them (SLUT_SHADER_HEADERS, CMakeLists.txt):
 *   slut_airlight_hg_integral.h    k_g, K_g by quadrature, a tail's scaling; G̃_g and F_g by quadrature;
 *   slut_airlight_hg_asymptotic.h  G̃_g as w → 0 and for large u, and beyond a table's u_max;
 *   slut_airlight_hg_bracket.h     the bracket B_g, the exact radiance, the thin and distant forms;
 *   this header                    the radiance from a table of G̃_g: its two ends, the bracket
 *                                  from two samples, the table's w axis.
 */
#ifndef SLUT_AIRLIGHT_HG_H
#define SLUT_AIRLIGHT_HG_H

#include "slut_compat.h"
#include "slut_phase.h"
#include "slut_airlight.h" /* the isotropic functions g = 0 hands to; slut_gl16_x/w; slut_exp_expint */
#include "slut_axes.h"     /* the w axis warps (slut_hg_airlight_w_warp) */
#include "slut_phase_arc.h" /* the thin-medium form: the phase's mean over the ray's arc */
#include "slut_airlight_hg_integral.h"   /* k_g, K_g, a tail's scaling */
#include "slut_airlight_hg_asymptotic.h" /* G̃_g where a table has no nodes */
#include "slut_airlight_hg_bracket.h"    /* the bracket B_g, the half angles */

/* ------------------------------------------------------------ radiance from a table */

/* The two ends of the bracket for a table of G̃_g (the GPU snippet; the C++ AirlightHgTable::radiance
 * does the same steps): B_g = [w2·G̃_g(u, w2) − e^{−σ_t Δ}·w1·G̃_g(u, w1)]/sin γ with
 *   u = σ_t D sin γ,  w2 = π/2 − γ/2 = atan2(cos(γ/2), sin(γ/2))  (exact near γ → π too),
 *   w1 = π/2 − v1 = atan2(1, tan v1),  tan v1 = tan(γ/2) + Δ/(D sin γ),
 * Δ/D without cancellation as in slut_hg_airlight_bracket (s' ≥ 1: (s' − 1) + d'; s' < 1:
 * 4s' sin²(γ/2)/(d' + 1 − s')); an infinite ray has no far term (w1 = 0). samples = 0 where the
 * table is not used: sin γ < 1e-6 (the geometry of γ → 0, where the bracket's own integral is
 * cheap and exact). s_over_D > SLUT_INFINITE_ABOVE: an infinite ray. */
SLUT_STRUCT_BEGIN(slut_hg_airlight_ends)
    int samples;          /* 1: sample G̃_g at (u, w2), and at (u, w1) where w1 > 0       */
    double optical_distance; /* σ_t D                                                  */
    double sin_gamma;     /* sin γ                                                       */
    double sin_half;      /* sin(γ/2)                                                    */
    double cos_half;      /* cos(γ/2)                                                    */
    double s_over_D;      /* s/D (+∞ for an infinite ray)                                */
    double u;             /* σ_t D sin γ                                                 */
    double w2;            /* π/2 − γ/2: the viewer end                                   */
    double w1;            /* π/2 − v1: the far end (0 for an infinite ray)               */
    double far_attenuation; /* e^{−σ_t Δ} (0 for an infinite ray)                          */
SLUT_STRUCT_END(slut_hg_airlight_ends);

SLUT_FN slut_hg_airlight_ends slut_hg_airlight_setup_ends(double optical_distance, double sin_gamma,
                                                          double cos_gamma, double s_over_D) {
    slut_hg_airlight_ends e;
    slut_hg_half_angle h = slut_hg_half_angles_of(sin_gamma, cos_gamma);
    e.optical_distance = optical_distance;
    e.sin_gamma = sin_gamma;
    e.sin_half = h.sin_half;
    e.cos_half = h.cos_half;
    e.s_over_D = s_over_D;
    e.samples = (sin_gamma >= 1e-6) ? 1 : 0;
    e.u = optical_distance * sin_gamma;
    e.w2 = atan2(h.cos_half, h.sin_half);
    e.w1 = 0.0;
    e.far_attenuation = 0.0;
    if (e.samples != 0 && s_over_D <= SLUT_INFINITE_ABOVE) {
        double sp = s_over_D, sh2 = h.sin_half * h.sin_half;
        double d_far = (sp > 1.0) ? sp * sqrt((1.0 - 1.0 / sp) * (1.0 - 1.0 / sp) + 4.0 * sh2 / sp)
                                  : sqrt((1.0 - sp) * (1.0 - sp) + 4.0 * sp * sh2);
        double delta_over_D = (sp >= 1.0) ? (sp - 1.0) + d_far : 4.0 * sp * sh2 / (d_far + (1.0 - sp));
        double tan_v1 = h.sin_half / h.cos_half + delta_over_D / sin_gamma;
        e.w1 = atan2(1.0, tan_v1);
        e.far_attenuation = exp(-optical_distance * delta_over_D);
    }
    return e;
}

/* B_g from the two samples gs2 = G̃_g(u, w2) and gs1 = G̃_g(u, w1) (unused where w1 = 0), where
 * the far term is at most half the viewer term; elsewhere (the two would cancel, or samples = 0)
 * the segment's integral itself, slut_hg_airlight_bracket. */
SLUT_FN double slut_hg_airlight_bracket_from_gs(slut_hg_airlight_ends e, double gs2, double gs1, double g) {
    if (e.samples != 0) {
        double a = e.w2 * gs2;
        double b = (e.w1 > 0.0) ? e.far_attenuation * e.w1 * gs1 : 0.0;
        if (SLUT_ISFINITE(a) && SLUT_ISFINITE(b) && b <= 0.5 * a && a > 0.0) return (a - b) / e.sin_gamma;
    }
    return slut_hg_airlight_bracket(e.optical_distance, e.sin_half, e.cos_half, e.s_over_D, g, 1.0);
}

/* The anisotropic table's w axis (its map is recorded in the file; this is the generator's
 * choice, here once for the generator and the snippets' convenience constructors): for g > 0
 * ASINH_COT_PEAK with scale s = (1 − g)/(2(1 + g)), half the forward peak's width (1 − g)/(1 + g)
 * in tan ξ — the best of 1/8 … 2 times that width by the sampling error against node count
 * (docs/AIRLIGHT.md); for g ≤ 0 ASINH_COT, the isotropic table's map (scale unused: 0). */
SLUT_FN double slut_hg_airlight_w_peak_scale(double g) { return (g > 0.0) ? 0.5 * (1.0 - g) / (1.0 + g) : 0.0; }
SLUT_FN int slut_hg_airlight_w_warp(double g) {
    return (g > 0.0) ? SLUT_WARP_ASINH_COT_PEAK : SLUT_WARP_ASINH_COT;
}

#endif /* SLUT_AIRLIGHT_HG_H */
