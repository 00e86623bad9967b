// θ/sin θ from cos θ and sin θ (internal; not installed): the thick medium's T·H of the
// near light, slut_nl_H_scaled(g, ∞) = acos(g)/√(1 − g²) (kernels/slut_nearlight_closed.h),
// for the scalar radiance's fast path, in one divide and a polynomial instead of the builtin
// atan and the three quotients around it.
#pragma once

#include <cmath>

#include "slut_compat.h"

namespace scatterlut::detail {

// θ/sin θ for θ ∈ [0, π] given g = cos θ and sg = sin θ ≥ 0 (sg as the kernel computes it:
// slut_nl_sin_from_cos(g)); 1 at sg = 0 < g, +∞ at sg = 0 > g (the ray runs through the
// light), π/2 at g = 0: the values slut_nl_H_scaled(g, ∞) gives.
//
// θ = atan2(sg, g) from a = atan(t), t = min(sg, |g|)/max(sg, |g|) ∈ [0, 1]:
//   sg ≤ |g|: θ = a (g > 0) or π − a (g < 0);   sg > |g|: θ = π/2 − a (g ≥ 0) or π/2 + a.
// atan(t) is fdlibm's (e_atan.c: its reduction intervals and the degree-22 odd polynomial,
// < 1 ulp for an exact reduced argument) with the reduction folded into t's quotient, so
// that the whole costs one divide: with n = min, d = max,
//   t < 7/16:          a = atan(n/d);
//   7/16 ≤ t < 11/16:  a = atan(1/2) + atan((2n − d)/(2d + n))      ((2t − 1)/(2 + t));
//   11/16 ≤ t ≤ 1:     a = π/4 + atan((n − d)/(n + d))               ((t − 1)/(t + 1)).
// The reduced argument's numerator and denominator round once each (2n is exact, n − d is
// exact near t = 1 by Sterbenz), so it carries ≤ ~1.5 ulp relative, and |x| ≤ 0.19 there
// against a ≥ 0.46: θ within ~2 ulp, θ/sg within ~3 (test
// NearLightTable.ThickAngleOverSineWithinUlpsOfTheReference, against long double, and the
// radiance against the general path's to 1e-12: ThickRadianceMatchesTheGeneralLookup).
// Real is double or a GCC vector of doubles (simd4::v2d): written once for both. The selects
// are `?:`, which GCC compiles to blends on vectors and, here, to branches on a double; the
// scalar radiance's fast path takes the vector form (one lane) because g is random per query
// (NearLightTable::radiance 3-D 1.03× faster: bench/README.md, "Issue #18's 3-D call").
template <class Real>
inline Real angle_over_sine(Real g, Real sg) {
    constexpr double aT[11] = {3.33333333333329318027e-01,  -1.99999999998764832476e-01, 1.42857142725034663711e-01,
                               -1.11111104054623557880e-01, 9.09088713343650656196e-02,  -7.69187620504482999495e-02,
                               6.66107313738753120669e-02,  -5.83357013379057348645e-02, 4.97687799461593236017e-02,
                               -3.65315727442169155270e-02, 1.62858201153657823623e-02};
    constexpr double atan_half_hi = 4.63647609000806093515e-01, atan_half_lo = 2.26987774529616870924e-17;
    constexpr double pio4_hi = 7.85398163397448278999e-01, pio4_lo = 3.06161699786838301793e-17;
    const Real zero{}; // 0, or a vector of zeros: the selects' constants take g's type from it
    const Real ag = g < 0.0 ? -g : g;
    const auto sine_smaller = sg <= ag;
    const Real n = sine_smaller ? sg : ag, d = sine_smaller ? ag : sg; // t = n/d ∈ [0, 1]
    const auto middle = n >= 0.4375 * d, upper = n >= 0.6875 * d;     // 7/16 ≤ t, 11/16 ≤ t
    const Real num = upper ? n - d : middle ? 2.0 * n - d : n;
    const Real den = upper ? n + d : middle ? 2.0 * d + n : d;
    const Real hi = upper ? zero + pio4_hi : middle ? zero + atan_half_hi : zero;
    const Real lo = upper ? zero + pio4_lo : middle ? zero + atan_half_lo : zero;
    const Real x = num / den, z = x * x, w = z * z;
    const Real s1 = z * (aT[0] + w * (aT[2] + w * (aT[4] + w * (aT[6] + w * (aT[8] + w * aT[10])))));
    const Real s2 = w * (aT[1] + w * (aT[3] + w * (aT[5] + w * (aT[7] + w * aT[9]))));
    const Real a = hi - ((x * (s1 + s2) - lo) - x); // fdlibm's sum: x − x(s1 + s2) for hi = lo = 0
    // θ with π and π/2 in two parts (SLUT_PIO2_HI + SLUT_PIO2_LO).
    const Real theta = sine_smaller ? (g > 0.0 ? a : (2.0 * SLUT_PIO2_HI - a) + 2.0 * SLUT_PIO2_LO)
                                    : (g >= 0.0 ? (SLUT_PIO2_HI - a) + SLUT_PIO2_LO : (SLUT_PIO2_HI + a) + SLUT_PIO2_LO);
    // sg = 0 (or NaN): g = ±1, θ = 0 (the limit 1) or θ = π (divergent)
    return sg > 0.0 ? theta / sg : g > 0.0 ? zero + 1.0 : zero + HUGE_VAL;
}

} // namespace scatterlut::detail
