/* scatterlut — the θ-integral of the airlight radiance (kernels/slut_airlight.h), written once:
 * the bracket ∫_0^{dv} exp(−c sin θ / sin(w2 − θ)) dθ by Gauss–Legendre panels (16 points for the
 * exact radiance, 8 where a table's accuracy is enough), and the one-panel rule of a short
 * segment in t = tan θ (6 points), with the test of which segments it serves.
 *
 * Compiled wherever kernels/slut_airlight.h is (it includes this header): OpenCL C, C++, and
 * GLSL/HLSL in float.
 */
#ifndef SLUT_AIRLIGHT_THETA_H
#define SLUT_AIRLIGHT_THETA_H

#include "slut_compat.h"
#include "slut_airlight_tail.h"     /* slut_gl16_x/w, slut_gl8_x/w */
#include "slut_airlight_geometry.h" /* slut_airlight_geometry */

/* ∫_0^{dv} exp(−c sin θ / sin(w2 − θ)) dθ, 0 ≤ dv ≤ w2 ≤ π/2: the bracket of the airlight
 * with ξ = v2 + θ (A1 (tan ξ − tan v2) = c sin θ / sin(w2 − θ)). The integrand is 1 at
 * θ = 0, decreasing and log-concave, with an essential singularity at the pole θ = w2.
 * Panels are placed by the distance δ to the pole (kept exactly, never as w2 − θ):
 * length ≤ δ/4 (pole outside the Bernstein ellipse, ρ_B ≥ 9.9) and ≤ 4/λ with
 * λ = c sin w2 / sin² δ the local decay rate. Stops when the log-concave remainder bound
 * f/λ drops below 1e-17 of the sum. Relative error ~1e-14 with 16 points per panel
 * (gl16 = 1). With 8 points (gl16 = 0, half the work) the same panels give: pole
 * ρ_B^{−16} ≤ 1.2e-16; decay, the n-point Gauss remainder of e^{−λθ} over λh ≤ 4,
 * (λh)^{2n} (n!)⁴/((2n + 1)((2n)!)³) ≤ 7e-14 at n = 8: ~1e-13 relative (≤ 1e-11 against
 * the Boost reference in tests/runtime/test_airlight_table, EightPointThetaRuleMatchesDirectQuadrature),
 * far below any table's error (the table radiance's tolerance there is 1e-3). */
#ifdef SLUT_SHADER
/* The shaders' form of one θ-panel's Gauss sum (below): the same node, weight, integrand and
 * order of additions, written out per node with constant array indices. SwiftShader
 * evidently keeps a constant array read with a variable index (and a local array) in per-lane
 * memory: the three array forms of the pixel's path cost 1.15–1.4× its frame there, none on
 * llvmpipe (bench/README.md, "SwiftShader"). With constant indices the nodes and weights are
 * constants. */
