/* scatterlut — near-light table kernel: ln E(T, g, r) (thick) or ln(E/B)(T, g, r, S) at every node.
 *
 * One work-item per (r group of up to SLUT_NL_MAX_LANES nodes, g node, T node): the r values
 * of a group share one panel mesh, and the S nodes of the slab axis at (T, g) share one
 * march (slut_nl_E_sweep: the cumulative sweep, SLUT_NL_MAX_SWEEP nodes per march).
 * Output layout, axis 0 fastest: index = ((iS·n_r + ir)·n_g + ig)·n_T + iT (the file layout
 * of axes T, g, r, S). A 3-D (thick) table passes S_count = 1 and S_min = S_max = +inf and
 * gets ln E; a 4-D table gets ln(E/B), B = slut_nl_E_base (the value base), with S at node iS
 * from its slab axis (slut_nl_S_node: the q map of slut_nearlight.h for warp
 * SLUT_WARP_NL_QODDS; ascending in iS at every (T, g)).
 */
#include "slut_axes.h"
#include "slut_nearlight.h"

__kernel void nearlight_ln_E(__global double *out,
                             double T_min, double T_max, double T_scale, int T_warp, int T_count,
                             double g_min, double g_max, double g_scale, int g_warp, int g_count,
                             double r_min, double r_max, double r_scale, int r_warp, int r_count,
                             double S_min, double S_max, double S_scale, int S_warp, int S_count,
                             double refine) {
    int group = get_global_id(0);
    int ig = get_global_id(1);
    int iT = get_global_id(2);
    int ir0 = group * SLUT_NL_MAX_LANES;
    if (ir0 >= r_count || ig >= g_count || iT >= T_count) return;
    slut_axis aT, ag, ar, aS;
    aT.min = T_min; aT.max = T_max; aT.scale = T_scale; aT.warp = T_warp; aT.count = T_count;
    ag.min = g_min; ag.max = g_max; ag.scale = g_scale; ag.warp = g_warp; ag.count = g_count;
    ar.min = r_min; ar.max = r_max; ar.scale = r_scale; ar.warp = r_warp; ar.count = r_count;
    aS.min = S_min; aS.max = S_max; aS.scale = S_scale; aS.warp = S_warp; aS.count = S_count;
    double T = slut_axis_node(&aT, iT);
    double g = slut_axis_node(&ag, ig);
    int lanes = min(SLUT_NL_MAX_LANES, r_count - ir0);
    double r[SLUT_NL_MAX_LANES], S[SLUT_NL_MAX_SWEEP], E[SLUT_NL_MAX_SWEEP * SLUT_NL_MAX_LANES];
    for (int l = 0; l < lanes; ++l) r[l] = slut_axis_node(&ar, ir0 + l);
    for (int iS0 = 0; iS0 < S_count; iS0 += SLUT_NL_MAX_SWEEP) {
        int n_S = min(SLUT_NL_MAX_SWEEP, S_count - iS0);
        for (int i = 0; i < n_S; ++i) S[i] = (S_count == 1) ? S_min : slut_nl_S_node(&aS, T, g, iS0 + i);
        slut_nl_E_sweep(T, g, S, n_S, r, lanes, E, refine);
        for (int i = 0; i < n_S; ++i) {
            for (int l = 0; l < lanes; ++l) {
                double base = (S_count == 1) ? 1.0 : slut_nl_E_base(T, r[l], S[i]);
                out[(((size_t)(iS0 + i) * r_count + (size_t)(ir0 + l)) * g_count + ig) * T_count + iT] =
                    log(E[i * lanes + l] / base);
            }
        }
    }
}
