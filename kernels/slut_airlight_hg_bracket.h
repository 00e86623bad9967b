/* scatterlut — the anisotropic airlight's bracket B_g (kernels/slut_airlight_hg.h), written once:
 * the half angles, the segment in the scaled variable, the bracket by quadrature and the exact
 * radiance from it, and the closed forms without a table (the thin medium: the phase's mean
 * over the arc; the distant light).
 *
 * Compiled wherever kernels/slut_airlight_hg.h is (it includes this header): C++, OpenCL C,
 * and GLSL/HLSL in float.
 */
#ifndef SLUT_AIRLIGHT_HG_BRACKET_H
#define SLUT_AIRLIGHT_HG_BRACKET_H

#include "slut_compat.h"
#include "slut_phase.h"
#include "slut_airlight_hg_integral.h" /* slut_hg_air_integral */
#include "slut_phase_arc.h"            /* the thin-medium form: the phase's mean over the ray's arc */

/* ------------------------------------------------------------ exact radiance */

/* sin(γ/2) and cos(γ/2) from sin γ ≥ 0 and cos γ without cancellation on either side
 * (as slut_airlight_setup: sin²γ = (1 − cos γ)(1 + cos γ)). */
SLUT_STRUCT_BEGIN(slut_hg_half_angle)
    double sin_half;
    double cos_half;
SLUT_STRUCT_END(slut_hg_half_angle);

SLUT_FN slut_hg_half_angle slut_hg_half_angles_of(double sin_gamma, double cos_gamma) {
    slut_hg_half_angle h;
    double sg = fmax(sin_gamma, 0.0);
    double one_minus_cos = (cos_gamma > 0.0) ? sg * sg / (1.0 + cos_gamma) : 1.0 - cos_gamma;
    double one_plus_cos = (cos_gamma < 0.0) ? sg * sg / (1.0 - cos_gamma) : 1.0 + cos_gamma;
    h.sin_half = sqrt(0.5 * one_minus_cos);
    h.cos_half = sqrt(0.5 * one_plus_cos);
    return h;
}

#ifndef SLUT_SHADER
SLUT_FN void slut_hg_half_angles(double sin_gamma, double cos_gamma, double *sin_half, double *cos_half) {
    slut_hg_half_angle h = slut_hg_half_angles_of(sin_gamma, cos_gamma);
    *sin_half = h.sin_half;
    *cos_half = h.cos_half;
}
#endif /* !SLUT_SHADER */

/* The dimensionless bracket of the anisotropic airlight,
 *   B_g = (1/sin γ) ∫_{v2}^{v1} ψ_g(2ξ) e^{−u (tan ξ − tan v2)} dξ,
 *   L = σ_s/(4π)·I0·(2/D)·e^{−σ_t D}·B_g,
 * from σ_t D (optical_distance), sin(γ/2), cos(γ/2) and s/D (> 1e300: an infinite ray).
 *
 * In t = tan ξ the segment runs from τ2 = tan(γ/2) to τ1 = τ2 + Δ/h, Δ = s + d(s) − D,
 * h = D sin γ; with the scaling λ = max(1, τ2) of the file comment (λ sin γ = μ):
 *   γ ≤ π/2: λ = 1,  τ̂ = tan(γ/2), ε̂ = 1,           μ = sin γ = 2 sin(γ/2) cos(γ/2);
 *   γ > π/2: λ = τ2, τ̂ = 1,        ε̂ = cot(γ/2),    μ = 1 − cos γ = 2 sin²(γ/2);
 *   û = σ_t D μ,  Z = Δ/(D μ),  B_g = K_g(û, τ̂, ε̂, Z)/μ.
 * Δ without cancellation (d' = d(s)/D, s' = s/D): s' ≥ 1: Δ/D = (s' − 1) + d'; s' < 1:
 * Δ/D = 4 s' sin²(γ/2)/(d' + 1 − s') (d'² − (1 − s')² = 4s' sin²(γ/2)), so that
 *   Z = 2s' tan(γ/2)/(d' + 1 − s')   (γ ≤ π/2),   Z = 2s'/(d' + 1 − s')   (γ > π/2),
 * finite and exact as γ → 0 (where Δ and h vanish together) and as γ → π (ε̂ → 0: the
 * integrand stays finite, nothing divides by sin γ). γ = 0 exactly: the light path is D
 * from every point and θ = 0, so B_g = ψ_g(0)·s'/(2(1 − s')) for s' < 1 and +∞ for s' ≥ 1
 * (the ray reaches the light); sin(γ/2) < 1e-150 with s' < 1 takes that limit too (relative
 * difference O(γ²)). Every term positive: relative accuracy ~1e-14. */
