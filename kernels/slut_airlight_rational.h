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
 *   x_m = (m/(m + K))^{1/4},  m = u (1 + t)  (K = SLUT_AIRLIGHT_RATIONAL_M_SCALE; the fourth
 *                                           root resolves H's m·ln m term at m → 0, which
 *                                           a square root leaves as the largest error)
 *   x_t = t/(1 + t)
 * Both are rational in the ray's geometry (one divide each and two square roots), so a sample
 * costs one filtered fetch and no exp or log: no warp, no decode, no regime beyond the table.
 * Bilinear interpolation of Ĥ on these axes, max relative error over 200 000 random points
 * (half of them drawn towards the edges): 2.9e-4 at 48², 1.6e-4 at 64², 7.1e-5 at 96²,
 * 4.0e-5 at 128², 9.9e-6 at 256² (the planner measures the planned size's).
 *
 * The radiance from two samples, one per end of the ray, and where their difference would
 * cancel a rule for the short segment: slut_airlight_rational_setup_of below.
 */
#ifndef SLUT_AIRLIGHT_RATIONAL_H
#define SLUT_AIRLIGHT_RATIONAL_H

#include "slut_compat.h"
#include "slut_airlight.h"

/* K of the first axis: m = K at x_m = 2^{−1/4} (measured: K = 4 puts the largest
 * interpolation error inside the square, not at an edge). */
#define SLUT_AIRLIGHT_RATIONAL_M_SCALE 4.0
#define SLUT_AIRLIGHT_RATIONAL_TWO_OVER_PI 0.636619772367581343

/* The unit coordinates of an end of the ray (lane-generic: plain arithmetic). m is clamped
 * below SLUT_INFINITE_ABOVE so that m/(m + K) is 1, not ∞/∞, for an infinite far end. */
SLUT_FN double slut_airlight_rational_x_m(double m) {
    double mc = fmin(m, SLUT_INFINITE_ABOVE);
    return sqrt(sqrt(mc / (mc + SLUT_AIRLIGHT_RATIONAL_M_SCALE)));
}

/* ------------------------------------------------------- the radiance, set up algebraically
 *
 * Both ends of the ray seen from the light: the perpendicular distance h = D sin γ (the same
 * for both) and q = r (1 − cos β) at each end (r its distance from the light, β the angle
 * between the view direction and the direction from that end to the light), so that
 * q² + h² = 2 r q. Then t = tan(β/2) = q/h, u = σ_t h, a = u t = σ_t q, m = σ_t (h + q),
 * x_t = q/(h + q), and the end's term H(u, t)/(r sin β) = Ĥ/(q (1 + 2σ_t r) + (2/π) h):
 *   viewer end: r = D,  q2 = D (1 − cos γ)  (as D sin²γ/(1 + cos γ) for cos γ > 0);
 *   far end:    r = d = √(x² + h²), x = s − D cos γ,  q1 = d + x  (as h²/(d − x) for x < 0);
 *   L = σ_s I0/(2π) · e^{−σ_t D} · [Ĥ2/den2 − e^{−σ_t Δ} Ĥ1/den1],  den = q (1 + 2σ_t r) + (2/π) h,
 * Δ = s + d − D (SLUT_AIRLIGHT_DELTA), the far term 0 for an infinite ray. One square root, two
 * exponentials, no angle and no branch: the tiers' whole set-up.
 *
 * Where the difference would cancel (the far term above (1 − 1/G) of the viewer's, G =
 * SLUT_AIRLIGHT_RATIONAL_GAIN) the segment is short: it subtends 2 dv ≤ 2 w2/(G − 1) at the light
 * (the θ-integrand decreases, so the tail beyond the segment is at least (w2 − dv)/dv times the
 * segment's integral) and decays by at most λ dv ≲ 0.15 over it (λ = 2σ_t D tan(γ/2) the decay
 * rate at its start: a segment with λ dv = x holds ≥ (1 − e^{−x}) of a tail ≤ 1/λ). There its
 * θ-integral in t = tan θ (slut_airlight_theta_integral_one_panel's integrand
 * g(t) = e^{−E(t)}/(1 + t²), E = c t/(sin w2 − t cos w2)) is the trapezoid rule with its end
 * correction (Euler–Maclaurin), from values the set-up has anyway:
 *   ∫_0^T g ≈ T/2 (g(0) + g(T)) + T²/12 (g'(0) − g'(T)),  error T⁵ max|g⁗|/720,
 * g(0) = 1, g(T) = e^{−σ_t Δ}/(1 + T²) (E(T) = σ_t Δ), g'(0) = −λ, T g'(T) = −g(T) (T E'(T) + 2T²/(1 + T²)),
 * T E'(T) = λ T/(1 − T tan(γ/2))², T = tan dv = s sin γ/(d + y), y = D − s cos γ > 0 there
 * (2 dv < π/2). In units of 1/h: T/h = s/(D (d + y)), λ T = 2σ_t D · (T/h) q2: no division by h,
 * so the ray along the line towards the light (h = 0, s < D) gets its closed form
 * σ_s I0 e^{−σ_t D} s/(4π D (D − s)) from the same expression.
 *
 * It serves lengths up to SLUT_SQUARABLE_MAX (s beyond is an infinite ray) and D within
 * [SLUT_SQUARABLE_MIN, SLUT_SQUARABLE_MAX]. */
#define SLUT_AIRLIGHT_RATIONAL_GAIN 8.0

SLUT_STRUCT_BEGIN(slut_airlight_rational_setup)
    int kind;           /* 0: the samples or the segment rule; 1: zero radiance; 2: +∞ (through the light) */
    double scale;       /* σ_s I0 e^{−σ_t D}/(2π), W/(m·sr)                                              */
    double x_m2, x_t2;  /* the viewer end's unit coordinates                                             */
    double weight2;     /* 1/den2, 1/m                                                                    */
    double x_m1, x_t1;  /* the far end's                                                                  */
    double weight1;     /* e^{−σ_t Δ}/den1, 1/m (0 for an infinite ray)                                   */
    double segment;     /* the segment's θ-integral over h by the corrected trapezoid, 1/m (where it is short) */
SLUT_STRUCT_END(slut_airlight_rational_setup);

SLUT_FN slut_airlight_rational_setup slut_airlight_rational_setup_of(double sigma_s, double sigma_a, double intensity,
                                                                   double distance, double sin_gamma,
                                                                   double cos_gamma, double length) {
    slut_airlight_rational_setup r;
    double sigma_t = sigma_s + sigma_a;
    double D = fmin(fmax(distance, SLUT_SQUARABLE_MIN), SLUT_SQUARABLE_MAX);
    double s = fmin(length, SLUT_INFINITE_ABOVE);
    double sg = fmax(sin_gamma, 0.0);
    int finite_ray = (s <= SLUT_SQUARABLE_MAX) ? 1 : 0;
    r.kind = (!(sigma_s > 0.0) || !(intensity > 0.0) || !(s > 0.0)) ? 1 : 0;
    if (r.kind == 0 && !(sg > 0.0) && cos_gamma > 0.0 && s >= D) r.kind = 2;
    /* I0 e^{−σ_t D} first: a σ_s I0 beyond the range never meets an e^{−σ_t D} that underflowed (∞·0) */
    r.scale = (sigma_s * (0.5 / SLUT_PI)) * (intensity * exp(-sigma_t * D));
    double h = D * fmax(sg, SLUT_TINY);
    double q2 = D * ((cos_gamma > 0.0) ? sg * (sg / (1.0 + cos_gamma)) : 1.0 - cos_gamma);
    r.x_m2 = slut_airlight_rational_x_m(sigma_t * (h + q2));
    r.x_t2 = q2 / (h + q2);
    r.weight2 = 1.0 / (q2 * (1.0 + 2.0 * sigma_t * D) + SLUT_AIRLIGHT_RATIONAL_TWO_OVER_PI * h);
    double sf = (finite_ray != 0) ? s : 0.0; /* the far end's arithmetic on a finite stand-in */
    double x = sf - D * cos_gamma, y = D - sf * cos_gamma;
    double d = sqrt(x * x + h * h);
    double q1 = (x >= 0.0) ? d + x : h * (h / (d - x));
    double far_attenuation = exp(-sigma_t * fmax(SLUT_AIRLIGHT_DELTA(sf, D, cos_gamma, d), 0.0));
    r.x_m1 = (finite_ray != 0) ? slut_airlight_rational_x_m(sigma_t * (h + q1)) : 1.0;
    r.x_t1 = (finite_ray != 0) ? q1 / (h + q1) : 1.0;
    r.weight1 = (finite_ray != 0)
                    ? far_attenuation / (q1 * (1.0 + 2.0 * sigma_t * d) + SLUT_AIRLIGHT_RATIONAL_TWO_OVER_PI * h)
                    : 0.0;
    /* The short segment's corrected trapezoid (y > 0 wherever it is used). */
    double t_over_h = sf / (D * (d + fabs(y)));
    double t = t_over_h * h;
    double lambda_t = 2.0 * sigma_t * D * t_over_h * q2;
    double t_tan_half = t_over_h * q2;
    double g_end = far_attenuation / (1.0 + t * t);
    double t_g_end_slope = -g_end * (lambda_t / ((1.0 - t_tan_half) * (1.0 - t_tan_half)) + 2.0 * t * t / (1.0 + t * t));
    r.segment = t_over_h * (0.5 * (1.0 + g_end) + (-lambda_t - t_g_end_slope) / 12.0);
    return r;
}

/* The radiance from the two stored samples Ĥ(x_m2, x_t2) and Ĥ(x_m1, x_t1): their difference,
 * or the segment's rule where that would cancel (the far term above (1 − 1/G) of the
 * viewer's, or not a number). W/(m²·sr); never negative, never NaN. */
SLUT_FN double slut_airlight_rational_radiance(slut_airlight_rational_setup r, double h2, double h1) {
    if (r.kind != 0) return (r.kind == 2) ? SLUT_HUGE_VAL : 0.0;
    double viewer = r.weight2 * h2, far = r.weight1 * h1;
    double ratio = (far <= (1.0 - 1.0 / SLUT_AIRLIGHT_RATIONAL_GAIN) * viewer) ? viewer - far : r.segment;
    return r.scale * fmax(ratio, 0.0);
}

#ifndef SLUT_SHADER /* the generator's: double only */
/* Ĥ at the node with unit coordinates (x_m, x_t), by slut_w_gs_quadrature (refine: 1 for the
 * table, larger for the independent check), with the edges' limits: x_m = 1 (u = ∞) is 1,
 * x_t = 1 (t = ∞) is e^m E_2(m)·(1 + m). */
SLUT_FN double slut_airlight_rational_node(double x_m, double x_t, double refine) {
    if (x_m >= 1.0) return 1.0;
    double x4 = (x_m * x_m) * (x_m * x_m);
    double m = SLUT_AIRLIGHT_RATIONAL_M_SCALE * x4 / (1.0 - x4);
    if (x_t >= 1.0) return slut_exp_expint(2, m) * (1.0 + m);
    double t = x_t / (1.0 - x_t);
    double u = m / (1.0 + t);
    double w = atan2(1.0, t); /* arccot t = π/2 − v */
    return slut_w_gs_quadrature(u, w, refine) * (t + SLUT_AIRLIGHT_RATIONAL_TWO_OVER_PI + u * (1.0 + t * t));
}
#endif /* !SLUT_SHADER */

#endif /* SLUT_AIRLIGHT_RATIONAL_H */
