/* scatterlut — the airlight function of Sun et al. 2005, written once.
 *
 * Compiled as OpenCL C by kernels/airlight_F.cl (table generation) and as C++ by
 * the host (exact quadrature, eval, validation) and by the runtime library
 * (radiance from a table). See docs/AIRLIGHT.md for the derivations in full.
 *
 *   F(u, v) = ∫_0^v exp(−u tan ξ) dξ,            u ≥ 0, 0 ≤ v ≤ π/2
 *   G(u, v) = ∫_v^{π/2} exp(−u tan ξ) dξ          (the tail; F(u,v) + G(u,v) = F(u,π/2))
 *
 * The table stores the scaled tail, bounded in (0, 1] and free of the e^{−u tan v}
 * dynamic range, as a function of u and w = π/2 − v (w carries full precision where v
 * approaches π/2):
 *
 *   G̃(u, w) = e^{u cot w} · G(u, π/2 − w) / w
 *           = (1/w) ∫_0^∞ e^{−u y} / (1 + (τ + y)²) dy,      τ = cot w = tan v.
 *
 * Airlight radiance (viewer and point light in the medium; sign convention: γ is the
 * angle between the view direction and the direction FROM THE VIEWER TO THE LIGHT,
 * so the light-to-point distance at ray depth x is d(x)² = x² + D² − 2xD cos γ):
 *
 *   L = σ_s/(4π) · I0 · ∫_0^s e^{−σ_t (x + d(x))} / d(x)² dx
 *     = σ_s/(4π) · I0 · 2 e^{−σ_t D} / (D sin γ) · [w2 G̃(u, w2) − e^{−σ_t Δ} w1 G̃(u, w1)]
 *
 * with u = σ_t D sin γ, w2 = π/2 − γ/2, w1 = ½ atan2(D sin γ, s − D cos γ) and
 * Δ = s + d(s) − D ≥ 0 (the extra light path via the ray's far end). Both exponents are
 * light paths, so nothing overflows (Sun's A0 = 2e^{−σ_t D cos γ}/(D sin γ) does).
 *
 * The parts, each included here (and each includable by itself), in the order the GPU
 * snippets concatenate them (SLUT_SHADER_HEADERS, CMakeLists.txt):
 *   slut_airlight_tail.h      G̃ by quadrature and its closed forms (w → 0, large u);
 *   slut_airlight_geometry.h  the geometry from (σ_s, σ_a, I0, D, γ, s): near end, scale, far end;
 *   slut_airlight_theta.h     the θ-integral: the panel rules and the one-panel rule;
 *   this header               the radiance: exact, from two samples of G̃, without extinction;
 *                             F from two tails; which representation serves G̃.
 */
#ifndef SLUT_AIRLIGHT_H
#define SLUT_AIRLIGHT_H

#include "slut_compat.h"
#include "slut_airlight_tail.h"
#include "slut_airlight_geometry.h"
#include "slut_airlight_theta.h"

/* ------------------------------------------- the closed forms engines use instead */

/* ∫_0^s dx/d(x)² (1/m for lengths in m), d(x)² = x² + D² − 2xD cos γ = (x + b)² + h² with
 * b = −D cos γ and h = D sin γ (γ as above: view direction ↔ direction viewer → light):
 *   ∫_0^s dx/((x + b)² + h²) = (atan((s + b)/h) − atan(b/h))/h = Δφ/h,
 *   Δφ = atan2(s·h, D² + s·b)      (the angle the segment subtends at the light),
 * evaluated as (s/den)·atan(s·h/den)/(s·h/den), den = D² + s·b = D (D − s cos γ), while
 * Δφ < π/2 (den > 0): no division by h, so the limit h → 0 is exact there (γ = π:
 * s/(D(s + D)); γ = 0 and s < D: s/(D(D − s))). For den ≤ 0 the angle is ≥ π/2 and
 * (π − atan(s·h/|den|))/h has no cancellation; it is +∞ at h = 0 (γ = 0, s ≥ D: the ray
 * passes through the light). s = +∞: Δφ = atan2(h, b). Never NaN for D > 0, s ≥ 0. */
