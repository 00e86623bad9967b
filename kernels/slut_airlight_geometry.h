/* scatterlut — the geometry of the airlight radiance (kernels/slut_airlight.h), written once:
 * everything the radiance needs from (σ_s, σ_a, I0, D, γ, s), the near end (from the half angle
 * γ/2 or from sin γ and cos γ), its scale e^{−σ_t D} and the far end. The notation is
 * kernels/slut_airlight.h's: u = σ_t D sin γ, w2 = π/2 − γ/2, w1 = ½ atan2(D sin γ, s − D cos γ),
 * Δ = s + d(s) − D.
 *
 * Compiled wherever kernels/slut_airlight.h is (it includes this header): OpenCL C, C++, and
 * GLSL/HLSL in float (the `#ifndef SLUT_SHADER` blocks left out).
 */
#ifndef SLUT_AIRLIGHT_GEOMETRY_H
#define SLUT_AIRLIGHT_GEOMETRY_H

#include "slut_compat.h"

/* ------------------------------------------------------------- airlight geometry */

/* Everything the radiance needs from (σ_s, σ_a, I0, D, γ, s), computed from the half
 * angle γ/2 without cancellation (so a caller holding γ gets w2 = π/2 − γ/2 exactly, and a
 * caller holding direction vectors passes sin γ and cos γ exactly).
 * kind: 0 finite (use the fields), 1 zero radiance, 2 divergent (the ray passes
 * through the light: γ = 0 and s ≥ D).
 * The three angles of the geometry come from their tangents by the half-angle formula
 * tan(φ/2) = sin φ/(1 + cos φ) = (1 − cos φ)/sin φ (the first for cos φ ≥ 0, the second
 * below: no cancellation either way), so each costs one atan, not an atan2:
 *   w1 = ½ atan2(D sin γ, x),  x = s − D cos γ:  tan w1 = D sin γ/(d + x) = (d − x)/(D sin γ);
 *   dv = ½ atan2(s sin γ, y),  y = D − s cos γ:  tan dv = s sin γ/(d + y) = (d − y)/(s sin γ);
 * with d = d(s) = √(x² + D² sin² γ) = √(y² + s² sin² γ). a1 = u·cot w1 = σ_t (x + d), written
 * σ_t D² sin² γ/(d − x) for x < 0. */
SLUT_STRUCT_BEGIN(slut_airlight_geometry)
    int kind;
    double scale;      /* σ_s/(4π)·I0·2e^{−σ_t D}/D (slut_airlight_set_scale)               */
    double log_scale;  /* ln scale, set only where scale is not a normal double (0, subnormal or
                          +∞ by overflow): slut_airlight_scaled multiplies in logarithms there */
    double scale_unattenuated; /* σ_s/(4π)·I0·2/D: scale = scale_unattenuated·e^{−optical_distance} */
    double log_scale_unattenuated; /* ln scale_unattenuated, set only where that is not a normal double */
    double optical_distance;   /* σ_t D                                                    */
    double sin_gamma;  /* sin γ, ≥ SLUT_TINY (exact 0 is nudged; the limits below are finite) */
    double sin_half;   /* sin(γ/2) = cos w2                                                 */
    double cos_half;   /* cos(γ/2) = sin w2                                                 */
    double u;          /* σ_t D sin γ                                                      */
    double w2, a2;     /* π/2 − γ/2 and u·cot w2 = σ_t D (1 − cos γ): viewer end           */
    double w1, a1;     /* ½ atan2(D sin γ, s − D cos γ) and u·cot w1 = σ_t (s + d(s) − D cos γ):
                          the far end                                                       */
    double far_attenuation; /* e^{−σ_t Δ}, Δ = s + d(s) − D ≥ 0                          */
    double c;          /* 2σ_t D sin(γ/2): exponent scale of the θ-integrand                */
    double dv;         /* w2 − w1 = ½ atan2(s sin γ, D − s cos γ): half the angle the ray
                          segment subtends at the light (the full setups set it;
                          slut_airlight_setup_far_end alone leaves −1: slut_airlight_dv)   */
    double tan_dv;     /* tan dv (+∞ for an infinite ray at γ = 0: never used there)        */
    double tan_w1;     /* tan w1 (0 for an infinite ray)                                   */
    double optical_delta; /* σ_t Δ (+∞ for an infinite ray)                                */