SLUT_FN double slut_airlight_theta_node_pair(double c, double st, double ct, double sd, double cd, double half_len,
                                             double node, double weight, double part) {
    double t = half_len + (-1.0) * half_len * node;
    part += weight * exp(-c * (st + t * ct) / (sd - t * cd)) / (1.0 + t * t);
    t = half_len + 1.0 * half_len * node;
    return part + weight * exp(-c * (st + t * ct) / (sd - t * cd)) / (1.0 + t * t);
}
#endif
SLUT_FN double slut_airlight_theta_integral_rule(double c, double w2, double dv, int gl16) {
    if (dv <= 0.0) return 0.0;
    if (c <= 0.0) return dv;
    int half_points = (gl16 != 0) ? 8 : 4;
    double sin_w2 = sin(w2);
    double delta = w2;            /* distance from the panel start to the pole */
    double remaining = dv;        /* distance from the panel start to the end */
    double sum = 0.0;
    for (int panel = 0; panel < SLUT_THETA_MAX_PANELS && remaining > 0.0; ++panel) {
        double theta = dv - remaining;
        double sd = sin(delta), cd = cos(delta), st = sin(theta), ct = cos(theta);
        double rate = c * sin_w2 / (sd * sd);
        double f_start = exp(-c * st / sd);
        if (panel > 0 && f_start <= SLUT_REMAINDER_NEGLIGIBLE * sum * rate) break;
        double h = fmin(remaining, fmin(0.25 * delta, 4.0 / rate));
        /* The panel in t = tan x, x = θ − theta ∈ [0, h]: dividing by cos x,
         *   sin(theta + x)/sin(delta − x) = (st + t ct)/(sd − t cd),  dθ = dt/(1 + t²),
         * so the nodes need no sine (the same integral: the rule's nodes move, its bounds hold,
         * as h ≤ π/8 keeps tan on the panel within 5 % of linear and the poles of 1/(1 + t²)
         * at ±i ≥ 2.4 panel lengths away: Bernstein ρ ≥ 9.8). */
        double half_len = 0.5 * tan(h), part = 0.0;
#ifdef SLUT_SHADER
        if (gl16 == 0) {
            part = slut_airlight_theta_node_pair(c, st, ct, sd, cd, half_len, slut_gl8_x[0], slut_gl8_w[0], part);
            part = slut_airlight_theta_node_pair(c, st, ct, sd, cd, half_len, slut_gl8_x[1], slut_gl8_w[1], part);
            part = slut_airlight_theta_node_pair(c, st, ct, sd, cd, half_len, slut_gl8_x[2], slut_gl8_w[2], part);
            part = slut_airlight_theta_node_pair(c, st, ct, sd, cd, half_len, slut_gl8_x[3], slut_gl8_w[3], part);
            half_points = 0; /* done: the loop below is the 16-point rule's */
        }
#endif
        for (int k = 0; k < half_points; ++k) {
            double node = (gl16 != 0) ? slut_gl16_x[k] : slut_gl8_x[k];
            double weight = (gl16 != 0) ? slut_gl16_w[k] : slut_gl8_w[k];
            for (int side = -1; side <= 1; side += 2) {
                double t = half_len + SLUT_DOUBLE(side) * half_len * node;
                part += weight * exp(-c * (st + t * ct) / (sd - t * cd)) / (1.0 + t * t);
            }
        }
        sum += half_len * part;
        remaining -= h;
        delta -= h;
    }
    return sum;
}
SLUT_FN double slut_airlight_theta_integral(double c, double w2, double dv) {
    return slut_airlight_theta_integral_rule(c, w2, dv, 1);
}

/* 6-point Gauss–Legendre on [−1, 1] (the positive nodes and weights, mpmath to 21 digits). */
SLUT_CONST_ARRAY3(slut_gl6_x, 0.238619186083196908631, 0.661209386466264513661, 0.932469514203152027812);
SLUT_CONST_ARRAY3(slut_gl6_w, 0.467913934572691047390, 0.360761573048138607570, 0.171324492379170345040);

/* The θ-integral of a segment short enough for one panel of slut_airlight_theta_integral_rule
 * (its first panel's bounds, with tan dv ≥ dv in place of dv: tan dv ≤ w2/4 and
 * λ·tan dv ≤ 4, λ = c/sin w2 the decay rate at θ = 0), in the variable t = tan θ:
 *   sin θ/sin(w2 − θ) = t/(sin w2 − t cos w2),  dθ = dt/(1 + t²),
 *   ∫_0^{dv} e^{−c sin θ/sin(w2 − θ)} dθ = ∫_0^{tan dv} e^{−c t/(sin w2 − t cos w2)} dt/(1 + t²),
 * an algebraic integrand (one divide and one exp per node, no sine) whose singularities stay
 * where the θ-rule's bounds keep them: the exponent's pole at t = tan w2 ≥ 4 tan dv, the
 * poles of 1/(1 + t²) at ±i, |i| ≥ 1/(π/8) times the panel. 6 points: the decay part of the
 * Gauss remainder for λh ≤ 4 is ≤ 3e-9 (the bound quoted at the θ-rule), the poles
 * ρ_B^{−12} ≤ 1e-12; measured ≤ 8e-12 against slut_airlight_theta_integral on 20000 of the
 * bench's geometries and 1.3e-12 against Boost.Math on the 384 of 400 test geometries that
 * fit (tests/runtime/test_airlight_table, OnePanelThetaRuleMatchesDirectQuadrature; tolerance 1e-9). sin w2 = cos(γ/2), cos w2 = sin(γ/2). */
