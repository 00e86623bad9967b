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
 *   slut_nl_expm1_panel            e^o − 1 at a panel's 8 near-half offsets o and e^D − 1 at its
 *                                  end D (the layer variable's nodes, slut_nl_E_sweep);
 *   slut_nl_lanes_exp2             2^v per element (the node loop's attenuation);
 *   slut_nl_lanes_expm1            e^y − 1 per element (the 4-D table kernel's value base);
 *   slut_nl_lanes_log              ln x per element (the table kernel's stored ln E).
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
/* k = rint(v) (ties to even) for |v| < 2^51, as a double and (*j) as a 64-bit integer:
 * v + 1.5·2^52 rounds v to an integer, whose low mantissa bits are k. Beyond, the callers'
 * selects replace their results. (PoCL's rint on a double16 is a long software sequence.) */
SLUT_FN slut_nl_lanes slut_nl_lanes_rint_shift(slut_nl_lanes v, long16 *j) {
#pragma OPENCL FP_CONTRACT OFF
    const slut_nl_lanes round_shift = (slut_nl_lanes)(0x1.8p52);
    slut_nl_lanes shifted = v + round_shift;
    *j = as_long16(shifted) - as_long16(round_shift);
    return shifted - round_shift;
}
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
 *  - elsewhere, k by the 1.5·2^52 shift (slut_nl_lanes_rint_shift) and 2^k built in 64-bit
 *    lanes. */
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
    long16 j;
    slut_nl_lanes k = slut_nl_lanes_rint_shift(v, &j);
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
    long16 j_half = j >> 1;
    u = u * as_double16(as_ulong16(j_half + 1023) << 52);
    u = u * as_double16(as_ulong16(j - j_half + 1023) << 52);
#endif
    u = select(u, (slut_nl_lanes)(SLUT_HUGE_VAL), v > 1100.0);
    return select(u, (slut_nl_lanes)(0.0), v < -1100.0);
}
/* e^y − 1 on a lane vector: the 4-D table kernel's value base (kernels/nearlight_E.cl), ≤ 3
 * ulps for y ≤ 0, the side the value base uses (measured 2.35), ≤ 4 for y > 0 (3.31, next to
 * y = ln 2/2, where the two terms below partly cancel; NearLightKernel.LaneExpm1WithinUlpBounds);
 * −1 below y = −42 (e^y < 2^−60), +∞ above 709.78, NaN for NaN. k = rint(y·log2(e)) as in
 * slut_nl_lanes_exp2, f = (y − k ln 2)·log2(e); 2^f − 1 = f·P(f), P of degree 10, the minimax
 * polynomial for the relative error of 2^f − 1 down to f = 0 (kernels/exp2_minimax.py,
 * "expm1": 5.4e-17 with its double coefficients); then e^y − 1 = 2^k·(2^f − 1) + (2^k − 1),
 * the product exact and 2^k − 1 exact for −53 ≤ k ≤ 53, one rounding in the sum.
 * Why not the builtin: PoCL 3.1's expm1 on a double8 works in double-double arithmetic; the
 * E4 kernel spent ~8 % of its time in it (bench/README.md, "The node loop in base 2"). */
SLUT_FN slut_nl_lanes slut_nl_lanes_expm1(slut_nl_lanes y) {
#pragma OPENCL FP_CONTRACT OFF
    y = select(y, (slut_nl_lanes)(-42.0), y < -42.0); /* e^y < 2^−60 below: the result rounds to −1 */
    long16 j;
    slut_nl_lanes k = slut_nl_lanes_rint_shift(y * 0x1.71547652b82fep+0, &j);
    /* f = (y − k ln 2)·log2(e), ln 2 in two parts (k ln 2's high part exact); y·log2(e) itself
     * carries |y·log2(e)|·2^−53 of rounding, which 2^f would turn into a relative error of
     * ~1e-14 at y = 500. */
    slut_nl_lanes f = fma(k, -0x1.62e42fefa3000p-1, y);
    f = fma(k, -0x1.3de6af278ece6p-42, f) * 0x1.71547652b82fep+0;
    /* expm1 polynomial begin (kernels/exp2_minimax.py --check compares these) */
    slut_nl_lanes u = fma(0x1.e8cab8bb70565p-32, f, 0x1.e605d28d2356ap-28);
    u = fma(u, f, 0x1.b525a092b3f97p-24);
    u = fma(u, f, 0x1.62bfd4b4acfe9p-20);
    u = fma(u, f, 0x1.ffcbfc1ea3ac5p-17);
    u = fma(u, f, 0x1.4309130958e7cp-13);
    u = fma(u, f, 0x1.5d87fe78b211ap-10);
    u = fma(u, f, 0x1.3b2ab6fba1e40p-7);
    u = fma(u, f, 0x1.c6b08d704a08ep-5);
    u = fma(u, f, 0x1.ebfbdff82c598p-3);
    u = fma(u, f, 0x1.62e42fefa39efp-1);
    /* expm1 polynomial end */
    /* 2^k for k ≤ 1023; k = 1024 (y within ln 2/2 of the overflow) as 2·(2^1023·(…)), the
     * doubling exact or +∞. */
    j = min(j, (long16)(1023));
    slut_nl_lanes two_k = as_double16((j + 1023) << 52);
    slut_nl_lanes e = fma(two_k, f * u, two_k - 1.0);
    e = select(e, 2.0 * e, k > 1023.0);
    return select(e, (slut_nl_lanes)(SLUT_HUGE_VAL), y > 0x1.62e42fefa39efp+9);
}
/* e^o − 1 for the 8 offsets o_near[] (into em[]) and e^D − 1 (returned): one lane vector,
 * lanes 0–7 the offsets, 8–15 D. Every argument is ≥ 0 here, so ≤ 4 ulps each (above). Why
 * not the builtin: PoCL 3.1's expm1 on a double8 and a double (SLEEF's, in double-double
 * arithmetic) took ~4 % of the 3-D table kernel's time (bench/README.md, "The airlight
 * batch's check and lookups; the sweep's pow and layer expm1"). */
SLUT_FN double slut_nl_expm1_panel(double D, const double *o_near, double *em) {
    slut_nl_lanes e = slut_nl_lanes_expm1((double16)(vload8(0, o_near), (double8)(D)));
    vstore8(e.lo, 0, em);
    return e.s8;
}
/* ln x on a lane vector: the table kernel's stored ln E (kernels/nearlight_E.cl), < 1 ulp
 * (NearLightKernel.LaneLogWithinAnUlp). fdlibm's __ieee754_log as musl's log.c has it, its
 * operations and constants unchanged, on 64-bit lanes: x = 2^k·m with m ∈ [√½, √2) (a
 * subnormal x scaled by 2^54 first), f = m − 1, s = f/(2 + f), ln m = f − ½f² + s(½f² + R(s²)),
 * R of degree 14 in s (Lg1 … Lg7), ln 2 in two parts. −∞ for ±0, NaN below 0 and for NaN, +∞
 * for +∞. Why not the builtin: PoCL 3.1's double16 log (SLEEF's, in double-double arithmetic)
 * took ~5 % of the 4-D table kernel's time (bench/README.md, "The node loop in base 2"). */
SLUT_FN slut_nl_lanes slut_nl_lanes_log(slut_nl_lanes x) {
#pragma OPENCL FP_CONTRACT OFF
    /* No contraction: fdlibm's error analysis assumes each operation rounded on its own. */
    long16 subnormal = (x < 0x1p-1022) & (x > 0.0);
    slut_nl_lanes xs = select(x, x * 0x1p54, subnormal);
    /* Reduce into [√½, √2): shift the exponent field so that m's high word starts at √½'s. */
    long16 bits = as_long16(xs) + ((long16)(0x3ff00000L - 0x3fe6a09eL) << 32);
    long16 k = (bits >> 52) - 0x3ff + select((long16)(0), (long16)(-54), subnormal);
    slut_nl_lanes m = as_double16((bits & 0x000fffffffffffffL) + (0x3fe6a09eL << 32));
    slut_nl_lanes f = m - 1.0;
    slut_nl_lanes hfsq = 0.5 * f * f;
    slut_nl_lanes s = f / (2.0 + f);
    slut_nl_lanes z = s * s;
    slut_nl_lanes w = z * z;
    slut_nl_lanes t1 = w * (3.999999999940941908e-01 + w * (2.222219843214978396e-01 + w * 1.531383769920937332e-01));
    slut_nl_lanes t2 = z * (6.666666666666735130e-01 +
                            w * (2.857142874366239149e-01 + w * (1.818357216161805012e-01 + w * 1.479819860511658591e-01)));
    slut_nl_lanes R = t2 + t1;
    slut_nl_lanes dk = convert_double16(k);
    slut_nl_lanes ln = s * (hfsq + R) + dk * 1.90821492927058770002e-10 - hfsq + f + dk * 6.93147180369123816490e-01;
    ln = select(ln, (slut_nl_lanes)(-SLUT_HUGE_VAL), x == 0.0);
    ln = select(ln, (slut_nl_lanes)(SLUT_HUGE_VAL), x == SLUT_HUGE_VAL);
    return select(ln, (slut_nl_lanes)(NAN), !(x >= 0.0));
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
SLUT_FN slut_nl_lanes slut_nl_lanes_exp2(slut_nl_lanes v) { return exp2(v); }
SLUT_FN slut_nl_lanes slut_nl_lanes_expm1(slut_nl_lanes y) { return expm1(y); }
SLUT_FN double slut_nl_expm1_panel(double D, const double *o_near, double *em) {
    for (int k = 0; k < 8; ++k) em[k] = expm1(o_near[k]);
    return expm1(D);
}
SLUT_FN slut_nl_lanes slut_nl_lanes_log(slut_nl_lanes x) { return log(x); }
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