SLUT_STRUCT_BEGIN(slut_hg_airlight_segment)
    int limit;      /* 1: no segment to integrate, the bracket is `value` (s = 0; γ → 0)    */
    double value;   /* the bracket where limit = 1                                        */
    double tau_hat; /* τ̂                                                                  */
    double eps_hat; /* ε̂                                                                  */
    double mu;      /* μ = λ sin γ                                                        */
    double z_end;   /* Z = Δ/(D μ) (+∞: an infinite ray)                                  */
SLUT_STRUCT_END(slut_hg_airlight_segment);

/* The segment of the bracket in the scaled variable (above), or its limit value. */
SLUT_FN slut_hg_airlight_segment slut_hg_airlight_segment_of(double sin_half, double cos_half, double s_over_D,
                                                             double g) {
    slut_hg_airlight_segment seg;
    seg.limit = 1;
    seg.value = 0.0;
    seg.tau_hat = 0.0;
    seg.eps_hat = 1.0;
    seg.mu = 1.0;
    seg.z_end = 0.0;
    double sp = s_over_D;
    if (!(sp > 0.0)) return seg;
    int infinite = !(sp <= SLUT_INFINITE_ABOVE) ? 1 : 0;
    if (!(sin_half >= SLUT_SQUARABLE_MIN)) {
        if (infinite != 0 || sp >= 1.0) {
            if (!(sin_half > 0.0)) {
                seg.value = SLUT_HUGE_VAL;
                return seg;
            }
        } else {
            seg.value = slut_hg_psi_forward(g) * sp / (2.0 * (1.0 - sp));
            return seg;
        }
    }
    double sh2 = sin_half * sin_half;
    int narrow = (cos_half >= sin_half) ? 1 : 0;
    seg.limit = 0;
    seg.tau_hat = (narrow != 0) ? sin_half / cos_half : 1.0;
    seg.eps_hat = (narrow != 0) ? 1.0 : cos_half / sin_half;
    seg.mu = (narrow != 0) ? 2.0 * sin_half * cos_half : 2.0 * sh2;
    if (infinite != 0) {
        seg.z_end = SLUT_HUGE_VAL;
        return seg;
    }
    double d_far = (sp > 1.0) ? sp * sqrt((1.0 - 1.0 / sp) * (1.0 - 1.0 / sp) + 4.0 * sh2 / sp)
                              : sqrt((1.0 - sp) * (1.0 - sp) + 4.0 * sp * sh2);
    if (sp >= 1.0) seg.z_end = ((sp - 1.0) + d_far) / seg.mu;
    else seg.z_end = 2.0 * sp * seg.tau_hat / (d_far + (1.0 - sp)); /* τ̂ = tan(γ/2) or 1 */
    return seg;
}

SLUT_FN double slut_hg_airlight_bracket(double optical_distance, double sin_half, double cos_half, double s_over_D,
                                        double g, double refine) {
    slut_hg_airlight_segment seg = slut_hg_airlight_segment_of(sin_half, cos_half, s_over_D, g);
    if (seg.limit != 0) return seg.value;
    double K = slut_hg_air_integral(optical_distance * seg.mu, seg.tau_hat, seg.eps_hat, seg.z_end, g, refine);
    return K / seg.mu;
}

/* The radiance from its bracket: σ_s/(4π)·I0·(2/D)·e^{−τ}·B_g, τ = σ_t D the optical distance
 * to the light, W/(m²·sr) for I0 in W/sr, σ_s in 1/m, D in m. 0 for B ≤ 0, +∞ for B = +∞;
 * where σ_s·I0·e^{−τ}/D leaves the working type's normal range the product is formed in
 * logarithms. */
SLUT_FN double slut_hg_airlight_from_bracket_at(double sigma_s, double intensity, double distance,
                                                double optical_distance, double B) {
    if (!(B > 0.0)) return 0.0;
    if (!SLUT_ISFINITE(B)) return SLUT_HUGE_VAL;
    double scale = sigma_s * SLUT_INV_4PI * intensity * 2.0 / distance * exp(-optical_distance);
    if (scale >= SLUT_REAL_MIN_NORMAL && scale <= SLUT_INFINITE_ABOVE) return scale * B;
    return exp(log(sigma_s) + log(SLUT_INV_4PI * 2.0) + log(intensity) - log(distance) - optical_distance + log(B));
}

