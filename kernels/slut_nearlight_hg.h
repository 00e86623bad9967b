/* scatterlut — the near-light integral of Gath 2008 with a Henyey–Greenstein phase, written once.
 *
 * Geometry, symbols and the isotropic integral: kernels/slut_nearlight.h and docs/PHYSICS.md
 * §1.2; the phase: docs/PHYSICS.md §1.4. The point at depth x is P(x) = O − xω, the light
 * sits at O + l ω_l, so the light propagates along (P − light)/h = −(xω + lω_l)/h and the
 * direction from P to the viewer is ω:
 *
 *   cos θ(x) = −(x + l g)/h(x),   g = ω·ω_l (the near-light g, NOT the phase's asymmetry),
 *
 * in optical units cos θ = −δ/η with δ = τ + g, η = √(δ² + 1 − g²) (τ = t/T, units of T).
 * The phase varies along the ray, so it enters under the integral:
 *
 *   N_g(T, g, r, S) = ∫_0^S ψ_{g_hg}(θ(t)) exp(−t − ĥ(t) t/(t + T r)) / ĥ(t)² dt,
 *   E_g = N_g / H(T, g, S)  ∈ (0, ψ_max],      L = σ_s/(4π)·I0·E_g·(T·H)/l,
 *
 * ψ = 4π p_{g_hg} (kernels/slut_phase.h), H the closed form of slut_nl_H. E_g is the
 * ĥ^{−2}-weighted mean of ψ·attenuation (E_0 = E). The half angles come without
 * cancellation: sin²(θ/2) = (η + δ)/(2η), cos²(θ/2) = (η − δ)/(2η), and the one of η ± δ
 * that would cancel is (1 − g²)/(η ∓ δ).
 *
 * r = 0 is the airlight with D = l, cos γ = −g and the same g_hg (cos θ = (D cos γ − x)/d
 * there): σ_t N_g(σ_t D, −cos γ, 0, σ_t s) = (4π/(σ_s I0))·L_airlight,g.
 *
 * C99/OpenCL C compatible, double precision; used by the runtime library and the tests; and
 * whole, in float, by the anisotropic near-light GPU snippet (docs/SHADERS.md): the phase at a
 * point and the tables' divisors are in the shared subset of kernels/slut_compat.h, the
 * quadratures (pointer arguments, double only) sit in `#ifndef SLUT_SHADER` blocks.
 */
#ifndef SLUT_NEARLIGHT_HG_H
#define SLUT_NEARLIGHT_HG_H

#include "slut_compat.h"
#include "slut_phase.h"
#include "slut_nearlight.h" /* slut_nl_H_scaled, slut_nl_inv_square_integral; slut_gl16_x/w */
#include "slut_phase_arc.h" /* the thin-medium form: the phase's mean over the path's arc */

#define SLUT_HG_NL_ELLIPSE 2.0   /* min (dist(a) + dist(b))/(b − a) for the poles of 1/η² */
#define SLUT_HG_NL_EFOLDS 12.0   /* max e-folds of the exponent per panel                */
#define SLUT_HG_NL_TAIL_EPS 1e-17 /* stop once the remainder bound is below this × sum   */
#define SLUT_HG_NL_MAX_PANELS 4096

/* ψ_{g_hg}(θ) at offset δ = τ + g, η = √(δ² + sg2), sg2 = 1 − g² (η > 0). */
SLUT_FN double slut_hg_nl_psi(double phase_g, double dl, double eta, double sg2) {
    double s2, c2;
    if (dl >= 0.0) {
        s2 = (eta + dl) / (2.0 * eta);
        c2 = sg2 / (eta + dl) / (2.0 * eta);
    } else {
        c2 = (eta - dl) / (2.0 * eta);
        s2 = sg2 / (eta - dl) / (2.0 * eta);
    }
    return slut_hg_psi_half(phase_g, s2, c2);
}

