/* scatterlut — airlight table kernel: ln G̃(u, w) at every node of the table.
 *
 * Node (i, j) of a table whose axis 0 is u and axis 1 is w = π/2 − v; one work-item
 * per node, output at out[j·count_u + i] (axis 0 fastest, the file layout). The
 * quadrature and the axis maps are the shared ones (slut_airlight.h, slut_axes.h), so
 * the host's exact evaluation and this kernel compute the same function.
 */
#include "slut_axes.h"
#include "slut_airlight.h"

__kernel void airlight_ln_gs(__global double *out,
                             double u_min, double u_max, double u_scale, int u_warp, int u_count,
                             double w_min, double w_max, double w_scale, int w_warp, int w_count,
                             double refine) {
    int i = get_global_id(0);
    int j = get_global_id(1);
    if (i >= u_count || j >= w_count) return;
    slut_axis au, aw;
    au.min = u_min; au.max = u_max; au.scale = u_scale; au.warp = u_warp; au.count = u_count;
    aw.min = w_min; aw.max = w_max; aw.scale = w_scale; aw.warp = w_warp; aw.count = w_count;
    double u = slut_axis_node(&au, i);
    double w = slut_axis_node(&aw, j);
    out[(size_t)j * (size_t)u_count + (size_t)i] = log(slut_gs_quadrature(u, w, refine));
}
