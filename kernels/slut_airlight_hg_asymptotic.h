/* scatterlut — the anisotropic airlight's G̃_g where a table has no nodes (kernels/slut_airlight_hg.h),
 * written once: its form as w → 0, Watson's series for large u (with its error bound, and the
 * table sweep's coefficients and onset in `#ifndef SLUT_SHADER`), and what the samplers use
 * beyond a table's u_max (the series where it holds, else the quadrature).
 *
 * Compiled wherever kernels/slut_airlight_hg.h is (it includes this header): C++, OpenCL C,
 * and GLSL/HLSL in float.
 */
#ifndef SLUT_AIRLIGHT_HG_ASYMPTOTIC_H
#define SLUT_AIRLIGHT_HG_ASYMPTOTIC_H

#include "slut_compat.h"
#include "slut_phase.h"
#include "slut_airlight.h"             /* slut_gs_small_w, slut_gs_large_u, slut_exp_expint, SLUT_GS_SERIES_TERMS */
#include "slut_airlight_hg_integral.h" /* slut_hg_tail_scaling_of, slut_hg_air_integral */

/* ------------------------------------------------------------ asymptotic forms of G̃_g */

/* G̃_g as w → 0 at fixed a = u·cot w. In the scaled integral (slut_airlight_hg_integral.h;
 * τ̂ = 1, ε = tan w), with x = ε²/(1 + z)² and κ = ((1 − g)/(1 + g))²,
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

#endif /* SLUT_AIRLIGHT_HG_ASYMPTOTIC_H */
