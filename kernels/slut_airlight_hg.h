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
 * and the bracket of the radiance (the segment's integral) is K_g over the segment (below).
 * For g = 0, k_0(T) = 1/(ε̂² + T²): the isotropic integrand.
 *
 * Compiled as C++ by the runtime library and the tests, as OpenCL C by kernels/airlight_Fg.cl
 * (double precision), and whole, a third time, as GLSL/HLSL in float for the anisotropic
 * airlight snippet (docs/SHADERS.md; kernels/slut_compat.h lists the subset that keeps to:
 * structs by value, precision-dependent thresholds as SLUT_* macros, every math call mapped).
 * The generator's quadratures of F_g and G̃_g sit in an `#ifndef SLUT_SHADER` block.
 */
#ifndef SLUT_AIRLIGHT_HG_H
#define SLUT_AIRLIGHT_HG_H

#include "slut_compat.h"
#include "slut_phase.h"
#include "slut_airlight.h" /* the isotropic functions g = 0 hands to; slut_gl16_x/w; slut_exp_expint */
#include "slut_axes.h"     /* the w axis warps (slut_hg_airlight_w_warp) */
#include "slut_phase_arc.h" /* the thin-medium form: the phase's mean over the ray's arc */

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

/* ------------------------------------------------------------ asymptotic forms of G̃_g */

/* G̃_g as w → 0 at fixed a = u·cot w. In the scaled integral (τ̂ = 1, ε = tan w, z as above),
 * with x = ε²/(1 + z)² and κ = ((1 − g)/(1 + g))²,
 *   k_g = ψ_g(π)·(1 + z)^{−2}·(1 + x)^{1/2}(1 + κx)^{−3/2}
 *       = ψ_g(π)·(1 + z)^{−2}·[1 + c1 x + c2 x² + c3 x³ + …],
 *   c1 = ½ − 3κ/2,  c2 = 15κ²/8 − 3κ/4 − 1/8,  c3 = −35κ³/16 + 15κ²/16 + 3κ/16 + 1/16,
 * and ∫_0^∞ e^{−az}(1 + z)^{−n} dz = e^a E_n(a), so
 *   G̃_g = (tan w/w)·ψ_g(π)·[e^aE_2(a) + c1 tan²w e^aE_4(a) + c2 tan⁴w e^aE_6(a) + O(tan⁶w)].
 * At g = 0 (κ = 1: c1 = −1, c2 = 1) the first two terms are slut_gs_small_w's. Truncation
 * error ≈ |c3| tan⁶w relative to the leading term (e^aE_8 ≤ e^aE_2): ≤ tan⁶w for g ≥ 0
 * (κ ≤ 1: |c3| ≤ 1), but for g < 0 the backward peak (width (1 + g)/(1 − g) in w) makes κ
 * large: ≈ 2.2 (κ tan²w)³, so ≤ 1e-13 needs w ≤ 3e-5 at g = −0.99 and w ≤ 2e-3 at
 * g = −0.5 (measured in tests/kernels/test_anisotropic.cpp, SmallWAndLargeUFormsMatchQuadrature).
 * g = 0 hands to slut_gs_small_w (today's two terms). */
SLUT_FN double slut_hg_gs_small_w(double w, double a, double g) {
    if (g == 0.0) return slut_gs_small_w(w, a);
    double tw = tan(w), e2 = tw * tw;
    double ratio = (w > 0.0) ? tw / w : 1.0;
    double kr = (1.0 - g) / (1.0 + g), kappa = kr * kr;
    double c1 = 0.5 - 1.5 * kappa;
    double c2 = 1.875 * kappa * kappa - 0.75 * kappa - 0.125;
    return ratio * slut_hg_psi_backward(g) *
           (slut_exp_expint(2, a) + e2 * (c1 * slut_exp_expint(4, a) + e2 * c2 * slut_exp_expint(6, a)));
}

#define SLUT_HG_SERIES_TERMS 24

/* Taylor coefficients c[0..n−1] of P(z)^α about z = 0, P = p0 + p1 z + p2 z² (p0 > 0):
 * from P y' = α P' y, c[k+1] = ((α − k) p1 c[k] + (2α − k + 1) p2 c[k−1]) / ((k + 1) p0). */
SLUT_FN void slut_hg_series_pow(double p0, double p1, double p2, double alpha, int n,
                                SLUT_OUT_ARRAY(double, c, SLUT_HG_SERIES_TERMS)) {
    c[0] = pow(p0, alpha);
    if (n > 1) c[1] = alpha * p1 * c[0] / p0;
    for (int k = 1; k + 1 < n; ++k)
        c[k + 1] = ((alpha - SLUT_DOUBLE(k)) * p1 * c[k] + (2.0 * alpha - SLUT_DOUBLE(k) + 1.0) * p2 * c[k - 1]) /
                   (SLUT_DOUBLE(k + 1) * p0);
}

/* K_g(û, τ̂, ε̂, ∞) for large û by Watson's lemma: with k_g(τ̂ + z) = Σ_n k_n z^n,
 *   K_g ~ Σ_n k_n n!/û^{n+1}.
 * Asymptotic: the terms shrink like n/(û·ρ) with ρ = |τ̂ + i b̂| the distance to the nearest
 * singularity (slut_hg_air_integral), so the sum stops at its smallest term
 * (≤ SLUT_HG_SERIES_TERMS), which is its error. For g → 1 and w → π/2 (τ̂ → 0)
 * ρ → (1 − g)/(1 + g): the forward peak needs û ≫ n(1 + g)/(1 − g); at g = 0.95, w = π/2 − 0.006
 * and û = 64 (ûρ = 1.7) the smallest term is the sum's own size and the sum is off by 130 %,
 * in double as in float (measured: docs/SHADERS.md) — slut_hg_gs_beyond_u_max falls back to
 * the quadrature there.
 *
 * Written so that nothing over- or underflows in float: in s = z/ρ, with
 *   ε̂² + (τ̂ + ρs)² = R0·(1 + (2τ̂ρ/R0) s + (ρ²/R0) s²),          R0 = ε̂² + τ̂² ≥ ρ²,
 *   (1 − g)²ε̂² + (1 + g)²(τ̂ + ρs)² = Q0·(1 + (2(1 + g)²τ̂ρ/Q0) s + ((1 + g)²ρ²/Q0) s²),
 *   Q0 = (1 − g)²ε̂² + (1 + g)²τ̂² ≥ (1 + g)²ρ²,
 * every coefficient of the two quadratics lies in [0, 2], so the Taylor coefficients of
 * their powers (slut_hg_series_pow) grow at most like 3^n, and
 *   K_g ~ (1 − g²)·√R0/Q0^{3/2}·ρ·Σ_n a_n n!/(ûρ)^{n+1}
 * (a_n those of the product): the factor n!/(ûρ)^{n+1} near the smallest term is of order 1.
 * (The series in z itself had coefficients ~ ρ^{−n} and factors ~ û^{−n}: in float they
 * overflowed and underflowed, ∞·0, for a sharp peak.) Where τ̂ → 0 the odd terms vanish, so
 * each term is compared with the one two places back: the sum stops where the terms begin to
 * grow or stop being numbers, or where two terms in a row are below SLUT_SERIES_NEGLIGIBLE of
 * the sum. error_bound: the larger of the first term left out and the last one taken (the
 * even and the odd terms are two series, each stopped at most one term before its smallest;
 * +∞ if a term was not a number; 0 where two negligible terms ended the sum) — the error of
 * the sum, to within a factor of a few. */
SLUT_STRUCT_BEGIN(slut_hg_series_result)
    double sum;         /* K_g                                                 */
    double error_bound; /* |the first term left out|: the sum's error, roughly */
SLUT_STRUCT_END(slut_hg_series_result);

SLUT_FN slut_hg_series_result slut_hg_air_series_large_u(double u, double tau, double eps, double g) {
    double r2c[SLUT_HG_SERIES_TERMS], qc[SLUT_HG_SERIES_TERMS];
    double gm = 1.0 - g, gp = 1.0 + g;
    double b_hat = eps * fmin(1.0, gm / gp);
    double rho = sqrt(tau * tau + b_hat * b_hat);
    double R0 = eps * eps + tau * tau;
    double Q0 = gm * gm * eps * eps + gp * gp * tau * tau;
    slut_hg_series_pow(1.0, 2.0 * tau * rho / R0, rho * rho / R0, 0.5, SLUT_HG_SERIES_TERMS, r2c);
    slut_hg_series_pow(1.0, 2.0 * gp * gp * tau * rho / Q0, gp * gp * rho * rho / Q0, -1.5, SLUT_HG_SERIES_TERMS, qc);
    double x = u * rho;
    double scale = gm * gp * sqrt(R0) / (Q0 * sqrt(Q0)) * rho;
    slut_hg_series_result res;
    res.sum = 0.0;
    res.error_bound = 0.0;
    double factor = 1.0 / x, before_last = SLUT_HUGE_VAL, last = SLUT_HUGE_VAL;
    for (int n = 0; n < SLUT_HG_SERIES_TERMS; ++n) {
        double an = 0.0;
        for (int j = 0; j <= n; ++j) an += r2c[j] * qc[n - j];
        double term = scale * an * factor;
        factor *= SLUT_DOUBLE(n + 1) / x;
        if (!(fabs(term) < before_last)) {
            res.error_bound = (fabs(term) <= SLUT_REAL_MAX) ? fmax(fabs(term), last) : SLUT_HUGE_VAL;
            return res;
        }
        res.sum += term;
        if (n > 0 && fabs(term) <= SLUT_SERIES_NEGLIGIBLE * fabs(res.sum) &&
            last <= SLUT_SERIES_NEGLIGIBLE * fabs(res.sum))
            return res;
        before_last = last;
        last = fabs(term);
        res.error_bound = fmax(last, before_last); /* out of terms: the last two taken */
    }
    return res;
}

SLUT_FN double slut_hg_air_integral_large_u(double u, double tau, double eps, double g) {
    return slut_hg_air_series_large_u(u, tau, eps, g).sum;
}

#ifndef SLUT_SHADER /* the table generator's sweep (kernels/airlight_F.cl, host/src/generate_airlight.cpp) */
/* The same Watson series in the sweep's unscaled variable (ε̂ = 1, τ = cot w_j up to cot w_min):
 *   S(u) = ∫_0^∞ e^{−u y} k_g(τ + y) dy ~ Σ_n c_n/u^{n+1},   c_n = k_g^{(n)}(τ) = P·a_n·n!/ρ^n,
 * with ρ, P = (1 − g²)√R0/Q0^{3/2} and a_n (the Taylor coefficients in s = y/ρ) those of
 * slut_hg_air_series_large_u at ε̂ = 1. At g = 0 this is the Lorentzian's
 * c_n = (−1)^n n! sin^{n+1}w sin((n + 1)w) of slut_gs_large_u_coefficients (up to rounding).
 * Fills c[0..n−1] (n ≤ SLUT_HG_SERIES_TERMS) and returns ρ = |τ + iβ|, the distance to k_g's
 * nearest singularity. */
SLUT_FN double slut_hg_sweep_large_u_coefficients(double tau, double g, int n, double *c) {
    double r2c[SLUT_HG_SERIES_TERMS], qc[SLUT_HG_SERIES_TERMS];
    double gm = 1.0 - g, gp = 1.0 + g;
    double beta = fmin(1.0, gm / gp);
    double rho = sqrt(tau * tau + beta * beta);
    double R0 = 1.0 + tau * tau;
    double Q0 = gm * gm + gp * gp * tau * tau;
    slut_hg_series_pow(1.0, 2.0 * tau * rho / R0, rho * rho / R0, 0.5, n, r2c);
    slut_hg_series_pow(1.0, 2.0 * gp * gp * tau * rho / Q0, gp * gp * rho * rho / Q0, -1.5, n, qc);
    double factor = gm * gp * sqrt(R0) / (Q0 * sqrt(Q0)); /* P·n!/ρ^n */
    for (int k = 0; k < n; ++k) {
        double ak = 0.0;
        for (int j = 0; j <= k; ++j) ak += r2c[j] * qc[k - j];
        c[k] = factor * ak;
        factor *= SLUT_DOUBLE(k + 1) / rho;
    }
    return rho;
}

/* The smallest u from which the first SLUT_GS_SERIES_TERMS terms of that series hold S to a
 * relative `target`, from its first SLUT_HG_SERIES_TERMS coefficients c and ρ
 * (slut_hg_sweep_large_u_coefficients): the terms n = 12 … 23 left out are each ≤ target/24 of
 * the leading one c_0/u, and uρ ≥ 48 (slut_hg_sweep_series_u_floor) so that the terms after
 * them keep shrinking (the n-th over the (n−1)-th ~ n/(uρ) ≤ ½). The sum's error is then
 * ≲ target·c_0/(2u) (S ≈ c_0/u there). An estimate from the terms, not a bound:
 * tests/kernels/test_anisotropic.cpp measures the series against the quadrature from this u
 * on, and the generator measures every table. Logarithms, not powers: the generator calls
 * this for every w node of a table. */
SLUT_FN double slut_hg_sweep_series_u_floor(double rho) { return 48.0 / rho; }
SLUT_FN double slut_hg_sweep_series_u_min(const double *c, double rho, double target) {
    double ln_u = log(slut_hg_sweep_series_u_floor(rho));
    double ln_scale = log(24.0 / (target * c[0])); /* |c_n|/u^{n+1} ≤ (target/24)·c_0/u ⇔ n ln u ≥ ln|c_n| + ln_scale */
    for (int n = SLUT_GS_SERIES_TERMS; n < SLUT_HG_SERIES_TERMS; ++n)
        if (c[n] != 0.0) ln_u = fmax(ln_u, (log(fabs(c[n])) + ln_scale) / SLUT_DOUBLE(n));
    return exp(ln_u);
}
#endif /* !SLUT_SHADER */

/* G̃_g(u, w) for large u (Watson's lemma above, whatever its accuracy: the generator measures
 * from which u on it holds a table's target, host/src/generate_airlight.cpp); g = 0 hands to
 * slut_gs_large_u. */
SLUT_FN double slut_hg_gs_large_u_general(double u, double w, double g) {
    slut_hg_tail_scale t = slut_hg_tail_scaling_of(w);
    return t.inv_lambda * slut_hg_air_integral_large_u(u / t.inv_lambda, t.tau_hat, t.eps_hat, g) / w;
}
SLUT_FN double slut_hg_gs_large_u(double u, double w, double g) {
    if (g == 0.0) return slut_gs_large_u(u, w);
    return slut_hg_gs_large_u_general(u, w, g);
}

/* G̃_g(u, w) beyond a table's u_max, what the samplers (C++ and GPU) use there: Watson's
 * series where its error bound is within SLUT_HG_SERIES_ACCEPT of its sum (1e-13 in double,
 * 1e-6 in float: kernels/slut_compat.h), else the quadrature slut_hg_air_integral (û ρ small:
 * the forward peak of g → 1 near w = π/2, a table whose u_max was set below the series'
 * onset; at large û the quadrature needs ~8 panels, e^{−ûz} confining it to z ≲ 40/û).
 * Never negative; g = 0 hands to slut_gs_large_u (the isotropic table's, unchanged). */
SLUT_FN double slut_hg_gs_beyond_u_max(double u, double w, double g) {
    if (g == 0.0) return slut_gs_large_u(u, w);
    slut_hg_tail_scale t = slut_hg_tail_scaling_of(w);
    double uh = u / t.inv_lambda;
    slut_hg_series_result s = slut_hg_air_series_large_u(uh, t.tau_hat, t.eps_hat, g);
    double K = s.sum;
    if (!(s.sum > 0.0) || !(s.error_bound <= SLUT_HG_SERIES_ACCEPT * s.sum))
        K = slut_hg_air_integral(uh, t.tau_hat, t.eps_hat, SLUT_HUGE_VAL, g, 1.0);
    return t.inv_lambda * K / w;
}

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
