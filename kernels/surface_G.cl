/* scatterlut — the surface tables' kernel: G_n(T, θ) of Sun et al. 2005 (diffuse n = 1, Phong
 * lobe n > 1; kernels/slut_surface.h, docs/PHYSICS.md §1.5) at every node, in double, by the
 * fixed composite Gauss–Legendre rule slut_surface_G_fixed with `subpanels` panels per interval
 * between the integrand's break points (slut_surface_subpanels_for_tolerance). The host encodes
 * the stored channel from G.
 *
 * One work-item per (T node, θ node). Output layout, axis 0 fastest: index = iθ·T_count + iT
 * (axes T, θ). The nodes come from the host (slut_axis_node).
 */
#include "slut_surface.h"

__kernel void surface_G(__global double *out,
                        __global const double *T_nodes, int T_count,
                        __global const double *theta_nodes, int theta_count,
                        int exponent, int subpanels) {
    int iT = get_global_id(0);
    int itheta = get_global_id(1);
    if (iT >= T_count || itheta >= theta_count) return;
    out[(size_t)itheta * T_count + iT] = slut_surface_G_fixed(exponent, T_nodes[iT], theta_nodes[itheta], subpanels);
}
