/* scatterlut — the scaled tail G̃(u, w) of the airlight function (kernels/slut_airlight.h), written once:
 * the Gauss–Legendre rules, G̃, F and the tail G by quadrature (the generator's and the
 * reference's), and G̃'s closed forms where a table has no nodes (w → 0, large u), with the
 * constants of the table sweep's short intervals.
 *
 *   G̃(u, w) = e^{u cot w} · G(u, π/2 − w) / w
 *           = (1/w) ∫_0^∞ e^{−u y} / (1 + (τ + y)²) dy,      τ = cot w = tan v.
 *
 * Compiled wherever kernels/slut_airlight.h is (it includes this header): OpenCL C, C++, and
 * GLSL/HLSL in float (the `#ifndef SLUT_SHADER` blocks left out).
 */
#ifndef SLUT_AIRLIGHT_TAIL_H
#define SLUT_AIRLIGHT_TAIL_H

#include "slut_compat.h"

/* ---------------------------------------------------------------- quadrature rule */

/* 16-point Gauss–Legendre on [−1, 1]: the positive nodes and their weights. */
SLUT_CONST_ARRAY8(slut_gl16_x,
                  0.0950125098376374401853, 0.28160355077925891323, 0.458016777657227386342,
                  0.617876244402643748447, 0.755404408355003033895, 0.86563120238783174388,
                  0.944575023073232576078, 0.989400934991649932596);
SLUT_CONST_ARRAY8(slut_gl16_w,
                  0.189450610455068496285, 0.182603415044923588867, 0.169156519395002538189,
                  0.149595988816576732082, 0.124628971255533872052, 0.0951585116824927848099,
                  0.0622535239386478928628, 0.0271524594117540948518);

/* 8-point Gauss–Legendre on [−1, 1] (the positive nodes and weights, mpmath to 21 digits):
 * the θ-integral's rule where the radiance needs only a table's accuracy (slut_airlight_theta.h). */
SLUT_CONST_ARRAY4(slut_gl8_x, 0.183434642495649804939, 0.525532409916328985818, 0.796666477413626739592,
                  0.960289856497536231684);
SLUT_CONST_ARRAY4(slut_gl8_w, 0.362683783378361982965, 0.313706645877887287338, 0.222381034453374470544,
                  0.101228536290376259153);

/* ------------------------------------------------------ scaled tail by quadrature */

#ifndef SLUT_SHADER /* the generator's and the reference's: double only */

/* ∫_a^b e^{−u y} / (1 + (τ + y)²) dy with 16-point Gauss–Legendre. */
SLUT_FN double slut_gs_panel(double u, double tau, double a, double b) {
    double half_len = 0.5 * (b - a), mid = 0.5 * (a + b), sum = 0.0;
    for (int k = 0; k < 8; ++k) {
        double dy = half_len * slut_gl16_x[k];
        double y0 = mid - dy, y1 = mid + dy;
        double t0 = tau + y0, t1 = tau + y1;
        sum += slut_gl16_w[k] * (exp(-u * y0) / (1.0 + t0 * t0) + exp(-u * y1) / (1.0 + t1 * t1));
    }
    return half_len * sum;
}

/* w·G̃(u, w) = ∫_0^∞ e^{−u y}/(1 + (τ + y)²) dy, τ = cot w, by composite Gauss–Legendre.
 *
 * Panels: [0, y0], then [y, ρ·y] growing geometrically (ρ = 1 + 1/refine; refine = 1 is
 * the production rule, larger values are the independent check). y0 = ½·min(1/u, |τ + i|):
 * the first panel sees at most a factor e^{−1/2} of decay and stays half its length away
 * from the poles of 1/(1 + t²) at t = ±i; a panel [y, ρy] is then at least 1.5y from the
 * poles for ρ ≤ 2, so every panel lies well inside its Bernstein ellipse (ρ_B ≥ 5.8:
 * error ≲ ρ_B^{−32}). The exponential varies by e^{−(ρ−1)uy} on a panel: ≤ 1e-13 relative
 * error for (ρ−1)uy ≤ 10, and panels beyond contribute less than e^{−10} of the total.
 * Stop once the remainder bound ∫_Y^∞ e^{−uy}/(τ+y)² dy ≤ e^{−uY}/(τ+Y) is below
 * 1e-17 of the sum. Work: 16·(log_ρ(40/(u·y0)) + 1) evaluations, ~200 at refine = 1.
 * u = 0 gives w·G̃ = atan(1/τ) = w exactly and is returned as such. */
