/* scatterlut — the lane layer of the near-light sweep: a double16 per block of r values on
 * the device (OpenCL C), one double on the host (C++).
 *
 * Used by kernels/slut_nearlight_march.h only; never compiled by the GPU snippets.
 */
#ifndef SLUT_NEARLIGHT_LANES_H
#define SLUT_NEARLIGHT_LANES_H

#include "slut_compat.h"

#define SLUT_NL_MAX_LANES 16      /* r values sharing one (T, g, S) panel mesh            */

/* ------------------------------------------------------------------ lane vectors */

/* The lanes of a march (the r values sharing one panel mesh, slut_nl_E_sweep) in blocks of
 * SLUT_NL_LANE_WIDTH elements of type slut_nl_lanes: a double16 on the device (one block for
 * a full group), a double on the host. Why: per (node, lane) the sweep costs one divide and
 * one exp; PoCL does not vectorise a scalar loop over the lanes, and in such a loop a scalar
 * exp costs ~10× what a double8 or double16 exp costs per element (docs/POCL.md, measured on
 * PoCL 3.1). The sweep is written once on slut_nl_lanes with C operators and the builtins
 * exp, fmin, fmax (overloaded for vectors in OpenCL C); only these definitions differ
 * between the languages:
 *   SLUT_NL_LANES_SPLAT(x)         every element x;
 *   SLUT_NL_LANES_SELECT(a, b, c)  b where the lane comparison c holds, else a (both evaluated);
 *   SLUT_NL_LANES_ANY(c)           whether c holds in some element;
 *   slut_nl_lanes_load             a block from SLUT_NL_LANE_WIDTH consecutive doubles;
 *   slut_nl_lanes_max / _min       the largest / smallest element;
 *   slut_nl_expm1_8                expm1 of 8 consecutive doubles (a double8 on the device:
 *                                  the layer variable's node offsets, slut_nl_E_sweep);
 *   slut_nl_lanes_exp2             2^v per element (the node loop's attenuation).
 * Lane comparisons combine with & (a vector comparison is −1/0 per element, a scalar one 1/0:
 * never mix the two). */
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
#define SLUT_NL_LANE_WIDTH 16
typedef double16 slut_nl_lanes;
#define SLUT_NL_LANES_SPLAT(x) ((double16)(x))
#define SLUT_NL_LANES_SELECT(a, b, c) select((a), (b), (c))
#define SLUT_NL_LANES_ANY(c) any(c)
SLUT_FN slut_nl_lanes slut_nl_lanes_load(const double *p) { return vload16(0, p); }
SLUT_FN void slut_nl_lanes_store(slut_nl_lanes v, double *p) { vstore16(v, 0, p); }
SLUT_FN double slut_nl_lanes_max(slut_nl_lanes v) {
    double8 a = fmax(v.lo, v.hi);
    double4 b = fmax(a.lo, a.hi);
    double2 c = fmax(b.lo, b.hi);
    return fmax(c.x, c.y);
}
SLUT_FN double slut_nl_lanes_min(slut_nl_lanes v) {
    double8 a = fmin(v.lo, v.hi);
    double4 b = fmin(a.lo, a.hi);
    double2 c = fmin(b.lo, b.hi);
    return fmin(c.x, c.y);
}
SLUT_FN void slut_nl_expm1_8(const double *x, double *out) { vstore8(expm1(vload8(0, x)), 0, out); }
/* 2^v on a lane vector: the node loop's attenuation (slut_nl_E_sweep), ≤ 3 ulps (measured
 * 2.41 over 1.5 million arguments: NearLightKernel.LaneExp2WithinThreeUlps). v = k + f with
 * k = rint(v) and f = v − k ∈ [−½, ½] exact; 2^f = 1 + f·P(f), P of degree 9 by Horner's
 * rule, the minimax polynomial for the relative error (kernels/exp2_minimax.py: 2.2e-16, ~1.5
 * ulps, with its double coefficients; the rest is the rounding of the Horner steps); then
 * u·2^k rounded once, as 2^⌊k/2⌋ · 2^(k−⌊k/2⌋) (both factors normal for |v| ≤ 1100, so a
 * subnormal result is rounded once, in the second product). 0 below v = −1100, +∞ above
 * 1100; NaN stays NaN. The sweep's sums carry ~1e-13 of quadrature error (the default
 * tolerance 1e-11): a few ulps per node change no table's measured accuracy.
 * Why not the builtin exp: PoCL 3.1's vector exp (SLEEF's Sleef_exp_u10, ≤ 1 ulp) reduces by
 * ln 2 in two parts and evaluates a polynomial of degree 12, after the caller's −T·(τ + η q)
 * and the ·1/ln 2: ~21 multiplies and multiply-adds per element. In base 2 the sweep folds
 * −T·log2(e) into its per-node factors (v = c0 + c1·q, one multiply-add), the reduction is
 * one subtraction and the polynomial of degree 10: ~14 (bench/README.md, "The node loop in
 * base 2", measures what that saves). The integer steps:
 *  - on a CPU with AVX-512 (SLUT_NL_EXP_AVX512, from the compiler's target), k by
 *    vrndscalepd (round to nearest even, as rint) and u·2^k by vscalefpd, which rounds the
 *    exact product once, as the two products do: the same doubles;
 *  - elsewhere, k by the 1.5·2^52 shift below and 2^k built in 64-bit lanes (PoCL's rint on a
 *    double16 is a long software sequence). */
