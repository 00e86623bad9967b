/* scatterlut — the surface terms of Sun et al. 2005: the airlight a surface point receives.
 *
 * C99 / OpenCL C / C++ (double; no shader subset yet). docs/PHYSICS.md §1.5 has the
 * derivations. A surface point P in the medium, the light at distance D, T = σ_t D. The
 * airlight arriving at P from direction ω (an infinite ray from P) depends only on
 *
 *   γ = the angle between ω and the direction FROM P TO THE LIGHT   (γ = 0: towards the light)
 *
 * and is L_in = σ_s I0/(4π D) · A(T, γ) with
 *
 *   A(T, γ) sin γ = 2 e^{−T} w2 G̃(T sin γ, w2),   w2 = π/2 − γ/2       (G̃: slut_airlight.h)
 *
 * bounded (π e^{−T} at γ = 0, where A itself diverges like 1/γ). With θ the angle between
 * the surface normal (diffuse, n = 1) or the mirror direction ρ (Phong lobe of exponent n)
 * and the direction to the light,
 *
 *   G_n(T, θ) = ∫_0^π A(T, γ) sin γ · K_n(θ, γ) dγ,
 *   K_n(θ, γ) = ∫_0^{2π} max(cos θ cos γ + sin θ sin γ cos φ, 0)^n dφ,
 *
 * E_ss = σ_s I0/(4π D) · G_1(T, θ_s) and S_n = σ_s I0/(4π D) · G_n(T, θ_r) (both W/m²).
 */
#ifndef SLUT_SURFACE_H
#define SLUT_SURFACE_H

#include "slut_compat.h"
#include "slut_airlight.h"
#include "slut_surface_table.h" /* slut_ellint_2, slut_surface_G0_no_extinction */

#ifndef SLUT_SHADER /* double only */

#define SLUT_SURFACE_PI 3.14159265358979323846
/* The ₂F₁ series of slut_surface_kernel stops at a term below this fraction of its sum
 * (its ratio is < ½, so ≤ 60 terms). */
#define SLUT_SURFACE_SERIES_NEGLIGIBLE 1e-17
#define SLUT_SURFACE_SERIES_MAX_TERMS 80

/* A(T, γ) sin γ for T ≥ 0, γ ∈ [0, π] (clamped), by slut_w_gs_quadrature (~1e-13 relative).
 * 0 where e^{−T} underflows (T > ~745). */
SLUT_FN double slut_surface_incident_sin(double optical_distance, double gamma) {
    double g = slut_clamp(gamma, 0.0, SLUT_SURFACE_PI);
    double w2 = slut_pio2_minus(0.5 * g); /* > 0 even at g = π (π/2's low part) */
    double u = optical_distance * sin(g);
    double scale = exp(-optical_distance);
    if (scale <= 0.0) return 0.0;
    return 2.0 * scale * slut_w_gs_quadrature(u, w2, 1.0);
}

/* K_n(θ, γ) for an integer n ≥ 1, θ and γ in [0, π] (docs/PHYSICS.md §1.5), with
 * a = cos θ cos γ, b = sin θ sin γ ≥ 0 and b² − a² = −cos(θ + γ) cos(θ − γ):
 *  - b² − a² ≤ 0, a > 0: the whole ring of directions at γ lies inside max(·, 0): Legendre's
 *    n K_n = (2n − 1) a K_{n−1} + (n − 1)(b² − a²) K_{n−2} from K_0 = 2π, K_1 = 2π a, upwards
 *    (stable: the wanted solution dominates), in the form below that never forms b² − a²;
 *    b² − a² ≤ 0, a ≤ 0: K_n = 0;
 *  - b² − a² > 0, a ≥ 0: the ring crosses the edge at φ0 = acos(−a/b): the same recurrence
 *    from K_0 = 2φ0, K_1 = 2(a φ0 + √(b² − a²)) (every term positive);
 *  - b² − a² > 0, a < 0: only a cap of the ring counts; with c = a + b = (b² − a²)/(b − a),
 *    K_n = 2 B(n + 1, ½) c^{n+½} (2b)^{−½} ₂F₁(½, ½; n + 3/2; c/(2b)), c/(2b) < ½.
 * Never negative; underflows to 0 gracefully for large n far from the lobe. */
