/* scatterlut — the 4-D near-light table's encoding: its slab axis (the coordinate of S at
 * (T, g)), its value base B(T, r, S), and the tables' domain test.
 *
 * Symbols: kernels/slut_nearlight.h. Compiled as OpenCL C (the E4 kernel's nodes), as C++
 * (the runtime sampler, the host) and, whole, as GLSL/HLSL in float (the near-light
 * snippet's slab coordinate and value base); written in the shared subset
 * (kernels/slut_compat.h) except the `#ifndef SLUT_SHADER` block (the inverse map and the
 * node placement, which only the generator and the C++ runtime need).
 */
#ifndef SLUT_NEARLIGHT_SLAB_H
#define SLUT_NEARLIGHT_SLAB_H

#include "slut_compat.h"
#include "slut_axes.h"             /* slut_axis, SLUT_WARP_NL_QODDS */
#include "slut_nearlight_closed.h" /* slut_nl_inv_square_integral, slut_nl_H_scaled */
#include "slut_nearlight_approx.h" /* slut_nl_E_thin (the value base) */

/* ------------------------------------------------------------------ the slab axis */

/* The finite-thickness table E(T, g, r, S) has a ridge that no separable axis in S follows:
 * for g < 0 the ray passes the light's foot point at t* = −T g, where 1/ĥ² peaks with width
 * w = T√(1 − g²), so E(S) (the ĥ⁻²-weighted mean of the attenuation over [0, S]) changes
 * within |S − t*| ≲ w and is frozen after it (a log S axis put 0.4 e-folds of S per cell
 * there, ~3 cells per peak width T√(1−g²)/t* = 0.14 at g = −0.99: 14.6 % error).
 *
 * The weight fraction. q(T, g, S) = H(T, g, S)/H(T, g, ∞) ∈ [0, 1]: the share of the inverse-
 * square weight inside the slab. In angles (slut_nl_inv_square_integral: H = Δφ/w), q = φ/θ
 * with θ = acos g the angle at the light between the directions to the entry point and to
 * the ray's far end, φ the angle subtended by [0, S]. In q the mean is a running average,
 *   E(q) = (1/q) ∫_0^q a(t(q')) dq',
 * and the peak is where q rises fastest (t changes little there), so in q it is no feature.
 * Near q → 0 (thin slab, S ≪ T) q ∝ S; near q → 1, 1 − q ∝ 1/S; both ends need log spacing
 * (in thin slabs E changes at S ~ r and S ~ T r; at S ≫ T the attenuation e^{−t} varies on
 * a scale of 1 in t). The odds do both:
 *   σ(T, g, S) = T·θ/sin θ · q/(1 − q) = T·H∞·I_in/I_out,     (T·H∞ = θ/sin θ in units of 1/T)
 * I_in = ∫_0^S ĥ⁻², I_out = ∫_S^∞ ĥ⁻² (both in units of 1/T). σ is the straightened depth:
 * σ ≈ S for S ≪ T, σ ≈ S·(θ/sin θ)² for S ≫ T, σ = S exactly at g = 1 (θ → 0: q/(1−q) = S/T),
 * and ln σ is linear in q's logit through the peak, where a log S axis had 0.28 e-folds
 * (g = −0.99) for what now takes ln (θ/sin θ)² = 6.1.
 *
 * The axis (warp SLUT_WARP_NL_QODDS, axis name "q", min = S_min, max = S_max > 0): at each
 * (T, g) the unit coordinate is ln σ normalised between the slab thicknesses S_min and S_max,
 *   x = ln(σ(S)/σ(S_min)) / ln(σ(S_max)/σ(S_min)),
 * so every (T, g) gets all the nodes for exactly [S_min, S_max]; nodes at x_i = i/(count − 1)
 * (slut_nl_S_node), texel centres as every axis (slut_texcoord_from_unit). At g = 1 this is
 * the LOG warp in S. Inverse: q/(1 − q) = σ/(T·T H∞) = ρ, and by the law of sines in the
 * triangle light–entry point–P(S), S/T = sin(qθ)/sin((1 − q)θ) = ρ·sinc(qθ)/sinc((1 − q)θ). */

