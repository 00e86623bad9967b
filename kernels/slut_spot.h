/* scatterlut — the spot light's cone, written once: glTF KHR_lights_punctual's angular falloff
 * and the crossings of a ray with the cone (docs/PHYSICS.md §1.6).
 *
 * Sign convention: θ is the angle between the spot's axis n (the direction the beam points)
 * and the direction FROM THE LIGHT TO THE POINT. The beam is the one nappe θ ≤ θ_o around +n
 * (a cone of half-angle θ_o ∈ [0, π]; for θ_o > π/2 the complement of the cone of half-angle
 * π − θ_o around −n). glTF's falloff, with θ_i ≤ θ_o the inner angle,
 *
 *   f(θ) = clamp((cos θ − cos θ_o)/(cos θ_i − cos θ_o), 0, 1)²,
 *
 * is written in versines, vers θ = 1 − cos θ = 2 sin²(θ/2) (cos θ − cos θ_o = vers θ_o − vers θ),
 * so that narrow beams keep their digits: vers θ of a point comes from |ŵ − n|²/2 (ŵ the unit
 * vector from the light to the point), never from 1 − cos. θ_i = θ_o is the hard cone (f = 1 for
 * θ ≤ θ_o, 0 beyond), θ_i = θ_o = π the point light (f ≡ 1), θ_o = 0 a beam of no solid angle
 * (f ≡ 0).
 *
 * The ray–cone algebra: a point x = o + t d (d unit) lies on a cone of half-angle α around n
 * with apex L where (n·w)² = cos²α |w|², w = x − L. Squaring loses the sign of n·w: the
 * quadratic's roots lie on BOTH NAPPES of the double cone {θ = α} ∪ {θ = π − α}. Only the
 * nappe with sign(n·w) = sign(cos α) is the beam's edge; a root on the other one is where
 * the ray crosses θ = π − α, which changes nothing about the light. The callers therefore use
 * the roots only as breakpoints of the ray and classify each piece between them by f at a
 * point inside it: an extra breakpoint costs a split, never a wrong answer.
 *
 * Compiled as C++ (runtime library, tests) and in OpenCL C; in the shared subset of
 * kernels/slut_compat.h (structs by value, an output array), double precision.
 */
#ifndef SLUT_SPOT_H
#define SLUT_SPOT_H

#include "slut_compat.h"
#include "slut_vec3.h"

/* vers α = 1 − cos α = 2 sin²(α/2), rad → dimensionless in [0, 2]. */
SLUT_FN double slut_spot_versine(double angle_rad) {
    double s = sin(0.5 * angle_rad);
    return 2.0 * s * s;
}

/* vers θ of a point from the unit vector light → point and the unit axis: |ŵ − n|²/2. */
SLUT_FN double slut_spot_versine_of(slut_vec3 unit_light_to_point, slut_vec3 unit_axis) {
    double x = unit_light_to_point.x - unit_axis.x, y = unit_light_to_point.y - unit_axis.y,
           z = unit_light_to_point.z - unit_axis.z;
    return 0.5 * (x * x + y * y + z * z);
}

/* glTF's falloff f ∈ [0, 1] from the versines of θ, θ_o and θ_i (vers_inner ≤ vers_outer). */
SLUT_FN double slut_spot_falloff(double vers_theta, double vers_outer, double vers_inner) {
    if (!(vers_outer > 0.0)) return 0.0;      /* θ_o = 0: no solid angle, no light */
    if (vers_theta > vers_outer) return 0.0;  /* outside the outer cone */
    if (vers_theta <= vers_inner) return 1.0; /* inside the inner cone (the whole hard cone) */
    double q = (vers_outer - vers_theta) / (vers_outer - vers_inner);
    return q * q;
}

/* df/d(vers θ) inside the band vers_inner < vers θ < vers_outer (0 elsewhere). */
SLUT_FN double slut_spot_falloff_slope(double vers_theta, double vers_outer, double vers_inner) {
    if (!(vers_theta > vers_inner) || !(vers_theta < vers_outer)) return 0.0;
    double width = vers_outer - vers_inner;
    return -2.0 * (vers_outer - vers_theta) / (width * width);
}

