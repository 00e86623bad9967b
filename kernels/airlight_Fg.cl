/* scatterlut — the anisotropic airlight table kernel: ln G̃_g(u, w) at every node, for one
 * Henyey–Greenstein asymmetry g (docs/PHYSICS.md §1.4).
 *
 *   G̃_g(u, w) = e^{u cot w} ∫_{π/2−w}^{π/2} ψ_g(2ξ) e^{−u tan ξ} dξ / w,   ψ_g = 4π p_g,
 *
 * integrated in double by slut_hg_gs_quadrature (kernels/slut_airlight_hg.h: composite
 * 16-point Gauss–Legendre in t = tan ξ, the panels kept 1.5 panel lengths from the phase's
 * singularities, ~1e-15 relative; every term positive). One work-item per node: the panel
 * layout depends on u and on the forward peak of width (1 − g)/(1 + g), so the nodes are
 * not shared between rows as in the isotropic sweep (airlight_F.cl).
 * Output: out[j·n_u + i] = ln G̃_g(u_i, w_j) (axis 0 fastest, the file layout).
 * g = 0 would hand every call to the isotropic functions; the planner never asks for it.
 */
#include "slut_airlight_hg.h"

__kernel void airlight_hg_ln_gs(__global double *out, int n_u, int n_w,
                                __global const double *u_nodes, /* n_u values u_i (dimensionless) */
                                __global const double *w_nodes, /* n_w values w_j (rad)           */
                                double g, double refine) {
    int i = get_global_id(0), j = get_global_id(1);
    if (i >= n_u || j >= n_w) return;
    out[(size_t)j * (size_t)n_u + (size_t)i] = log(slut_hg_gs_quadrature(u_nodes[i], w_nodes[j], g, refine));
}