/* The same with τ = σ_t·D formed here (σ_t in 1/m). */
SLUT_FN double slut_hg_airlight_from_bracket(double sigma_s, double sigma_t, double intensity, double distance,
                                             double B) {
    return slut_hg_airlight_from_bracket_at(sigma_s, intensity, distance, sigma_t * distance, B);
}

/* Exact anisotropic airlight radiance, W/(m²·sr) for I0 in W/sr, coefficients in 1/m,
 * lengths in m (length > 1e300: an infinite ray), γ given by its half angle: sin(γ/2) and
 * cos(γ/2), both ≥ 0 (a caller holding γ itself takes them from γ/2 directly).
 * 0 for σ_s = 0, I0 = 0, s = 0 or σ_t D ≥ 1e300; +∞ where the ray reaches the light; never
 * NaN. Where σ_s·I0·e^{−σ_t D}/D leaves the double range the product is formed in
 * logarithms. refine = 1 is the rule (larger: the finer independent one). (In float, the
 * GPU snippet's: 1e30 for 1e300.) */
SLUT_FN double slut_hg_airlight_radiance_half(double sigma_s, double sigma_a, double intensity, double distance,
                                              double sin_half, double cos_half, double length, double g,
                                              double refine) {
    double sigma_t = sigma_s + sigma_a;
    if (!(sigma_s > 0.0) || !(intensity > 0.0) || !(length > 0.0)) return 0.0;
    if (!(sigma_t * distance < SLUT_INFINITE_ABOVE)) return 0.0;
    double s_over_D = (length > SLUT_INFINITE_ABOVE) ? SLUT_HUGE_VAL : length / distance;
    double B = slut_hg_airlight_bracket(sigma_t * distance, sin_half, cos_half, s_over_D, g, refine);
    return slut_hg_airlight_from_bracket(sigma_s, sigma_t, intensity, distance, B);
}

/* The same with γ given by sin γ ≥ 0 and cos γ (the half angles by slut_hg_half_angles_of). */
SLUT_FN double slut_hg_airlight_radiance(double sigma_s, double sigma_a, double intensity, double distance,
                                         double sin_gamma, double cos_gamma, double length, double g,
                                         double refine) {
    slut_hg_half_angle h = slut_hg_half_angles_of(sin_gamma, cos_gamma);
    return slut_hg_airlight_radiance_half(sigma_s, sigma_a, intensity, distance, h.sin_half, h.cos_half, length, g,
                                          refine);
}

/* ------------------------------------------------------------ closed forms (no table) */

/* The thin-medium bracket (no extinction along either leg: B_g at σ_t = 0), from sin(γ/2),
 * cos(γ/2) and s/D (> 1e300: an infinite ray). Without extinction the isotropic bracket is
 * the arc the ray subtends at the light over sin γ, B_0 = (v1 − v2)/sin γ (Sun et al. 2005's
 * F(0, v) = v), and the phase enters as its mean over that arc (kernels/slut_phase_arc.h):
 *   B_g = B_0 · M_g(γ, γ + 2(v1 − v2)),   θ from γ at the viewer to 2v1 at the far end.
 * With the scaling of slut_hg_airlight_bracket (τ̂, ε̂, μ, Z), v1 − v2 = atan2(Z ε̂, ε̂² + τ̂(τ̂ + Z))
 * (an infinite ray: atan2(ε̂, τ̂)) without cancellation, and B_0 = (v1 − v2)/(ε̂ μ) (ε̂ = 0,
 * γ = π: Z/(τ̂(τ̂ + Z))/μ). γ → 0 takes slut_hg_airlight_bracket's limits. The phase's mean is a
 * fixed rule (relative error ≤ 1e-13 in double, measured against the adaptive quadrature:
 * tests/kernels/test_anisotropic.cpp); the bracket is exact for σ_t = 0. */
