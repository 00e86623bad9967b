/* scatterlut — the mean of the Henyey–Greenstein phase over an arc of scattering angle, by a
 * fixed rule (at most three 16-point Gauss–Legendre panels), written once.
 *
 *   M_k(θ0, θ1) = (1/(θ1 − θ0)) ∫_{θ0}^{θ1} ψ_k(θ) dθ,   ψ_k = 4π p_k (kernels/slut_phase.h),
 *   0 ≤ θ0 ≤ θ1 ≤ π, |k| < 1 (k: the phase's asymmetry g; θ1 = θ0: ψ_k(θ0)).
 *
 * Where it is needed: without extinction every point of a ray contributes in proportion to
 * dθ — the inverse-square weight times the path element is dθ divided by the light's distance
 * to the line of the ray (the airlight's 2 dξ = dθ of Sun et al. 2005; the near light's
 * ĥ⁻² dτ = dθ/√(1 − g²) of kernels/slut_nearlight_hg.h) — so the thin-medium forms with the
 * phase are the isotropic ones times M_k over the arc of θ the ray sweeps (docs/PHYSICS.md §1.4).
 *
 * No elementary closed form: with A = 1 + k², B = 2k, Q = A − B cos θ,
 *   ∫ Q^{−3/2} dθ = (2B sin θ/√Q + ∫ √Q dθ)/(1 − k²)²
 * and ∫ √Q dθ is an incomplete elliptic integral of the second kind (parameter m = 4|k|/(1 + |k|)²);
 * the difference of its values at θ0 and θ1 cancels (relative ~1/((1 − |k|)²(θ1 − θ0)), 1e6 in
 * float at |k| = 0.99), so the rule integrates the arc itself.
 *
 * The rule. With the peak moved to φ = 0 (φ = θ for k ≥ 0, φ = π − θ for k < 0, since
 * ψ_k(θ) = ψ_{−k}(π − θ)), a = |k|, ψ_a(φ) is analytic but at φ = ±i w,
 * w = 2 asinh((1 − a)/(2√a)) (the zeros of Q: the forward peak's width):
 *  - an arc no longer than twice its distance d = |φ0 + i w| from the nearest singularity:
 *    one 16-point panel in φ (Bernstein ellipse ρ ≥ 2 + √3: error ≲ ρ^{−32} ≈ 5e-19);
 *  - a longer one (it then starts near the peak, φ0 < ½(φ1 − φ0)): [φ0, min(φ1, π/2)] in
 *    y = asinh(tan(φ/2)/ρ_a), ρ_a = (1 − a)/(1 + a), where
 *      ψ_a dφ = (2/(1 − a))·√(1 + ρ_a² sinh² y)/cosh² y dy
 *    (with t = tan(φ/2): ψ_a dφ = 2(1 − a²)√(1 + t²) dt/((1 − a)² + (1 + a)² t²)^{3/2}, the
 *    airlight's k_g; t = ρ_a sinh y flattens the peak), analytic in the strip |Im y| < π/2
 *    whatever a (split in two equal panels where it is longer than 3: it is ≤ asinh(1/ρ_a)
 *    long, 6 at a = 0.99); and [max(φ0, π/2), φ1] in φ (the singularities ≥ π/2 away, the
 *    panel ≤ π/2 long: ρ ≥ 5.8). At most 48 evaluations of the integrand; the error grows with a
 *    (measured: tests/kernels/test_anisotropic.cpp, PhaseArcMean.FixedRuleMatchesTheEllipticIntegral,
 *    ≤ 1e-13 in double at |g| ≤ 0.99; docs/PHYSICS.md §1.4).
 * Every term is positive. Compiled as C++, OpenCL C and, whole, in float by the GPU snippets
 * (the shared subset of kernels/slut_compat.h).
 */
#ifndef SLUT_PHASE_ARC_H
#define SLUT_PHASE_ARC_H

#include "slut_compat.h"
#include "slut_phase.h"
#include "slut_airlight.h" /* slut_gl16_x/w */