SLUT_FN double slut_airlight_inv_square_integral(double distance, double sin_gamma, double cos_gamma, double length) {
    double D = distance, s = length, h = D * fmax(sin_gamma, 0.0), b = -D * cos_gamma;
    double x, den;
    if (!(s > 0.0)) return 0.0;
    if (s > SLUT_INFINITE_ABOVE) {
        if (b > 0.0) { x = h / b; return ((x == 0.0) ? 1.0 : atan(x) / x) / b; }
        if (!(h > 0.0)) return SLUT_HUGE_VAL;
        if (b == 0.0) return 0.5 * SLUT_PI / h;
        return (SLUT_PI - atan(h / (-b))) / h;
    }
    den = D * (D - s * cos_gamma);
    if (den > 0.0) {
        x = s * h / den;
        return ((x == 0.0) ? 1.0 : atan(x) / x) * (s / den);
    }
    if (!(h > 0.0)) return SLUT_HUGE_VAL;
    if (den == 0.0) return 0.5 * SLUT_PI / h;
    return (SLUT_PI - atan(s * h / (-den))) / h;
}

/* The airlight without extinction (Macklin 2010, "in-scattering of a point light"), the
 * closed form engines evaluate per pixel instead of a table (W/(m²·sr), I0 in W/sr):
 *   L_0 = σ_s/(4π) · I0 · (atan((s + b)/h) − atan(b/h))/h,   b = −D cos γ, h = D sin γ.
 * The approximation: e^{−σ_t (x + d(x))} = 1 in the integrand, i.e. no attenuation on either
 * leg of the light path. Exact as σ_t → 0 and an overestimate otherwise: with
 * D ≤ x + d(x) ≤ 2x + D, the exact L satisfies L_0·e^{−σ_t (2s + D)} ≤ L ≤ L_0·e^{−σ_t D}, so
 * the relative error (L_0 − L)/L is at most e^{σ_t (2s + D)} − 1 (without bound for s = ∞). 0 for σ_s = 0, I0 = 0 or s = 0;
 * +∞ where the ray passes through the light. */
SLUT_FN double slut_airlight_no_extinction(double sigma_s, double intensity, double distance, double sin_gamma,
                                           double cos_gamma, double length) {
    if (!(sigma_s > 0.0) || !(intensity > 0.0) || !(length > 0.0)) return 0.0;
    return sigma_s * SLUT_INV_4PI * intensity * slut_airlight_inv_square_integral(distance, sin_gamma, cos_gamma, length);
}

/* The same times e^{−σ_t D}, σ_t = σ_s + σ_a (the attenuation of the direct viewer–light
 * path, applied to every point of the ray: a common engine fudge). Since x + d(x) ≥ D
 * (triangle inequality) it bounds the exact radiance from above, L ≤ L_0·e^{−σ_t D} ≤ L_0,
 * and equals it as σ_t → 0; it misses the extra path x + d(x) − D, so its error grows with
 * σ_t times the segment's length and its distance from the light. */
SLUT_FN double slut_airlight_no_extinction_attenuated(double sigma_s, double sigma_a, double intensity,
                                                      double distance, double sin_gamma, double cos_gamma,
                                                      double length) {
    double L0 = slut_airlight_no_extinction(sigma_s, intensity, distance, sin_gamma, cos_gamma, length);
    if (!(L0 > 0.0) || !SLUT_ISFINITE(L0)) return L0; /* 0, or +∞ through the light (never ∞·0) */
    return L0 * exp(-(sigma_s + sigma_a) * distance);
}

/* scale·ratio (ratio ≥ 0): a product where scale is a normal double, else in logarithms,
 * so that a scale beyond the double range (σ_s·I0 overflowing, e^{−σ_t D} underflowing)
 * still gives the limit: 0, a finite value, or +∞ where the radiance itself overflows. */