/* σ/(T·T H∞) = I_in/I_out: the factor of σ that depends on S (sg = √(1 − g²)). */
SLUT_FN double slut_nl_depth_odds_over_TH(double g, double sg, double S_over_T) {
    double d = S_over_T + g;
    double inside = slut_nl_inv_square_integral(S_over_T, 1.0, g, sg);
    double outside = slut_nl_inv_square_integral(SLUT_HUGE_VAL, d * d + sg * sg, d, sg);
    return inside / outside;
}
/* σ(T, g, S) of the derivation above: S > 0 finite, T > 0, g ∈ [−1 + ε, 1]. Robust at g = 1
 * (no division by sin θ: I_in/I_out and T·H∞ come from slut_nl_inv_square_integral). */
SLUT_FN double slut_nl_depth_odds(double T, double g, double S) {
    return T * slut_nl_H_scaled(g, SLUT_HUGE_VAL) * slut_nl_depth_odds_over_TH(g, slut_nl_sin_from_cos(g), S / T);
}

/* S → unit coordinate x on a slab axis [S_min, S_max] at (T, g):
 *   x = ln(σ(S)/σ(S_min)) / ln(σ(S_max)/σ(S_min));  not clamped.
 * The factor T·T H∞ of σ cancels in both ratios: only I_in/I_out is evaluated. */
SLUT_FN double slut_nl_unit_from_S_between(double T, double g, double S, double S_min, double S_max) {
    double sg = slut_nl_sin_from_cos(g);
    double lo = slut_nl_depth_odds_over_TH(g, sg, S_min / T), hi = slut_nl_depth_odds_over_TH(g, sg, S_max / T);
    return log(slut_nl_depth_odds_over_TH(g, sg, S / T) / lo) / log(hi / lo);
}

#ifndef SLUT_SHADER
#include "slut_nearlight_lanes.h" /* slut_nl_lanes: the node placement on a lane vector */

/* sin(x)/x (1 at x = 0), on a double or a lane vector (slut_nl_lanes). */
#define SLUT_NL_SINC(x) (((x) == 0.0) ? 1.0 : sin(x) / (x))
/* S from ρ = q/(1 − q) = σ/(T·T H∞) by the law of sines, on a double or a lane vector:
 * T·ρ·sinc(qθ)/sinc((1 − q)θ) with q = ρ/(1 + ρ) and 1 − q = 1/(1 + ρ), both to full precision. */
#define SLUT_NL_S_OF_ODDS(T, rho, theta) \
    ((T) * (rho) * SLUT_NL_SINC((rho) / (1.0 + (rho)) * (theta)) / SLUT_NL_SINC(1.0 / (1.0 + (rho)) * (theta)))

/* The inverse: S with slut_nl_depth_odds(T, g, S) = sigma (> 0), given T·H∞ = TH_inf
 * (slut_nl_H_scaled(g, ∞)) and θ = acos g = atan2(√(1 − g²), g). */
SLUT_FN double slut_nl_S_from_depth_odds_given(double T, double TH_inf, double theta, double sigma) {
    double rho = sigma / (T * TH_inf); /* q/(1 − q) */
    return SLUT_NL_S_OF_ODDS(T, rho, theta);
}
SLUT_FN double slut_nl_S_from_depth_odds(double T, double g, double sigma) {
    return slut_nl_S_from_depth_odds_given(T, slut_nl_H_scaled(g, SLUT_HUGE_VAL), atan2(slut_nl_sin_from_cos(g), g),
                                           sigma);
}

/* S → unit coordinate x on the slab axis a (SLUT_WARP_NL_QODDS) at (T, g); not clamped. */
SLUT_FN double slut_nl_unit_from_S(const slut_axis *a, double T, double g, double S) {
    return slut_nl_unit_from_S_between(T, g, S, a->min, a->max);
}

/* The slab axis's q map at one (T, g): what all its nodes share (the ends' ln σ, T·H∞, θ;
 * ~8 atan), computed once by slut_nl_slab_at, and the per-node part slut_nl_slab_S (an exp
 * and two sin). */
