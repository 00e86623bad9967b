/* scatterlut — table axes: each warp is a pair of maps, parameter ↔ unit coordinate.
 *
 * A table axis covers [min, max] with `count` nodes. The unit coordinate
 * x ∈ [0, 1] is the warped, normalised position:
 *     x = (g(p) − g(min)) / (g(max) − g(min)),   p = g⁻¹(g(min) + x·(g(max) − g(min)))
 * with g the warp below. Node i sits at x_i = i / (count − 1): the domain ends
 * are the first and last nodes. On a GPU texture of `count` texels the texel
 * centres sit at (i + 0.5)/count, so a texture coordinate is
 *     tc = (x·(count − 1) + 0.5) / count                      (slut_texcoord_from_unit)
 * which is exactly what the C++ sampler does with node indices (Bruneton's
 * texel-centre convention). Outside [min, max] x is clamped by the sampler,
 * never wrapped; callers that need behaviour beyond the domain use the
 * asymptotic forms of the quantity instead (see slut_airlight.h).
 *
 * Warps (the id is stored in table files; never renumber):
 *   LINEAR    g(p) = p
 *   LOG       g(p) = ln p                              (min > 0)
 *   LOG1P     g(p) = ln(1 + (p − min)/s), s = scale     (log spacing above min + s,
 *                                                         linear below; min itself a node)
 *   ASINH_COT g(p) = −asinh(cot p),  p ∈ (0, π/2]       (p = π/2 − v: log spacing in p as
 *                                                         p → 0, linear in v near v = 0)
 *   SQRT1P    g(p) = sqrt(1 + p),    p ∈ [−1, 1]        (follows √(1+g), the width of a
 *                                                         peak as g → −1)
 */
#ifndef SLUT_AXES_H
#define SLUT_AXES_H

#include "slut_compat.h"

#define SLUT_WARP_LINEAR 0
#define SLUT_WARP_LOG 1
#define SLUT_WARP_LOG1P 2
#define SLUT_WARP_ASINH_COT 3
#define SLUT_WARP_SQRT1P 4
#define SLUT_WARP_COUNT 5

/* One axis as the maps need it (plain data, identical in C++ and OpenCL C). */
typedef struct slut_axis {
    double min;   /* parameter at node 0 */
    double max;   /* parameter at node count − 1 */
    double scale; /* warp parameter (LOG1P: s); unused by the others */
    int warp;     /* SLUT_WARP_* */
    int count;    /* nodes, ≥ 2 */
} slut_axis;

/* Warp g(p). */
SLUT_FN double slut_warp_forward(int warp, double p, double min, double scale) {
    switch (warp) {
    case SLUT_WARP_LOG: return log(p);
    case SLUT_WARP_LOG1P: return log1p((p - min) / scale);
    case SLUT_WARP_ASINH_COT: {
        /* asinh(cot p) = ln(cot p + csc p) = ln((1 + cos p)/sin p); the last form keeps
           full relative precision as p → 0 and is exact 0 at p = π/2. */
        return -log((1.0 + cos(p)) / sin(p));
    }
    case SLUT_WARP_SQRT1P: return sqrt(fmax(1.0 + p, 0.0));
    default: return p;
    }
}

/* Inverse warp g⁻¹(y). */
SLUT_FN double slut_warp_inverse(int warp, double y, double min, double scale) {
    switch (warp) {
    case SLUT_WARP_LOG: return exp(y);
    case SLUT_WARP_LOG1P: return min + scale * expm1(y);
    case SLUT_WARP_ASINH_COT: {
        /* y = −asinh(cot p)  ⇒  cot p = sinh(−y)  ⇒  p = atan2(1, sinh(−y)). */
        return atan2(1.0, sinh(-y));
    }
    case SLUT_WARP_SQRT1P: return y * y - 1.0;
    default: return y;
    }
}

/* The warped ends g(min), g(max) of an axis. They are constant per axis: a sampler that
   looks up many points computes them once and calls slut_unit_from_warped. */
SLUT_FN void slut_axis_warped_ends(const slut_axis *a, double *g0, double *g1) {
    *g0 = slut_warp_forward(a->warp, a->min, a->min, a->scale);
    *g1 = slut_warp_forward(a->warp, a->max, a->min, a->scale);
}

/* Parameter → unit coordinate x (not clamped), given the axis's warped ends. */
SLUT_FN double slut_unit_from_warped(const slut_axis *a, double p, double g0, double g1) {
    return (slut_warp_forward(a->warp, p, a->min, a->scale) - g0) / (g1 - g0);
}

/* Parameter → unit coordinate x (not clamped). */
SLUT_FN double slut_unit_from_param(const slut_axis *a, double p) {
    double g0, g1;
    slut_axis_warped_ends(a, &g0, &g1);
    return slut_unit_from_warped(a, p, g0, g1);
}

/* Unit coordinate x → parameter. Node i is slut_param_from_unit(a, i/(count−1)). */
SLUT_FN double slut_param_from_unit(const slut_axis *a, double x) {
    double g0 = slut_warp_forward(a->warp, a->min, a->min, a->scale);
    double g1 = slut_warp_forward(a->warp, a->max, a->min, a->scale);
    if (x <= 0.0) return a->min; /* ends exact, whatever the rounding of g⁻¹(g(·)) */
    if (x >= 1.0) return a->max;
    return slut_warp_inverse(a->warp, g0 + x * (g1 - g0), a->min, a->scale);
}

/* Parameter of node i. */
SLUT_FN double slut_axis_node(const slut_axis *a, int i) {
    return slut_param_from_unit(a, (double)i / (double)(a->count - 1));
}

/* Unit coordinate → GPU texture coordinate (texel centres at the domain ends). */
SLUT_FN double slut_texcoord_from_unit(double x, int count) {
    return (slut_clamp(x, 0.0, 1.0) * (double)(count - 1) + 0.5) / (double)count;
}

/* Unit coordinate → (node index i0, fraction f) for linear interpolation between
   nodes i0 and i0 + 1; clamped to the domain (clamp-to-edge, never wrap). */
SLUT_FN void slut_cell_from_unit(double x, int count, int *i0, double *f) {
    double t = slut_clamp(x, 0.0, 1.0) * (double)(count - 1);
    int i = (int)t;
    if (i > count - 2) i = count - 2;
    *i0 = i;
    *f = t - (double)i;
}

#endif /* SLUT_AXES_H */