/* The test on the plain numbers, t = tan dv, w2 (rad), c = 2 σ_t D sin(γ/2) and ch = cos(γ/2),
 * as a lane-generic expression (as slut_axes.h's SLUT_WARP_X): a scalar's is a truth value,
 * the runtime's 4-lane vectors' a lane mask (GCC's && on vectors; both sides evaluated); the
 * runtime's fast paths (tables/src/airlight.cpp, airlight_avx2.cpp, airlight_batch.cpp) test
 * their plain numbers with it. One line: GLSL before 4.20 has no line continuation. */
#define SLUT_AIRLIGHT_THETA_FITS_ONE_PANEL(t, w2, c, ch) ((t) <= 0.25 * (w2) && (c) * (t) <= 4.0 * (ch))
/* The same for a set-up geometry: kind 0 (a finite segment to integrate) and the test above. */
SLUT_FN int slut_airlight_theta_fits_one_panel(slut_airlight_geometry g) {
    return (g.kind == 0 && SLUT_AIRLIGHT_THETA_FITS_ONE_PANEL(g.tan_dv, g.w2, g.c, g.cos_half)) ? 1 : 0;
}
#ifdef SLUT_SHADER
/* The shaders' form of slut_airlight_theta_integral_one_panel below: the same nodes, weights
 * and order of additions, one node at a time with constant array indices (no local arrays,
 * no variable index: see slut_airlight_theta_node_pair). */
SLUT_FN double slut_airlight_theta_one_panel_node(double c, double sin_w2, double cos_w2, double half_len, double x,
                                                  double weight, double sum) {
    double t = half_len * (1.0 + x);
    return sum + (weight / (1.0 + t * t)) * exp(-c * t / (sin_w2 - t * cos_w2));
}
SLUT_FN double slut_airlight_theta_integral_one_panel(double c, double sin_w2, double cos_w2, double tan_dv) {
    double half_len = 0.5 * tan_dv, sum = 0.0;
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, -slut_gl6_x[0], slut_gl6_w[0], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, -slut_gl6_x[1], slut_gl6_w[1], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, -slut_gl6_x[2], slut_gl6_w[2], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, slut_gl6_x[0], slut_gl6_w[0], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, slut_gl6_x[1], slut_gl6_w[1], sum);
    sum = slut_airlight_theta_one_panel_node(c, sin_w2, cos_w2, half_len, slut_gl6_x[2], slut_gl6_w[2], sum);
    return half_len * sum;
}
#else
SLUT_FN double slut_airlight_theta_integral_one_panel(double c, double sin_w2, double cos_w2, double tan_dv) {
    /* The exponents first, then the exps, then the sum: the six divides and the six exp
     * calls are independent and overlap (a loop of exp-then-divide serialises on them). */
    double half_len = 0.5 * tan_dv, sum = 0.0;
    double exponent[6];
    double weight[6];
    for (int k = 0; k < 6; ++k) {
        double x = (k < 3) ? -slut_gl6_x[k] : slut_gl6_x[k - 3];
        double t = half_len * (1.0 + x);
        exponent[k] = -c * t / (sin_w2 - t * cos_w2);
        weight[k] = slut_gl6_w[k < 3 ? k : k - 3] / (1.0 + t * t);
    }
    for (int k = 0; k < 6; ++k) exponent[k] = exp(exponent[k]);
    for (int k = 0; k < 6; ++k) sum += weight[k] * exponent[k];
    return half_len * sum;
}
#endif /* SLUT_SHADER */

#endif /* SLUT_AIRLIGHT_THETA_H */
