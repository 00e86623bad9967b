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
 *   LOGLIN    g(p) = ln p + p/s,     p > 0, s = scale    (log spacing below s, linear
 *                                                         spacing s·Δ above: both ends of T)
 *   ASINH_COT_PEAK                                      (ASINH_COT with a forward peak at v = 0:
 *             g(p) = −asinh(cot p) − asinh((π/2 − p)/s),  log spacing in v = π/2 − p above
 *             s = scale > 0, p ∈ (0, π/2]               s as well, linear below it; the
 *                                                       anisotropic airlight's w axis, s the
 *                                                       phase's forward-peak width)
 *   NL_QODDS  the near-light slab axis (E4's axis "q"): its unit coordinate depends on T
 *             and g as well, so only slut_nearlight.h (slut_nl_unit_from_S) computes it.
 *             The one-parameter maps below treat it as LOG in S, which it equals at g = 1.
 *
 * Compiled three times: as OpenCL C (generator), as C++ (runtime sampler, validator) and,
 * whole, as GLSL and HLSL in float (cmake/assemble_shaders.cmake; docs/SHADERS.md), in the
 * subset the five languages share (kernels/slut_compat.h): slut_axis passed by value, casts
 * through SLUT_INT / SLUT_DOUBLE, precision-dependent caps as compat macros. The functions
 * that take an axis by pointer or write through pointers (C callers only) and the runtime's
 * fast path sit in the `#ifndef SLUT_SHADER` block below.
 */
#ifndef SLUT_AXES_H
#define SLUT_AXES_H

#include "slut_compat.h"
#include "slut_fastmath.h"

#define SLUT_WARP_LINEAR 0
#define SLUT_WARP_LOG 1
#define SLUT_WARP_LOG1P 2
#define SLUT_WARP_ASINH_COT 3
#define SLUT_WARP_SQRT1P 4
#define SLUT_WARP_LOGLIN 5
#define SLUT_WARP_NL_QODDS 6
#define SLUT_WARP_ASINH_COT_PEAK 7
#define SLUT_WARP_COUNT 8

/* Warp g(p). Written as a chain of ifs, not a switch, as is slut_warp_inverse: compiled as a
 * shader (the near-light snippet inlines it nine times, three per axis) a switch on the warp
 * id made SwiftShader's shader compile explode (three axis positions: 0.2 s with the ifs
 * against more than a minute of CPU with the switch: bench/README.md, "Compile cost on
 * SwiftShader"). The warps that share a form evaluate it once (the logarithm of LOG, LOGLIN
 * and NL_QODDS; ASINH_COT's, which ASINH_COT_PEAK extends): SwiftShader runs every case for
 * every pixel, masked, so the snippet pays for all of them (1.16x the web demo's frame
 * before). The same operations either way. */
SLUT_FN double slut_warp_forward(int warp, double p, double p_min, double scale) {
    if (warp == SLUT_WARP_LOG || warp == SLUT_WARP_LOGLIN || warp == SLUT_WARP_NL_QODDS) {
        double ln_p = log(p);
        return (warp == SLUT_WARP_LOGLIN) ? ln_p + p / scale : ln_p;
    }
    if (warp == SLUT_WARP_LOG1P) {
        /* log1p only where 1 + x would lose digits: above x = 1, ln(1 + x) ≥ ln 2 and the
           rounding of 1 + x costs ≤ 1 ulp, at the price of a plain log. */
        double x = (p - p_min) / scale;
        return (x > 1.0) ? log(1.0 + x) : log1p(x);
    }
    if (warp == SLUT_WARP_ASINH_COT || warp == SLUT_WARP_ASINH_COT_PEAK) {
        /* asinh(cot p) = ln(cot p + csc p) = ln((1 + cos p)/sin p); the last form keeps
           full relative precision as p → 0 and is exact 0 at p = π/2. */
        double g = -log(SLUT_ONE_PLUS_COS_OVER_SIN(p));
        if (warp == SLUT_WARP_ASINH_COT) return g;
        /* ASINH_COT_PEAK: minus asinh(v/s) = ln(v/s + √(1 + (v/s)²)) (v ≥ 0: no cancellation). */
        double v_over_s = fmax(SLUT_PIO2_HI - p, 0.0) / scale;
        return g - log(v_over_s + sqrt(1.0 + v_over_s * v_over_s));
    }
    if (warp == SLUT_WARP_SQRT1P) return sqrt(fmax(1.0 + p, 0.0));
    return p; /* SLUT_WARP_LINEAR */
}

/* Inverse of ASINH_COT_PEAK in t = cot p ≥ 0 (v = π/2 − p = atan t): the root of
 * h(t) = asinh(t) + asinh(atan(t)/s) − target, target = −y ≥ 0. h is increasing and concave
 * (asinh and atan are, and so is their composition), so, as for LOGLIN, Newton's steps from
 * t = 0 (below the root) increase monotonically to it. p = atan2(1, t) keeps p's relative
 * precision as p → 0. Stops at a relative step ≤ 4e-16; round trip tested in
 * tests/kernels/test_axes.cpp. */
SLUT_FN double slut_asinh_cot_peak_inverse(double y, double s) {
    double target = -y, t = 0.0;
    if (!(target > 0.0)) return SLUT_PIO2_HI;
    for (int k = 0; k < 200; ++k) {
        double v = atan(t), v_over_s = v / s, one_t2 = 1.0 + t * t;
        double h = log(t + sqrt(one_t2)) + log(v_over_s + sqrt(1.0 + v_over_s * v_over_s)) - target;
        double dh = 1.0 / sqrt(one_t2) + 1.0 / (one_t2 * sqrt(s * s + v * v));
        double next = t - h / dh;
        if (!(next >= t)) break; /* at the root (rounding): the steps only increase */
        double step = next - t;
        t = next;
        if (step <= 4e-16 * t) break;
    }
    return atan2(1.0, t);
}

/* Inverse of LOGLIN: the root p > 0 of f(p) = ln p + p/s − y. f is increasing and concave,
 * so its tangent lies above it: one Newton step from any p0 > 0 lands at or below the root,
 * and from below the steps increase monotonically to it (quadratically near it). The start,
 * p0 = e^y for y ≤ ln s + 1 and s·(y − ln s) otherwise, follows the two asymptotes (log and
 * linear). Stops at a relative step ≤ SLUT_LOGLIN_CONVERGED (4e-16; float 2.4e-7, two ulp) or
 * after SLUT_LOGLIN_MAX_STEPS; round trip tested in tests/kernels/test_axes.cpp. */
SLUT_FN double slut_loglin_inverse(double y, double s) {
    double p = (y <= log(s) + 1.0) ? exp(y) : s * (y - log(s));
    for (int k = 0; k < SLUT_LOGLIN_MAX_STEPS; ++k) {
        double f = log(p) + p / s - y;
        double next = p - f / (1.0 / p + 1.0 / s);
        if (!(next > 0.0)) next = 0.5 * p; /* cannot happen from below the root; never leave p > 0 */
        double step = fabs(next - p);
        p = next;
        if (step <= SLUT_LOGLIN_CONVERGED * p) break;
    }
    return p;
}

/* Inverse warp g⁻¹(y) (ifs, not a switch: see slut_warp_forward). */
SLUT_FN double slut_warp_inverse(int warp, double y, double p_min, double scale) {
    if (warp == SLUT_WARP_LOG) return exp(y);
    if (warp == SLUT_WARP_LOG1P) return p_min + scale * expm1(y);
    if (warp == SLUT_WARP_ASINH_COT) {
        /* y = −asinh(cot p)  ⇒  cot p = sinh(−y)  ⇒  p = atan2(1, sinh(−y)). */
        return atan2(1.0, sinh(-y));
    }
    if (warp == SLUT_WARP_SQRT1P) return y * y - 1.0;
    if (warp == SLUT_WARP_LOGLIN) return slut_loglin_inverse(y, scale);
    if (warp == SLUT_WARP_NL_QODDS) return exp(y);
    if (warp == SLUT_WARP_ASINH_COT_PEAK) return slut_asinh_cot_peak_inverse(y, scale);
    return y; /* SLUT_WARP_LINEAR */
}

/* p clamped to an axis [p_min, p_max], NaN to p_min (clamp-to-edge, as the samplers). */
SLUT_FN double slut_clamp_to_axis_range(double p, double p_min, double p_max) {
    return (p > p_min) ? ((p < p_max) ? p : p_max) : p_min;
}

/* Parameter → unit coordinate x ∈ [0, 1], for an axis [p_min, p_max] with this warp, whose
   warped ends g0 = g(p_min), g1 = g(p_max) a sampler may compute once. The parameter is clamped to the axis first (clamp-to-edge): a warp need not be defined
   beyond the ends (LOG1P below p_min − scale, LOG at p ≤ 0), and NaN goes to p_min, so
   that no parameter can give a node index outside the table. */
SLUT_FN double slut_unit_from_warped_ends(int warp, double p, double p_min, double p_max, double scale, double g0,
                                          double g1) {
    double q = slut_clamp_to_axis_range(p, p_min, p_max);
    return (slut_warp_forward(warp, q, p_min, scale) - g0) / (g1 - g0);
}
SLUT_FN double slut_unit_from_warp(int warp, double p, double p_min, double p_max, double scale) {
    return slut_unit_from_warped_ends(warp, p, p_min, p_max, scale, slut_warp_forward(warp, p_min, p_min, scale),
                                      slut_warp_forward(warp, p_max, p_min, scale));
}

/* Unit coordinate → GPU texture coordinate (texel centres at the domain ends). */
SLUT_FN double slut_texcoord_from_unit(double x, int count) {
    return (slut_clamp(x, 0.0, 1.0) * SLUT_DOUBLE(count - 1) + 0.5) / SLUT_DOUBLE(count);
}

/* Unit coordinate → position in nodes from node 0, clamped to [0, count − 1]
   (clamp-to-edge, never wrap). */
SLUT_FN double slut_node_position_from_unit(double x, int count) {
    return slut_clamp(x, 0.0, 1.0) * SLUT_DOUBLE(count - 1);
}

/* Node position t → the lower node i0 of the cell holding it (≤ count − 2) and the
   fraction f = t − i0 ∈ [0, 1] for linear interpolation between nodes i0 and i0 + 1. */
SLUT_FN int slut_cell_index(double t, int count) {
    int i = SLUT_INT(t);
    return (i > count - 2) ? count - 2 : i;
}
SLUT_FN double slut_cell_fraction(double t, int i0) { return t - SLUT_DOUBLE(i0); }

/* One axis as the maps need it (plain data, the same in every language; by value in shared
 * code that the snippets compile). */
SLUT_STRUCT_BEGIN(slut_axis)
    double min;   /* parameter at node 0 */
    double max;   /* parameter at node count − 1 */
    double scale; /* warp parameter (LOG1P: s); unused by the others */
    int warp;     /* SLUT_WARP_* */
    int count;    /* nodes, ≥ 2 */
SLUT_STRUCT_END(slut_axis);

/* Whether p lies on the axis, [min, max] (NaN: no). 1 or 0. */
SLUT_FN int slut_on_axis(slut_axis a, double p) { return (p >= a.min && p <= a.max) ? 1 : 0; }

#ifndef SLUT_SHADER /* the pointer forms and the runtime's fast path: C callers only */

/* The warped ends g(min), g(max) of an axis. They are constant per axis: a sampler that
   looks up many points computes them once and calls slut_unit_from_warped. */
SLUT_FN void slut_axis_warped_ends(const slut_axis *a, double *g0, double *g1) {
    *g0 = slut_warp_forward(a->warp, a->min, a->min, a->scale);
    *g1 = slut_warp_forward(a->warp, a->max, a->min, a->scale);
}

/* Parameter → unit coordinate x ∈ [0, 1] given the axis's warped ends (as slut_unit_from_warp). */
SLUT_FN double slut_unit_from_warped(const slut_axis *a, double p, double g0, double g1) {
    return slut_unit_from_warped_ends(a->warp, p, a->min, a->max, a->scale, g0, g1);
}

/* The runtime's five one-transcendental warps (LINEAR, LOG, LOG1P, SQRT1P, LOGLIN) in steps
 * around that transcendental, as lane-generic expressions: written once for a scalar
 * (slut_unit_from_warped_runtime below), for the runtime's 4-lane vectors of four queries on
 * one axis (warp a scalar) and of one query's axes (warp a vector of warp ids: the tests
 * select per lane, GCC's == and ?:; every operand is evaluated). p, x, arg, t, warped of one
 * type; the axis constants scalars or vectors of it.
 *   x      = SLUT_WARP_X(warp, p, p_min, scale):  (p − min)/s for LOG1P, p/s for LOGLIN
 *            (SLUT_WARP_X_TIMES_SCALE: its numerator, for a caller holding 1/s);
 *   arg    = SLUT_WARP_ARG(warp, p, x):           1 + x for LOG1P, 1 + p for SQRT1P, else p;
 *   t      = ln arg (LOG, LOGLIN, LOG1P), √max(arg, 0) (SQRT1P), arg (LINEAR): the caller's, so
 *            that independent ones can share a vector call;
 *   warped = SLUT_WARPED_GIVEN(warp, p, x, arg, t): g(p) (slut_warp_forward), LOG1P by
 *            Goldberg's form ln(1 + x)·x/((1 + x) − 1) (slut_log1p_goldberg: within a few ulps
 *            of libm's log1p; its log1p fallback for 1 + x = ∞ is ln ∞ = ∞ itself);
 *   unit   = SLUT_UNIT_OF_WARPED(p, warped, p_min, p_max, g0, g1): the ends returned exactly
 *            (0 for p ≤ min and NaN, 1 for p ≥ max: the end nodes are hit whatever the
 *            rounding of the warp there); SLUT_UNIT_CLAMPED with the inside given (a caller
 *            holding 1/(g1 − g0)).
 * The same operations in the same order as slut_warp_forward's (bit-identical on the axis). */
#define SLUT_WARP_HAS_RUNTIME_FORM(warp)                                                                      \
    ((warp) == SLUT_WARP_LINEAR || (warp) == SLUT_WARP_LOG || (warp) == SLUT_WARP_LOG1P ||                   \
     (warp) == SLUT_WARP_SQRT1P || (warp) == SLUT_WARP_LOGLIN)
#define SLUT_WARP_X_TIMES_SCALE(warp, p, p_min) (((warp) == SLUT_WARP_LOG1P) ? (p) - (p_min) : (p))
#define SLUT_WARP_X(warp, p, p_min, scale) (SLUT_WARP_X_TIMES_SCALE(warp, p, p_min) / (scale))
#define SLUT_WARP_ARG(warp, p, x)                                                                             \
    (((warp) == SLUT_WARP_LOG1P) ? 1.0 + (x) : ((warp) == SLUT_WARP_SQRT1P) ? 1.0 + (p) : (p))
#define SLUT_WARPED_GIVEN(warp, p, x, arg, t)                                                                 \
    (((warp) == SLUT_WARP_LOG) ? (t)                                                                          \
     : ((warp) == SLUT_WARP_LOGLIN) ? (t) + (x)                                                               \
     : ((warp) == SLUT_WARP_LOG1P) ? (((arg) == 1.0) ? (x) : ((arg) > 1.7976931348623157e308) ? (t)          \
                                                                : (t) * ((x) / ((arg) - 1.0)))                \
     : ((warp) == SLUT_WARP_SQRT1P) ? (t) : (p))
#define SLUT_UNIT_CLAMPED(p, p_min, p_max, inside) ((!((p) > (p_min))) ? 0.0 : ((p) >= (p_max)) ? 1.0 : (inside))
#define SLUT_UNIT_OF_WARPED(p, warped, p_min, p_max, g0, g1)                                                  \
    SLUT_UNIT_CLAMPED(p, p_min, p_max, ((warped) - (g0)) / ((g1) - (g0)))

/* The runtime samplers' parameter → unit coordinate: slut_unit_from_warped with the ends
   returned exactly and LOG1P by Goldberg's form (a log and a divide instead of libm's log1p;
   tests/kernels/test_fastmath): the steps above, the other warps by slut_warp_forward. */
SLUT_FN double slut_unit_from_warped_runtime(const slut_axis *a, double p, double g0, double g1) {
    if (!(p > a->min)) return 0.0;
    if (p >= a->max) return 1.0;
    int warp = a->warp;
    if (!SLUT_WARP_HAS_RUNTIME_FORM(warp)) return (slut_warp_forward(warp, p, a->min, a->scale) - g0) / (g1 - g0);
    double x = SLUT_WARP_X(warp, p, a->min, a->scale), arg = SLUT_WARP_ARG(warp, p, x);
    double t = (warp == SLUT_WARP_SQRT1P) ? sqrt(fmax(arg, 0.0)) : (warp == SLUT_WARP_LINEAR) ? arg : log(arg);
    return SLUT_UNIT_OF_WARPED(p, SLUT_WARPED_GIVEN(warp, p, x, arg, t), a->min, a->max, g0, g1);
}

/* The ASINH_COT warp from cot p instead of p: g = −asinh(cot p) = −ln(cot p + √(1 + cot² p)),
   cot p ≥ 0 (no cancellation in the sum; the log's absolute error ~1e-16 is all the unit
   coordinate sees). A caller that holds cot p (the airlight radiance has u·cot w and u)
   pays a log and a sqrt instead of the cos, sin and log of slut_warp_forward (libm's
   asinh costs about as much as those three here). cot p ≤ 1e150 (p ≥ 1e-150). */
SLUT_FN double slut_warp_asinh_cot_from_cot(double cot_p) { return -log(cot_p + sqrt(1.0 + cot_p * cot_p)); }

/* Parameter → unit coordinate x ∈ [0, 1] (the parameter clamped to the axis). */
SLUT_FN double slut_unit_from_param(const slut_axis *a, double p) {
    return slut_unit_from_warp(a->warp, p, a->min, a->max, a->scale);
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

/* Unit coordinate → (node index i0, fraction f) for linear interpolation between
   nodes i0 and i0 + 1; clamped to the domain (clamp-to-edge, never wrap). */
SLUT_FN void slut_cell_from_unit(double x, int count, int *i0, double *f) {
    double t = slut_node_position_from_unit(x, count);
    *i0 = slut_cell_index(t, count);
    *f = slut_cell_fraction(t, *i0);
}
#endif /* !SLUT_SHADER */

#endif /* SLUT_AXES_H */