SLUT_STRUCT_END(slut_airlight_geometry);

/* From sin(γ/2), cos(γ/2) and w2 = π/2 − γ/2 (all three given: a caller with γ computes
 * w2 exactly, one with sin γ and cos γ derives them below): everything but the far end's
 * angles w1, dv and its attenuation, which take an atan, an atan and an exp
 * (slut_airlight_setup_far_end; the table radiance needs them only where it samples). */
/* slut_airlight_setup_near_end_unscaled leaves scale (its exp) to the caller: the runtime
 * folds e^{−σ_t D} into the exponentials it evaluates anyway (tables/src/airlight.cpp,
 * airlight_avx2.cpp, airlight_batch.cpp). */
/* Its formulas of the triangle viewer–light–far end, as lane-generic expressions (as
 * SLUT_AIRLIGHT_THETA_FITS_ONE_PANEL, slut_airlight_theta.h): the runtime's vector paths
 * evaluate them on 4-lane vectors (tables/src/airlight_near_end.hpp, near_end). sh, ch =
 * sin(γ/2), cos(γ/2); s, D in m.
 *   SLUT_AIRLIGHT_COS_GAMMA:     cos γ = (ch − sh)(ch + sh), accurate where γ → π/2 too;
 *   SLUT_AIRLIGHT_FAR_DISTANCE2: d² = (s − D)² + 4 s D sh², the far end's squared distance
 *                                from the light (moderate lengths: no square under- or overflows);
 *   SLUT_AIRLIGHT_DELTA:         Δ = s + d − D as s + (s² − 2 s D cos γ)/(d + D), no
 *                                cancellation (moderate lengths).
 * One line each: GLSL before 4.20 has no line continuation. */
#define SLUT_AIRLIGHT_COS_GAMMA(sh, ch) (((ch) - (sh)) * ((ch) + (sh)))
#define SLUT_AIRLIGHT_FAR_DISTANCE2(s, D, sh) (((s) - (D)) * ((s) - (D)) + 4.0 * (s) * (D) * (sh) * (sh))
#define SLUT_AIRLIGHT_DELTA(s, D, cos_gamma, d_far) ((s) + ((s) * (s) - 2.0 * (s) * (D) * (cos_gamma)) / ((d_far) + (D)))
SLUT_FN slut_airlight_geometry slut_airlight_setup_near_end_unscaled(double sigma_s, double sigma_a, double intensity,
                                                                     double distance, double sin_half, double cos_half,
                                                                     double w2, double length) {
    slut_airlight_geometry g;
    double sigma_t = sigma_s + sigma_a;
    double D = distance, s = length;
    g.kind = 0;
    if (!(sigma_s > 0.0) || !(intensity > 0.0) || !(s > 0.0)) { g.kind = 1; return g; }
    if (!(sin_half > 0.0) && s >= D) { g.kind = 2; return g; }
    /* σ_t D ≥ SLUT_INFINITE_ABOVE: e^{−σ_t D} is 0 against any finite factor (the limit, not an underflow
     * artefact), and c, u would overflow into ∞·0 in the integrands. */
    if (!(sigma_t * D < SLUT_INFINITE_ABOVE)) { g.kind = 1; return g; }
    double sg = fmax(2.0 * sin_half * cos_half, SLUT_TINY);
    double cos_gamma = SLUT_AIRLIGHT_COS_GAMMA(sin_half, cos_half);
    g.sin_gamma = sg;
    g.sin_half = sin_half;
    g.cos_half = cos_half;
    g.scale_unattenuated = sigma_s * SLUT_INV_4PI * intensity * 2.0 / D;
    g.log_scale_unattenuated = 0.0;
    /* σ_s·I0/D beyond range: */
    if (!(g.scale_unattenuated >= SLUT_REAL_MIN_NORMAL && g.scale_unattenuated <= SLUT_REAL_MAX))
        g.log_scale_unattenuated = log(sigma_s) + log(SLUT_INV_4PI * 2.0) + log(intensity) - log(D);
    g.optical_distance = sigma_t * D;
    g.u = sigma_t * D * sg;
    g.w2 = w2;
    g.a2 = sigma_t * D * (2.0 * sin_half * sin_half);
    g.c = 2.0 * sigma_t * D * sin_half;
    if (!SLUT_ISFINITE(s)) { /* an infinite ray: the far end is at ξ = π/2 */
        g.tan_w1 = 0.0;
        g.a1 = SLUT_HUGE_VAL;
        g.optical_delta = SLUT_HUGE_VAL;
        g.tan_dv = cos_half / sin_half;
        return g;
    }
    /* d(s)² = (s − D)² + 4sD sin²(γ/2); Δ = s + d − D = s + s(s − 2D cos γ)/(d + D). Lengths
     * beyond [SLUT_SQUARABLE_MIN, SLUT_SQUARABLE_MAX] (double: 1e∓150) would under- or overflow
     * in the squares: there d is computed in
     * units of max(s, D) and Δ's quotient without s² (same value, other rounding). */
    double m = fmax(s, D);
    int moderate = (m >= SLUT_SQUARABLE_MIN && m <= SLUT_SQUARABLE_MAX) ? 1 : 0;
    double d_far = (moderate != 0) ? sqrt(SLUT_AIRLIGHT_FAR_DISTANCE2(s, D, sin_half))
                            : m * sqrt(((s - D) / m) * ((s - D) / m) + 4.0 * (s / m) * (D / m) * sin_half * sin_half);
    double x = s - D * cos_gamma, ds = D * sg;
    double y = D - s * cos_gamma, ss = s * sg;
    g.tan_w1 = (x >= 0.0) ? ds / (d_far + x) : (d_far - x) / ds;
    g.a1 = sigma_t * ((x >= 0.0) ? x + d_far : ds * (ds / (d_far - x)));
    g.tan_dv = (y >= 0.0) ? ss / (d_far + y) : (d_far - y) / ss;
    g.optical_delta = sigma_t * fmax((moderate != 0) ? SLUT_AIRLIGHT_DELTA(s, D, cos_gamma, d_far)
                                               : s + s * ((s - 2.0 * D * cos_gamma) / (d_far + D)),
                                      0.0);
    return g;
}