/* The phase's factor of the thin-medium form (Gath 2008 §4.2 with the phase): without
 * attenuation E_g is the ĥ⁻²-weighted mean of ψ over the path, and ĥ⁻² dτ = dθ/√(1 − g²) makes
 * that the plain mean of ψ over the scattering angles the path sweeps,
 *   E_g(T = 0) = M_{phase_g}(θ(0), θ(s/l)),   θ(τ) = atan2(√(1 − g²), −(τ + g)),
 * from θ(0) = acos(−g) at the entry point to π for a thick medium (S_over_T = s/l > 1e300).
 * The thin form is the isotropic one times this (near_light_radiance_thin(q, phase_g), the
 * snippet's slut_near_light_hg_radiance_thin): exact as σ_t s → 0.
 * kernels/slut_phase_arc.h's fixed rule: within 1e-13 of slut_hg_nl_E(0, g, r, s/l) in double
 * (measured: tests/kernels/test_anisotropic.cpp, ThinPhaseMeanMatchesTheQuadrature). */
SLUT_FN double slut_hg_nl_thin_psi_mean(double phase_g, double g, double S_over_T) {
    g = slut_clamp(g, -1.0, 1.0);
    double sg = sqrt((1.0 - fabs(g)) * (1.0 + fabs(g)));
    double theta0 = atan2(sg, -g);
    double theta1 = (S_over_T > SLUT_INFINITE_ABOVE) ? SLUT_PI : atan2(sg, -(S_over_T + g));
    return slut_hg_psi_arc_mean(phase_g, theta0, fmax(theta1, theta0));
}

/* The phase's factor of the distant-light form (Gath 2008 eq. 5 with the phase): the light's
 * rays taken parallel over the path, θ is the one angle at the entry point, cos θ = −g, and the
 * isotropic form is multiplied by ψ(θ) (near_light_radiance_distant(q, phase_g), the snippet's
 * slut_near_light_hg_radiance_distant). Exact as l → ∞. */
SLUT_FN double slut_hg_nl_distant_psi(double phase_g, double g) {
    g = slut_clamp(g, -1.0, 1.0);
    return slut_hg_nl_psi(phase_g, g, 1.0, (1.0 - fabs(g)) * (1.0 + fabs(g)));
}

#ifndef SLUT_SHADER /* the quadrature: the generator's, the runtime's and the tests' (double only) */
/* E_g at n ascending slab depths in one march (the 4-D table's S nodes at one (T, g, r); one
 * depth: the march of slut_hg_nl_E below, whose rules it follows):
 * S_over_T[k] = S_k/T, 0 < S_0 ≤ … ≤ S_{n−1} (the last may be > 1e300: thick). The panels of
 * slut_hg_nl_E (below), each also cut at every S_k; the raw sum N_g·T is recorded at each S_k and
 * divided by H there. The tail rule is slut_hg_nl_E's to the last depth: once it stops the
 * march, the depths not reached take the sum at the stop (their remainder is a part of the
 * bounded one). Not for g = −1 with S ≥ T (the caller uses slut_hg_nl_E there). */