SLUT_FN double slut_w_gs_quadrature(double u, double w, double refine) {
    if (u <= 0.0) return w;
    double tau = cos(w) / sin(w);
    double ratio = 1.0 + 1.0 / refine;
    double y0 = 0.5 * fmin(1.0 / u, sqrt(1.0 + tau * tau)) / refine;
    double sum = slut_gs_panel(u, tau, 0.0, y0);
    double y = y0;
    for (int panel = 0; panel < 4000; ++panel) {
        double remainder_bound = exp(-u * y) / (tau + y);
        if (remainder_bound <= 1e-17 * sum) break;
        double y_next = y * ratio;
        sum += slut_gs_panel(u, tau, y, y_next);
        y = y_next;
    }
    return sum;
}

/* G̃(u, w) by quadrature; G̃ ∈ (0, 1]. */
SLUT_FN double slut_gs_quadrature(double u, double w, double refine) {
    return slut_w_gs_quadrature(u, w, refine) / w;
}

/* tan v with full relative precision: directly below π/4, as cot w (w = π/2 − v,
 * computed without cancellation) above. */
SLUT_FN double slut_tan_v(double v, double w) { return (v < 0.78) ? tan(v) : cos(w) / sin(w); }

/* F(u, v) = ∫_0^{tan v} e^{−ut}/(1 + t²) dt by composite Gauss–Legendre: panels [0, t0],
 * then geometric [t, 2t] up to tan v, t0 = ½ min(1/u, 1) (same reasoning as above: the
 * poles at ±i and the decay length 1/u). Panels past 40/u (e^{−40} of the total) are
 * skipped. */
SLUT_FN double slut_F_quadrature(double u, double v) {
    if (v <= 0.0) return 0.0;
    if (u <= 0.0) return v;
    double w = slut_pio2_minus(v);
    double tan_v = slut_tan_v(v, w);
    double t_end = fmin(tan_v, 45.0 / u + 1.0);
    double t0 = 0.5 * fmin(1.0 / u, 1.0);
    if (t_end <= t0) return slut_gs_panel(u, 0.0, 0.0, t_end);
    double sum = slut_gs_panel(u, 0.0, 0.0, t0);
    double t = t0;
    while (t < t_end) {
        double t_next = fmin(2.0 * t, t_end);
        sum += slut_gs_panel(u, 0.0, t, t_next);
        t = t_next;
    }
    return sum;
}

/* G(u, v) = ∫_v^{π/2} e^{−u tan ξ} dξ = e^{−u tan v}·w·G̃(u, w): 0 where it underflows. */
SLUT_FN double slut_tail_quadrature(double u, double v) {
    double w = slut_pio2_minus(v);
    if (w <= 0.0) return 0.0;
    double tan_v = slut_tan_v(v, w);
    return exp(-u * tan_v) * slut_w_gs_quadrature(u, w, 1.0);
}

#endif /* !SLUT_SHADER */

/* ------------------------------------------------------------ closed forms of G̃ */

/* e^a E_n(a) for n ≥ 1, a ≥ 0 (E_n the exponential integral), relative error ~1e-15.
 * a ≥ 1: the continued fraction e^a E_n(a) = 1/(a + n − 1·n/(a + n + 2 − 2(n+1)/(a + n + 4 − …)))
 * by the modified Lentz method (Numerical Recipes §6.3). a < 1: E_1 by its power series
 * E_1(a) = −γ_E − ln a − Σ_{k≥1} (−a)^k/(k·k!), then the upward recurrence
 * E_{m+1}(a) = (e^{−a} − a E_m(a))/m, which loses nothing for a < 1. E_n(0) = 1/(n−1). */