/* scale = scale_unattenuated·e^{−σ_t D}, and its logarithm where the product is not a normal
 * double (σ_s·I0 overflowing, e^{−σ_t D} underflowing): slut_airlight_scaled then multiplies
 * in logarithms and still gives the limit. */
SLUT_FN slut_airlight_geometry slut_airlight_set_scale(slut_airlight_geometry g) {
    if (g.kind != 0) return g;
    g.scale = g.scale_unattenuated * exp(-g.optical_distance);
    g.log_scale = 0.0;
    if (!(g.scale >= SLUT_REAL_MIN_NORMAL && g.scale <= SLUT_REAL_MAX)) /* under- or overflowed */
        g.log_scale = ((g.log_scale_unattenuated != 0.0) ? g.log_scale_unattenuated : log(g.scale_unattenuated)) -
                       g.optical_distance;
    return g;
}

#ifndef SLUT_SHADER /* the runtime's fast paths (double ranges) */
/* Where a caller may form scale·ratio as plain products with e^{−σ_t D} folded into its own
 * exponentials (the runtime's fast paths, tables/src/airlight.cpp): σ_s·I0·2/(4πD) within
 * [1e-100, 1e100], σ_t D ≤ 300 and D, s within [1e-100, 1e100] (s = ∞ allowed) keep every
 * factor and product a normal double. Elsewhere slut_airlight_set_scale and
 * slut_airlight_scaled (logarithms) serve. */
SLUT_FN int slut_airlight_scale_is_plain(slut_airlight_geometry g, double distance, double length) {
    return g.scale_unattenuated >= 1e-100 && g.scale_unattenuated <= 1e100 && g.optical_distance <= 300.0 &&
           distance >= 1e-100 && distance <= 1e100 && length >= 1e-100 &&
           (length <= 1e100 || length > SLUT_INFINITE_ABOVE);
}
#endif /* !SLUT_SHADER */

SLUT_FN slut_airlight_geometry slut_airlight_setup_near_end(double sigma_s, double sigma_a, double intensity,
                                                            double distance, double sin_half, double cos_half,
                                                            double w2, double length) {
    return slut_airlight_set_scale(slut_airlight_setup_near_end_unscaled(sigma_s, sigma_a, intensity, distance,
                                                                         sin_half, cos_half, w2, length));
}

