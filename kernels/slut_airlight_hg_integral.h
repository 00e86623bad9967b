/* scatterlut — the anisotropic airlight's integral K_g (kernels/slut_airlight_hg.h), written once:
 * the scaled integrand k_g and the phase ψ_g(2ξ) along it, K_g(û, τ̂, ε̂, Z) = ∫_0^Z e^{−û z}
 * k_g(τ̂ + z) dz by composite Gauss–Legendre, the scaling of a tail at w (λ = max(1, cot w)), and
 * the generator's quadratures of G̃_g and F_g (`#ifndef SLUT_SHADER`). The notation
 * (û, τ̂, ε̂, λ) is kernels/slut_airlight_hg.h's, which includes this header.
 *
 * Compiled wherever kernels/slut_airlight_hg.h is: C++, OpenCL C, and GLSL/HLSL in float.
 */
#ifndef SLUT_AIRLIGHT_HG_INTEGRAL_H
#define SLUT_AIRLIGHT_HG_INTEGRAL_H

#include "slut_compat.h"
#include "slut_phase.h"
#include "slut_airlight.h" /* the isotropic functions g = 0 hands to; slut_gl16_x/w */

/* ------------------------------------------------------------ the scaled integrand */

/* k_g(T) for T ≥ 0, ε̂ ∈ [0, 1], not both 0. Where T ≥ ε̂ it is evaluated in e = ε̂/T ≤ 1,
 *   k_g = (1 − g²)·√(1 + e²) / (T²·((1 − g)² e² + (1 + g)²)^{3/2}),
 * which cannot overflow for T up to the double range (it underflows to 0 beyond 1e154, where
 * the integrand is below any sum it is added to). */
SLUT_FN double slut_hg_air_kernel(double g, double eps, double T) {
    double one_minus_g2 = (1.0 - g) * (1.0 + g);
    if (T >= eps) {
        double e = eps / T, a = (1.0 - g) * e, b = 1.0 + g;
        double Q = a * a + b * b;
        return one_minus_g2 * sqrt(1.0 + e * e) / ((T * T) * (Q * sqrt(Q)));
    }
    {
        double f = T / eps, a = 1.0 - g, b = (1.0 + g) * f;
        double Q = a * a + b * b;
        return one_minus_g2 * sqrt(1.0 + f * f) / ((eps * eps) * (Q * sqrt(Q)));
    }
}

/* ψ_g(2ξ) at T = τ̂ + z: sin²ξ = T²/(ε̂² + T²), cos²ξ = ε̂²/(ε̂² + T²). */
SLUT_FN double slut_hg_air_psi(double g, double eps, double T) {
    if (T >= eps) {
        double e2 = (eps / T) * (eps / T);
        return slut_hg_psi_half(g, 1.0 / (1.0 + e2), e2 / (1.0 + e2));
    }
    {
        double f2 = (T / eps) * (T / eps);
        return slut_hg_psi_half(g, f2 / (1.0 + f2), 1.0 / (1.0 + f2));
    }
}

/* ∫_a^b e^{−û z} k_g(τ̂ + z) dz with 16-point Gauss–Legendre. */
SLUT_FN double slut_hg_air_panel(double u, double tau, double eps, double g, double a, double b) {
    double half_len = 0.5 * (b - a), mid = 0.5 * (a + b), sum = 0.0;
    for (int k = 0; k < 8; ++k) {
        double dz = half_len * slut_gl16_x[k];
        double z0 = mid - dz, z1 = mid + dz;
        sum += slut_gl16_w[k] * (exp(-u * z0) * slut_hg_air_kernel(g, eps, tau + z0) +
                                 exp(-u * z1) * slut_hg_air_kernel(g, eps, tau + z1));
    }
    return half_len * sum;
}

/* K_g(û, τ̂, ε̂, Z) = ∫_0^Z e^{−û z} k_g(τ̂ + z) dz by composite Gauss–Legendre; Z may be +∞
 * (anything above 1e300), û ≥ 0, τ̂ ∈ [0, 1], ε̂ ∈ [0, 1] with max(τ̂, ε̂) = 1, |g| < 1.
 *
 * The panels of slut_w_gs_quadrature, with the phase's singularities added: k_g is analytic
 * except at T = ±iε̂ (branch points of r) and T = ±iε̂(1 − g)/(1 + g) (zeros of Q: the forward
 * peak, width (1 − g)/(1 + g) in tan ξ, as g → 1). With b̂ = ε̂·min(1, (1 − g)/(1 + g)) the
 * nearest one lies |τ̂ + i b̂| from z = 0 and at least τ̂ + z from any z > 0. Panels: [0, z0]
 * with z0 = ½ min(1/û, |τ̂ + i b̂|) (at most e^{−1/2} of decay, the singularities ≥ 2 panel
 * lengths away), then [z, ρz] growing geometrically (ρ = 1 + 1/refine; refine = 1 is the
 * rule, larger values an independent finer one), each ≥ 1.5 panel lengths from every
 * singularity (Bernstein ρ_B ≥ 5.8: 16-point error ≲ ρ_B^{−32}); the exponential varies by
 * at most e^{−(ρ−1)ûz} over a panel, and panels past ûz ≈ 40 carry less than e^{−40}.
 * For g → −1 the integrand rises ~ T up to T ≈ ε̂(1 − g)/(1 + g) (the backward peak at
 * ξ → π/2) and falls like 1/T² after it: smooth on the panels' own scale.
 * Stop once the remainder bound ∫_Y^∞ ≤ e^{−ûY}·ψ_max/(τ̂ + Y) is below 1e-17 of the sum,
 * ψ_max = ψ_g at Y for g ≥ 0 (ψ falls as ξ grows) and ψ_g(π) for g < 0. Relative error
 * ~1e-15 (every term is positive). û > 1e300: the leading Watson term k_g(τ̂)/û. */
