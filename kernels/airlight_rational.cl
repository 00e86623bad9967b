/* scatterlut — the airlight_rational table's kernel: Ĥ(x_m, x_t), the airlight's tail
 * H(u, t) = ∫_0^∞ e^{−u y}/(1 + (t + y)²) dy normalised by N = t + 2/π + u (1 + t²), at every
 * node of the unit square of rational coordinates x_m = (m/(m + K))^{1/4}, m = u (1 + t), and
 * x_t = t/(1 + t) (kernels/slut_airlight_rational.h), in double, by the shared node function
 * slut_airlight_rational_node (slut_w_gs_quadrature, refine = 1, with the edges' limits).
 *
 * One work-item per node: a work-item is a whole quadrature (~200–400 exps). Output layout,
 * axis 0 fastest: index = j·m_count + i (axes x_m, x_t). The nodes' unit coordinates come from
 * the host (slut_axis_node), so that the host's checks evaluate the same arguments.
 */
#include "slut_airlight_rational.h"

__kernel void airlight_rational_hn(__global double *out,
                                   __global const double *m_nodes, int m_count,
                                   __global const double *t_nodes, int t_count) {
    int i = get_global_id(0);
    int j = get_global_id(1);
    if (i >= m_count || j >= t_count) return;
    out[(size_t)j * (size_t)m_count + (size_t)i] = slut_airlight_rational_node(m_nodes[i], t_nodes[j], 1.0);
}