typedef struct slut_nl_slab {
    double T, TH_inf, theta; /* T, T·H∞ = slut_nl_H_scaled(g, ∞), θ = acos g  */
    double lo, hi;           /* ln σ at the axis ends S_min, S_max              */
    double S_min, S_max;
} slut_nl_slab;

SLUT_FN void slut_nl_slab_at(const slut_axis *a, double T, double g, slut_nl_slab *s) {
    s->T = T;
    s->TH_inf = slut_nl_H_scaled(g, SLUT_HUGE_VAL);
    s->theta = atan2(slut_nl_sin_from_cos(g), g);
    s->lo = log(slut_nl_depth_odds(T, g, a->min));
    s->hi = log(slut_nl_depth_odds(T, g, a->max));
    s->S_min = a->min;
    s->S_max = a->max;
}

/* ρ = σ/(T·T H∞) at unit coordinate x of the slab s, σ = exp(lo + x·(hi − lo)): on a double
 * or a lane vector x (slut_nl_S_nodes). */
#define SLUT_NL_SLAB_ODDS(s, x) (exp((s).lo + (x) * ((s).hi - (s).lo)) / ((s).T * (s).TH_inf))

/* Unit coordinate x → S in the slab s; the ends exact. */
SLUT_FN double slut_nl_slab_S(const slut_nl_slab *s, double x) {
    if (x <= 0.0) return s->S_min;
    if (x >= 1.0) return s->S_max;
    return SLUT_NL_S_OF_ODDS(s->T, SLUT_NL_SLAB_ODDS(*s, x), s->theta);
}

/* Unit coordinate x → S on the slab axis a at (T, g); the ends exact. */
SLUT_FN double slut_nl_S_from_unit(const slut_axis *a, double T, double g, double x) {
    if (x <= 0.0) return a->min;
    if (x >= 1.0) return a->max;
    slut_nl_slab s;
    slut_nl_slab_at(a, T, g, &s);
    return slut_nl_slab_S(&s, x);
}

/* S of node i of a slab axis at (T, g): the q map for SLUT_WARP_NL_QODDS, else the axis's own
 * one-parameter warp (older layouts, tests). */
SLUT_FN double slut_nl_S_node(const slut_axis *a, double T, double g, int i) {
    if (a->warp != SLUT_WARP_NL_QODDS) return slut_axis_node(a, i);
    return slut_nl_S_from_unit(a, T, g, (double)i / (double)(a->count - 1));
}

/* S_out[k] = slut_nl_S_node(a, T, g, first + k) for k < count: the shared part of the q map
 * computed once, the nodes' exp and two sines on a lane vector (the device's double16: on
 * PoCL 3.1 a scalar builtin costs many times a vector one per element, docs/POCL.md; the E4
 * kernel 1.02× less CPU time than with scalar calls, bench/README.md). The same expressions
 * as slut_nl_slab_S; on the device the vector builtins may round differently from the scalar
 * ones by an ulp. */
SLUT_FN void slut_nl_S_nodes(const slut_axis *a, double T, double g, int first, int count, double *S_out) {
    if (a->warp != SLUT_WARP_NL_QODDS) {
        for (int k = 0; k < count; ++k) S_out[k] = slut_axis_node(a, first + k);
        return;
    }
    slut_nl_slab s;
    slut_nl_slab_at(a, T, g, &s);
    const double last = (double)(a->count - 1);
    for (int k0 = 0; k0 < count; k0 += SLUT_NL_LANE_WIDTH) {
        double node_at[SLUT_NL_LANE_WIDTH], S_at[SLUT_NL_LANE_WIDTH];
        for (int k = 0; k < SLUT_NL_LANE_WIDTH; ++k) node_at[k] = (double)(first + k0 + k); /* past count: unused */
        slut_nl_lanes x = slut_nl_lanes_load(node_at) / last;
        slut_nl_lanes S = SLUT_NL_S_OF_ODDS(s.T, SLUT_NL_SLAB_ODDS(s, x), s.theta);
        S = SLUT_NL_LANES_SELECT(S, SLUT_NL_LANES_SPLAT(s.S_min), x <= 0.0);
        S = SLUT_NL_LANES_SELECT(S, SLUT_NL_LANES_SPLAT(s.S_max), x >= 1.0);
        slut_nl_lanes_store(S, S_at);
        for (int k = 0; k < SLUT_NL_LANE_WIDTH && k0 + k < count; ++k) S_out[k0 + k] = S_at[k];
    }
}
#endif /* !SLUT_SHADER */

