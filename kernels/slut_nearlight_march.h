/* scatterlut — E(T, g, r, S) and N by quadrature: the panel rule, the cumulative sweep over
 * slab depths, the exact radiance.
 *
 * Double precision only: compiled as OpenCL C by the near-light table kernels
 * (kernels/nearlight_E.cl) and as C++ by the host (exact evaluation, eval, validation) and the
 * runtime library (E outside a table's domain). Symbols: kernels/slut_nearlight.h;
 * the derivations of every rule are below.
 */
#ifndef SLUT_NEARLIGHT_MARCH_H
#define SLUT_NEARLIGHT_MARCH_H

#include "slut_compat.h"
#include "slut_airlight.h"           /* slut_gl16_x / slut_gl16_w: the project's 16-point Gauss–Legendre rule */
#include "slut_nearlight_closed.h"   /* H */
#include "slut_nearlight_lanes.h"    /* slut_nl_lanes */
#include "slut_nearlight_frontend.h" /* slut_nl_params (slut_nl_radiance_exact) */

/* ------------------------------------------------------------------ E and N by quadrature */

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
 * and one exp2 per lane). N = E·H.
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

/* T·H = slut_nl_H_scaled(g, τ_i) at count depths tau[i] (the sweep's S_i/T; sg = √(1 − g²)),
 * SLUT_NL_LANE_WIDTH at a time: the steps of slut_nl_inv_square_integral (its lane-generic
 * macros, slut_nearlight_closed.h) around one vector atan. On the device (double16) one call
 * per 16 slab nodes instead of 16 scalar ones: the E4 32³ × 17 kernel ~4 % less CPU time
 * (bench/README.md, "The node loop in base 2"). The vector atan may round differently from
 * the scalar one by an ulp. */
SLUT_FN void slut_nl_H_scaled_at(double g, double sg, const double *tau, int count, double *H_out) {
    for (int i0 = 0; i0 < count; i0 += SLUT_NL_LANE_WIDTH) {
        double len_at[SLUT_NL_LANE_WIDTH], H_lanes[SLUT_NL_LANE_WIDTH];
        for (int k = 0; k < SLUT_NL_LANE_WIDTH; ++k) len_at[k] = (i0 + k < count) ? tau[i0 + k] : 1.0; /* padding */
        slut_nl_lanes len = slut_nl_lanes_load(len_at);
        slut_nl_lanes den = SLUT_NL_ISQ_DEN(len, 1.0, g);
        slut_nl_lanes x = SLUT_NL_ISQ_NUM(len, sg) / fabs(den);
        slut_nl_lanes a = atan(x);
        slut_nl_lanes_store(SLUT_NL_ISQ_OF_ATAN(len, den, sg, x, a), H_lanes);
        for (int k = 0; k < SLUT_NL_LANE_WIDTH && i0 + k < count; ++k) H_out[i0 + k] = H_lanes[k];
    }
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
    double tau_at[SLUT_NL_MAX_SWEEP], H_at[SLUT_NL_MAX_SWEEP]; /* the nodes' S_i/T and T·H there */
    for (i = first; i < stop; ++i) tau_at[i] = SLUT_NL_NODE_TAU(i);
    if (stop - first == 1) H_at[first] = slut_nl_H_scaled(g, tau_at[first]); /* a thick table: one scalar atan */
    else slut_nl_H_scaled_at(g, sg, &tau_at[first], stop - first, &H_at[first]);
    double H_next = H_at[first];
    double inv_H = 1.0 / H_next;
    double sg2 = sg * sg, half_peak = -0.5 * g;
    /* refine^15 by six products (a few ulps from pow, nothing the stopping test can see:
     * PoCL's pow, in double-double arithmetic, took ~2 % of the 3-D table kernel's time;
     * bench/README.md, "The airlight batch's check and lookups; the sweep's pow …"). */
    double refine2 = refine * refine, refine4 = refine2 * refine2, refine8 = refine4 * refine4;
    double tail_eps = SLUT_NL_TAIL_EPS / (((refine8 * refine4) * refine2) * refine);
    double minus_T_log2e = -T * 0x1.71547652b82fep+0; /* −T·log2(e): the node loop's exponent in base 2 */
    /* One block where a block holds every lane (the device's double16): a constant, so that
     * the sums and r stay in registers instead of an array indexed at run time. */
    int blocks = (SLUT_NL_LANE_BLOCKS == 1) ? 1 : (lanes + SLUT_NL_LANE_WIDTH - 1) / SLUT_NL_LANE_WIDTH;
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
            double o_near[8], em[8];
            for (int k = 0; k < 8; ++k) o_near[k] = 0.5 * D * (1.0 - slut_gl16_x[k]);
            double em_D = slut_nl_expm1_panel(D, o_near, em);
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
        /* Each node's τ, η and weight over η², SLUT_NL_LANE_WIDTH nodes at a time (the
         * device's double16: the 16 nodes' sqrt and divide as one vector each, correctly
         * rounded like the scalar ones), then the lanes node by node. */
        double tn_at[17], en_at[16], base_at[16]; /* tn_at[16]: the node loop's look-ahead */
        for (int n = 0; n < 16; n += SLUT_NL_LANE_WIDTH) {
            slut_nl_lanes o = slut_nl_lanes_load(&off[n]), tn, dn;
            if (carry_d) { dn = dl + o; tn = dn - g; }
            else { tn = tau + o; dn = tn + g; }
            slut_nl_lanes en2 = dn * dn + sg2;
            slut_nl_lanes_store(tn, &tn_at[n]);
            slut_nl_lanes_store(sqrt(en2), &en_at[n]);
            slut_nl_lanes_store(slut_nl_lanes_load(&wt[n]) * inv_H / en2, &base_at[n]);
        }
        /* The attenuation e^{−T(τ + η q)} = 2^{c0 + c1 q}, c0 = −T log2(e)·τ, c1 = −T log2(e)·η
         * per node (slut_nl_lanes_exp2). The next node's q is divided out before this node's
         * exp2, so that the divide runs beside the exp2's multiply-adds rather than ahead of
         * them (the same values; E3 64³ kernel 1.01× less CPU time, bench/README.md);
         * tn_at[16] repeats the last node so that the look-ahead needs no branch. */
        slut_nl_lanes q_next[SLUT_NL_LANE_BLOCKS];
        tn_at[16] = tn_at[15];
        for (b = 0; b < blocks; ++b) q_next[b] = slut_nl_q(tn_at[0], rr[b]);
        for (int n = 0; n < 16; ++n) {
            double tn = tn_at[n], base = base_at[n];
            double c0 = minus_T_log2e * tn, c1 = minus_T_log2e * en_at[n];
            for (b = 0; b < blocks; ++b) {
                slut_nl_lanes q = q_next[b];
                q_next[b] = slut_nl_q(tn_at[n + 1], rr[b]);
                sum[b] += base * slut_nl_lanes_exp2(c0 + c1 * q);
            }
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
            H_next = H_at[next];
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
        double scale = (i == next) ? 1.0 : H_next / H_at[i];
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

#endif /* SLUT_NEARLIGHT_MARCH_H */