SLUT_FN double slut_exp_expint(int n, double a) {
    if (a > SLUT_EXPINT_LEADING_ABOVE) return 1.0 / (a + SLUT_DOUBLE(n)); /* also a = +∞ */
    if (a >= 1.0) {
        double b = a + SLUT_DOUBLE(n), c = 1.0 / SLUT_TINY, d = 1.0 / b, h = d;
        for (int i = 1; i < SLUT_EXPINT_CF_MAX_ITER; ++i) {
            double an = -SLUT_DOUBLE(i) * (SLUT_DOUBLE(n - 1) + SLUT_DOUBLE(i));
            b += 2.0;
            d = 1.0 / (an * d + b);
            c = b + an / c;
            double del = c * d;
            h *= del;
            if (fabs(del - 1.0) < SLUT_CF_CONVERGED) break;
        }
        return h;
    }
    double ea = exp(a);
    double e_m; /* e^a E_m(a), starting at m = 1 */
    if (a <= 0.0) {
        if (n == 1) return SLUT_HUGE_VAL;
        return 1.0 / SLUT_DOUBLE(n - 1);
    }
    {
        double sum = 0.0, term = 1.0;
        for (int k = 1; k < SLUT_EXPINT_SERIES_MAX_TERMS; ++k) {
            term *= -a / SLUT_DOUBLE(k);     /* (−a)^k / k! */
            sum += term / SLUT_DOUBLE(k);
            if (fabs(term) < SLUT_SERIES_NEGLIGIBLE) break;
        }
        e_m = ea * (-0.57721566490153286061 - log(a) - sum);
    }
    for (int m = 1; m < n; ++m) e_m = (1.0 - a * e_m) / SLUT_DOUBLE(m);
    return e_m;
}

/* G̃ as w → 0 at fixed a = u·cot w. With y = τz in the integral above,
 *   G̃ = (tan w / w) ∫_0^∞ e^{−az} / ((1+z)² + tan² w) dz
 *     = (tan w / w) · [e^a E_2(a) − tan² w · e^a E_4(a) + O(w⁴)],
 * so the leading term is a function of a alone: the table needs no nodes below w_min.
 * Truncation error ≤ tan⁴w · e^aE_6(a) ≤ w⁴/5 (≤ 2e-13 at w = 1e-3). */
SLUT_FN double slut_gs_small_w(double w, double a) {
    double tw = tan(w);
    double ratio = (w > 0.0) ? tw / w : 1.0;
    return ratio * (slut_exp_expint(2, a) - tw * tw * slut_exp_expint(4, a));
}

/* G̃ for large u (Watson's lemma on ∫_0^∞ e^{−uy} f(y) dy with f(y) = 1/(1 + (τ+y)²)):
 * f^{(k)}(0) = (−1)^k k! Im[(τ − i)^{−(k+1)}] = (−1)^k k! cos^{k+1} v · sin((k+1) w), so
 *   G̃ = (1/w) Σ_k (−1)^k k! (sin w)^{k+1} sin((k+1) w) / u^{k+1}      (cos v = sin w)
 * an asymptotic series whose terms shrink by ≤ (k+1)/u: summed to its smallest term,
 * relative error ≲ 8!/u^8 ≈ 1e-10 at u = 48. Uniform in w. */
#define SLUT_GS_SERIES_TERMS 12
/* c_k(w) = (−1)^k k! (sin w)^{k+1} sin((k+1) w), k < SLUT_GS_SERIES_TERMS: w·G̃ ~ Σ_k c_k(w)/u^{k+1}.
 * sin((k+1) w) by the recurrence sin((k+1)w) = 2 cos w · sin(kw) − sin((k−1)w) (one sin and
 * one cos instead of twelve sines; the table generator calls this once per w node). Its
 * rounding error grows like the Chebyshev polynomials U_k(cos w), ≤ k²/6 ≈ 24 ulp of the
 * largest |sin(jw)| at k = 12: ~5e-15 of a coefficient whose term is a small correction. */
SLUT_FN void slut_gs_large_u_coefficients(double w, SLUT_OUT_ARRAY(double, c, SLUT_GS_SERIES_TERMS)) {
    double sw = sin(w), two_cos = 2.0 * cos(w), power = sw; /* k!·(sin w)^{k+1} */
    double sin_k = 0.0, sin_k1 = sw;                             /* sin(k w), sin((k + 1) w) */
    for (int k = 0; k < SLUT_GS_SERIES_TERMS; ++k) {
        double term = power * sin_k1;
        c[k] = ((k & 1) != 0) ? -term : term;
        power *= sw * SLUT_DOUBLE(k + 1);
        double next = two_cos * sin_k1 - sin_k;
        sin_k = sin_k1;
        sin_k1 = next;
    }
}

#ifdef SLUT_SHADER
/* The shaders' form: each c_k(w) formed as slut_gs_large_u_coefficients forms it (the same
 * operations in the same order), inside the summation loop instead of in a local array
 * (see slut_airlight_theta_node_pair, kernels/slut_airlight_theta.h). */