SLUT_FN void slut_hg_nl_E_sweep(double T, double g, double r, const double *S_over_T, int n, double phase_g,
                                double refine, double *E_out) {
    g = slut_clamp(g, -1.0, 1.0);
    double sg2 = (1.0 - fabs(g)) * (1.0 + fabs(g)), sg = sqrt(sg2);
    double tau_end = (S_over_T[n - 1] > 1e300) ? SLUT_HUGE_VAL : S_over_T[n - 1];
    int finite_S = !(tau_end > 1e300);
    int r_inf = !(r <= 1e300);
    double A = 1.0 + (SLUT_HG_NL_ELLIPSE - 1.0) * refine;
    double efolds = SLUT_HG_NL_EFOLDS / refine;
    double tail_eps = SLUT_HG_NL_TAIL_EPS / pow(refine, 15.0);
    double psi_back = slut_hg_psi_backward(phase_g);
    double tau = 0.0, dl = g, d_end = tau_end + g, sum = 0.0;
    int carry_d = 0, next = 0;
    for (int panel = 0; panel < SLUT_HG_NL_MAX_PANELS && next < n; ++panel) {
        if (!carry_d && g < 0.0 && tau >= -0.5 * g) carry_d = 1;
        double eta2 = dl * dl + sg2, eta = sqrt(eta2);
        if (panel > 0) {
            double q0 = r_inf ? 0.0 : ((r > 0.0) ? tau / (tau + r) : 1.0);
            double attenuation = exp(-T * (tau + eta * q0));
            double psi_rest = (phase_g >= 0.0) ? slut_hg_nl_psi(phase_g, dl, eta, sg2) : psi_back;
            double len = finite_S ? (carry_d ? d_end - dl : tau_end - tau) : SLUT_HUGE_VAL;
            double rest = slut_nl_inv_square_integral(len, eta2, dl, sg);
            if (dl >= 0.0 && T > 0.0) rest = fmin(rest, 1.0 / (T * eta2));
            if (attenuation * psi_rest * rest <= tail_eps * sum) break;
        }
        double h = 2.0 * (A * eta + dl) / (A * A - 1.0);
        double k_rate = (r > 0.0 && !r_inf) ? r / ((tau + r) * (tau + r)) : 0.0;
        if (r > 0.0 && !r_inf && T * r * fmax(eta / (tau + r), 1.0) > 1e-17) h = fmin(h, 2.0 * (tau + r) / (A - 1.0));
        if (T > 0.0) {
            double L = efolds / T, B = 2.0 + 2.0 * eta * k_rate;
            h = fmin(h, (2.0 * L / B) / (1.0 + sqrt(1.0 + (8.0 * L / B) * (k_rate / B))));
        }
        if (!(h > 0.0)) break;
        int at_node = 0;
        if (S_over_T[next] <= 1e300) {
            double remaining = carry_d ? (S_over_T[next] + g) - dl : S_over_T[next] - tau;
            if (h >= remaining) {
                h = fmax(remaining, 0.0);
                at_node = 1;
            }
        }
        double half_len = 0.5 * h, part = 0.0;
        for (int k = 0; k < 16; ++k) {
            double x = (k < 8) ? -slut_gl16_x[k] : slut_gl16_x[k - 8];
            double off = half_len + half_len * x;
            double tn = carry_d ? (dl + off) - g : tau + off;
            double dn = carry_d ? dl + off : tn + g;
            double en2 = dn * dn + sg2, en = sqrt(en2);
            double q = r_inf ? 0.0 : ((r > 0.0) ? tn / (tn + r) : 1.0);
            part += slut_gl16_w[(k < 8) ? k : k - 8] * slut_hg_nl_psi(phase_g, dn, en, sg2) *
                    exp(-T * (tn + en * q)) / en2;
        }
        sum += half_len * part;
        if (at_node) { /* land exactly on the node */
            double S_node = S_over_T[next];
            if (carry_d) {
                dl = S_node + g;
                tau = dl - g;
            } else {
                tau = S_node;
                dl = tau + g;
            }
            while (next < n && S_over_T[next] <= S_node) {
                E_out[next] = sum / slut_nl_H_scaled(g, S_over_T[next]);
                ++next;
            }
        } else if (carry_d) {
            dl += h;
            tau = dl - g;
        } else {
            tau += h;
            dl = tau + g;
        }
    }
    for (; next < n; ++next) E_out[next] = sum / slut_nl_H_scaled(g, (S_over_T[next] > 1e300) ? SLUT_HUGE_VAL : S_over_T[next]);
}

