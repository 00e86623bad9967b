/* scatterlut — the anisotropic airlight table kernels: ln G̃_g(u, w) at every node, for one
 * Henyey–Greenstein asymmetry g (docs/PHYSICS.md §1.4):
 *
 *   w·G̃_g(u, w) = S(u) = ∫_0^∞ e^{−u y} k_g(τ + y) dy,   τ = cot w,
 *   k_g(t) = (1 − g²)·√(1 + t²) / ((1 − g)² + (1 + g)² t²)^{3/2}     (kernels/slut_airlight_hg.h)
 *
 * airlight_hg_ln_gs_sweep: the sweep of airlight_F.cl (see there: the exact recurrence
 * S_j = ∫_0^{Δ_j} e^{−u y} k_g(τ_j + y) dy + e^{−u Δ_j} S_{j−1}, one set of nodes shared by all
 * rows, 8 rows per work-item as a double8, the Taylor form on short intervals) with the
 * weights W_jn = (Gauss–Legendre weight)·k_g(τ_j + y_jn) that the host builds with
 * slut_hg_air_kernel, the panels kept clear of k_g's singularities at y = −τ ± iβ,
 * β = min(1, (1 − g)/(1 + g)) (generate_airlight.cpp). There is no large-u series branch (its
 * coefficients are the Lorentzian's): the rule sets resolve the layer of width 1/u at every u.
 * The rows u = 0 the host overwrites (G̃_g(0, w) is the mean of ψ_g, not 1: the same recurrence
 * at u = 0, generate_airlight.cpp). The Henyey–Greenstein functions of slut_airlight_hg.h are
 * compiled here too (OpenCL C), so that PoCL checks them.
 * Output: out[j·n_u + i] = ln G̃_g(u_i, w_j) (axis 0 fastest, the file layout).
 */
#include "slut_airlight_hg.h" /* and through it slut_airlight.h: SLUT_GS_TAYLOR_TERMS, SLUT_GS_TAYLOR_X */

__kernel void airlight_hg_ln_gs_sweep(__global double *out, int n_u, int n_w,
                                   __global const double *u_rows,     /* n_u padded to 8k, ascending */
                                   __global const double *w_nodes,    /* n_w values w_j            */
                                   __global const double *delta,      /* n_w values Δ_j (Δ_0 unused) */
                                   __global const int *item_set,      /* rule set of each work-item */
                                   __global const int *node_begin,    /* n_w + 1 offsets per set   */
                                   __global const double *node_y,     /* y_jn, ascending per j     */
                                   __global const double *node_weight, /* W_jn                      */
                                   __global const double *taylor_moment /* n_w × SLUT_GS_TAYLOR_TERMS: m_jk about Δ_j/2 */) {
    int item = get_global_id(0);
    if (8 * item >= n_u) return;
    double8 u = vload8(item, u_rows);
    double u_lo = u.s0, u_hi = u.s7;
    __global const int *begin = node_begin + (size_t)item_set[item] * (size_t)(n_w + 1);
    double8 sum = (double8)(0.0);
    for (int j = 0; j < n_w; ++j) {
        if (j > 0 && u_hi * delta[j] <= 2.0 * SLUT_GS_TAYLOR_X) { /* the recurrence, short interval */
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
        double8 ln_gs = log(sum / w_nodes[j]); /* a lane with u = 0: overwritten by the host */
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
