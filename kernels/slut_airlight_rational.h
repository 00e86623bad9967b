/* scatterlut — the airlight's tail on rational axes: a table that hardware bilinear
 * filtering serves directly (the GPU snippets' fast tier, docs/SHADERS.md "Tiers").
 *
 * In the tangent variable t = tan v = cot w the tail of Sun et al. 2005's F, scaled by its
 * exponential (slut_airlight.h: H = w·G̃), is
 *
 *   H(u, t) = e^{u t} ∫_{atan t}^{π/2} e^{−u tan ξ} dξ = ∫_0^∞ e^{−u y} / (1 + (t + y)²) dy,
 *
 * u = σ_t D sin γ ≥ 0, t ∈ [0, ∞]. Its three limits fix a normaliser that needs no
 * transcendental function:
 *   u → 0:        H = arccot t        (π/2 at t = 0, ~1/t as t → ∞);
 *   u → ∞:        H ~ 1/(u (1 + t²))  (Watson's lemma, slut_gs_large_u);
 *   t → ∞, a = u t fixed:  H ~ e^a E_2(a) / t  (slut_gs_small_w).
 * With N(u, t) = t + 2/π + u (1 + t²), the stored value Ĥ = H·N is 1 at u = ∞, arccot(t)·(t + 2/π)
 * at u = 0 and e^m E_2(m)·(1 + m) at t = ∞: bounded in [0.80, 1.29] over the whole quarter
 * plane, with no coupled corner once the first axis follows m = u (1 + t) (≈ the optical
 * distance from the ray's end to the light times a function of t, which carries the
 * e^a E_2(a) limit to the edge t = ∞).
 *
 * The axes, unit coordinates in [0, 1] with the ends on the first and last texel centres:
 *   x_m = √(m/(m + K)),  m = u (1 + t)    (K = SLUT_AIRLIGHT_RATIONAL_M_SCALE; the root
 *                                           resolves H's u·ln u term at u → 0)
 *   x_t = t/(1 + t)
 * Both are rational in the ray's geometry (one divide each and a square root), so a sample
 * costs one filtered fetch and no exp or log: no warp, no decode, no regime beyond the table.
 * Bilinear interpolation of Ĥ on these axes: max relative error 6e-5 at 256 × 256,
 * 1.1e-4 at 192², 1.5e-4 at 160² (K = 1; measured by the planner, kinds/airlight_rational_kind.cpp).
 *
 * The radiance (slut_airlight.h's convention: γ between the view direction and the direction
 * FROM THE VIEWER TO THE LIGHT):
 *   L = scale · [H(u, t2) − e^{−σ_t Δ} H(u, t1)] / sin γ,
 * t2 = tan(γ/2) (viewer end), t1 = cot w1 (far end). Each end term H/sin γ = Ĥ·weight/sin γ
 * with weight = 1/N written without overflow: 1/((1 + a2) t2 + u + 2/π) at the viewer end,
 * tan w1/((1 + a1) + (u + 2/π) tan w1) at the far end (a = u t as in slut_airlight_geometry).
 */
#ifndef SLUT_AIRLIGHT_RATIONAL_H
#define SLUT_AIRLIGHT_RATIONAL_H

#include "slut_compat.h"
#include "slut_airlight.h"

/* K of the first axis: m = K at x_m = 1/√2 (measured: K in [1, 2] balances the two edges). */
#define SLUT_AIRLIGHT_RATIONAL_M_SCALE 1.0
#define SLUT_AIRLIGHT_RATIONAL_TWO_OVER_PI 0.636619772367581343

/* The unit coordinates of an end of the ray (lane-generic: plain arithmetic). m is clamped
 * below SLUT_INFINITE_ABOVE so that m/(m + K) is 1, not ∞/∞, for an infinite far end. */
SLUT_FN double slut_airlight_rational_x_m(double m) {
    double mc = fmin(m, SLUT_INFINITE_ABOVE);
    return sqrt(mc / (mc + SLUT_AIRLIGHT_RATIONAL_M_SCALE));
}
SLUT_FN double slut_airlight_rational_x_t_of_tan_w(double tan_w) { return 1.0 / (1.0 + tan_w); }