SLUT_FN double slut_hg_air_integral(double u, double tau, double eps, double z_end, double g, double refine) {
    if (!(z_end > 0.0)) return 0.0;
    if (!(u <= SLUT_INFINITE_ABOVE)) return slut_hg_air_kernel(g, eps, tau) / u;
    double ratio = 1.0 + 1.0 / refine;
    double b_hat = eps * fmin(1.0, (1.0 - g) / (1.0 + g));
    double dist = sqrt(tau * tau + b_hat * b_hat);
    double z0 = 0.5 * fmin((u > 0.0) ? 1.0 / u : SLUT_HUGE_VAL, dist) / refine;
    if (z_end <= z0) return slut_hg_air_panel(u, tau, eps, g, 0.0, z_end);
    double sum = slut_hg_air_panel(u, tau, eps, g, 0.0, z0);
    double psi_back = slut_hg_psi_backward(g);
    double z = z0;
    for (int panel = 0; panel < 4000 && z < z_end; ++panel) {
        double T = tau + z;
        double psi_bound = (g >= 0.0) ? slut_hg_air_psi(g, eps, T) : psi_back;
        if (exp(-u * z) * psi_bound / T <= SLUT_REMAINDER_NEGLIGIBLE * sum) break;
        double z_next = fmin(z * ratio, z_end);
        sum += slut_hg_air_panel(u, tau, eps, g, z, z_next);
        z = z_next;
    }
    return sum;
}

/* The scaling of a tail at w ∈ (0, π/2]: λ = max(1, cot w); τ̂ = cot w/λ, ε̂ = 1/λ, and the
 * factor 1/λ of w·G̃_g. */
SLUT_STRUCT_BEGIN(slut_hg_tail_scale)
    double tau_hat;
    double eps_hat;
    double inv_lambda;
SLUT_STRUCT_END(slut_hg_tail_scale);

SLUT_FN slut_hg_tail_scale slut_hg_tail_scaling_of(double w) {
    slut_hg_tail_scale t;
    double sw = sin(w), cw = cos(w);
    if (cw <= sw) { /* w ≥ π/4: cot w ≤ 1 */
        t.tau_hat = cw / sw;
        t.eps_hat = 1.0;
        t.inv_lambda = 1.0;
    } else {
        t.tau_hat = 1.0;
        t.eps_hat = sw / cw;
        t.inv_lambda = sw / cw;
    }
    return t;
}

#ifndef SLUT_SHADER /* the generator's, the reference's and the tests' (double only) */
SLUT_FN void slut_hg_tail_scaling(double w, double *tau_hat, double *eps_hat, double *inv_lambda) {
    slut_hg_tail_scale t = slut_hg_tail_scaling_of(w);
    *tau_hat = t.tau_hat;
    *eps_hat = t.eps_hat;
    *inv_lambda = t.inv_lambda;
}

/* w·G̃_g(u, w) by quadrature for every g (g = 0 included: the general rule, for the tests). */
SLUT_FN double slut_hg_w_gs_quadrature_general(double u, double w, double g, double refine) {
    slut_hg_tail_scale t = slut_hg_tail_scaling_of(w);
    return t.inv_lambda * slut_hg_air_integral(u / t.inv_lambda, t.tau_hat, t.eps_hat, SLUT_HUGE_VAL, g, refine);
}

/* w·G̃_g(u, w), u ≥ 0, w ∈ (0, π/2]; g = 0 is slut_w_gs_quadrature. */
SLUT_FN double slut_hg_w_gs_quadrature(double u, double w, double g, double refine) {
    if (g == 0.0) return slut_w_gs_quadrature(u, w, refine);
    return slut_hg_w_gs_quadrature_general(u, w, g, refine);
}

/* G̃_g(u, w) ∈ (0, ψ_max]: G̃_g(0, w) = mean of ψ_g(2ξ) over ξ ∈ [π/2 − w, π/2]. */
SLUT_FN double slut_hg_gs_quadrature(double u, double w, double g, double refine) {
    return slut_hg_w_gs_quadrature(u, w, g, refine) / w;
}

/* F_g(u, v) = ∫_0^v ψ_g(2ξ) e^{−u tan ξ} dξ, u ≥ 0, v ∈ [0, π/2]; g = 0 is slut_F_quadrature. */
SLUT_FN double slut_hg_F_quadrature_general(double u, double v, double g) {
    if (!(v > 0.0)) return 0.0;
    double w = slut_pio2_minus(v);
    double tan_v = (w > 0.0) ? slut_tan_v(v, w) : SLUT_HUGE_VAL;
    return slut_hg_air_integral(u, 0.0, 1.0, tan_v, g, 1.0);
}
SLUT_FN double slut_hg_F_quadrature(double u, double v, double g) {
    if (g == 0.0) return slut_F_quadrature(u, v);
    return slut_hg_F_quadrature_general(u, v, g);
}
#endif /* !SLUT_SHADER */

#endif /* SLUT_AIRLIGHT_HG_INTEGRAL_H */