/* ------------------------------------------------------------------ the ray and the cone
 *
 * The ray x = o + t d (d unit) is written from its closest approach to the light:
 * x − L = e + τ d, τ = t − t*, t* = d·(L − o), e ⊥ d the vector from the light to the foot of
 * the perpendicular, h = |e| (the light's distance from the ray's line), ê = e/h. A cone of
 * half-angle α ≤ π/2 around a unit axis m is written by the versine ν = vers α ∈ [0, 1] and the
 * versines of d and ê about m, ν_d = |d − m|²/2 and ν_e = |ê − m|²/2 (so m·d = 1 − ν_d,
 * m·e = h (1 − ν_e), cos α = 1 − ν). The squared cone equation (m·w)² = cos²α |w|² in τ is
 *
 *   A τ² + 2 B τ + C = 0,   A = (m·d)² − cos²α = (ν − ν_d)(2 − ν − ν_d),
 *                           B = (m·e)(m·d),
 *                           C = (m·e)² − cos²α h² = h² (ν − ν_e)(2 − ν − ν_e):
 *
 * both differences of squares are products of versine differences, which keep their digits
 * for narrow cones (1 − cos α from a cosine would not: θ_o = 1e-3 has vers 5e-7, below
 * float's rounding of 1). Its roots lie on the double cone (both nappes: the one around m
 * and its mirror around −m; for α = π/2 the plane m·w = 0). */

/* The real roots τ[0] ≤ τ[1] of the quadratic above; returns how many (0, 1 or 2). The pair by
 * the cancellation-free q = −(B + sign(B)√(B² − AC)), τ = q/A and C/q, each clamped to
 * ±SLUT_INFINITE_ABOVE (A → 0: the ray nearly parallel to a generator sends one root there).
 * A = 0 leaves the one root −C/(2B) (= C/q); a discriminant that rounding pushed below 0 by at
 * most SLUT_SPOT_TANGENT_SLACK of its terms is a tangent (a double root). Written with selects
 * only (no branch: the GPU snippets run it for every pixel). */
SLUT_FN int slut_spot_cone_roots(double nu, double nu_d, double nu_e, double miss, SLUT_OUT_ARRAY(double, tau, 2)) {
    double mu_d = 1.0 - nu_d, mu_e = miss * (1.0 - nu_e);
    double A = (nu - nu_d) * (2.0 - nu - nu_d);
    double B = mu_e * mu_d;
    double C = (miss * miss) * ((nu - nu_e) * (2.0 - nu - nu_e));
    double disc = B * B - A * C;
    int real = (disc >= -SLUT_SPOT_TANGENT_SLACK * (B * B + fabs(A * C))) ? 1 : 0;
    double root = sqrt(fmax(disc, 0.0));
    double q = -(B + SLUT_SELECT(B >= 0.0, root, -root));
    double r0 = SLUT_SELECT(fabs(q) < SLUT_INFINITE_ABOVE * fabs(A), q / A, SLUT_SELECT((q > 0.0) == (A > 0.0), SLUT_INFINITE_ABOVE, -SLUT_INFINITE_ABOVE));
    double r1 = SLUT_SELECT(q != 0.0, slut_clamp(C / q, -SLUT_INFINITE_ABOVE, SLUT_INFINITE_ABOVE), 0.0);
    /* A = 0 && B = 0: the ray lies on the cone or never meets it; q = 0 (B = 0, C = 0): τ = 0 */
    int n = (real == 0) ? 0 : ((A == 0.0) ? ((B == 0.0) ? 0 : 1) : ((q == 0.0) ? 1 : 2));
    tau[0] = SLUT_SELECT(n == 2, fmin(r0, r1), SLUT_SELECT(n == 1, r1, 0.0));
    tau[1] = SLUT_SELECT(n == 2, fmax(r0, r1), tau[0]);
    return n;
}

/* A cone of the spot (the outer or the inner one, half-angle α ∈ [0, π]) as the convex cone its
 * edge bounds: for α ≤ π/2 the lit side {θ ≤ α} itself (axis +n, the lit side is convex); for
 * α > π/2 the dark side {θ ≥ α}, the cone of half-angle π − α around −n. nu: the versine of the
 * convex cone's half-angle (2 sin²(α/2), or 2 cos²(α/2) for the dark side: no 2 − vers α), 0 for
 * α = 0 and α ≥ π (a cone of no solid angle: a ray); axis_sign: +1 (lit side) or −1 (dark). */
