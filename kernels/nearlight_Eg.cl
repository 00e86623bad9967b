/* scatterlut — near-light table kernel with a Henyey–Greenstein phase: at every node the
 * stored ln(E_g/D) (thick, S = ∞) or ln(E_g/(D·B))(T, g, r, S) (slab), E_g of
 * kernels/slut_nearlight_hg.h (Gath 2008 §4.2 with p_g(θ) under the integral), D =
 * slut_hg_nl_divisor(phase_g, T, g, S) (thick: the phase at the entry point; slab: an estimate
 * of the attenuation-weighted mean of the phase along the path) and B = slut_nl_E_base
 * (the value base of the isotropic slab table). E_g/D ≤ E, so the stored values have the
 * isotropic tables' ranges (ln ≤ 0 thick, ln ≤ T slab) and one runtime front-end reads both.
 *
 * One work-item per (r node, g node, T node); it marches each S node of its slab axis (S
 * from slut_nl_S_nodes, ascending at every (T, g)) in one cumulative march
 * (slut_hg_nl_E_sweep). Unlike nearlight_E.cl there are no r lanes (the HG march has no lane
 * form). Output layout, axis 0 fastest:
 * index = ((iS·n_r + ir)·n_g + ig)·n_T + iT (axes T, g, r, S). A thick table passes S_count = 1
 * and S_min = S_max = +inf. The T, g, r nodes come from the host (slut_axis_node).
 */
#include "slut_axes.h"
#include "slut_nearlight_hg.h"

#define SLUT_NLG_MAX_S 64 /* the most slab nodes of one work-item (the host checks) */

__kernel void nearlight_ln_Eg(__global double *out,
                              __global const double *T_nodes, int T_count,
                              __global const double *g_nodes, int g_count,
                              __global const double *r_nodes, int r_count,
                              double S_min, double S_max, double S_scale, int S_warp, int S_count,
                              double phase_g, double refine) {
    int ir = get_global_id(0);
    int ig = get_global_id(1);
    int iT = get_global_id(2);
    if (ir >= r_count || ig >= g_count || iT >= T_count || S_count > SLUT_NLG_MAX_S) return;
    slut_axis aS;
    aS.min = S_min; aS.max = S_max; aS.scale = S_scale; aS.warp = S_warp; aS.count = S_count;
    double T = T_nodes[iT], g = g_nodes[ig], r = r_nodes[ir];
    double S[SLUT_NLG_MAX_S], S_over_T[SLUT_NLG_MAX_S], E[SLUT_NLG_MAX_S];
    if (S_count == 1) S[0] = S_min;
    else slut_nl_S_nodes(&aS, T, g, 0, S_count, S);
    for (int iS = 0; iS < S_count; ++iS) S_over_T[iS] = (S[iS] > 1e300) ? SLUT_HUGE_VAL : S[iS] / T;
    /* A slab's S nodes share one march (slut_hg_nl_E_sweep); a thick node, a zero depth and
     * g = −1 (the light on the ray) take slut_hg_nl_E's own special cases. */
    if (S_count > 1 && S_over_T[0] > 0.0 && g > -1.0) slut_hg_nl_E_sweep(T, g, r, S_over_T, S_count, phase_g, refine, E);
    else
        for (int iS = 0; iS < S_count; ++iS) E[iS] = slut_hg_nl_E(T, g, r, S_over_T[iS], phase_g, refine);
    for (int iS = 0; iS < S_count; ++iS) {
        double ln_E = log(E[iS]) - log(slut_hg_nl_divisor(phase_g, T, g, S[iS]));
        if (S_count > 1) ln_E -= log(slut_nl_E_base(T, r, S[iS]));
        out[(((size_t)iS * r_count + (size_t)ir) * g_count + ig) * T_count + iT] = ln_E;
    }
}
