/* scatterlut — the near-light integral (light outside a medium, viewer outside), written once.
 *
 * Compiled as OpenCL C by the near-light table kernels and as C++ by the host (exact
 * evaluation, eval, validation), the tests and the runtime library (closed forms,
 * parameters from geometry). The physics and its conventions: docs/PHYSICS.md §1.2–§1.3.
 *
 * Geometry (docs/PHYSICS.md §1.2). A plane with outward unit normal n bounds the medium (below it).
 * The view ray enters at O and runs a length s inside; ω = unit vector from O towards the
 * viewer (so the ray inside is P(x) = O − x ω), μ_e = ω·n > 0. The light sits at
 * O + l ω_l, μ_l = ω_l·n, g = ω·ω_l. The light-to-point distance is h(x)² = x² + l² + 2 x l g
 * and the part of the light path inside the medium is k(x) = h(x)·x μ_e/(x μ_e + l μ_l)
 * (similar triangles: the depth of P(x) is x μ_e, the height of the light l μ_l).
 *
 *   L_near = σ_s/(4π) · I0 · ∫_0^s e^{−σ_t (x + k(x))} / h(x)² dx = σ_s/(4π) · I0 · σ_t · N(T, g, r, S)
 *   N(T, g, r, S) = ∫_0^S exp(−t − ĥ(t)·t/(t + T r)) / ĥ(t)² dt,   ĥ(t)² = t² + T² + 2 t T g
 *   T = σ_t l,  S = σ_t s (may be +∞),  r = μ_l/μ_e ≥ 0,  t = σ_t x.
 *   H(T, g, S) = ∫_0^S ĥ^{−2} dt (closed form),  E = N/H ∈ (0, 1] (ĥ^{−2}-weighted mean attenuation).
 *
 * Throughout, w = T√(1 − g²) is the distance from the light to the ray's line and
 * d(t) = t + T g the signed distance along the ray past the foot of that perpendicular, so
 * ĥ² = d² + w². The peak of 1/ĥ² sits at t* = −T g (inside the ray when g < 0), with
 * width w; 1/ĥ² has its poles at t* ± i w, at distance exactly ĥ(t) from a real t.
 */
#ifndef SLUT_NEARLIGHT_H
#define SLUT_NEARLIGHT_H

#include "slut_compat.h"
#include "slut_axes.h"     /* slut_axis: the slab axis of the 4-D table (below) */
#include "slut_airlight.h" /* slut_gl16_x / slut_gl16_w: the project's 16-point Gauss–Legendre rule */

/* ------------------------------------------------------------------ small helpers */

/* SLUT_SHADER_BEGIN (the closed-form H: also the GLSL/HLSL snippets') */
/* √(1 − g²) without cancellation as |g| → 1 (1 − |g| is exact for |g| ≥ ½, Sterbenz). */
SLUT_FN double slut_nl_sin_from_cos(double g) {
    double a = fabs(g);
    return (a >= 1.0) ? 0.0 : sqrt((1.0 - a) * (1.0 + a));
}

/* atan(x)/x for x ≥ 0 (1 at x = 0; atan returns tiny x exactly, so no series is needed). */
SLUT_FN double slut_nl_atanc(double x) { return (x == 0.0) ? 1.0 : atan(x) / x; }

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
 * Citation: elementary; the angle substitution of Sun et al. 2005 (the airlight F, §1.1). */
SLUT_FN double slut_nl_inv_square_integral(double len, double hh2, double d, double w) {
    if (!(len > 0.0)) return 0.0;
    if (len > SLUT_INFINITE_ABOVE) {
        if (d > 0.0) return slut_nl_atanc(w / d) / d;
        if (!(w > 0.0)) return SLUT_HUGE_VAL;
        if (d == 0.0) return 0.5 * SLUT_PI / w;
        return (SLUT_PI - atan(w / (-d))) / w;
    }
    double den = hh2 + len * d;
    if (den > 0.0) return slut_nl_atanc(len * w / den) * (len / den);
    if (!(w > 0.0)) return SLUT_HUGE_VAL;
    if (den == 0.0) return 0.5 * SLUT_PI / w;
    return (SLUT_PI - atan(len * w / (-den))) / w;
}

/* SLUT_SHADER_END */

/* Range checks shared by the entry points: rounding at the edges is tolerated (g is clamped
 * to [−1, 1]), real violations (NaN, negative T, r or S, |g| > 1 beyond rounding) are
 * stop the host with SLUT_CHECK (callers validate user input first) and vanish on the device. */
SLUT_FN double slut_nl_checked_g(double T, double g, double r, double S) {
    SLUT_CHECK_GE(T, 0.0);
    SLUT_CHECK_GE(r, 0.0);
    SLUT_CHECK_GE(S, 0.0);
    SLUT_CHECK_GE(g, -1.0 - 1e-12);
    SLUT_CHECK_LE(g, 1.0 + 1e-12);
    (void)T; (void)r; (void)S;
    return slut_clamp(g, -1.0, 1.0);
}

/* ------------------------------------------------------------------ H (closed form) */

/* SLUT_SHADER_BEGIN */
/* T·H(T, g, S) = ∫_0^{S/T} (τ² + 2τg + 1)^{−1} dτ: H in units of 1/T, a function of (g, S/T)
 * only. Bounded for T → 0 and T → ∞ (H itself overflows or underflows there). */
SLUT_FN double slut_nl_H_scaled(double g, double S_over_T) {
    return slut_nl_inv_square_integral(S_over_T, 1.0, g, slut_nl_sin_from_cos(g));
}
/* SLUT_SHADER_END */

/* H(T, g, S) = ∫_0^S ĥ^{−2} dt
 *            = atan2(S√(1−g²), T + S g)/(T√(1−g²))       (docs/PHYSICS.md §1.2, angle-difference form)
 * Limits: S/(T(S+T)) at g = 1; S/(T(T−S)) at g = −1, S < T; +∞ at g = −1, S ≥ T;
 * acos(g)/(T√(1−g²)) at S = ∞; 0 at S = 0; +∞ at T = 0 (S > 0). No cancellation anywhere:
 * see slut_nl_inv_square_integral. S may be +∞ (anything above 1e300 counts as ∞). */
SLUT_FN double slut_nl_H(double T, double g, double S) {
    g = slut_nl_checked_g(T, g, 0.0, S);
    if (!(S > 0.0)) return 0.0;
    if (!(T > 0.0)) return SLUT_HUGE_VAL;
    double S_over_T = (S > 1e300) ? SLUT_HUGE_VAL : S / T;
    return slut_nl_H_scaled(g, S_over_T) / T;
}

/* ------------------------------------------------------------------ E and N by quadrature */

#define SLUT_NL_MAX_LANES 16      /* r values sharing one (T, g, S) panel mesh            */
#define SLUT_NL_MAX_SWEEP 64      /* S values sharing one march (slut_nl_E_sweep)         */
#define SLUT_NL_MAX_PANELS 4096   /* safety cap: in-domain calls use ≤ 40 panels, absurd
                                     inputs (r = 1e-300, T = 700) ~300                     */