SLUT_FN double slut_airlight_scaled(slut_airlight_geometry g, double ratio) {
    if (g.scale >= SLUT_REAL_MIN_NORMAL && g.scale <= SLUT_REAL_MAX) return g.scale * ratio;
    if (!(ratio > 0.0)) return 0.0;
    return exp(g.log_scale + log(ratio));
}

/* Exact airlight radiance (W/(m²·sr) for I0 in W/sr, coefficients in 1/m, lengths in m)
 * by the θ-integral: independent of any table, ~1e-13 relative. */
SLUT_FN double slut_airlight_exact(slut_airlight_geometry g) {
    if (g.kind == 1) return 0.0;
    if (g.kind == 2) return SLUT_HUGE_VAL;
    return slut_airlight_scaled(g, slut_airlight_theta_integral(g.c, g.w2, g.dv) / g.sin_gamma);
}

/* Radiance from two samples of G̃ (at the viewer end and at the far end), falling back to
 * the θ-integral where the difference would cancel (far-end term > half the viewer-end
 * term: a short segment, whose integrand varies by at most a factor e and which a few
 * Gauss panels integrate exactly; 8 points per panel, ~1e-13, as the samples of G̃ are
 * table values). gs2 = G̃(u, w2), gs1 = G̃(u, w1); gs1 is unused
 * when w1 = 0 (an infinite ray). */
SLUT_FN double slut_airlight_from_gs(slut_airlight_geometry g, double gs2, double gs1) {
    if (g.kind == 1) return 0.0;
    if (g.kind == 2) return SLUT_HUGE_VAL;
    double viewer_term = (g.w2 / g.sin_gamma) * gs2;
    double far_term = (g.w1 > 0.0) ? g.far_attenuation * (g.w1 / g.sin_gamma) * gs1 : 0.0;
    if (far_term <= 0.5 * viewer_term) return slut_airlight_scaled(g, viewer_term - far_term);
    return slut_airlight_scaled(g, slut_airlight_theta_integral_rule(g.c, g.w2, slut_airlight_dv(g), 0) / g.sin_gamma);
}

/* F(u, v) = ∫_0^v e^{−u tan ξ} dξ (Sun et al. 2005) from two tail samples, whole = G(u, 0)
 * and tail = G(u, v): F = whole − tail, except where that difference cancels (tail above
 * half of whole: u·v small, F ≪ G(u, 0), where a table's relative error on G would become
 * an absolute one on F). There F is integrated directly: it is the θ-integral
 * (slut_airlight_theta.h) with w2 = π/2, c = u (c sin θ/sin(π/2 − θ) = u tan θ), 8 points
 * per panel, ~1e-13 relative,
 * for every v down to subnormal ones. tail > whole/2 implies v < π/4 (G(u, v) ≤ π/2 − v),
 * so the panels stay ≥ π/4 from the pole at θ = π/2 and there are few of them. */
SLUT_FN double slut_F_from_tails(double u, double v, double whole, double tail) {
    if (!(v > 0.0)) return 0.0;
    if (tail <= 0.5 * whole) return whole - tail;
    return slut_airlight_theta_integral_rule(u, SLUT_PIO2_HI, v, 0);
}

/* Which representation serves G̃(u, w) for a table covering u ≤ u_max, w ≥ w_min:
 * SLUT_GS_TABLE (interpolate), SLUT_GS_LARGE_U (slut_gs_large_u), SLUT_GS_SMALL_W
 * (slut_gs_small_w). Never a clamp: beyond the table the asymptotic forms are exact
 * to the table's own accuracy (see their error bounds in slut_airlight_tail.h). */
#define SLUT_GS_TABLE 0
#define SLUT_GS_LARGE_U 1
#define SLUT_GS_SMALL_W 2
SLUT_FN int slut_gs_regime(double u, double w, double u_max, double w_min) {
    if (u > u_max) return SLUT_GS_LARGE_U;
    if (w < w_min) return SLUT_GS_SMALL_W;
    return SLUT_GS_TABLE;
}

#endif /* SLUT_AIRLIGHT_H */
