/* scatterlut — airlight table kernel: ln G̃_g(u, w) at every node of the table, for one
 * Henyey–Greenstein asymmetry g (g = 0: the isotropic table; docs/PHYSICS.md §1.4), by a sweep
 * along w that shares one set of quadrature nodes between all rows u.
 *
 * With τ_j = cot w_j (w_0 = w_min < w_1 < … < w_{n−1} = π/2, so τ decreases) and
 *   S_j(u) = w_j·G̃_g(u, w_j) = ∫_0^∞ e^{−u y} k_g(τ_j + y) dy,
 *   k_0(t) = 1/(1 + t²)                                                   (slut_airlight.h)
 *   k_g(t) = (1 − g²)·√(1 + t²) / ((1 − g)² + (1 + g)² t²)^{3/2}           (slut_airlight_hg.h)
 * splitting the range at y = Δ_j = τ_{j−1} − τ_j gives the exact recurrence
 *   S_j = ∫_0^{Δ_j} e^{−u y} k_g(τ_j + y) dy + e^{−u Δ_j} S_{j−1},
 * and the first (semi-infinite) S_0 is the same integral with Δ_0 = ∞. Every term is
 * positive, so relative accuracy carries through the sweep (no cancellation, unlike
 * F(u, π/2) − F(u, v)). The integral over [0, Δ_j] is a fixed rule
 *   Σ_n W_jn e^{−u y_jn},   W_jn = (Gauss–Legendre weight)·k_g(τ_j + y_jn),
 * whose nodes do not depend on u: the host builds them once per table (graded panels
 * towards y = 0 resolve the layer of width 1/u for every u ≤ u_max, panels kept clear of
 * k_g's singularities at y = −τ ± iβ, β = min(1, (1 − g)/(1 + g)); see
 * generate_airlight.cpp), and one node costs one exp per row. The integrand lives in the
 * weights only: this one kernel serves every g. Rows of small u need far fewer nodes (no
 * layer to resolve), so the host builds rule sets for u ≤ u_max/4^c and each work-item uses
 * the set that covers its largest u.
 *
 * One work-item holds 8 consecutive rows u as a double8 (PoCL does not vectorise across
 * work-items around a data-dependent loop; explicit vectors do). Rows are ascending, so
 * lane 0 has the smallest u of the item: once u_0·y > 40 every lane's remaining terms are
 * below e^{−40} of the first one and the interval's rule is cut there (nodes ascend in y).
 * Where the layer at y = 0 is thin (u ≥ slut_gs_series_u_min(w_j) for lane 0, hence all
 * lanes) the whole S_j is the large-u series Σ_k c_k(w_j)/u^{k+1} instead (slut_airlight.h:
 * ≤ 1e-16 relative there; the host passes the coefficients), and the sweep continues from it.
 * For g ≠ 0 the host passes k_g's coefficients and onset instead (slut_hg_sweep_large_u_coefficients,
 * slut_hg_sweep_series_u_min in slut_airlight_hg.h: the same 1e-16, estimated from the terms).
 * Where the interval is short for every lane (u_7·Δ_j ≤ 2·SLUT_GS_TAYLOR_X, lane 7 the
 * largest u) the rule is its Taylor form about Δ_j/2, e^{−u Δ_j/2} Σ_k m_jk u^k
 * (slut_airlight.h: ≤ 2e-18 relative; the host passes the moments of interval j's rule):
 * one exp for the interval, whose square is the recurrence's e^{−u Δ_j}, and 15 fma.
 * Output: out[j·n_u + i] = ln G̃_g(u_i, w_j) (axis 0 fastest, the file layout); u = 0 is
 * exactly ln 1 = 0 for g = 0 (G̃_g(0, w) for g ≠ 0 is the mean of ψ_g, not 1: the host
 * overwrites those rows, generate_airlight.cpp).
 * The Henyey–Greenstein functions of slut_airlight_hg.h are compiled here too (OpenCL C), so
 * that PoCL checks them.
 */
#include "slut_airlight_hg.h" /* and through it slut_airlight.h: SLUT_GS_SERIES_TERMS, SLUT_GS_TAYLOR_TERMS, SLUT_GS_TAYLOR_X */

__kernel void airlight_ln_gs_sweep(__global double *out, int n_u, int n_w,
                                   __global const double *u_rows,     /* n_u padded to 8k, ascending */
                                   __global const double *w_nodes,    /* n_w values w_j            */
                                   __global const double *delta,      /* n_w values Δ_j (Δ_0 unused) */
                                   __global const int *item_set,      /* rule set of each work-item */
                                   __global const int *node_begin,    /* n_w + 1 offsets per set   */
                                   __global const double *node_y,     /* y_jn, ascending per j     */
                                   __global const double *node_weight, /* W_jn                      */
                                   __global const double *series_u_min, /* n_w: the series holds above */
                                   __global const double *series_coef, /* n_w × SLUT_GS_SERIES_TERMS */
                                   __global const double *taylor_moment /* n_w × SLUT_GS_TAYLOR_TERMS: m_jk about Δ_j/2 */) {
    int item = get_global_id(0);
    if (8 * item >= n_u) return;
    double8 u = vload8(item, u_rows);
    double u_lo = u.s0, u_hi = u.s7;
    __global const int *begin = node_begin + (size_t)item_set[item] * (size_t)(n_w + 1);
    double8 sum = (double8)(0.0);
    double8 inv_u = 1.0 / u;
    for (int j = 0; j < n_w; ++j) {
        if (u_lo >= series_u_min[j]) { /* the whole S_j from the series, Horner in 1/u */
            __global const double *c = series_coef + (size_t)j * SLUT_GS_SERIES_TERMS;
            double8 s = (double8)(c[SLUT_GS_SERIES_TERMS - 1]);
            for (int k = SLUT_GS_SERIES_TERMS - 2; k >= 0; --k) s = fma(s, inv_u, (double8)(c[k]));
            sum = s * inv_u;
        } else if (j > 0 && u_hi * delta[j] <= 2.0 * SLUT_GS_TAYLOR_X) { /* the recurrence, short interval */
            __global const double *m = taylor_moment + (size_t)j * SLUT_GS_TAYLOR_TERMS;
            double8 s = (double8)(m[SLUT_GS_TAYLOR_TERMS - 1]);
            for (int k = SLUT_GS_TAYLOR_TERMS - 2; k >= 0; --k) s = fma(s, u, (double8)(m[k]));
            double8 decay_half = exp(-u * (0.5 * delta[j])); /* e^{−u Δ_j/2} */
            sum = decay_half * fma(sum, decay_half, s);
        } else { /* the recurrence */
            if (j > 0) sum *= exp(-u * delta[j]);
            int end = begin[j + 1];
            for (int n = begin[j]; n < end; ++n) {
                double y = node_y[n];
                if (u_lo * y > 40.0) break;
                sum += node_weight[n] * exp(-u * y);
            }
        }
        double8 ln_gs = log(sum / w_nodes[j]);
        ln_gs = select(ln_gs, (double8)(0.0), u == (double8)(0.0));
        __global double *row = out + (size_t)j * (size_t)n_u + (size_t)(8 * item);
        if (8 * item + 8 <= n_u) {
            vstore8(ln_gs, 0, row);
        } else {
            double lanes[8];
            vstore8(ln_gs, 0, lanes);
            for (int k = 0; k < n_u - 8 * item; ++k) row[k] = lanes[k];
        }
    }
}
