/* scatterlut — ln(1 + x) in a form whose log a vector call can share, and the sine and cosine
 * of a half angle cheaper than libm's, for the runtime lookups (tables/src: the table radiance
 * and the samplers' warps).
 *
 * Why: a table lookup costs a few multiply-adds; the transcendentals around it (one warp
 * per axis, an exp to decode, the geometry's angles) are what a radiance call pays. glibc's
 * exp, log, atan and expm1 are table-driven and as fast as any polynomial of the same
 * accuracy (a Taylor exp and log written here were slower than libm's, in a throughput loop
 * and again in the runtime's 4-lane calls against libmvec's), so those stay libm's. The two
 * below (`scatterlut_bench --benchmark_filter=BM_FastMath`: /0 against sincos /1, /2 against
 * log1p /3; on a 2-core AMD EPYC VM, glibc 2.36: 9.8 against 23 ns, 16.1 against 15.5 ns):
 *   log1p: Goldberg's form ln(1 + x) = ln(u)·x/(u − 1), u = fl(1 + x): a log and a divide,
 *          within a few ulps (Goldberg 1991, "What every computer scientist should know
 *          about floating-point arithmetic", Theorem 4). No cheaper than glibc's log1p
 *          there; what it buys is its log, which the runtime's 4-lane warps share with the other
 *          axes' (slut_axes.h's SLUT_WARPED_GIVEN);
 *   sin, cos of h ∈ [0, π/2]: Taylor series on [0, π/4] to h^17 and h^18 (remainders
 *          ≤ 6e-17 and 2e-18 relative), above it by the complement π/2 − h (π/2 as hi + lo).
 * Both are tested against libm over their domains in tests/kernels/test_fastmath.cpp (maximum
 * error in ulps, the special points exactly). Compiled as C++ (valid OpenCL C); not part
 * of the GLSL/HLSL snippets.
 */
#ifndef SLUT_FASTMATH_H
#define SLUT_FASTMATH_H

#include "slut_compat.h"

/* ln(1 + x) for x > −1 with full relative precision near 0 (Goldberg's form; libm's
 * log1p for NaN, x ≤ −1 and 1 + x = ∞). */
SLUT_FN double slut_log1p_goldberg(double x) {
    double u = 1.0 + x;
    if (u == 1.0) return x;
    if (!(x > -1.0) || !(u <= 1.7976931348623157e308)) return log1p(x);
    return log(u) * (x / (u - 1.0));
}

/* sin h and cos h for h ∈ [0, π/4] (Taylor; see the header). The polynomials in z = h² by
 * Estrin's scheme (pairs of terms beside z² and z⁴): a chain of 5 operations after z where
 * Horner's is 9 (the airlight's scalar call waits on it); cos's leading 1/2 by Horner, for
 * Horner's rounding (≤ 1 ulp; an Estrin sum of all of cos's terms was 1.4 ulps). Written once
 * as lane-generic steps, so that the runtime's 4-lane batch (a vector h) takes the same
 * operations: SLUT_SIN_QUARTER(h, z, z2, z4) and SLUT_COS_QUARTER(z, z2, z4) with z = h²,
 * z2 = z², z4 = z2². */
#define SLUT_SIN_QUARTER(h, z, z2, z4)                                                                     \
    ((h) + ((h) * (z)) * (((-1.0 / 6.0 + (z) * (1.0 / 120.0)) + (z2) * (-1.0 / 5040.0 + (z) * (1.0 / 362880.0))) + \
                          (z4) * ((-1.0 / 39916800.0 + (z) * (1.0 / 6227020800.0)) +                          \
                                  (z2) * (-1.0 / 1307674368000.0 + (z) * (1.0 / 355687428096000.0)))))
#define SLUT_COS_QUARTER(z, z2, z4)                                                                        \
    (1.0 - (z) * (0.5 + (z) * (((-1.0 / 24.0 + (z) * (1.0 / 720.0)) + (z2) * (-1.0 / 40320.0 + (z) * (1.0 / 3628800.0))) + \
                               (z4) * ((-1.0 / 479001600.0 + (z) * (1.0 / 87178291200.0)) +                  \
                                       (z2) * (-1.0 / 20922789888000.0 + (z) * (1.0 / 6402373705728000.0))))))
SLUT_FN void slut_sincos_quarter(double h, double *sin_h, double *cos_h) {
    double z = h * h, z2 = z * z, z4 = z2 * z2;
    *sin_h = SLUT_SIN_QUARTER(h, z, z2, z4);
    *cos_h = SLUT_COS_QUARTER(z, z2, z4);
}

/* sin h and cos h for h ∈ [0, π/2] (a half angle γ/2 of γ ∈ [0, π]). */
SLUT_FN void slut_sincos_half_angle(double h, double *sin_h, double *cos_h) {
    if (h <= 0.78539816339744828) {
        slut_sincos_quarter(h, sin_h, cos_h);
    } else {
        slut_sincos_quarter(slut_pio2_minus(h), cos_h, sin_h);
    }
}

#endif /* SLUT_FASTMATH_H */