SLUT_STRUCT_BEGIN(slut_spot_cone)
    double nu;
    double axis_sign;
SLUT_STRUCT_END(slut_spot_cone);

SLUT_FN slut_spot_cone slut_spot_cone_of(double angle_rad) {
    slut_spot_cone c;
    double s = sin(0.5 * angle_rad), co = cos(0.5 * angle_rad);
    int lit = (angle_rad > 0.5 * SLUT_PI) ? 0 : 1;
    c.axis_sign = SLUT_SELECT(lit != 0, 1.0, -1.0);
    c.nu = SLUT_SELECT(angle_rad >= SLUT_PI, 0.0, SLUT_SELECT(lit != 0, 2.0 * s * s, 2.0 * co * co));
    return c;
}

/* The part of the ray's line inside a convex cone (a convex set: an interval, maybe unbounded)
 * in τ, from the roots above: lo = hi = +SLUT_INFINITE_ABOVE when empty (a cone of ν = 0 too),
 * ∓SLUT_INFINITE_ABOVE for an unbounded end. Which part of the line lies inside follows from
 * A's sign: A < 0 (|m·d| < cos α: the direction outside the cone's) bounds the part between the
 * roots, which lies in the cone around m where m·e > 0 (the line's point nearest the axis there,
 * τ = −B/A, has m·w = (m·e) cos²α/(−A)); A ≥ 0 (the direction within it) leaves a ray on each
 * nappe, the one around m on the side m·d points to. A line through the apex (h = 0) has the
 * double root τ = 0. */
SLUT_STRUCT_BEGIN(slut_spot_span)
    double lo;
    double hi;
SLUT_STRUCT_END(slut_spot_span);

SLUT_FN slut_spot_span slut_spot_convex_span(double nu, double nu_d, double nu_e, double miss) {
    slut_spot_span j;
    double tau[2];
    int n = slut_spot_cone_roots(nu, nu_d, nu_e, miss, tau);
    double mu_d = 1.0 - nu_d, mu_e = miss * (1.0 - nu_e);
    double A = (nu - nu_d) * (2.0 - nu - nu_d);
    double B = mu_e * mu_d;
    /* no real root with A > 0 is rounding near the apex: the vertex −B/A stands for both */
    double vertex = SLUT_SELECT(fabs(B) < SLUT_INFINITE_ABOVE * fabs(A), -B / A, 0.0);
    double near_root = SLUT_SELECT(n == 0, vertex, tau[0]);
    double far_root = SLUT_SELECT(n == 2, tau[1], near_root);
    int between = (A < 0.0 && n == 2 && mu_e > 0.0) ? 1 : 0; /* the part between the roots */
    int in_plane = (A == 0.0 && mu_d == 0.0) ? 1 : 0;         /* α = π/2, d in the plane: all or nothing */
    int one_ray = (A > 0.0 || (A == 0.0 && mu_d != 0.0 && mu_e > 0.0)) ? 1 : 0; /* A = 0: a generator's direction */
    double lo = SLUT_SELECT(one_ray != 0, SLUT_SELECT(mu_d > 0.0, far_root, -SLUT_INFINITE_ABOVE), SLUT_INFINITE_ABOVE);
    double hi = SLUT_SELECT(one_ray != 0, SLUT_SELECT(mu_d > 0.0, SLUT_INFINITE_ABOVE, near_root), SLUT_INFINITE_ABOVE);
    lo = SLUT_SELECT(in_plane != 0, SLUT_SELECT(mu_e > 0.0, -SLUT_INFINITE_ABOVE, SLUT_INFINITE_ABOVE), lo);
    lo = SLUT_SELECT(between != 0, tau[0], lo);
    hi = SLUT_SELECT(between != 0, tau[1], hi);
    j.lo = SLUT_SELECT(nu > 0.0, lo, SLUT_INFINITE_ABOVE);
    j.hi = SLUT_SELECT(nu > 0.0, hi, SLUT_INFINITE_ABOVE);
    return j;
}

#endif /* SLUT_SPOT_H */
