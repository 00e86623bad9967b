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
 *                                  the layer variable's node offsets, slut_nl_E_sweep).
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
/* exp on a lane vector, the same double as the device's builtin exp gives: PoCL 3.1's vector
 * exp (SLEEF's Sleef_exp_u10, ≤ 1 ulp) restated operation by operation with its constants:
 * x = k ln 2 + s, k = rint(x/ln 2) (ln 2 in two parts, two fma), e^s by a polynomial of degree
 * 12 (its odd and even parts in s², then twice u·s + 1, all fma), then u·2^k rounded once
 * (SLEEF: 2^⌊k/2⌋ · 2^(k−⌊k/2⌋), both factors normal down to x = −1000, so a subnormal result
 * is rounded once, in the second product); +∞ above 709.78, 0 below −1000. Only the integer
 * steps are cheaper than the builtin's (it rounds each 4-lane quarter with vroundpd and builds
 * 2^k in 32-bit halves; PoCL's rint on a double16 is a long software sequence):
 *  - on a CPU with AVX-512 (the macro SLUT_NL_EXP_AVX512, from the compiler's target), k by
 *    vrndscalepd (round to nearest even, as rint) and u·2^k by vscalefpd, which rounds the
 *    exact product once, as the two products do: two instructions per 8 lanes for the ~10
 *    integer steps and two multiplies of 2^k. E3 64³ kernel: ~1.09× less CPU time
 *    (bench/README.md, "the node loop's exp, second round");
 *  - elsewhere, k by the 1.5·2^52 shift below and 2^k built in 64-bit lanes (~1.08× less
 *    than the builtin; "the node loop's exp").
 * The node loop of slut_nl_E_sweep spends most of its time in this exp; tables unchanged bit
 * for bit. Test: NearLightKernel.LaneExpMatchesBuiltin (1.3 million arguments, none differs). */
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
SLUT_FN slut_nl_lanes slut_nl_lanes_exp(slut_nl_lanes x) {
#pragma OPENCL FP_CONTRACT OFF
    /* No contraction: v is rounded before it is rounded to an integer, as in the builtin. */
    slut_nl_lanes v = x * 0x1.71547652b82fep+0;
#if SLUT_NL_EXP_AVX512
    /* vrndscalepd, immediate 8: round to nearest even, no precision exception. */
    slut_nl_lanes k;
    k.lo = __builtin_ia32_rndscalepd_mask(v.lo, 8, v.lo, (uchar)0xff, 4);
    k.hi = __builtin_ia32_rndscalepd_mask(v.hi, 8, v.hi, (uchar)0xff, 4);
#else
    /* k = rint(v) as (v + 1.5·2^52) − 1.5·2^52: the sum rounds v to an integer (ties to even,
     * as rint) wherever |v| < 2^51, i.e. |x| < 1.5e15, and its low mantissa bits are k.
     * Beyond, both results are replaced (0 or +∞) by the last two selects. */
    const slut_nl_lanes round_shift = (slut_nl_lanes)(0x1.8p52);
    slut_nl_lanes shifted = v + round_shift;
    slut_nl_lanes k = shifted - round_shift;
#endif
    slut_nl_lanes s = fma(k, -0x1.62e42fefa3000p-1, x);
    s = fma(k, -0x1.3de6af278ece6p-42, s);
    slut_nl_lanes s2 = s * s;
    slut_nl_lanes even = fma(0x1.1e0c670afff06p-29, s2, 0x1.27e5d38a23654p-22);
    even = fma(even, s2, 0x1.a01a0127f883ap-16);
    even = fma(even, s2, 0x1.6c16c16c3396bp-10);
    even = fma(even, s2, 0x1.55555555554f9p-5);
    even = fma(even, s2, 0.5);
    slut_nl_lanes odd = fma(0x1.af6c36f75740cp-26, s2, 0x1.71ddef633fb47p-19);
    odd = fma(odd, s2, 0x1.a01a01b4421fdp-13);
    odd = fma(odd, s2, 0x1.111111110e7a5p-7);
    odd = fma(odd, s2, 0x1.555555555555ep-3);
    slut_nl_lanes u = fma(odd, s, even);
    u = fma(u, s, 1.0);
    u = fma(u, s, 1.0);
#if SLUT_NL_EXP_AVX512
    /* vscalefpd: u·2^⌊k⌋ rounded once (mask all lanes, current rounding mode). */
    u.lo = __builtin_ia32_scalefpd512_mask(u.lo, k.lo, u.lo, (uchar)0xff, 4);
    u.hi = __builtin_ia32_scalefpd512_mask(u.hi, k.hi, u.hi, (uchar)0xff, 4);
#else
    long16 j = as_long16(shifted) - as_long16(round_shift), j_half = j >> 1;
    u = u * as_double16(as_ulong16(j_half + 1023) << 52);
    u = u * as_double16(as_ulong16(j - j_half + 1023) << 52);
#endif
    u = select(u, (slut_nl_lanes)(SLUT_HUGE_VAL), x > 0x1.62e42fe102c83p+9);
    return select(u, (slut_nl_lanes)(0.0), x < -1000.0);
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
SLUT_FN slut_nl_lanes slut_nl_lanes_exp(slut_nl_lanes x) { return exp(x); }
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
