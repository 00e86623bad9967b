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
 */
#ifndef SLUT_AIRLIGHT_H
#define SLUT_AIRLIGHT_H

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
 * the θ-integral's rule where the radiance needs only a table's accuracy (see below). */
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
 * (see slut_airlight_theta_node_pair). */
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
 * folds e^{−σ_t D} into the exponentials it evaluates anyway (tables/src/airlight.cpp). */
/* Its formulas of the triangle viewer–light–far end, as lane-generic expressions (as
 * SLUT_AIRLIGHT_THETA_FITS_ONE_PANEL below): the runtime's vector paths evaluate them on
 * 4-lane vectors (tables/src/airlight.cpp, near_end). sh, ch = sin(γ/2), cos(γ/2); s, D in m.
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

/* ∫_0^{dv} exp(−c sin θ / sin(w2 − θ)) dθ, 0 ≤ dv ≤ w2 ≤ π/2: the bracket of the airlight
 * with ξ = v2 + θ (A1 (tan ξ − tan v2) = c sin θ / sin(w2 − θ)). The integrand is 1 at
 * θ = 0, decreasing and log-concave, with an essential singularity at the pole θ = w2.
 * Panels are placed by the distance δ to the pole (kept exactly, never as w2 − θ):
 * length ≤ δ/4 (pole outside the Bernstein ellipse, ρ_B ≥ 9.9) and ≤ 4/λ with
 * λ = c sin w2 / sin² δ the local decay rate. Stops when the log-concave remainder bound
 * f/λ drops below 1e-17 of the sum. Relative error ~1e-14 with 16 points per panel
 * (gl16 = 1). With 8 points (gl16 = 0, half the work) the same panels give: pole
 * ρ_B^{−16} ≤ 1.2e-16; decay, the n-point Gauss remainder of e^{−λθ} over λh ≤ 4,
 * (λh)^{2n} (n!)⁴/((2n + 1)((2n)!)³) ≤ 7e-14 at n = 8: ~1e-13 relative (≤ 1e-11 against
 * the Boost reference in tests/runtime/test_airlight_table, EightPointThetaRuleMatchesDirectQuadrature),
 * far below any table's error (the table radiance's tolerance there is 1e-3). */
#ifdef SLUT_SHADER
/* The shaders' form of one θ-panel's Gauss sum (below): the same node, weight, integrand and
 * order of additions, written out per node with constant array indices. SwiftShader
 * evidently keeps a constant array read with a variable index (and a local array) in per-lane
 * memory: the three array forms of the pixel's path cost 1.15–1.4× its frame there, none on
 * llvmpipe (bench/README.md, "SwiftShader"). With constant indices the nodes and weights are
 * constants. */