/* E_g(T, g, r, S) by composite 16-point Gauss–Legendre in τ = t/T, with the lengths given as
 * S/T (S_over_T > 1e300: a thick medium), so that T = 0 (σ_t → 0: E_g is then the
 * ĥ^{−2}-weighted mean of ψ alone) needs no special case.
 *
 * Panels: the rules of slut_nl_panel_length, restated here for one r:
 *  1. the poles of 1/η² at δ = ±i√(1 − g²) (Bernstein ellipse, A = 2): h ≤ 2(Aη + δ)/(A² − 1);
 *  2. the essential singularity of the layer at τ = −r, where it matters
 *     (T r max(η/(τ + r), 1) > 1e-17): h ≤ 2(τ + r)/(A − 1);
 *  3. decay: T h (2 + 2(η + h) k) ≤ 12 e-folds, k = r/(τ + r)².
 * The phase adds no closer singularity: 1 + g_hg² + 2g_hg δ/η = 0 at δ = ±i√(1 − g²)(1 + g_hg²)/(1 − g_hg²),
 * always farther from the real axis than η's poles, and its forward peak (θ → 0, reached
 * for δ → −∞ before the light's foot point) varies on the scale |δ| that rule 1 resolves.
 * Stop once a(τ)·ψ_rest·rest ≤ 1e-17 of the sum, a the attenuation (non-increasing along the
 * ray), ψ_rest = ψ at τ for g_hg ≥ 0 (θ grows along the ray) and ψ(π) for g_hg < 0, rest =
 * ∫_τ^end η^{−2} (closed form) or, past the foot point (δ ≥ 0, where the exponent's slope is
 * ≥ T), 1/(T η²). Near the peak (g < 0, τ ≥ −g/2) the march carries δ instead of τ (exact
 * offsets from the foot point). refine > 1: A → 1 + (A − 1) refine and 12 → 12/refine, a finer
 * independent mesh. Special cases: S = 0: ψ(θ(0))·(e^{−T} for r = 0, else 1); g = −1 with
 * S ≥ T (the ray runs through the light): ψ_g(0)·e^{−T} (the weight gathers at the light,
 * reached with θ = 0). */
SLUT_FN double slut_hg_nl_E(double T, double g, double r, double S_over_T, double phase_g, double refine) {
    g = slut_clamp(g, -1.0, 1.0);
    double sg2 = (1.0 - fabs(g)) * (1.0 + fabs(g));
    double tau_end = (S_over_T > 1e300) ? SLUT_HUGE_VAL : S_over_T;
    if (!(tau_end > 0.0)) return slut_hg_nl_psi(phase_g, g, 1.0, sg2) * ((r > 0.0) ? 1.0 : exp(-T));
    if (sg2 == 0.0 && g < 0.0 && tau_end >= 1.0) return slut_hg_psi_forward(phase_g) * exp(-T);
    double E;
    slut_hg_nl_E_sweep(T, g, r, &tau_end, 1, phase_g, refine, &E);
    return E;
}

#endif /* !SLUT_SHADER */

/* The divisor D(T, g) of the anisotropic near-light tables (kernels/nearlight_Eg.cl stores
 * ln(E_g/D), the runtime multiplies by it). ψ0 = ψ(θ(0)), cos θ(0) = −g, the phase at the entry
 * point, carries E_g's sharp dependence on g near the phase's peak once the attenuation gathers
 * at the entry point (E_g → ψ0·E as T grows); for small T, E_g is the mean of ψ over a long
 * path and smooth in g. θ grows along the ray, so:
 *  - g_hg ≥ 0 (ψ falls along the ray): E_g ≤ ψ0·E, D = ψ0;
 *  - g_hg < 0 (ψ rises along the ray towards ψ_max = ψ(π)): E_g ≤ ψ_max·E, D = ψ_max·(ψ0/ψ_min)^w
 *    with w = 1 − e^{−T} (ψ_max at small T, ψ0 times a constant at large T; ≥ ψ_max).
 * E_g/D ≤ E: the stored values have the isotropic tables' ranges (ln ≤ 0 thick; ln(·/B) ≤ T slab). */
SLUT_FN double slut_hg_nl_table_divisor(double phase_g, double T, double g) {
    g = slut_clamp(g, -1.0, 1.0);
    double sg2 = (1.0 - fabs(g)) * (1.0 + fabs(g));
    double psi0 = slut_hg_nl_psi(phase_g, g, 1.0, sg2);
    if (phase_g >= 0.0) return psi0;
    double w = -expm1(-fmax(T, 0.0));
    return slut_hg_psi_max(phase_g) * pow(psi0 / slut_hg_psi_forward(phase_g), w);
}