/* ------------------------------------------------------------------ the value base */

/* B(T, r, S): a closed-form guess of E for finite slabs; the 4-D table stores ln(E/B).
 *   B = e^{−T} + (1 − e^{−T}) · E_thin(r, S_eff),   S_eff = S T/(S + T)
 * Why: in a thin slab the light path inside, ĥ t/(t + T r) ≈ T t/(t + T r), grows like t/r
 * (the distant light: E_thin's transition at S ~ r) and saturates at T (the floor e^{−T}),
 * so E ≈ e^{−T}·c + r/S: a sum of two smooth terms whose logarithm has a sharp crossover
 * where r e^{T} ~ S (width ~1 in T, ln r and ln S: 4.7 % trilinear error at T ≈ 14 with
 * ~1.3 optical depths per T cell). B has the same crossover, so ln(E/B) is smooth there.
 * S_eff caps the averaging length at ~T, where the ĥ⁻² weight ends in thick slabs (E_thin
 * would fall like 1/S while E stays). B is not an approximation anyone should use: it is an
 * encoding, exact by construction (E = B·e^{stored}). Measured: docs/NEARLIGHT.md.
 * B ≥ e^{−T} > 0 for T ≤ 700; B = 1 at T = 0. */
/* B from its factors that depend on T alone, floor_T = e^{−T} and rise_T = 1 − e^{−T}
 * (= −expm1(−T)): the table kernel computes them once per T node, and S_eff once per S node
 * (slut_nl_base_depth), and evaluates E_thin and B on its lane vector of r (SLUT_NL_THIN_X,
 * SLUT_NL_THIN_OF_X, SLUT_NL_BASE_OF_THIN: the same expressions). */
#define SLUT_NL_BASE_OF_THIN(floor_T, rise_T, thin) ((floor_T) + (rise_T) * (thin))
SLUT_FN double slut_nl_base_depth(double T, double S) {
    return (S > SLUT_INFINITE_ABOVE) ? T : S * (T / (S + T));
}
SLUT_FN double slut_nl_E_base_from(double floor_T, double rise_T, double T, double r, double S) {
    return SLUT_NL_BASE_OF_THIN(floor_T, rise_T, slut_nl_E_thin(r, slut_nl_base_depth(T, S)));
}
SLUT_FN double slut_nl_E_base(double T, double r, double S) {
    return slut_nl_E_base_from(exp(-T), -expm1(-T), T, r, S);
}

/* ------------------------------------------------------------------ the tables' domain */

/* Whether a near-light table covers (T, g, r, S): inside the axes T, g, r and, for the 4-D
 * table (thick_only = 0), S finite inside its slab axis [S_min, S_max]; the 3-D table
 * (thick_only ≠ 0) covers only the thick medium, S infinite (SLUT_ISFINITE: in float ≥ 1e30).
 * NaN is covered nowhere. Outside, the C++ runtime integrates E exactly (slut_nl_E) and the
 * snippets clamp to the axes. 1 or 0. */
SLUT_FN int slut_nl_table_covers(slut_axis T_axis, slut_axis g_axis, slut_axis r_axis, slut_axis S_axis,
                                 int thick_only, double T, double g, double r, double S) {
    if (slut_on_axis(T_axis, T) == 0 || slut_on_axis(g_axis, g) == 0 || slut_on_axis(r_axis, r) == 0) return 0;
    int thick = SLUT_ISFINITE(S) ? 0 : 1;
    if (thick_only != 0) return thick;
    return (thick == 0 && slut_on_axis(S_axis, S) != 0) ? 1 : 0;
}

#endif /* SLUT_NEARLIGHT_SLAB_H */