/* The two ends of a set-up geometry (kind 0, slut_airlight_setup_far_end applied): their
 * unit coordinates and weights (the far end's e^{−σ_t Δ} included; 0 for an infinite ray). */
SLUT_STRUCT_BEGIN(slut_airlight_rational_ends)
    double x_m2, x_t2, weight2; /* viewer end */
    double x_m1, x_t1, weight1; /* far end    */
SLUT_STRUCT_END(slut_airlight_rational_ends);

SLUT_FN slut_airlight_rational_ends slut_airlight_rational_ends_of(slut_airlight_geometry g) {
    slut_airlight_rational_ends e;
    double t2 = g.sin_half / g.cos_half; /* tan(γ/2) = cot w2; cos(γ/2) ≥ SLUT_SQUARABLE_MIN */
    e.x_m2 = slut_airlight_rational_x_m(g.u + g.a2);
    e.x_t2 = g.sin_half / (g.sin_half + g.cos_half);
    e.weight2 = 1.0 / ((1.0 + g.a2) * t2 + g.u + SLUT_AIRLIGHT_RATIONAL_TWO_OVER_PI);
    if (!SLUT_ISFINITE(g.optical_delta)) { /* an infinite ray: no far end */
        e.x_m1 = 1.0;
        e.x_t1 = 1.0;
        e.weight1 = 0.0;
        return e;
    }
    e.x_m1 = slut_airlight_rational_x_m(g.u + g.a1);
    e.x_t1 = slut_airlight_rational_x_t_of_tan_w(g.tan_w1);
    e.weight1 = g.far_attenuation * g.tan_w1 /
                ((1.0 + g.a1) + (g.u + SLUT_AIRLIGHT_RATIONAL_TWO_OVER_PI) * g.tan_w1);
    return e;
}

/* The radiance from the two stored samples Ĥ(x_m2, x_t2) and Ĥ(x_m1, x_t1), for a geometry
 * whose segment does not fit one θ-panel (slut_airlight_theta_fits_one_panel: the caller
 * integrates those directly). There the difference loses at most a factor 4.4 of the
 * samples' relative accuracy: a segment longer than a quarter of the angle w2 to the pole
 * leaves a tail beyond it of at most 3.35 times its own integral (the θ-integrand
 * decreases), and one with λ·tan dv > 4 (λ the decay rate at its start) at most 0.23 times.
 * Never negative. */
SLUT_FN double slut_airlight_rational_radiance_from_samples(slut_airlight_geometry g, slut_airlight_rational_ends e,
                                                            double h2, double h1) {
    return slut_airlight_scaled(g, fmax(e.weight2 * h2 - e.weight1 * h1, 0.0) / g.sin_gamma);
}

#ifndef SLUT_SHADER /* the generator's: double only */
/* Ĥ at the node with unit coordinates (x_m, x_t), by slut_w_gs_quadrature (refine: 1 for the
 * table, larger for the independent check), with the edges' limits: x_m = 1 (u = ∞) is 1,
 * x_t = 1 (t = ∞) is e^m E_2(m)·(1 + m). */
SLUT_FN double slut_airlight_rational_node(double x_m, double x_t, double refine) {
    if (x_m >= 1.0) return 1.0;
    double xx = x_m * x_m;
    double m = SLUT_AIRLIGHT_RATIONAL_M_SCALE * xx / (1.0 - xx);
    if (x_t >= 1.0) return slut_exp_expint(2, m) * (1.0 + m);
    double t = x_t / (1.0 - x_t);
    double u = m / (1.0 + t);
    double w = atan2(1.0, t); /* arccot t = π/2 − v */
    return slut_w_gs_quadrature(u, w, refine) * (t + SLUT_AIRLIGHT_RATIONAL_TWO_OVER_PI + u * (1.0 + t * t));
}
#endif /* !SLUT_SHADER */

#endif /* SLUT_AIRLIGHT_RATIONAL_H */