SLUT_FN double slut_gs_large_u(double u, double w) {
    double sw = sin(w), two_cos = 2.0 * cos(w), coefficient_power = sw;
    double sin_k = 0.0, sin_k1 = sw;
    double inv_u = 1.0 / u, power = inv_u, sum = 0.0, last = SLUT_HUGE_VAL;
    for (int k = 0; k < SLUT_GS_SERIES_TERMS; ++k) {
        double c_k = coefficient_power * sin_k1;
        c_k = ((k & 1) != 0) ? -c_k : c_k;
        coefficient_power *= sw * SLUT_DOUBLE(k + 1);
        double next = two_cos * sin_k1 - sin_k;
        sin_k = sin_k1;
        sin_k1 = next;
        double term = c_k * power;                        /* c_k(w)/u^{k+1} */
        if (fabs(term) > last && k > 2) break;            /* asymptotic: stop at the smallest */
        sum += term;
        last = fabs(term);
        power *= inv_u;
    }
    return sum / w;
}
#else
SLUT_FN double slut_gs_large_u(double u, double w) {
    double c[SLUT_GS_SERIES_TERMS];
    slut_gs_large_u_coefficients(w, c);
    double inv_u = 1.0 / u, power = inv_u, sum = 0.0, last = SLUT_HUGE_VAL;
    for (int k = 0; k < SLUT_GS_SERIES_TERMS; ++k) {
        double term = c[k] * power;                       /* c_k(w)/u^{k+1} */
        if (fabs(term) > last && k > 2) break;            /* asymptotic: stop at the smallest */
        sum += term;
        last = fabs(term);
        power *= inv_u;
    }
    return sum / w;
}
#endif /* SLUT_SHADER */

#ifndef SLUT_SHADER /* the generator's */
/* The same series at all SLUT_GS_SERIES_TERMS = 12 terms for every u ≥ slut_gs_series_u_min(w): Watson's
 * remainder is ≤ sup|f^{(12)}|/u^{13} ≤ 12! (sin w)^{13}/u^{13} (|τ + y + i| ≥ 1/sin w), and
 * w·G̃ ≥ 0.63 f(τ + 1/u)/u ≳ ½ sin² w/u, so the relative error is
 * ≤ 2·12! (sin w)^{11}/u^{12} ≤ 1e-16 there. (w = 1e-3: u ≥ 0.26; w = 0.1: u ≥ 15;
 * w = π/2: u ≥ 120.) The table generator uses it wherever the layer at ξ = v is too thin
 * for a quadrature rule to be cheap (kernels/airlight_F.cl). */
SLUT_FN double slut_gs_series_u_min(double w) {
    double sw = sin(w);
    /* (2·12!·sin^11 w / 1e-16)^{1/12}, 12! = 479001600 */
    return exp((log(2.0 * 479001600.0 / 1e-16) + 11.0 * log(sw)) / 12.0);
}
#endif /* !SLUT_SHADER */

/* Short intervals of the table sweep (kernels/airlight_F.cl): a rule Σ_n W_n e^{−u y_n}
 * with every node in [0, Δ] and u·Δ ≤ 2X (X = SLUT_GS_TAYLOR_X) needs one exponential,
 * not one per node. About the midpoint c = Δ/2, with x_n = u (y_n − c), |x_n| ≤ X, and
 * the Taylor polynomial of e^{−x} to K = SLUT_GS_TAYLOR_TERMS terms,
 *   Σ_n W_n e^{−u y_n} = e^{−u c} (Σ_{k<K} m_k u^k + R),  m_k = ((−1)^k / k!) Σ_n W_n (y_n − c)^k,
 *   |R| ≤ Σ_n W_n e^{|x_n|} |x_n|^K / K! ≤ e^{2X} (X^K / K!) Σ_n W_n e^{−x_n}
 * (Lagrange remainder; weights positive), so the relative error is
 * ≤ e·0.5^16/16! = 2.0e-18 at X = ½, K = 16. The host forms the moments once per interval;
 * the kernel needs e^{−u c} for the factor and its square e^{−u Δ} for the recurrence.
 * Horner in u: Σ_k |m_k| u^k ≤ e^X Σ W while the sum is ≥ e^{−X} Σ W, so the terms'
 * magnitudes add up to at most e times the result, and rounding stays at a few ulp. */
#define SLUT_GS_TAYLOR_TERMS 16
#define SLUT_GS_TAYLOR_X 0.5

#endif /* SLUT_AIRLIGHT_TAIL_H */
