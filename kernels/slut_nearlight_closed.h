/* scatterlut — the near-light integral's closed-form weight H(T, g, S) and its small helpers.
 *
 * H = ∫_0^S ĥ^{−2} dt, the inverse-square weight of the near-light integral (symbols and
 * geometry: kernels/slut_nearlight.h, docs/PHYSICS.md §1.2). Compiled as OpenCL C (the
 * table kernels' sweep), as C++ (the runtime library, the host) and, whole, as GLSL/HLSL
 * in float (the near-light snippet: cmake/assemble_shaders.cmake); written in the subset
 * the five languages share (kernels/slut_compat.h).
 */
#ifndef SLUT_NEARLIGHT_CLOSED_H
#define SLUT_NEARLIGHT_CLOSED_H

#include "slut_compat.h"

/* ------------------------------------------------------------------ small helpers */

/* √(1 − g²) without cancellation as |g| → 1 (1 − |g| is exact for |g| ≥ ½, Sterbenz). */
SLUT_FN double slut_nl_sin_from_cos(double g) {
    double a = fabs(g);
    return (a >= 1.0) ? 0.0 : sqrt((1.0 - a) * (1.0 + a));
}


/* ∫ ĥ^{−2} dt over a segment of the ray of length len (≥ 0, may be +∞) that starts at a point
 * with ĥ² = hh2 and offset d = t + T g, w = T√(1 − g²) (all lengths in any one unit).
 *
 * Derivation: with the light at the origin, P(t) = P0 + t e (|P0| = T, P0·e = T g), the
 * angle φ subtended at the light obeys dφ = w dt/ĥ², and between the segment ends
 * |P(a) × P(a+len)| = len·w, P(a)·P(a+len) = ĥ(a)² + len·d(a). Hence
 *   ∫ = Δφ/w,  Δφ = atan2(len·w, hh2 + len·d)      (len = ∞: Δφ = atan2(w, d)),
 * evaluated as (len/den)·atanc(len·w/den) while the angle is below π/2 (den > 0): no
 * division by w, so the limits w → 0 (g → ±1) are exact: len/(ĥ(a)(ĥ(a) + len·sign)).
 * Above π/2 the angle is ≥ π/2 and (π − atan(len·w/|den|))/w has no cancellation; it is
 * +∞ at w = 0 (the segment runs through the light: g = −1, S ≥ T).
 * Citation: elementary; the angle substitution of Sun et al. 2005 (the airlight F, §1.1).
 *
 * In lane-generic steps around the one atan (as slut_axes.h's SLUT_WARP_X): written once for
 * the scalar function below and the runtime's 4-lane vectors of four queries
 * (tables/src/nearlight.cpp; GCC's comparisons, ! and ?: select per lane, every operand
 * evaluated). len, hh2, d, w, den, x, a of one type:
 *   den = SLUT_NL_ISQ_DEN(len, hh2, d):  hh2 + len·d (d for len = ∞);
 *   x   = SLUT_NL_ISQ_NUM(len, w)/|den|: len·w/|den| (w/|d| for len = ∞), and
 *   a   = atan x: the caller's, so that a vector call serves four lanes (a call the compiler
 *         does not merge, as libmvec's, goes in a variable: the macro names a twice);
 *   ∫   = SLUT_NL_ISQ_OF_ATAN(len, den, w, x, a): 0 for len ≤ 0; den > 0: atanc(x)·(len/den)
 *         (atanc(x)/d for len = ∞); den ≤ 0: (π − a)/w, +∞ at w = 0, and den = 0 (±0):
 *         (π − π/2)/w = π/(2w) whatever x (0/0 where len·w underflows). Each case's
 *         operations in a fixed order: the generator's sweep (so the default tables) depends
 *         on them to the bit.
 * One line each: GLSL before 4.20 has no line continuation. */