#ifndef SLUT_NL_EXP_AVX512 /* a build option -DSLUT_NL_EXP_AVX512=0 selects the portable steps (test) */
#if defined(__AVX512F__) && defined(__has_builtin)
#if __has_builtin(__builtin_ia32_scalefpd512_mask) && __has_builtin(__builtin_ia32_rndscalepd_mask)
#define SLUT_NL_EXP_AVX512 1
#endif
#endif
#endif
#ifndef SLUT_NL_EXP_AVX512
#define SLUT_NL_EXP_AVX512 0
#endif
SLUT_FN slut_nl_lanes slut_nl_lanes_exp2(slut_nl_lanes v) {
#pragma OPENCL FP_CONTRACT OFF
    /* No contraction: the polynomial's fma are explicit, f = v − k is exact. */
#if SLUT_NL_EXP_AVX512
    /* vrndscalepd, immediate 8: round to nearest even, no precision exception. */
    slut_nl_lanes k;
    k.lo = __builtin_ia32_rndscalepd_mask(v.lo, 8, v.lo, (uchar)0xff, 4);
    k.hi = __builtin_ia32_rndscalepd_mask(v.hi, 8, v.hi, (uchar)0xff, 4);
#else
    /* k = rint(v) as (v + 1.5·2^52) − 1.5·2^52: the sum rounds v to an integer (ties to even,
     * as rint) wherever |v| < 2^51, and its low mantissa bits are k. Beyond, the last two
     * selects replace the result. */
    const slut_nl_lanes round_shift = (slut_nl_lanes)(0x1.8p52);
    slut_nl_lanes shifted = v + round_shift;
    slut_nl_lanes k = shifted - round_shift;
#endif
    slut_nl_lanes f = v - k;
    /* exp2 polynomial begin (kernels/exp2_minimax.py --check compares these) */
    slut_nl_lanes u = fma(0x1.e3a907013632dp-28, f, 0x1.b671b301aba6fp-24);
    u = fma(u, f, 0x1.62c147a345fe0p-20);
    u = fma(u, f, 0x1.ffcb58ca1f55dp-17);
    u = fma(u, f, 0x1.4309126c01410p-13);
    u = fma(u, f, 0x1.5d87fe9b8f035p-10);
    u = fma(u, f, 0x1.3b2ab6fbd6d03p-7);
    u = fma(u, f, 0x1.c6b08d703e17ap-5);
    u = fma(u, f, 0x1.ebfbdff82c431p-3);
    u = fma(u, f, 0x1.62e42fefa3a12p-1);
    /* exp2 polynomial end */
    u = fma(u, f, 1.0);
#if SLUT_NL_EXP_AVX512
    /* vscalefpd: u·2^⌊k⌋ rounded once (mask all lanes, current rounding mode). */
    u.lo = __builtin_ia32_scalefpd512_mask(u.lo, k.lo, u.lo, (uchar)0xff, 4);
    u.hi = __builtin_ia32_scalefpd512_mask(u.hi, k.hi, u.hi, (uchar)0xff, 4);
#else
    long16 j = as_long16(shifted) - as_long16(round_shift), j_half = j >> 1;
    u = u * as_double16(as_ulong16(j_half + 1023) << 52);
    u = u * as_double16(as_ulong16(j - j_half + 1023) << 52);
#endif
    u = select(u, (slut_nl_lanes)(SLUT_HUGE_VAL), v > 1100.0);
    return select(u, (slut_nl_lanes)(0.0), v < -1100.0);
}
#else
#define SLUT_NL_LANE_WIDTH 1
typedef double slut_nl_lanes;
#define SLUT_NL_LANES_SPLAT(x) ((double)(x))
#define SLUT_NL_LANES_SELECT(a, b, c) ((c) ? (b) : (a))
#define SLUT_NL_LANES_ANY(c) (c)
SLUT_FN slut_nl_lanes slut_nl_lanes_load(const double *p) { return *p; }
SLUT_FN void slut_nl_lanes_store(slut_nl_lanes v, double *p) { *p = v; }
SLUT_FN double slut_nl_lanes_max(slut_nl_lanes v) { return v; }
SLUT_FN double slut_nl_lanes_min(slut_nl_lanes v) { return v; }
SLUT_FN void slut_nl_expm1_8(const double *x, double *out) {
    for (int k = 0; k < 8; ++k) out[k] = expm1(x[k]);
}
SLUT_FN slut_nl_lanes slut_nl_lanes_exp2(slut_nl_lanes v) { return exp2(v); }
#endif
#define SLUT_NL_LANE_BLOCKS (SLUT_NL_MAX_LANES / SLUT_NL_LANE_WIDTH) /* blocks of a full group */

/* Lanes first_lane … first_lane + W − 1 of out[] (those below `lanes`) from block v. */
SLUT_FN void slut_nl_lanes_put(slut_nl_lanes v, double *out, int first_lane, int lanes) {
    double e[SLUT_NL_LANE_WIDTH];
    slut_nl_lanes_store(v, e);
    for (int k = 0; k < SLUT_NL_LANE_WIDTH && first_lane + k < lanes; ++k) out[first_lane + k] = e[k];
}

/* q(τ) = τ/(τ + r): the fraction of the light path inside the medium, for τ > 0 (every
 * quadrature node and every panel start after the first). r = 0 gives q = 1 exactly (x/x),
 * r = +∞ gives q = 0. */
SLUT_FN slut_nl_lanes slut_nl_q(double tau, slut_nl_lanes r) { return tau / (tau + r); }

/* r/(τ + r)² = dq/dτ: the layer's share of the exponent's slope, divided by Tη; 0 for r = 0
 * and r = +∞ (also at τ = 0, where 0/0 would arise). */
SLUT_FN slut_nl_lanes slut_nl_layer_slope(double tau, slut_nl_lanes r) {
    return SLUT_NL_LANES_SELECT(SLUT_NL_LANES_SPLAT(0.0), (r / (tau + r)) / (tau + r), (r > 0.0) & (r <= 1e300));
}

#endif /* SLUT_NEARLIGHT_LANES_H */