/* w1 and e^{−σ_t Δ} from tan w1 and σ_t Δ (slut_airlight_setup_near_end); dv is left to
 * the callers that integrate (slut_airlight_setup_half_angle; slut_airlight_from_gs computes
 * it where it falls back to the θ-integral). */
SLUT_FN slut_airlight_geometry slut_airlight_setup_far_end(slut_airlight_geometry g) {
    if (g.kind != 0) return g;
    if (!SLUT_ISFINITE(g.optical_delta)) { /* an infinite ray */
        g.w1 = 0.0;
        g.dv = g.w2;
        g.far_attenuation = 0.0;
        return g;
    }
    g.w1 = atan(g.tan_w1);
    g.dv = -1.0; /* not computed: atan(tan_dv) */
    g.far_attenuation = exp(-g.optical_delta);
    return g;
}

/* dv = w2 − w1, the θ-integral's length (from tan dv; w2 for an infinite ray). */
SLUT_FN double slut_airlight_dv(slut_airlight_geometry g) {
    return SLUT_ISFINITE(g.optical_delta) ? atan(g.tan_dv) : g.w2;
}

/* The far end and dv: what slut_airlight_setup_near_end leaves, for the exact radiance. */
SLUT_FN slut_airlight_geometry slut_airlight_setup_far_end_and_dv(slut_airlight_geometry g) {
    slut_airlight_geometry both = slut_airlight_setup_far_end(g);
    if (both.kind == 0) both.dv = slut_airlight_dv(both);
    return both;
}

SLUT_FN slut_airlight_geometry slut_airlight_setup_half_angle(double sigma_s, double sigma_a, double intensity,
                                                              double distance, double sin_half, double cos_half,
                                                              double w2, double length) {
    return slut_airlight_setup_far_end_and_dv(
        slut_airlight_setup_near_end(sigma_s, sigma_a, intensity, distance, sin_half, cos_half, w2, length));
}

/* From sin γ and cos γ (γ ∈ [0, π]): sin(γ/2) = √((1 − cos γ)/2) and cos(γ/2) = √((1 + cos γ)/2),
 * the one of them whose 1 ∓ cos γ would cancel as sin γ/(2 cos(γ/2)) or sin γ/(2 sin(γ/2))
 * (sin² γ = (1 − cos γ)(1 + cos γ); no square of sin γ, which float would underflow), and
 * w2 = π/2 − γ/2 = ½ atan2(sin γ, −cos γ). The near end alone: the far end as above. */
SLUT_FN slut_airlight_geometry slut_airlight_setup_near_end_gamma(double sigma_s, double sigma_a, double intensity,
                                                                  double distance, double sin_gamma, double cos_gamma,
                                                                  double length) {
    double sg = fmax(sin_gamma, 0.0);
    double sin_half = (cos_gamma > 0.0) ? sg / sqrt(2.0 * (1.0 + cos_gamma)) : sqrt(0.5 * (1.0 - cos_gamma));
    /* Near γ = π, sin γ is floored at SLUT_SQUARABLE_MIN (1e-150; float 1e-18) for cos(γ/2)
     * and w2: never 0 (the limits divide by them, as the half-angle callers' cos(π/2) = 6e-17
     * does) and with a normal square (the θ-rules' decay rate divides by sin² of their pole
     * distance, ≤ w2). sin(γ/2) = 0 at γ = 0 stays exact: it marks the ray through the light. */
    double sg_floored = fmax(sg, SLUT_SQUARABLE_MIN);
    double cos_half = (cos_gamma < 0.0) ? sg_floored / sqrt(2.0 * (1.0 - cos_gamma)) : sqrt(0.5 * (1.0 + cos_gamma));
    return slut_airlight_setup_near_end(sigma_s, sigma_a, intensity, distance, sin_half, cos_half,
                                        0.5 * atan2(sg_floored, -cos_gamma), length);
}

/* Both ends from sin γ and cos γ. */
SLUT_FN slut_airlight_geometry slut_airlight_setup(double sigma_s, double sigma_a, double intensity, double distance,
                                                   double sin_gamma, double cos_gamma, double length) {
    return slut_airlight_setup_far_end_and_dv(
        slut_airlight_setup_near_end_gamma(sigma_s, sigma_a, intensity, distance, sin_gamma, cos_gamma, length));
}

#endif /* SLUT_AIRLIGHT_GEOMETRY_H */