#define SLUT_NL_ISQ_INFINITE(len) ((len) > SLUT_INFINITE_ABOVE)
#define SLUT_NL_ISQ_DEN(len, hh2, d) (SLUT_NL_ISQ_INFINITE(len) ? (d) : (hh2) + (len) * (d))
#define SLUT_NL_ISQ_NUM(len, w) (SLUT_NL_ISQ_INFINITE(len) ? (w) : (len) * (w))
#define SLUT_NL_ISQ_ATANC(x, a) (((x) == 0.0) ? 1.0 : (a) / (x)) /* atan(x)/x, x ≥ 0 (atan returns tiny x exactly) */
#define SLUT_NL_ISQ_AHEAD(len, den, atanc) (SLUT_NL_ISQ_INFINITE(len) ? (atanc) / (den) : (atanc) * ((len) / (den)))
#define SLUT_NL_ISQ_BEHIND(den, w, a) (((w) > 0.0) ? (SLUT_PI - (((den) == 0.0) ? 0.5 * SLUT_PI : (a))) / (w) : SLUT_HUGE_VAL)
#define SLUT_NL_ISQ_OF_ATAN(len, den, w, x, a) ((!((len) > 0.0)) ? 0.0 : ((den) > 0.0) ? SLUT_NL_ISQ_AHEAD(len, den, SLUT_NL_ISQ_ATANC(x, a)) : SLUT_NL_ISQ_BEHIND(den, w, a))
SLUT_FN double slut_nl_inv_square_integral(double len, double hh2, double d, double w) {
    if (!(len > 0.0)) return 0.0;
    double den = SLUT_NL_ISQ_DEN(len, hh2, d);
    double x = SLUT_NL_ISQ_NUM(len, w) / fabs(den);
    return SLUT_NL_ISQ_OF_ATAN(len, den, w, x, atan(x)); /* one atan: the compiler's built-in */
}


/* Range checks shared by the entry points: rounding at the edges is tolerated (g is clamped
 * to [−1, 1]), real violations (NaN, negative T, r or S, |g| > 1 beyond rounding)
 * stop the host with SLUT_CHECK (callers validate user input first) and vanish on the device. */
SLUT_FN double slut_nl_checked_g(double T, double g, double r, double S) {
    SLUT_CHECK_GE(T, 0.0);
    SLUT_CHECK_GE(r, 0.0);
    SLUT_CHECK_GE(S, 0.0);
    SLUT_CHECK_GE(g, -1.0 - 1e-12);
    SLUT_CHECK_LE(g, 1.0 + 1e-12);
    return slut_clamp(g, -1.0, 1.0);
}

/* ------------------------------------------------------------------ H (closed form) */

/* T·H(T, g, S) = ∫_0^{S/T} (τ² + 2τg + 1)^{−1} dτ: H in units of 1/T, a function of (g, S/T)
 * only. Bounded for T → 0 and T → ∞ (H itself overflows or underflows there). */
SLUT_FN double slut_nl_H_scaled(double g, double S_over_T) {
    return slut_nl_inv_square_integral(S_over_T, 1.0, g, slut_nl_sin_from_cos(g));
}

/* H(T, g, S) = ∫_0^S ĥ^{−2} dt
 *            = atan2(S√(1−g²), T + S g)/(T√(1−g²))       (docs/PHYSICS.md §1.2, angle-difference form)
 * Limits: S/(T(S+T)) at g = 1; S/(T(T−S)) at g = −1, S < T; +∞ at g = −1, S ≥ T;
 * acos(g)/(T√(1−g²)) at S = ∞; 0 at S = 0; +∞ at T = 0 (S > 0). No cancellation anywhere:
 * see slut_nl_inv_square_integral. S may be +∞ (anything above 1e300 counts as ∞). */
SLUT_FN double slut_nl_H(double T, double g, double S) {
    g = slut_nl_checked_g(T, g, 0.0, S);
    if (!(S > 0.0)) return 0.0;
    if (!(T > 0.0)) return SLUT_HUGE_VAL;
    double S_over_T = (S > SLUT_INFINITE_ABOVE) ? SLUT_HUGE_VAL : S / T;
    return slut_nl_H_scaled(g, S_over_T) / T;
}

#endif /* SLUT_NEARLIGHT_CLOSED_H */