SLUT_FN double slut_hg_airlight_bracket_thin(double sin_half, double cos_half, double s_over_D, double g) {
    slut_hg_airlight_segment seg = slut_hg_airlight_segment_of(sin_half, cos_half, s_over_D, g);
    if (seg.limit != 0) return seg.value;
    double tau = seg.tau_hat, eps = seg.eps_hat;
    double arc_half; /* v1 − v2 */
    double K0;       /* ∫_0^Z dz/(ε̂² + (τ̂ + z)²) */
    if (seg.z_end > SLUT_INFINITE_ABOVE) {
        arc_half = atan2(eps, tau);
        K0 = (eps > 0.0) ? arc_half / eps : 1.0 / tau;
    } else {
        double den = eps * eps + tau * (tau + seg.z_end);
        arc_half = atan2(seg.z_end * eps, den);
        K0 = (eps > 0.0) ? arc_half / eps : seg.z_end / den;
    }
    double theta0 = 2.0 * atan2(sin_half, cos_half);
    double theta1 = fmin(theta0 + 2.0 * arc_half, SLUT_PI);
    return K0 / seg.mu * slut_hg_psi_arc_mean(g, theta0, theta1);
}

/* The thin-medium airlight with the phase, W/(m²·sr) (arguments as slut_hg_airlight_radiance):
 *   L ≈ σ_s/(4π)·I0·(2/D)·B_g(σ_t = 0)
 * — no extinction along either leg (e^{−σ_t(x + d(x))} → 1), exact as σ_t·(D + s) → 0 and an
 * overestimate otherwise (by e^{σ_t (D + s)} at most). 0 for σ_s = 0, I0 = 0 or s = 0; +∞
 * where the ray reaches the light. */
SLUT_FN double slut_hg_airlight_radiance_thin(double sigma_s, double intensity, double distance, double sin_gamma,
                                              double cos_gamma, double length, double g) {
    if (!(sigma_s > 0.0) || !(intensity > 0.0) || !(length > 0.0)) return 0.0;
    slut_hg_half_angle h = slut_hg_half_angles_of(sin_gamma, cos_gamma);
    double s_over_D = (length > SLUT_INFINITE_ABOVE) ? SLUT_HUGE_VAL : length / distance;
    double B = slut_hg_airlight_bracket_thin(h.sin_half, h.cos_half, s_over_D, g);
    return slut_hg_airlight_from_bracket(sigma_s, 0.0, intensity, distance, B);
}

/* The distant-light airlight with the phase, W/(m²·sr) (arguments as slut_hg_airlight_radiance):
 * every point of the ray taken at the light's distance D and scattering angle γ (the light
 * far beyond the ray, s ≪ D), the light path's length D + x(1 − cos γ) to first order:
 *   L ≈ σ_s/(4π)·ψ_g(γ)·I0/D²·e^{−σ_t D}·∫_0^s e^{−σ_t (1 − cos γ) x} dx,
 *   ∫ = −expm1(−k s)/k, k = σ_t (1 − cos γ) (s for k s → 0, 1/k for s = ∞).
 * Exact as D → ∞ at fixed s; wrong near the light (D ≲ s). Formed in logarithms (no overflow
 * or underflow of the factors); 0 for σ_s = 0, I0 = 0 or s = 0; +∞ for an infinite ray
 * without extinction along it (k = 0). */
SLUT_FN double slut_hg_airlight_radiance_distant(double sigma_s, double sigma_a, double intensity, double distance,
                                                 double sin_gamma, double cos_gamma, double length, double g) {
    if (!(sigma_s > 0.0) || !(intensity > 0.0) || !(length > 0.0)) return 0.0;
    double sigma_t = sigma_s + sigma_a;
    slut_hg_half_angle h = slut_hg_half_angles_of(sin_gamma, cos_gamma);
    double rate = sigma_t * 2.0 * h.sin_half * h.sin_half; /* σ_t (1 − cos γ), 1/m */
    double path;                                            /* ∫_0^s e^{−rate x} dx, m */
    if (length > SLUT_INFINITE_ABOVE) path = (rate > 0.0) ? 1.0 / rate : SLUT_HUGE_VAL;
    else path = (rate * length > SLUT_TINY) ? -expm1(-rate * length) / rate : length;
    if (!SLUT_ISFINITE(path)) return SLUT_HUGE_VAL;
    double psi = slut_hg_psi_half(g, h.sin_half * h.sin_half, h.cos_half * h.cos_half); /* ψ_g at θ = γ */
    double ln_L = log(sigma_s) + log(SLUT_INV_4PI * psi) + log(intensity) - 2.0 * log(distance) -
                  sigma_t * distance + log(path);
    double L = exp(ln_L);
    return SLUT_ISFINITE(L) ? L : ((ln_L > 0.0) ? SLUT_HUGE_VAL : 0.0);
}

#endif /* SLUT_AIRLIGHT_HG_BRACKET_H */
