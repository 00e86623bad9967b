/* scatterlut — near-light table kernel: ln E(T, g, r) (thick) or ln(E/B)(T, g, r, S) at every node.
 *
 * One work-item per (r group of up to SLUT_NL_MAX_LANES nodes, g node, T node): the r values
 * of a group share one panel mesh, and the S nodes of the slab axis at (T, g) share one
 * march (slut_nl_E_sweep: the cumulative sweep, SLUT_NL_MAX_SWEEP nodes per march).
 * Output layout, axis 0 fastest: index = ((iS·n_r + ir)·n_g + ig)·n_T + iT (the file layout
 * of axes T, g, r, S). The host may launch more work-items than nodes (the T extent padded to
 * a multiple of its work-group, kNearLightGroupT): those past a count return at once. A 3-D (thick) table passes S_count = 1 and S_min = S_max = +inf and
 * gets ln E; a 4-D table gets ln(E/B), B = slut_nl_E_base (the value base), with S at node iS
 * from its slab axis (slut_nl_S_node: the q map of slut_nearlight.h for warp
 * SLUT_WARP_NL_QODDS; ascending in iS at every (T, g)).
 *
 * The nodes of T, g and r come from the host (T_nodes[i] = slut_axis_node of the table's axis
 * there: the node values every table reader assumes, and no transcendental per work-item);
 * S depends on (T, g) and is computed here. A partial last r group is padded to
 * SLUT_NL_MAX_LANES lanes with its last r (the sweep's lane vector is full; the padding
 * changes no mesh rule) and only the real lanes are stored. The logarithm is taken on the
 * lane vector (a scalar log costs ~40× a vector one per element on PoCL 3.1: docs/POCL.md).
 */
#include "slut_axes.h"
#include "slut_nearlight.h"

#if SLUT_NL_LANE_WIDTH != SLUT_NL_MAX_LANES
#error "the kernel takes one r group as one lane vector"
#endif

/* SLUT_NL_THIN_OF_X on the lane vector, its expm1 (needed for x in [SLUT_TINY, 40]) by
 * slut_nl_lanes_expm1 (≤ 3 ulps; PoCL's double8 expm1 took ~8 % of the 4-D table's time,
 * bench/README.md, "The node loop in base 2"). The value base is an encoding (E = B·e^stored):
 * a reader's B from its own expm1 differs by a few ulps, which E then carries. */
slut_nl_lanes thin_of_x(slut_nl_lanes x) { return SLUT_NL_THIN_OF_X_GIVEN(x, slut_nl_lanes_expm1(-x)); }

__kernel void nearlight_ln_E(__global double *out,
                             __global const double *T_nodes, int T_count,
                             __global const double *g_nodes, int g_count,
                             __global const double *r_nodes, int r_count,
                             double S_min, double S_max, double S_scale, int S_warp, int S_count,
                             double refine) {
    int group = get_global_id(0);
    int ig = get_global_id(1);
    int iT = get_global_id(2);
    int ir0 = group * SLUT_NL_MAX_LANES;
    if (ir0 >= r_count || ig >= g_count || iT >= T_count) return;
    slut_axis aS;
    aS.min = S_min; aS.max = S_max; aS.scale = S_scale; aS.warp = S_warp; aS.count = S_count;
    double T = T_nodes[iT];
    double g = g_nodes[ig];
    int lanes = min(SLUT_NL_MAX_LANES, r_count - ir0);
    double r[SLUT_NL_MAX_LANES], S[SLUT_NL_MAX_SWEEP], E[SLUT_NL_MAX_SWEEP * SLUT_NL_MAX_LANES];
    for (int l = 0; l < SLUT_NL_MAX_LANES; ++l) r[l] = r_nodes[min(ir0 + l, ir0 + lanes - 1)];
    /* The value base's factors of T alone, and SLUT_NL_THIN_X as S times a factor of r alone
     * (1 where r = ∞): that factor once here, then x = S_eff × it per S node (the same
     * product, bit for bit). A thick table (one S node) needs none of them: its scalar
     * expm1 and lane divides are skipped. */
    double floor_T = 1.0, rise_T = 0.0;
    slut_nl_lanes thin_x_per_S = SLUT_NL_LANES_SPLAT(1.0);
    if (S_count > 1) {
        floor_T = exp(-T);
        rise_T = -expm1(-T);
        thin_x_per_S = SLUT_NL_THIN_X(slut_nl_lanes_load(r), 1.0);
    }
    for (int iS0 = 0; iS0 < S_count; iS0 += SLUT_NL_MAX_SWEEP) {
        int n_S = min(SLUT_NL_MAX_SWEEP, S_count - iS0);
        if (S_count == 1) S[0] = S_min;
        else slut_nl_S_nodes(&aS, T, g, iS0, n_S, S);
        slut_nl_E_sweep(T, g, S, n_S, r, SLUT_NL_MAX_LANES, E, refine);
        for (int i = 0; i < n_S; ++i) {
            double *E_i = &E[i * SLUT_NL_MAX_LANES];
            slut_nl_lanes E_lanes = slut_nl_lanes_load(E_i);
            if (S_count > 1) {
                /* E/B, B = slut_nl_E_base_from: S_eff once, E_thin on the lane vector (its
                 * expressions for 0 < S_eff < ∞; the scalar function's guards otherwise). */
                double S_eff = slut_nl_base_depth(T, S[i]);
                if (S_eff > 0.0 && S_eff <= SLUT_INFINITE_ABOVE) {
                    E_lanes /= SLUT_NL_BASE_OF_THIN(floor_T, rise_T, thin_of_x(S_eff * thin_x_per_S));
                } else {
                    for (int l = 0; l < lanes; ++l) E_i[l] /= slut_nl_E_base_from(floor_T, rise_T, T, r[l], S[i]);
                    E_lanes = slut_nl_lanes_load(E_i);
                }
            }
            slut_nl_lanes_store(slut_nl_lanes_log(E_lanes), E_i);
            for (int l = 0; l < lanes; ++l)
                out[(((size_t)(iS0 + i) * r_count + (size_t)(ir0 + l)) * g_count + ig) * T_count + iT] = E_i[l];
        }
    }
}