/* ∫ ψ_a(φ) dφ over [lo, hi] (a ≥ 0) by one 16-point Gauss–Legendre panel in φ. */
SLUT_FN double slut_hg_arc_panel_phi(double a, double lo, double hi) {
    double half_len = 0.5 * (hi - lo), mid = 0.5 * (lo + hi), sum = 0.0;
    for (int k = 0; k < 8; ++k) {
        double d = half_len * slut_gl16_x[k];
        double s0 = sin(0.5 * (mid - d)), s1 = sin(0.5 * (mid + d));
        double c0 = cos(0.5 * (mid - d)), c1 = cos(0.5 * (mid + d));
        sum += slut_gl16_w[k] * (slut_hg_psi_half(a, s0 * s0, c0 * c0) + slut_hg_psi_half(a, s1 * s1, c1 * c1));
    }
    return half_len * sum;
}

/* asinh(x) for x ≥ 0 (no cancellation: both terms positive). */
SLUT_FN double slut_hg_arc_asinh(double x) { return log(x + sqrt(1.0 + x * x)); }

/* ∫ of ψ_a over y ∈ [y0, y1] (y = asinh(tan(φ/2)/ρ_a), 0 ≤ a < 1) by one 16-point panel. */
SLUT_FN double slut_hg_arc_panel_y(double a, double rho, double y0, double y1) {
    double half_len = 0.5 * (y1 - y0), mid = 0.5 * (y0 + y1), sum = 0.0;
    for (int k = 0; k < 8; ++k) {
        double d = half_len * slut_gl16_x[k];
        double sh0 = sinh(mid - d), sh1 = sinh(mid + d);
        double t0 = rho * sh0, t1 = rho * sh1;
        sum += slut_gl16_w[k] * (sqrt(1.0 + t0 * t0) / (1.0 + sh0 * sh0) + sqrt(1.0 + t1 * t1) / (1.0 + sh1 * sh1));
    }
    return half_len * sum * 2.0 / (1.0 - a);
}

/* ∫ ψ_a(φ) dφ over [lo, hi] ⊂ [0, π/2] (0 ≤ a < 1) in y = asinh(tan(φ/2)/ρ_a): one 16-point
 * panel, two equal ones where the y interval is longer than 3 (a ≳ 0.9 from the peak on:
 * the strip's half-width π/2 against a panel half-length above 1.5). */
SLUT_FN double slut_hg_arc_panel_peak(double a, double lo, double hi) {
    double rho = (1.0 - a) / (1.0 + a);
    double y0 = slut_hg_arc_asinh(tan(0.5 * lo) / rho), y1 = slut_hg_arc_asinh(tan(0.5 * hi) / rho);
    if (y1 - y0 <= 3.0) return slut_hg_arc_panel_y(a, rho, y0, y1);
    double ym = 0.5 * (y0 + y1);
    return slut_hg_arc_panel_y(a, rho, y0, ym) + slut_hg_arc_panel_y(a, rho, ym, y1);
}

/* M_k(θ0, θ1): the mean of ψ_k over θ ∈ [θ0, θ1] (radians, 0 ≤ θ0 ≤ θ1 ≤ π), |k| < 1. */
SLUT_FN double slut_hg_psi_arc_mean(double phase_g, double theta0, double theta1) {
    double a = fabs(phase_g);
    double lo = (phase_g >= 0.0) ? theta0 : SLUT_PI - theta1;
    double hi = (phase_g >= 0.0) ? theta1 : SLUT_PI - theta0;
    lo = fmax(lo, 0.0);
    hi = fmax(hi, lo);
    double len = hi - lo;
    if (!(a > 0.0)) return 1.0;
    double w = 2.0 * slut_hg_arc_asinh((1.0 - a) / (2.0 * sqrt(a)));
    if (!(len > 0.0)) {
        double s = sin(0.5 * lo), c = cos(0.5 * lo);
        return slut_hg_psi_half(a, s * s, c * c);
    }
    if (len <= 2.0 * sqrt(lo * lo + w * w)) return slut_hg_arc_panel_phi(a, lo, hi) / len;
    double split = 0.5 * SLUT_PI;
    double sum = 0.0;
    if (lo < split) sum += slut_hg_arc_panel_peak(a, lo, fmin(hi, split));
    if (hi > split) sum += slut_hg_arc_panel_phi(a, fmax(lo, split), hi);
    return sum / len;
}

#endif /* SLUT_PHASE_ARC_H */