#define SLUT_NL_EFOLDS 12.0       /* max e-folds of the integrand's exponent per panel    */
#define SLUT_NL_ELLIPSE 2.0       /* min (dist(a) + dist(b))/(b − a) for every singularity */
#define SLUT_NL_TAIL_EPS 1e-16    /* stop once the remainder bound is below this × sum, at
                                     refine = 1 (× refine^−15: the rule's error, below)     */

/* The quadrature works in units of T: τ = t/T, δ = τ + g, η = ĥ/T = √(δ² + 1 − g²), so
 *   T·N = ∫_0^{S/T} exp(−T (τ + η τ/(τ + r))) / η² dτ,   T·H = ∫_0^{S/T} η^{−2} dτ.
 * Every length of the mesh is O(1)-scaled whatever T is (T = 1e-300 or 1e300 neither
 * underflows η² nor overflows T²); T appears only as the exponent's scale. The layer sits
 * at τ ~ r, the peak at τ* = −g with width √(1 − g²), the poles of 1/η² at −g ± i√(1−g²). */

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

/* Length h of the next Gauss–Legendre panel [τ, τ + h] (16 points), in units of T;
 * dl = δ(τ) = τ + g, eta = η(τ), r_pole = the smallest r whose layer still matters,
 * k_rate = max over the lanes of r/(τ + r)².
 *
 * The integrand exp(−T φ(τ))/η², φ = τ + η q, is analytic except at the poles −g ± i√(1−g²)
 * of 1/η² (also branch points of η) and the essential singularity of e^{−Tηq} at τ = −r.
 * Three rules, all evaluated in closed form at the panel start, each valid over the panel:
 *  1. Bernstein ellipse: for a singularity at distances δ_a, δ_b from the ends,
 *     ρ + 1/ρ = 2 (δ_a + δ_b)/h; require (δ_a + δ_b)/h ≥ A = SLUT_NL_ELLIPSE (ρ ≥ 3.7:
 *     16-point GL error ≲ ρ^{−32} ~ 1e-17 of the panel, measured 2e-17 on 1/(x+δ)² and on a
 *     Lorentzian at A = 2). For the poles of 1/η² the distance from a real τ is exactly
 *     η(τ), η(τ + h)² = η² + 2hδ + h², and η + η(τ + h) = A h solves to
 *     h = 2 (A η + δ)/(A² − 1): panels of ~√(1−g²) across the peak, geometric growth away
 *     from it. For −r: distances τ + r, τ + h + r give h = 2 (τ + r)/(A − 1).
 *  2. Decay: |φ'| = |1 + η' q + η r/(τ+r)²| ≤ 2 + (η(τ) + h) k, k = max over lanes of
 *     r/(τ + r)² at the panel start (η is 1-Lipschitz, r/(τ+r)² decreasing). The layer
 *     term is counted twice: it comes from the essential singularity at −r, whose
 *     continuation off the real axis grows faster than an exponential of the same slope
 *     (Bernstein: on a panel of length ~(τ + r) the ellipse sees e^{Tηr/(z+r)} at about
 *     twice the real-axis e-folds). Require T h (2 + 2(η + h) k) ≤ L = SLUT_NL_EFOLDS, the
 *     root of a quadratic in h. 16-point GL integrates e^{−λx} over L e-folds to ≤ 1e-16
 *     relative for L ≤ 20 (measured). Counting the layer once left errors up to 4e-12;
 *     twice, ≤ 3e-14 against a 3× finer mesh on 40000 random points.
 *     In the boundary layer (τ ≲ r, T large) this rule sets the panels: ~2T/L panels of
 *     ~L r/(2T) — the mesh a panel variable u = t/(t + T r) would give (e^{−Tηu}, rate Tη),
 *     without a change of variable per lane, so lanes with different r share it.
 * Where rule 1 for −r_pole is the shortest, the march may take the panel in the layer
 * variable instead (slut_nl_layer_panel_length, below).
 * refine > 1 shrinks every panel (A → 1 + (A − 1)·refine, L → L/refine): an independent
 * finer mesh for self-checks. */
/* The refinement that holds E to a relative tolerance eps (refine < 1: longer panels, fewer
 * nodes). Measured: at refine = 1 the rule reaches 6e-15 against refine = 2.5 over 3000 random
 * (T, g, r, S), and its error grows like refine^−15 below that (2.6e-10 at 1/2, 1e-5 at
 * 1/5; the 16-point rule's h^32 is halved by the layer and ellipse terms, which scale
 * more slowly) — so refine = (eps/1e-14)^(−1/15), at most 1 (the rule as derived, which
 * slut_nl_E uses; the tables default to eps = 1e-11, refine 0.63: generate_nearlight.hpp),
 * at least 0.15 (below it the ellipse bound A → 1 loses control of the poles). The report's
 * tolerance ladder re-measures what each eps reaches. */
SLUT_FN double slut_nl_refine_for_tolerance(double eps) {
    double refine = pow(eps / 1e-14, -1.0 / 15.0);
    return fmax(0.15, fmin(1.0, refine));
}

/* Rule 2 alone: the longest h with T h (2 + 2(η + h) k) ≤ efolds (e-folds of the panel). */
SLUT_FN double slut_nl_decay_length(double eta, double k_rate, double T, double efolds) {
    double L = efolds / T; /* e-folds per unit τ */
    /* h (B + 2kh) = L, B = 2 + 2ηk; the root written so that nothing overflows for r → 0
     * (k ~ 1/r): k/B ≤ 1/(2η). */
    double B = 2.0 + 2.0 * eta * k_rate;
    return (2.0 * L / B) / (1.0 + sqrt(1.0 + (8.0 * L / B) * (k_rate / B)));
}

/* *layer_bound = 1 when the ellipse rule of −r_pole sets the panel (where the layer variable
 * may give a longer one: slut_nl_layer_panel_length). */
SLUT_FN double slut_nl_panel_length(double tau, double dl, double eta, double r_pole, double k_rate,
                                    double T, double refine, int *layer_bound) {
    double A = 1.0 + (SLUT_NL_ELLIPSE - 1.0) * refine;
    double h = 2.0 * (A * eta + dl) / (A * A - 1.0);
    double h_decay = slut_nl_decay_length(eta, k_rate, T, SLUT_NL_EFOLDS / refine);
    double h_layer = (r_pole > 0.0 && r_pole <= 1e300) ? 2.0 * (tau + r_pole) / (A - 1.0) : SLUT_HUGE_VAL;
    *layer_bound = (h_layer < h && h_layer < h_decay);
    return fmin(fmin(h, h_layer), h_decay);
}

/* The next panel [τ, τ + h] in the layer variable s = ln(1 + τ/c) (dτ = (c + τ) ds), c = r_pole;
 * returns h (in τ; the panel in s is D = ln(1 + h/(c + τ))). Arguments as for
 * slut_nl_panel_length, and the poles of 1/η² relative to −c: ln_pole = ln|c − g ± i√(1−g²)|,
 * arg_pole = atan2(√(1 − g²), c − g) (they depend on c alone; the march keeps them per c).
 * The march uses it where the ellipse rule of −c sets the panel in τ and this one is longer.
 *
 * Why: in τ the ellipse rule of the singularity at τ = −c lets panels grow only by
 * 1 + 2/(A − 1) each (×4.2 at the default refine 0.63), ~ln(1/c)/1.4 panels from c to τ ~ 1.
 * In s that singularity sits at s = −∞, and the others at τ = −r_j (r_j > c) at
 * s_j = ln((r_j − c)/(c + τ)) + iπ (relative to the panel start): at height π whatever r_j is.
 * Rules, in s relative to the panel start, each valid over the panel:
 *  1. Bernstein ellipse (as slut_nl_panel_length): a singularity at x + iy needs
 *     |s_p| + |s_p − D| ≥ A D, which solves to D ≤ 2(A|s_p| − x)/(A² − 1) (the sum minus A D
 *     decreases in D). At y = π its minimum over x (at x = π/√(A² − 1), above the middle of
 *     the panel) is D ≤ 2π/√(A² − 1) (3.6 at A = 2, 4.9 at refine 0.63: panels of ×37 … ×130
 *     in c + τ), for every lane at once. The poles of 1/η² at τ = −g ± i√(1−g²) sit at
 *     x = ln_pole − ln(c + τ), y = arg_pole. (Lanes with r < c do not matter, as in the τ
 *     rules: their layer is < 1e-17 e-folds.)
 *  2. Decay: the e-folds of the exponent over the panel, ∫|dφ/ds| ds = ∫|φ'| dτ, do not
 *     depend on the variable: the τ rule's bound T h (2 + 2(η + h) k) holds, plus D e-folds of
 *     the Jacobian c + τ(s) = (c + τ)e^s: h = slut_nl_decay_length(…, L − D_max) with D_max the
 *     ellipse bound of 1.
 * refine scales as in slut_nl_panel_length (A → 1 + (A − 1)·refine, L → L/refine).
 * Measured (C++ sweep over the bench's tables, every node against refine 2.5): bench/README.md. */
SLUT_FN double slut_nl_layer_panel_length(double tau, double eta, double c, double ln_pole, double arg_pole,
                                          double k_rate, double T, double refine) {
    double A = 1.0 + (SLUT_NL_ELLIPSE - 1.0) * refine, A2m1 = A * A - 1.0;
    double ct = c + tau;
    double x = ln_pole - log(ct), y = arg_pole;
    double D_max = fmin(2.0 * 3.14159265358979323846 / sqrt(A2m1), 2.0 * (A * sqrt(x * x + y * y) - x) / A2m1);
    return fmin(ct * expm1(D_max), slut_nl_decay_length(eta, k_rate, T, SLUT_NL_EFOLDS / refine - D_max));
}

/* E(T, g, r_j, S_i) for up to SLUT_NL_MAX_LANES values r_j sharing one panel mesh and up to
 * SLUT_NL_MAX_SWEEP slab depths S_0 ≤ S_1 ≤ … (ascending; +∞ allowed last) sharing one march
 * (the cumulative sweep); E_out[i·lanes + j] = E(T, g, r_j, S_i) ∈ [0, 1]. Returns the number
 * of quadrature nodes (each node: one sqrt and divide shared by the lanes, then one divide
 * and one exp per lane). N = E·H.
 *
 * Derivation. E = N/H = Σ_n [W_n/(η_n² T·H)] e^{−Tφ_j(τ_n)} with the panels in τ units
 * (slut_nl_panel_length) and T·H = slut_nl_H_scaled: the weights in brackets form a
 * probability measure, so E is computed directly, never as a ratio of two under/overflowed
 * numbers. The march starts at τ = 0 and runs to the last S/T (or ∞); a panel that would
 * cross a node S_i/T ends there, so the partial sum at S_i is the whole panel rule on
 * [0, S_i/T] (the same rules as a march to S_i alone, with the earlier nodes' breaks). The
 * weights are normalised by T·H(S_i) of the next node i, so the sum there is E_i itself;
 * past it the sums are rescaled by H(S_i)/H(S_{i+1}) ≤ 1 (one S value: exactly the
 * single-depth march). Per node the cost is a break in the mesh and one multiply per lane,
 * instead of a march of its own.
 * Near the peak (g < 0, τ ≥ ½|g|) it carries δ = τ − τ* exactly and derives τ from it,
 * elsewhere it carries τ: the layer needs τ (and q) to full relative precision, the peak
 * needs δ to precision relative to its width √(1−g²).
 *
 * Stopping (at each panel start τ). The attenuation a(τ') = e^{−T(τ' + η(τ') q(τ'))} never
 * increases: q is increasing, and with q0 = q(τ) the exponent τ' + η(τ') q0 has slope
 * 1 + q0 η' ≥ 1 − q0 ≥ 0 (η is 1-Lipschitz). So for τ' ≥ τ, a(τ') ≤ a(τ) e^{−T(1−q0)(τ'−τ)}
 * and the remainder of lane j up to the last node is at most
 *   R_j = a_j(τ) · min(∫_τ^{S/T} η^{−2}, 1/(T (1 − q0) η_min²)),  η_min = min of η on [τ, S/T]
 * (a bound, not an estimate); the march stops once R_j ≤ ε_tail × (sum so far), ε_tail =
 * SLUT_NL_TAIL_EPS·refine^−15: the panel rule's error scales like refine^−15
 * (slut_nl_refine_for_tolerance), the truncation follows it 100× below (1e-13 at the default
 * tolerance 1e-11, 6 % fewer nodes than 1e-16 there)
 * for every lane. The remainder up to an earlier node S_i is smaller still (a sub-interval,
 * the same sum so far), so the nodes not reached take the sum at the stop. A peak or layer
 * still ahead keeps a_j(τ)·∫η^{−2} large unless the attenuation already makes it
 * negligible, so nothing that matters can be skipped.
 *
 * Special cases: S = 0: E = e^{−T} for r = 0 (the light path is the whole ĥ) and 1 for r > 0;
 * T = 0: E = 1; g = −1 with S ≥ T (the ray runs through the light; N and H diverge): the
 * weight concentrates at t = T where ĥ = 0, so E = e^{−T}. In a sweep the first are a
 * prefix of the nodes and the last a suffix; the march covers the nodes between.
 * Citation: docs/PHYSICS.md §1.2 (the integral) and §2 (its layer and peak). */
/* The sweep's stopping test at a panel start τ (see "Stopping" above): whether for every lane
 * the remainder bound a_j(τ)·min(rest, 1/(T(1 − q0) η_min²)·inv_H) is ≤ tail_eps × sum
 * so far; rest = the normalised ∫ η^{−2} up to the last node (or a lower bound of it: then a
 * "no" is final), eta_min2 = η_min². */
SLUT_FN int slut_nl_rest_negligible(const slut_nl_lanes *rr, const slut_nl_lanes *sum, int blocks, double T,
                                    double tau, double eta, double eta_min2, double inv_H, double rest,
                                    double tail_eps) {
    for (int b = 0; b < blocks; ++b) {
        slut_nl_lanes q0 = slut_nl_q(tau, rr[b]);
        slut_nl_lanes rest2 = SLUT_NL_LANES_SPLAT(SLUT_HUGE_VAL);
        if (eta_min2 > 0.0) rest2 = SLUT_NL_LANES_SELECT(rest2, inv_H / (T * (1.0 - q0) * eta_min2), q0 < 1.0);
        if (SLUT_NL_LANES_ANY(exp(-T * (tau + eta * q0)) * fmin(rest2, rest) > tail_eps * sum[b])) return 0;
    }
    return 1;
}

SLUT_FN int slut_nl_E_sweep(double T, double g, const double *S, int n_S, const double *r, int lanes,
                            double *E_out, double refine) {
    /* The lanes in blocks (slut_nl_lanes): a partial last block repeats the last r, which
     * changes no mesh rule (a maximum or minimum over the lanes) and is never stored. */
    slut_nl_lanes rr[SLUT_NL_LANE_BLOCKS], sum[SLUT_NL_LANE_BLOCKS];
    double r_padded[SLUT_NL_MAX_LANES];
    int i, j, b;
    SLUT_CHECK_GE(lanes, 1);
    SLUT_CHECK_LE(lanes, SLUT_NL_MAX_LANES);
    SLUT_CHECK_GE(n_S, 1);
    SLUT_CHECK_LE(n_S, SLUT_NL_MAX_SWEEP);
    if (lanes > SLUT_NL_MAX_LANES) lanes = SLUT_NL_MAX_LANES;
    if (n_S > SLUT_NL_MAX_SWEEP) n_S = SLUT_NL_MAX_SWEEP;
    g = slut_nl_checked_g(T, g, 0.0, S[n_S - 1]);
    double sg = slut_nl_sin_from_cos(g);
    /* The nodes the march covers: first..stop−1 (ascending S: the special cases are the ends). */
    int first = 0, stop = n_S;
    for (i = 0; i < n_S; ++i) {
        SLUT_CHECK(i == 0 || S[i] >= S[i - 1]); /* the sweep's S nodes ascend */
        double tau_i = (S[i] > 1e300 || !(T > 0.0)) ? SLUT_HUGE_VAL : S[i] / T;
        int through_light = (sg == 0.0 && g < 0.0 && S[i] >= T);
        if (!(tau_i > 0.0) || !(T > 0.0) || through_light) {
            for (j = 0; j < lanes; ++j) {
                SLUT_CHECK_GE(r[j], 0.0);
                double *E = &E_out[i * lanes + j];
                if (!(T > 0.0)) *E = 1.0;
                else if (!(tau_i > 0.0)) *E = (r[j] > 0.0) ? 1.0 : exp(-T); /* S → 0 (S/T may underflow) */
                else *E = exp(-T);
            }
            if (!(tau_i > 0.0) && first == i) first = i + 1;
            else if (stop == n_S) stop = i;
        }
    }
    if (first >= stop) return 0;
    double tau_end = (S[stop - 1] > 1e300) ? SLUT_HUGE_VAL : S[stop - 1] / T;
    int finite_S = !(tau_end > 1e300);
    /* Weights are normalised by T·H of the next node: they sum to 1 over [0, S_next/T], so
     * the sum is E itself there and cannot underflow for tiny S (where T·H ~ S/T). */
#define SLUT_NL_NODE_TAU(i) (((i) == stop - 1) ? tau_end : S[i] / T) /* S_i/T (the last: exact tau_end) */
    double H_next = slut_nl_H_scaled(g, (first == stop - 1) ? (finite_S ? tau_end : SLUT_HUGE_VAL) : S[first] / T);
    double inv_H = 1.0 / H_next;
    double sg2 = sg * sg, half_peak = -0.5 * g;
    double tail_eps = SLUT_NL_TAIL_EPS / pow(refine, 15.0);
    int blocks = (lanes + SLUT_NL_LANE_WIDTH - 1) / SLUT_NL_LANE_WIDTH;
    for (j = 0; j < blocks * SLUT_NL_LANE_WIDTH; ++j) {
        double r_j = r[(j < lanes) ? j : lanes - 1];
        SLUT_CHECK_GE(r_j, 0.0);
        r_padded[j] = (r_j < 1e300) ? r_j : SLUT_HUGE_VAL;
    }
    for (b = 0; b < blocks; ++b) {
        rr[b] = slut_nl_lanes_load(&r_padded[b * SLUT_NL_LANE_WIDTH]);
        sum[b] = SLUT_NL_LANES_SPLAT(0.0);
    }
    double tau = 0.0, dl = g;        /* march state: τ and δ = τ + g (one of them exact) */
    int carry_d = 0;                 /* 1 once the march carries δ (near the peak) */
    double d_end = tau_end + g;      /* δ at the last τ = S/T (S finite) */
    int next = first;                /* the next node the march reaches */
    int nodes = 0;
    double pole_c = -1.0, ln_pole = 0.0, arg_pole = 0.0; /* slut_nl_layer_panel_length's pole terms at c = pole_c */
    for (int panel = 0; panel < SLUT_NL_MAX_PANELS; ++panel) {
        if (!carry_d && g < 0.0 && tau >= half_peak) { carry_d = 1; }
        double eta2 = dl * dl + sg2, eta = sqrt(eta2);
        /* Remainder bound up to the last node, normalised like the sums. */
        if (panel > 0) {
            double d_min = (dl >= 0.0) ? dl : ((finite_S && d_end < 0.0) ? d_end : 0.0); /* η_min's δ */
            double eta_min2 = d_min * d_min + sg2;
            double len = finite_S ? tau_end - tau : SLUT_HUGE_VAL;
            /* First with a lower bound of ∫ η^{−2} that needs no atan: η(τ + x) ≤ η + x
             * (1-Lipschitz), so ∫_0^len (η + x)^{−2} dx = len/(η(η + len)) (1/η for len = ∞)
             * is below it (× (1 − 1e-12): below the rounded exact value too). A lane that is
             * not negligible with it is not with the exact integral either, so the exact one
             * (an atan) is evaluated only when the march may stop: the same decision. */
            double rest_low = (1.0 - 1e-12) * inv_H * (finite_S ? len / (eta * (eta + len)) : 1.0 / eta);
            if (slut_nl_rest_negligible(rr, sum, blocks, T, tau, eta, eta_min2, inv_H, rest_low, tail_eps) &&
                slut_nl_rest_negligible(rr, sum, blocks, T, tau, eta, eta_min2, inv_H,
                                        inv_H * slut_nl_inv_square_integral(len, eta2, dl, sg), tail_eps))
                break;
        }
        /* Layer slope (max over lanes) and the nearest layer singularity −r that still matters:
         * on [τ, τ + h] the layer changes the exponent by Tηr/(τ'+r) ≤ T r·max(η(τ)/(τ+r), 1);
         * below 1e-17 it changes no double and its pole needs no rule (else r = 1e-300 would
         * cost ~700 geometric panels). */
        double k_rate = 0.0, r_pole = SLUT_HUGE_VAL;
        for (b = 0; b < blocks; ++b) {
            slut_nl_lanes matters = SLUT_NL_LANES_SELECT(
                SLUT_NL_LANES_SPLAT(SLUT_HUGE_VAL), rr[b],
                (rr[b] > 0.0) & (T * rr[b] * fmax(eta / (tau + rr[b]), 1.0) > 1e-17));
            k_rate = fmax(k_rate, slut_nl_lanes_max(slut_nl_layer_slope(tau, rr[b])));
            r_pole = fmin(r_pole, slut_nl_lanes_min(matters));
        }
        int layer_bound;
        double h = slut_nl_panel_length(tau, dl, eta, r_pole, k_rate, T, refine, &layer_bound);
        /* Where the ellipse of −r_pole sets the panel, the layer variable s = ln(1 + τ/r_pole)
         * if it gives a longer one (slut_nl_layer_panel_length); D = the panel in s. */
        int in_s = 0;
        double D = 0.0, ct = tau + r_pole;
        if (layer_bound && !carry_d) {
            if (r_pole != pole_c) { /* the poles of 1/η² relative to −r_pole (r_pole rarely changes) */
                pole_c = r_pole;
                double cg = r_pole - g;
                ln_pole = 0.5 * log(cg * cg + sg2);
                arg_pole = atan2(sg, cg);
            }
            double h_s = slut_nl_layer_panel_length(tau, eta, r_pole, ln_pole, arg_pole, k_rate, T, refine);
            if (h_s > h) { in_s = 1; h = h_s; }
        }
        SLUT_DCHECK_GT(h, 0.0); /* per panel: debug builds only */
        if (!(h > 0.0)) break; /* cannot happen (every rule is > 0 for η > 0); never loop on it */
        /* The panel ends at the next node if it would cross it (a node at S/T > 1e300 counts
         * as ∞: never reached, it takes the sum at the stop). */
        int at_node = 0;
        double tau_node = SLUT_NL_NODE_TAU(next), d_node = 0.0;
        if (!(tau_node > 1e300)) {
            d_node = (next == stop - 1) ? d_end : tau_node + g;
            double remaining = carry_d ? d_node - dl : tau_node - tau;
            if (h >= remaining) {
                h = fmax(remaining, 0.0); /* ≥ 0: the nodes ascend */
                at_node = 1;
            }
        }
        if (in_s) D = log1p(h / ct);
        /* The 16 nodes' offsets from the panel start and weights: in τ, h/2 (1 ± x_k) and
         * h/2 w_k; in s, o = D/2 (1 ∓ x_k), τ_n − τ = (c + τ)(e^o − 1), weights D/2 w_k (c + τ)e^o,
         * e^o − 1 by expm1 on the half near the start (relative precision where τ_n is small,
         * which the layer needs) and from it on the far half, (e^D − 1 − (e^o − 1))/e^o (no
         * cancellation: e^D − 1 ≥ 2(e^o − 1) there). Filled in two whole loops: a select per
         * node would evaluate the expm1 for every panel. */
        double off[16], wt[16];
        if (in_s) {
            double em_D = expm1(D), o_near[8], em[8];
            for (int k = 0; k < 8; ++k) o_near[k] = 0.5 * D * (1.0 - slut_gl16_x[k]);
            slut_nl_expm1_8(o_near, em);
            for (int k = 0; k < 8; ++k) {
                double em_near = em[k];
                double em_far = (em_D - em_near) / (1.0 + em_near);
                off[2 * k] = ct * em_near;
                wt[2 * k] = 0.5 * D * slut_gl16_w[k] * ct * (1.0 + em_near);
                off[2 * k + 1] = ct * em_far;
                wt[2 * k + 1] = 0.5 * D * slut_gl16_w[k] * ct * (1.0 + em_far);
            }
        } else {
            double half_len = 0.5 * h; /* not "half": a type name in OpenCL C */
            for (int k = 0; k < 8; ++k) {
                off[2 * k] = half_len - half_len * slut_gl16_x[k];
                off[2 * k + 1] = half_len + half_len * slut_gl16_x[k];
                wt[2 * k] = wt[2 * k + 1] = half_len * slut_gl16_w[k];
            }
        }
        for (int n = 0; n < 16; ++n) {
            double tn = carry_d ? (dl + off[n]) - g : tau + off[n];
            double dn = carry_d ? dl + off[n] : tn + g;
            double en2 = dn * dn + sg2, en = sqrt(en2);
            double base = wt[n] * inv_H / en2;
            for (b = 0; b < blocks; ++b) sum[b] += base * exp(-T * (tn + en * slut_nl_q(tn, rr[b])));
            ++nodes;
        }
        if (at_node) {
            /* Record every node at this depth (equal S values share it), then renormalise the
             * sums from this node's T·H to the next one's. */
            while (next < stop && SLUT_NL_NODE_TAU(next) <= tau_node) {
                for (b = 0; b < blocks; ++b)
                    slut_nl_lanes_put(fmin(sum[b], 1.0), &E_out[next * lanes], b * SLUT_NL_LANE_WIDTH, lanes);
                ++next;
            }
            if (next >= stop) break;
            double H_node = H_next;
            H_next = slut_nl_H_scaled(g, SLUT_NL_NODE_TAU(next));
            inv_H = 1.0 / H_next;
            for (b = 0; b < blocks; ++b) sum[b] *= H_node / H_next;
            if (carry_d) { dl = d_node; tau = dl - g; }
            else { tau = tau_node; dl = tau + g; }
            continue;
        }
        if (carry_d) { dl += h; tau = dl - g; }
        else { tau += h; dl = tau + g; }
    }
    /* Nodes the march did not reach (stopped on the remainder bound) take the sum at the stop,
     * renormalised from the next node's T·H to their own. */
    for (i = next; i < stop; ++i) {
        double scale = (i == next) ? 1.0 : H_next / slut_nl_H_scaled(g, SLUT_NL_NODE_TAU(i));
        for (b = 0; b < blocks; ++b)
            slut_nl_lanes_put(fmin(sum[b] * scale, 1.0), &E_out[i * lanes], b * SLUT_NL_LANE_WIDTH, lanes);
    }
#undef SLUT_NL_NODE_TAU
    return nodes;
}

/* E(T, g, r_j, S) for up to SLUT_NL_MAX_LANES values r_j at one depth S sharing one panel
 * mesh: slut_nl_E_sweep with a single node (the march to S alone). */
SLUT_FN int slut_nl_E_lanes(double T, double g, double S, const double *r, int lanes, double *E_out,
                            double refine) {
    return slut_nl_E_sweep(T, g, &S, 1, r, lanes, E_out, refine);
}

/* E(T, g, r, S) = N/H ∈ (0, 1]: see slut_nl_E_lanes. Contract: 1e-10 relative; measured
 * ≤ 2e-14 against a Boost.Math reference on 20000 random points of T ∈ [1e-3, 100],
 * g ∈ [−0.999999, 1], r ∈ {0} ∪ [1e-6, 1e4], S ∈ {∞} ∪ [1e-6, 100]
 * (tests/kernels/test_nearlight_math.cpp). ~115 nodes per call on average, ≤ 550 there. */
SLUT_FN double slut_nl_E(double T, double g, double r, double S) {
    double E;
    slut_nl_E_lanes(T, g, S, &r, 1, &E, 1.0);
    return E;
}

/* N(T, g, r, S) = E·H (docs/PHYSICS.md §1.2). +∞ where H diverges (T = 0, or g = −1 with S ≥ T). */
SLUT_FN double slut_nl_N(double T, double g, double r, double S) {
    double H = slut_nl_H(T, g, S);
    if (!(H > 0.0)) return 0.0;
    if (!SLUT_ISFINITE(H)) return SLUT_HUGE_VAL;
    return slut_nl_E(T, g, r, S) * H;
}

/* ------------------------------------------------------------------ the 4-D table's slab axis */

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

/* SLUT_SHADER_BEGIN (the slab coordinate: also the GLSL/HLSL snippets') */
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
/* SLUT_SHADER_END */

/* sin(x)/x (1 at x = 0). */
SLUT_FN double slut_nl_sinc(double x) { return (x == 0.0) ? 1.0 : sin(x) / x; }

/* The inverse: S with slut_nl_depth_odds(T, g, S) = sigma (> 0), given T·H∞ = TH_inf
 * (slut_nl_H_scaled(g, ∞)) and θ = acos g = atan2(√(1 − g²), g). */
SLUT_FN double slut_nl_S_from_depth_odds_given(double T, double TH_inf, double theta, double sigma) {
    double rho = sigma / (T * TH_inf);                        /* q/(1 − q) */
    double q = rho / (1.0 + rho), q_out = 1.0 / (1.0 + rho); /* q and 1 − q, both to full precision */
    return T * rho * slut_nl_sinc(q * theta) / slut_nl_sinc(q_out * theta);
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

/* Unit coordinate x → S in the slab s; the ends exact. */
SLUT_FN double slut_nl_slab_S(const slut_nl_slab *s, double x) {
    if (x <= 0.0) return s->S_min;
    if (x >= 1.0) return s->S_max;
    return slut_nl_S_from_depth_odds_given(s->T, s->TH_inf, s->theta, exp(s->lo + x * (s->hi - s->lo)));
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

/* S_out[k] = slut_nl_S_node(a, T, g, first + k) for k < count (the same values), the shared
 * part of the q map computed once. */
SLUT_FN void slut_nl_S_nodes(const slut_axis *a, double T, double g, int first, int count, double *S_out) {
    if (a->warp != SLUT_WARP_NL_QODDS) {
        for (int k = 0; k < count; ++k) S_out[k] = slut_axis_node(a, first + k);
        return;
    }
    slut_nl_slab s;
    slut_nl_slab_at(a, T, g, &s);
    for (int k = 0; k < count; ++k) S_out[k] = slut_nl_slab_S(&s, (double)(first + k) / (double)(a->count - 1));
}

/* ------------------------------------------------------------------ parameters from geometry */

/* SLUT_SHADER_BEGIN (the near-light front-end: also the GLSL/HLSL snippets') */
#define SLUT_NL_OK 0            /* parameters valid */
#define SLUT_NL_LIGHT_BELOW 1   /* μ_l < 0: no direct light reaches the medium: radiance 0 */
#define SLUT_NL_VIEWER_BELOW 2  /* μ_e ≤ 0: the viewer does not see the medium: invalid input */

SLUT_STRUCT_BEGIN(slut_nl_params)
    int kind;         /* SLUT_NL_*                                                      */
    double T;         /* σ_t l (optical distance entry point–light)                     */
    double g;         /* ω·ω_l                                                          */
    double r;         /* μ_l/μ_e                                                        */
    double S;         /* σ_t s (+∞ for a thick medium)                                  */
    double distance_m;/* l, m                                                           */
    double S_over_T;  /* s/l (+∞ for a thick medium): H·T depends on (g, s/l) only      */
    double mu_e, mu_l;
SLUT_STRUCT_END(slut_nl_params);

/* (T, g, r, S) from a geometry in physical units (docs/PHYSICS.md §1.2), given as the scalars
 * the vectors below make (the caller forms them: C arrays here, GPU vectors in the snippets):
 *   l = |light_rel|, mu_e = ω·n, n_dot_l = light_rel·n, e_dot_l = light_rel·ω, with
 *   n:            outward unit normal of the surface (the medium is below);
 *   ω:            unit vector from the entry point O towards the viewer (not into the medium;
 *                 the refracted one where the surface refracts, with mu_e = cos θ_t);
 *   light_rel:    light position minus O, m;
 *   sigma_t_per_m: extinction σ_t, 1/m;  length_m: path s inside the medium, m (above
 *                 SLUT_INFINITE_ABOVE = thick).
 * T = σ_t l, ω_l = light_rel/l, g = ω·ω_l, r = μ_l/μ_e, S = σ_t s.
 * Sign convention: ĥ² = t² + T² + 2tTg because the point at depth x is O − xω, so
 * P − light = −(x ω + l ω_l). A light in the plane (μ_l = 0, rounding tolerated down to
 * −SLUT_IN_PLANE_TOLERANCE: 1e-15, float 1e-6) is r = 0 (its whole path runs inside: the
 * r = 0 case of docs/PHYSICS.md §1.2); only a light strictly below the plane gives
 * SLUT_NL_LIGHT_BELOW. */
SLUT_FN slut_nl_params slut_nl_params_from_dots(double l, double mu_e, double n_dot_l, double e_dot_l,
                                                double sigma_t_per_m, double length_m) {
    slut_nl_params p;
    SLUT_CHECK_GE(sigma_t_per_m, 0.0);
    SLUT_CHECK_GE(length_m, 0.0);
    p.kind = SLUT_NL_OK;
    p.distance_m = l;
    p.mu_e = mu_e;
    p.mu_l = (l > 0.0) ? n_dot_l / l : 0.0;
    p.g = (l > 0.0) ? slut_clamp(e_dot_l / l, -1.0, 1.0) : 0.0;
    p.T = sigma_t_per_m * l;
    p.S = (length_m > SLUT_INFINITE_ABOVE) ? ((sigma_t_per_m > 0.0) ? SLUT_HUGE_VAL : 0.0) : sigma_t_per_m * length_m;
    p.S_over_T = (length_m > SLUT_INFINITE_ABOVE) ? SLUT_HUGE_VAL : ((l > 0.0) ? length_m / l : SLUT_HUGE_VAL);
    p.r = 0.0;
    if (!(mu_e > 0.0)) {
        p.kind = SLUT_NL_VIEWER_BELOW;
        return p;
    }
    if (p.mu_l < -SLUT_IN_PLANE_TOLERANCE) {
        p.kind = SLUT_NL_LIGHT_BELOW;
        return p;
    }
    p.r = fmax(p.mu_l, 0.0) / mu_e;
    return p;
}

/* Near-light radiance from E, W/(m²·sr) for I0 in W/sr, coefficients in 1/m, lengths in m:
 *   L = transmittance · σ_s/(4π) · I0 · E · (T·H)/l,
 * the form finite as σ_t → 0 (T·H depends on g and s/l only); transmittance is the exit's
 * Fresnel factor (1 without one). 0 without light (kind ≠ SLUT_NL_OK, σ_s = 0, I0 = 0,
 * s = 0); +∞ where H diverges (the ray runs through the light) or the light sits at O. */
SLUT_FN double slut_nl_assemble(slut_nl_params p, double sigma_s_per_m, double intensity_w_sr, double length_m,
                                double transmittance, double E) {
    if (p.kind != SLUT_NL_OK || !(sigma_s_per_m > 0.0) || !(intensity_w_sr > 0.0) || !(length_m > 0.0))
        return 0.0;
    if (!(p.distance_m > 0.0)) return SLUT_HUGE_VAL;
    double H_scaled = slut_nl_H_scaled(p.g, p.S_over_T);
    if (!SLUT_ISFINITE(H_scaled)) return SLUT_HUGE_VAL;
    return transmittance * sigma_s_per_m * SLUT_INV_4PI * intensity_w_sr * E * H_scaled / p.distance_m;
}
/* SLUT_SHADER_END */

/* slut_nl_params_from_dots from the vectors (3-element arrays): normal n, eye_dir ω,
 * light_rel_m (see there). */
SLUT_FN void slut_nl_params_from_geometry(const double *normal, const double *eye_dir,
                                          const double *light_rel_m, double sigma_t_per_m,
                                          double length_m, slut_nl_params *p) {
    double l = sqrt(light_rel_m[0] * light_rel_m[0] + light_rel_m[1] * light_rel_m[1] +
                    light_rel_m[2] * light_rel_m[2]);
    double mu_e = eye_dir[0] * normal[0] + eye_dir[1] * normal[1] + eye_dir[2] * normal[2];
    double n_dot_l = light_rel_m[0] * normal[0] + light_rel_m[1] * normal[1] + light_rel_m[2] * normal[2];
    double e_dot_l = light_rel_m[0] * eye_dir[0] + light_rel_m[1] * eye_dir[1] + light_rel_m[2] * eye_dir[2];
    *p = slut_nl_params_from_dots(l, mu_e, n_dot_l, e_dot_l, sigma_t_per_m, length_m);
}

/* Exact near-light radiance, W/(m²·sr) for I0 in W/sr, coefficients in 1/m, lengths in m:
 *   L = σ_s/(4π) · I0 · σ_t · N(T, g, r, S) = σ_s/(4π) · I0 · E · (T·H)/l,
 * the second form finite as σ_t → 0 (T·H depends on g and s/l only). 0 for a light below the
 * plane; NaN-free; +∞ when the ray runs through the light or the light sits at O. */
SLUT_FN double slut_nl_radiance_exact(double sigma_s_per_m, double sigma_a_per_m, double intensity_w_sr,
                                      const double *normal, const double *eye_dir,
                                      const double *light_rel_m, double length_m) {
    slut_nl_params p;
    double sigma_t = sigma_s_per_m + sigma_a_per_m;
    slut_nl_params_from_geometry(normal, eye_dir, light_rel_m, sigma_t, length_m, &p);
    /* E only where the assembly uses it (the zero limits and T = 0 need none: E(0, ...) = 1). */
    if (p.kind != SLUT_NL_OK || !(sigma_s_per_m > 0.0) || !(intensity_w_sr > 0.0) || !(length_m > 0.0) ||
        !(p.distance_m > 0.0) || !(p.T > 0.0))
        return slut_nl_assemble(p, sigma_s_per_m, intensity_w_sr, length_m, 1.0, 1.0);
    return slut_nl_assemble(p, sigma_s_per_m, intensity_w_sr, length_m, 1.0, slut_nl_E(p.T, p.g, p.r, p.S));
}

/* ------------------------------------------------------------------ eye-side refraction */

/* SLUT_SHADER_BEGIN (refraction and Fresnel: also the GLSL/HLSL snippets') */
/* cos θ_t of the eye ray refracted into the medium, from μ_e = cos θ_i outside and
 * η = n_medium/n_outside > 0 (Snell: sin θ_t = sin θ_i/η):
 *   cos² θ_t = 1 − (1 − μ_e²)/η² = ((η − 1)(η + 1) + μ_e²)/η².
 * The second form has no cancellation for η ≥ 1 (both terms ≥ 0) and, for η < 1, only the
 * one inherent near the critical angle (μ_e² ≈ 1 − η²), between two terms each rounded
 * once (η − 1 is exact for η ∈ [½, 2], Sterbenz); the first form subtracted from 1 a
 * quantity near 1, whose rounding (an ulp of 1) is as large as cos² θ_t itself there. For
 * η < 1 beyond the critical angle the ray grazes (0); never total internal reflection from
 * outside (η ≥ 1). */
SLUT_FN double slut_refracted_cos(double mu_e, double eta) {
    return sqrt(fmax((eta - 1.0) * (eta + 1.0) + mu_e * mu_e, 0.0)) / eta;
}

/* Unpolarised Fresnel transmittance 1 − (R_s + R_p)/2 through the interface, from the
 * cosines on the outside (cos_i) and the inside (cos_t) and η = n_medium/n_outside.
 * With a = cos_i, b = η cos_t: 1 − r_s² = 1 − ((a − b)/(a + b))² = 4ab/(a + b)², and with
 * a = η cos_i, b = cos_t the same for 1 − r_p², so
 *   T = 2 η cos_i cos_t · (1/(cos_i + η cos_t)² + 1/(η cos_i + cos_t)²),
 * a sum of positive terms: full relative precision where T → 0 (grazing incidence, and the
 * critical angle for η < 1), where 1 − (r_s² + r_p²)/2 cancels. */
SLUT_FN double slut_fresnel_transmittance(double cos_i, double cos_t, double eta) {
    if (!(cos_t > 0.0) || !(cos_i > 0.0)) return 0.0;
    double s = cos_i + eta * cos_t, p = eta * cos_i + cos_t;
    return 2.0 * eta * cos_i * cos_t * (1.0 / (s * s) + 1.0 / (p * p));
}
/* SLUT_SHADER_END */

/* The eye ray refracted into the medium (docs/PHYSICS.md §1.3): ω = unit vector from O towards the
 * viewer (outside), n the outward normal, eta = n_medium/n_outside > 0. Writes the unit
 * vector ω_t pointing from O back along the refracted ray (so the point at depth x is
 * O − x ω_t, the same convention as eye_dir) and returns cos θ_t = ω_t·n (≥ 0,
 * slut_refracted_cos): ω_t = (ω − μ_e n)/η + cos θ_t n, of unit length by Snell. */
SLUT_FN double slut_refract_eye_dir(const double *normal, const double *eye_dir, double eta, double *out) {
    double mu_e = eye_dir[0] * normal[0] + eye_dir[1] * normal[1] + eye_dir[2] * normal[2];
    double cos_t = slut_refracted_cos(mu_e, eta);
    double len2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        out[k] = (eye_dir[k] - mu_e * normal[k]) / eta + cos_t * normal[k];
        len2 += out[k] * out[k];
    }
    double inv = 1.0 / sqrt(len2);
    for (int k = 0; k < 3; ++k) out[k] *= inv;
    return cos_t;
}

/* SLUT_SHADER_BEGIN (the closed forms: also the GLSL/HLSL snippets') */
/* ------------------------------------------------------------------ closed forms (no table) */

/* Distant-light attenuation integral ∫_0^S e^{−(1+c)t} dt = (1 − e^{−(1+c)S})/(1+c), c = 1/r
 * (Gath 2008 eq. 5; docs/PHYSICS.md §1.2–§1.3). Written with r: 1/(1+c) = r/(1+r), (1+c)S = S(1+r)/r, and
 * −expm1 for small exponents. Limits: r = 0 → 0; r = ∞ → 1 − e^{−S}; S = ∞ → r/(1+r);
 * S = 0 → 0. This is also the T → ∞ limit of T²·N(T, g, r, S). */
SLUT_FN double slut_distant_light_factor(double r, double S) {
    SLUT_CHECK_GE(r, 0.0);
    SLUT_CHECK_GE(S, 0.0);
    if (!(S > 0.0) || !(r > 0.0)) return 0.0;
    if (r > SLUT_INFINITE_ABOVE) return -expm1(-S);
    double frac = r / (1.0 + r);
    if (S > SLUT_INFINITE_ABOVE) return frac;
    return frac * -expm1(-S / frac);
}

/* Distant light (sun over an ocean; Gath 2008 eq. 5), W/(m²·sr):
 *   L = Λ/(4π) · L_in · (1 − e^{−σ_t (1+c) s})/(1+c),  c = μ_e/μ_l,  Λ = σ_s/σ_t,
 * L_in the beam's irradiance at normal incidence (W/m²; docs/PHYSICS.md §1.3), μ_e = ω·n of the viewer,
 * μ_l = ω_l·n of the light (0 for a light at or below the horizon), s in m (+∞ = thick). */
SLUT_FN double slut_distant_light_radiance(double sigma_s_per_m, double sigma_a_per_m, double L_in,
                                           double mu_e, double mu_l, double length_m) {
    double sigma_t = sigma_s_per_m + sigma_a_per_m;
    if (!(mu_e > 0.0) || !(mu_l > 0.0) || !(sigma_s_per_m > 0.0) || !(length_m > 0.0)) return 0.0;
    double S = (length_m > SLUT_INFINITE_ABOVE) ? SLUT_HUGE_VAL : sigma_t * length_m;
    return (sigma_s_per_m / sigma_t) * SLUT_INV_4PI * L_in * slut_distant_light_factor(mu_l / mu_e, S);
}

/* Thin-medium approximation of E (Gath 2008 §4.2; docs/PHYSICS.md §1.3): the distant-light attenuation
 * averaged over the path, E ≈ (1 − e^{−x})/x, x = (1+c)S = S(1+r)/r. Limits: x → 0 gives 1
 * (also S = 0), S = ∞ or r = 0 (S > 0) gives 0 — the approximation is wrong for thick media
 * and as r → 0 (docs/PHYSICS.md §1.3); it never returns NaN. */
/* Its two steps for 0 < S < ∞ as expressions of variables r (≥ 0), S and x, written once for
 * a scalar and for the table kernel's lane vector of r (OpenCL C's ?: selects per element
 * where the condition is a lane comparison; S is a scalar): x = (1 + c)S (r = ∞: S, r = 0: ∞),
 * then (1 − e^{−x})/x: 1 below SLUT_TINY, 1/x above 40 (e^{−x} < 5e-18: 1 − e^{−x} rounds to 1,
 * the same value without expm1; also x = ∞: 0). */
#define SLUT_NL_THIN_X(r, S) (((r) > SLUT_INFINITE_ABOVE) ? (S) : (S) * ((1.0 + (r)) / (r)))
#define SLUT_NL_THIN_NEEDS_EXPM1(x) ((x) >= SLUT_TINY && (x) <= 40.0)
#define SLUT_NL_THIN_OF_X_WITHOUT_EXPM1(x) (((x) < SLUT_TINY) ? 1.0 : 1.0 / (x)) /* x outside [TINY, 40] */
#define SLUT_NL_THIN_OF_X(x) (SLUT_NL_THIN_NEEDS_EXPM1(x) ? -expm1(-(x)) / (x) : SLUT_NL_THIN_OF_X_WITHOUT_EXPM1(x))
SLUT_FN double slut_nl_E_thin(double r, double S) {
    SLUT_CHECK_GE(r, 0.0);
    SLUT_CHECK_GE(S, 0.0);
    if (!(S > 0.0)) return 1.0;
    if (!(r > 0.0) || S > SLUT_INFINITE_ABOVE) return 0.0;
    double x = SLUT_NL_THIN_X(r, S);
    return SLUT_NL_THIN_OF_X(x);
}

/* SLUT_SHADER_END */

/* N ≈ H(T, g, S)·(1 − e^{−(1+c)S})/((1+c)S): closed-form H times slut_nl_E_thin. */
SLUT_FN double slut_nl_N_thin(double T, double g, double r, double S) {
    double H = slut_nl_H(T, g, S);
    if (!(H > 0.0)) return 0.0;
    double E = slut_nl_E_thin(r, S);
    if (!SLUT_ISFINITE(H)) return (E > 0.0) ? SLUT_HUGE_VAL : 0.0;
    return H * E;
}

/* ------------------------------------------------------------------ the 4-D table's value base */

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
/* SLUT_SHADER_BEGIN (the value base: also the GLSL/HLSL snippets') */
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
/* SLUT_SHADER_END */

#endif /* SLUT_NEARLIGHT_H */