SLUT_FN double slut_airlight_theta_node_pair(double c, double st, double ct, double sd, double cd, double half_len,
                                             double node, double weight, double part) {
    double t = half_len + (-1.0) * half_len * node;
    part += weight * exp(-c * (st + t * ct) / (sd - t * cd)) / (1.0 + t * t);
    t = half_len + 1.0 * half_len * node;
    return part + weight * exp(-c * (st + t * ct) / (sd - t * cd)) / (1.0 + t * t);
}
#endif
SLUT_FN double slut_airlight_theta_integral_rule(double c, double w2, double dv, int gl16) {
    if (dv <= 0.0) return 0.0;
    if (c <= 0.0) return dv;
    int half_points = (gl16 != 0) ? 8 : 4;
    double sin_w2 = sin(w2);
    double delta = w2;            /* distance from the panel start to the pole */
    double remaining = dv;        /* distance from the panel start to the end */
    double sum = 0.0;
    for (int panel = 0; panel < SLUT_THETA_MAX_PANELS && remaining > 0.0; ++panel) {
        double theta = dv - remaining;
        double sd = sin(delta), cd = cos(delta), st = sin(theta), ct = cos(theta);
        double rate = c * sin_w2 / (sd * sd);
        double f_start = exp(-c * st / sd);
        if (panel > 0 && f_start <= SLUT_REMAINDER_NEGLIGIBLE * sum * rate) break;
        double h = fmin(remaining, fmin(0.25 * delta, 4.0 / rate));
        /* The panel in t = tan x, x = θ − theta ∈ [0, h]: dividing by cos x,
         *   sin(theta + x)/sin(delta − x) = (st + t ct)/(sd − t cd),  dθ = dt/(1 + t²),
         * so the nodes need no sine (the same integral: the rule's nodes move, its bounds hold,
         * as h ≤ π/8 keeps tan on the panel within 5 % of linear and the poles of 1/(1 + t²)
         * at ±i ≥ 2.4 panel lengths away: Bernstein ρ ≥ 9.8). */
        double half_len = 0.5 * tan(h), part = 0.0;
#ifdef SLUT_SHADER
        if (gl16 == 0) {
            part = slut_airlight_theta_node_pair(c, st, ct, sd, cd, half_len, slut_gl8_x[0], slut_gl8_w[0], part);
            part = slut_airlight_theta_node_pair(c, st, ct, sd, cd, half_len, slut_gl8_x[1], slut_gl8_w[1], part);
            part = slut_airlight_theta_node_pair(c, st, ct, sd, cd, half_len, slut_gl8_x[2], slut_gl8_w[2], part);
            part = slut_airlight_theta_node_pair(c, st, ct, sd, cd, half_len, slut_gl8_x[3], slut_gl8_w[3], part);
            half_points = 0; /* done: the loop below is the 16-point rule's */
        }
#endif
        for (int k = 0; k < half_points; ++k) {
            double node = (gl16 != 0) ? slut_gl16_x[k] : slut_gl8_x[k];
            double weight = (gl16 != 0) ? slut_gl16_w[k] : slut_gl8_w[k];
            for (int side = -1; side <= 1; side += 2) {
                double t = half_len + SLUT_DOUBLE(side) * half_len * node;
                part += weight * exp(-c * (st + t * ct) / (sd - t * cd)) / (1.0 + t * t);
            }
        }
        sum += half_len * part;
        remaining -= h;
        delta -= h;
    }
    return sum;
}
SLUT_FN double slut_airlight_theta_integral(double c, double w2, double dv) {
    return slut_airlight_theta_integral_rule(c, w2, dv, 1);
}

/* 6-point Gauss–Legendre on [−1, 1] (the positive nodes and weights, mpmath to 21 digits). */
SLUT_CONST_ARRAY3(slut_gl6_x, 0.238619186083196908631, 0.661209386466264513661, 0.932469514203152027812);
SLUT_CONST_ARRAY3(slut_gl6_w, 0.467913934572691047390, 0.360761573048138607570, 0.171324492379170345040);

/* The θ-integral of a segment short enough for one panel of slut_airlight_theta_integral_rule
 * (its first panel's bounds, with tan dv ≥ dv in place of dv: tan dv ≤ w2/4 and
 * λ·tan dv ≤ 4, λ = c/sin w2 the decay rate at θ = 0), in the variable t = tan θ:
 *   sin θ/sin(w2 − θ) = t/(sin w2 − t cos w2),  dθ = dt/(1 + t²),
 *   ∫_0^{dv} e^{−c sin θ/sin(w2 − θ)} dθ = ∫_0^{tan dv} e^{−c t/(sin w2 − t cos w2)} dt/(1 + t²),
 * an algebraic integrand (one divide and one exp per node, no sine) whose singularities stay
 * where the θ-rule's bounds keep them: the exponent's pole at t = tan w2 ≥ 4 tan dv, the
 * poles of 1/(1 + t²) at ±i, |i| ≥ 1/(π/8) times the panel. 6 points: the decay part of the
 * Gauss remainder for λh ≤ 4 is ≤ 3e-9 (the bound quoted at the θ-rule), the poles
 * ρ_B^{−12} ≤ 1e-12; measured ≤ 8e-12 against slut_airlight_theta_integral on 20000 of the
 * bench's geometries and 1.3e-12 against Boost.Math on the 384 of 400 test geometries that
 * fit (tests/runtime/test_airlight_table, OnePanelThetaRuleMatchesDirectQuadrature; tolerance 1e-9). sin w2 = cos(γ/2), cos w2 = sin(γ/2). */
