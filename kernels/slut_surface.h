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

#endif /* !SLUT_SHADER */

#endif /* SLUT_SURFACE_H */
