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

/* The ray's crossings of the double cone (both nappes, see above) of half-angle α (given as
 * cos α) around the unit axis n with apex L: the real roots t of
 *   A t² + 2 b t + C = 0,  A = (n·d)² − cos²α,  b = (n·d)(n·w0) − cos²α (d·w0),
 *   C = (n·w0)² − cos²α |w0|²,  w0 = o − L = apex_to_origin,  d the unit ray direction,
 * written t[0] ≤ t[1]; returns how many (0, 1 or 2). A and C are formed as products of
 * (x − c)(x + c), the root pair by the cancellation-free q = −(b + sign(b)√(b² − AC)),
 * t = q/A and C/q. A = 0 (d parallel to a generator) leaves the one root −C/(2b); a
 * discriminant that rounding pushed below 0 by at most 8 ulps of its terms is a tangent (a
 * double root), as for α = π/2 where the cone is the plane n·w = 0. */
SLUT_FN int slut_spot_cone_crossings(slut_vec3 apex_to_origin, slut_vec3 dir, slut_vec3 axis, double cos_alpha,
                                     SLUT_OUT_ARRAY(double, t, 2)) {
    double nd = slut_vec3_dot(axis, dir), nw = slut_vec3_dot(axis, apex_to_origin);
    double dw = slut_vec3_dot(dir, apex_to_origin), ww = slut_vec3_length(apex_to_origin);
    double c2 = cos_alpha * cos_alpha;
    double A = (nd - cos_alpha) * (nd + cos_alpha);
    double b = nd * nw - c2 * dw;
    double C = (nw - cos_alpha * ww) * (nw + cos_alpha * ww);
    double disc = b * b - A * C;
    double scale = b * b + fabs(A * C);
    t[0] = 0.0;
    t[1] = 0.0;
    if (disc < 0.0) {
        if (disc < -1.8e-15 * scale) return 0; /* 8 ulps */
        disc = 0.0;
    }
    double root = sqrt(disc);
    double q = -(b + (b >= 0.0 ? root : -root));
    if (A == 0.0) {
        if (b == 0.0) return 0; /* the ray lies on the cone or never meets it */
        t[0] = -C / (2.0 * b);
        return 1;
    }
    if (q == 0.0) return 1; /* b = 0 and C = 0: the double root t = 0 */
    double r0 = q / A, r1 = C / q;
    t[0] = fmin(r0, r1);
    t[1] = fmax(r0, r1);
    return 2;
}

#endif /* SLUT_SPOT_H */