/* The test on the plain numbers, t = tan dv, w2 (rad), c = 2 σ_t D sin(γ/2) and ch = cos(γ/2),
 * as a lane-generic expression (as slut_axes.h's SLUT_WARP_X): a scalar's is a truth value,
 * the runtime's 4-lane vectors' a lane mask (GCC's && on vectors; both sides evaluated); the
 * runtime's fast paths (tables/src/airlight.cpp) test their plain numbers with it. One line:
 * GLSL before 4.20 has no line continuation. */
#define SLUT_AIRLIGHT_THETA_FITS_ONE_PANEL(t, w2, c, ch) ((t) <= 0.25 * (w2) && (c) * (t) <= 4.0 * (ch))
/* The same for a set-up geometry: kind 0 (a finite segment to integrate) and the test above. */
SLUT_FN int slut_airlight_theta_fits_one_panel(slut_airlight_geometry g) {
    return (g.kind == 0 && SLUT_AIRLIGHT_THETA_FITS_ONE_PANEL(g.tan_dv, g.w2, g.c, g.cos_half)) ? 1 : 0;
}
#ifdef SLUT_SHADER
/* The shaders' form of slut_airlight_theta_integral_one_panel below: the same nodes, weights
 * and order of additions, one node at a time with constant array indices (no local arrays,
 * no variable index: see slut_airlight_theta_node_pair). */
SLUT_FN double slut_airlight_theta_one_panel_node(double c, double sin_w2, double cos_w2, double half_len, double x,
                                                  double weight, double sum) {
    double t = half_len * (1.0 + x);
    return sum + (weight / (1.0 + t * t)) * exp(-c * t / (sin_w2 - t * cos_w2));
}
SLUT_FN double slut_airlight_theta_integral_one_panel(double c, double sin_w2, double cos_w2, double tan_dv) {
    double half_len = 0.5 * tan_dv, sum = 0.0;
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, -slut_gl6_x[0], slut_gl6_w[0], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, -slut_gl6_x[1], slut_gl6_w[1], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, -slut_gl6_x[2], slut_gl6_w[2], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, slut_gl6_x[0], slut_gl6_w[0], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, slut_gl6_x[1], slut_gl6_w[1], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, slut_gl6_x[2], slut_gl6_w[2], sum);
    return half_len * sum;
}
#else
SLUT_FN double slut_airlight_theta_integral_one_panel(double c, double sin_w2, double cos_w2, double tan_dv) {
    /* The exponents first, then the exps, then the sum: the six divides and the six exp
     * calls are independent and overlap (a loop of exp-then-divide serialises on them). */
    double half_len = 0.5 * tan_dv, sum = 0.0;
    double exponent[6];
    double weight[6];
    for (int k = 0; k < 6; ++k) {
        double x = (k < 3) ? -slut_gl6_x[k] : slut_gl6_x[k - 3];
        double t = half_len * (1.0 + x);
        exponent[k] = -c * t / (sin_w2 - t * cos_w2);
        weight[k] = slut_gl6_w[k < 3 ? k : k - 3] / (1.0 + t * t);
    }
    for (int k = 0; k < 6; ++k) exponent[k] = exp(exponent[k]);
    for (int k = 0; k < 6; ++k) sum += weight[k] * exponent[k];
    return half_len * sum;
}
#endif /* SLUT_SHADER */

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
 * an absolute one on F). There F is integrated directly: it is the θ-integral above with
 * w2 = π/2, c = u (c sin θ/sin(π/2 − θ) = u tan θ), 8 points per panel, ~1e-13 relative,
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
 * to the table's own accuracy (see the error bounds above). */
#define SLUT_GS_TABLE 0
#define SLUT_GS_LARGE_U 1
#define SLUT_GS_SMALL_W 2
SLUT_FN int slut_gs_regime(double u, double w, double u_max, double w_min) {
    if (u > u_max) return SLUT_GS_LARGE_U;
    if (w < w_min) return SLUT_GS_SMALL_W;
    return SLUT_GS_TABLE;
}

#endif /* SLUT_AIRLIGHT_H */