/* The divisor of the slab tables (kind near_light_E4_hg, finite S): E_g/E itself — the mean of
 * ψ over the path weighted by ĥ^{−2} and the attenuation — estimated by one 16-point
 * Gauss–Legendre rule in the scattering angle instead of in depth. With ĥ^{−2}dτ = dθ/√(1 − g²)
 * the path [0, S/T] (units of l) maps to θ ∈ [θ(0), θ(S/T)], θ(τ) = atan2(√(1 − g²), −(τ + g)),
 * a finite interval even for a long slab; at each node τ = −√(1 − g²)·cot θ − g, η = √(1 − g²)/sin θ
 * and the weight is the attenuation of the r = 0 geometry relative to the entry point,
 * e^{−T(τ + η − 1)} (the view ray's and the light path's lengths; the table's r is left to the
 * stored values). The estimate is an approximation, but an analytic function of T, g and S,
 * which is all a divisor needs: the table stores E_g/D and the runtime multiplies D back.
 * With the entry point's ψ0 (the thick divisor) the slab tables missed 1 % by far (1.7 % at
 * g_hg = 0.95, where a slab ending before the light's foot point sees ψ fall ~60× along it, 20 %
 * at g_hg = −0.9); the path mean with a hard cut at one attenuation length still missed it
 * (2 %); this estimate follows both (docs/NEARLIGHT.md, measured). D = C·M with the constant
 * C = ψ_max/ψ_min = ((1 + |g_hg|)/(1 − |g_hg|))³: E_g/E is a mean of ψ ≤ ψ_max and M ≥ ψ_min
 * (positive weights), so E_g/D ≤ E and the stored ln(E_g/(D·B)) keeps the isotropic slab
 * table's range (≤ T); a constant factor shifts ln by a constant and leaves the interpolation
 * as it is. S = 0: C·ψ0. */
SLUT_FN double slut_hg_nl_slab_divisor(double phase_g, double T, double g, double S) {
    g = slut_clamp(g, -1.0, 1.0);
    T = fmax(T, 0.0);
    double sg = sqrt((1.0 - fabs(g)) * (1.0 + fabs(g)));
    double s = (S > 0.0) ? S / T : 0.0; /* the path in units of l (+∞ at T = 0) */
    double theta0 = atan2(sg, -g), theta1 = atan2(sg, -(s + g));
    double mid = 0.5 * (theta0 + theta1), half_width = 0.5 * (theta1 - theta0), num = 0.0, den = 0.0;
    for (int k = 0; k < 16; ++k) {
        double theta = mid + half_width * ((k < 8) ? -slut_gl16_x[k] : slut_gl16_x[k - 8]);
        double sin_t = sin(theta), cos_t = cos(theta);
        double tau = -sg * cos_t / sin_t - g, eta = sg / sin_t;
        double weight = slut_gl16_w[(k < 8) ? k : k - 8] * exp(-T * (tau + eta - 1.0));
        num += weight * slut_hg_psi(phase_g, cos_t);
        den += weight;
    }
    double ratio = (1.0 + fabs(phase_g)) / (1.0 - fabs(phase_g)); /* C = ratio³ = ψ_max/ψ_min */
    double mean = (den > 0.0 && num > 0.0) ? num / den : slut_hg_psi(phase_g, cos(theta0));
    return ratio * ratio * ratio * mean;
}

/* The divisor of either table: slut_hg_nl_table_divisor for a thick one (S = +∞), the slab
 * divisor for finite S. */
SLUT_FN double slut_hg_nl_divisor(double phase_g, double T, double g, double S) {
    return (S > SLUT_INFINITE_ABOVE) ? slut_hg_nl_table_divisor(phase_g, T, g) : slut_hg_nl_slab_divisor(phase_g, T, g, S);
}

#ifndef SLUT_SHADER
/* N_g = E_g·H (+∞ where H diverges: T = 0 with S > 0, or g = −1 with S ≥ T). */
SLUT_FN double slut_hg_nl_N(double T, double g, double r, double S, double phase_g) {
    double H = slut_nl_H(T, g, S);
    if (!(H > 0.0)) return 0.0;
    if (!SLUT_ISFINITE(H)) return SLUT_HUGE_VAL;
    double S_over_T = (S > 1e300) ? SLUT_HUGE_VAL : S / T;
    return slut_hg_nl_E(T, g, r, S_over_T, phase_g, 1.0) * H;
}
#endif /* !SLUT_SHADER */

#endif /* SLUT_NEARLIGHT_HG_H */