SLUT_FN double slut_surface_kernel(int n, double theta, double gamma) {
    double ct = cos(theta), st = sin(theta), cg = cos(gamma), sg = sin(gamma);
    double a = ct * cg, b = fmax(st * sg, 0.0);
    double d = -cos(theta + gamma) * cos(theta - gamma); /* b² − a² */
    if (b <= 0.0) d = fmin(d, 0.0); /* θ or γ at 0 or π: no crossing, whatever the rounding */
    if (d <= 0.0 && a <= 0.0) return 0.0;
    if (d > 0.0 && a < 0.0) {
        double c = d / (b - a); /* a + b without cancellation */
        double x = fmin(c / (2.0 * b), 0.5);
        double beta = 2.0; /* B(k + 1, ½), k = 0 */
        for (int k = 1; k <= n; ++k) beta *= SLUT_DOUBLE(k) / (SLUT_DOUBLE(k) + 0.5);
        double sum = 1.0, term = 1.0;
        for (int k = 0; k < SLUT_SURFACE_SERIES_MAX_TERMS; ++k) {
            double h = SLUT_DOUBLE(k) + 0.5;
            term *= h * h / ((SLUT_DOUBLE(n) + 1.5 + SLUT_DOUBLE(k)) * SLUT_DOUBLE(k + 1)) * x;
            sum += term;
            if (term < SLUT_SURFACE_SERIES_NEGLIGIBLE * sum) break;
        }
        return 2.0 * beta * exp((SLUT_DOUBLE(n) + 0.5) * log(c)) * sum / sqrt(2.0 * b);
    }
    if (d <= 0.0) {
        /* The whole ring: K_n/(2π) = a^n + f_n with f_n = a^n e_n the part due to b. Written this
         * way the recurrence needs a² and b² but never their difference, whose rounding (eps·a²)
         * K_n would amplify by ~n²/4 where b ≪ a/n (2.5e-11 at n = 1000); substituting
         * K_n/(2π) = a^n (1 + e_n) into it, the constant parts cancel exactly:
         *   n f_n = (2n − 1) a f_{n−1} − (n − 1) a² f_{n−2} + (n − 1) b² (a^{n−2} + f_{n−2}). */
        double a2 = a * a, b2 = b * b;
        double g_prev = 1.0, g_cur = a, f_prev = 0.0, f_cur = 0.0; /* a^{k−2}, a^{k−1}, f_{k−2}, f_{k−1} */
        for (int k = 2; k <= n; ++k) {
            double f_next = (SLUT_DOUBLE(2 * k - 1) * a * f_cur - SLUT_DOUBLE(k - 1) * a2 * f_prev +
                             SLUT_DOUBLE(k - 1) * b2 * (g_prev + f_prev)) / SLUT_DOUBLE(k);
            f_prev = f_cur;
            f_cur = f_next;
            g_prev = g_cur;
            g_cur *= a;
        }
        return 2.0 * SLUT_SURFACE_PI * fmax(g_cur + f_cur, 0.0);
    }
    {
        double phi0 = acos(slut_clamp(-a / b, -1.0, 1.0));
        double k_prev = 2.0 * phi0, k_cur = 2.0 * (a * phi0 + sqrt(d));
        for (int k = 2; k <= n; ++k) {
            double next = (SLUT_DOUBLE(2 * k - 1) * a * k_cur + SLUT_DOUBLE(k - 1) * d * k_prev) / SLUT_DOUBLE(k);
            k_prev = k_cur;
            k_cur = next;
        }
        return fmax(k_cur, 0.0);
    }
}

/* The integrand of G_n in γ: A(T, γ) sin γ · K_n(θ, γ). */
SLUT_FN double slut_surface_integrand(int n, double optical_distance, double theta, double gamma) {
    double k = slut_surface_kernel(n, theta, gamma);
    if (k <= 0.0) return 0.0;
    return slut_surface_incident_sin(optical_distance, gamma) * k;
}

/* ------------------------------------------------ G_n by a fixed composite rule (the generator's) */

/* The most break points slut_surface_break_points returns (11 candidates and π once more). */
#define SLUT_SURFACE_MAX_BREAKS 12

/* The break points of G_n's integrand in γ ∈ [0, π] into b[] (ascending, from 0, ending at π,
 * neighbours more than 1e-12 apart; returns their count ≤ SLUT_SURFACE_MAX_BREAKS), where it
 * changes form or scale (docs/PHYSICS.md §1.5):
 *  - γ_1 = |π/2 − θ| and π − γ_1: the ring of directions at γ starts / stops crossing the
 *    horizon of the normal or lobe axis (K_n's kinks);
 *  - n > 1: the lobe at γ = θ and θ ± 4/√n, θ ± 12/√n (K_n ∝ cos^n, width 1/√n);
 *  - T > 1: 1/T and 8/T, where A sin γ falls from its γ = 0 value (scale 1/T).
 * The adaptive quadrature of tables/src/surface.cpp and the fixed rule below share them. */
SLUT_FN int slut_surface_break_points(int n, double optical_distance, double theta, double *b) {
    double cand[11];
    int count = 0, kept = 0;
    double g1 = fabs(0.5 * SLUT_SURFACE_PI - theta);
    cand[count++] = 0.0;
    cand[count++] = SLUT_SURFACE_PI;
    cand[count++] = g1;
    cand[count++] = SLUT_SURFACE_PI - g1;
    if (n > 1) {
        double width = 1.0 / sqrt(SLUT_DOUBLE(n));
        cand[count++] = theta;
        cand[count++] = theta - 4.0 * width;
        cand[count++] = theta + 4.0 * width;
        cand[count++] = theta - 12.0 * width;
        cand[count++] = theta + 12.0 * width;
    }
    if (optical_distance > 1.0) { /* A sin γ varies on the scale 1/T near γ = 0 */
        cand[count++] = 1.0 / optical_distance;
        cand[count++] = 8.0 / optical_distance;
    }
    /* Those in [0, π], sorted (insertion sort: at most 11), without near-duplicates. */
    double sorted[11];
    int m = 0;
    for (int i = 0; i < count; ++i) {
        double x = cand[i];
        if (!(x >= 0.0 && x <= SLUT_SURFACE_PI)) continue;
        int j = m++;
        while (j > 0 && sorted[j - 1] > x) {
            sorted[j] = sorted[j - 1];
            --j;
        }
        sorted[j] = x;
    }
    for (int i = 0; i < m; ++i)
        if (kept == 0 || sorted[i] - b[kept - 1] > 1e-12) b[kept++] = sorted[i];
    if (b[kept - 1] < SLUT_SURFACE_PI) b[kept++] = SLUT_SURFACE_PI;
    return kept;
}

/* The fixed rule's panel count per interval between break points (slut_surface_G_fixed) for a
 * relative tolerance on G_n. Measured against the adaptive quadrature (surface_G_exact, ~1e-10)
 * at n ∈ {1, 2, 20, 50, 200, 1000}, T ∈ [0, 300] (11 values), 25 θ ∈ [0, π]: the largest
 * relative error is 3.5e-6 with 1 panel, 6.1e-9 with 2, 2.8e-10 with 3, 8.9e-11 with 4,
 * 1.8e-11 with 6, 5.5e-12 with 8 (tests/kernels/test_surface_fixed_rule.cpp checks 4). */
SLUT_FN int slut_surface_subpanels_for_tolerance(double tolerance) {
    if (tolerance >= 1e-5) return 1;
    if (tolerance >= 1e-8) return 2;
    if (tolerance >= 5e-10) return 3;
    if (tolerance >= 1e-10) return 4;
    if (tolerance >= 3e-11) return 6;
    return 8;
}

/* G_n(T, θ) = ∫_0^π A(T, γ) sin γ K_n(θ, γ) dγ (n ≥ 1, T ≥ 0, θ ∈ [0, π]) by a fixed composite
 * rule: every interval [γ_i, γ_{i+1}] between slut_surface_break_points is taken in t ∈ [0, 1]
 * with γ = γ_i + (γ_{i+1} − γ_i)(3t² − 2t³) (dγ = 6 t (1 − t) dt · length), cut into `subpanels`
 * equal panels of 16-point Gauss–Legendre (slut_gl16_x/w). The substitution's derivative
 * vanishes at both ends, which is where the integrand is not smooth: A sin γ behaves like
 * c + γ ln γ at γ = 0 (A itself like 1/γ), and K_n like (γ − γ_k)^{3/2} where the ring of
 * directions starts or stops crossing the horizon (γ_k = |π/2 − θ|, π − |π/2 − θ|). Never
 * negative, never NaN. */
SLUT_FN double slut_surface_G_fixed(int n, double optical_distance, double theta, int subpanels) {
    double b[SLUT_SURFACE_MAX_BREAKS];
    double th = slut_clamp(theta, 0.0, SLUT_SURFACE_PI);
    int nb = slut_surface_break_points(n, optical_distance, th, b);
    double sum = 0.0, panel = 1.0 / SLUT_DOUBLE(subpanels);
    for (int i = 0; i + 1 < nb; ++i) {
        double lo = b[i], length = b[i + 1] - b[i];
        for (int p = 0; p < subpanels; ++p) {
            double half_len = 0.5 * panel, mid = panel * SLUT_DOUBLE(p) + half_len, part = 0.0;
            for (int k = 0; k < 16; ++k) {
                double t = mid + half_len * ((k < 8) ? -slut_gl16_x[k] : slut_gl16_x[k - 8]);
                double weight = slut_gl16_w[(k < 8) ? k : k - 8];
                double gamma = lo + length * t * t * (3.0 - 2.0 * t);
                part += weight * slut_surface_integrand(n, optical_distance, th, gamma) * 6.0 * t * (1.0 - t);
            }
            sum += half_len * length * part;
        }
    }
    return fmax(sum, 0.0);
}

#endif /* !SLUT_SHADER */

#endif /* SLUT_SURFACE_H */
