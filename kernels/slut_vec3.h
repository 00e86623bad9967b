/* scatterlut — 3-vectors: the struct slut_vec3 passed and returned by value, its dot product,
 * the length of a cross product, a length without overflow and the angle between two vectors
 * (as an angle, or as its sine and cosine).
 *
 * Compiled as OpenCL C, as C++ (the runtime library) and, whole, as GLSL/HLSL in float (every
 * snippet; their glue converts vec3/float3 with slut_vec3_make); written in the shared subset
 * (kernels/slut_compat.h).
 */
#ifndef SLUT_VEC3_H
#define SLUT_VEC3_H

#include "slut_compat.h"

/* A 3-vector, passed and returned by value. */
SLUT_STRUCT_BEGIN(slut_vec3)
    double x;
    double y;
    double z;
SLUT_STRUCT_END(slut_vec3);

SLUT_FN slut_vec3 slut_vec3_make(double x, double y, double z) {
    slut_vec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

SLUT_FN double slut_vec3_dot(slut_vec3 a, slut_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* |a × b| for any a, b. */
SLUT_FN double slut_vec3_cross_length(slut_vec3 a, slut_vec3 b) {
    double x = a.y * b.z - a.z * b.y, y = a.z * b.x - a.x * b.z, z = a.x * b.y - a.y * b.x;
    return sqrt(x * x + y * y + z * z);
}

/* |v| without overflow or underflow of the squares (a light 1e-200 m away is not at 0). */
SLUT_FN double slut_vec3_length(slut_vec3 v) {
    double m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
    if (!(m > 0.0) || !(m < SLUT_REAL_MAX)) return m; /* 0, +inf or NaN */
    double x = v.x / m, y = v.y / m, z = v.z / m;
    return m * sqrt(x * x + y * y + z * z);
}

/* The angle between a and b (any lengths > 0), rad in [0, π]: atan2(|a × b|, a·b), accurate
 * at 0 and at π, where acos of the normalised dot product loses half the digits. A caller
 * that wants sin and cos of the angle divides the same pair by its norm (the snippets'
 * *_points entries). */
SLUT_FN double slut_vec3_angle(slut_vec3 a, slut_vec3 b) {
    return atan2(slut_vec3_cross_length(a, b), slut_vec3_dot(a, b));
}

/* sin and cos of the angle between a and b (any lengths > 0): slut_vec3_angle's pair
 * (|a × b|, a·b) divided by its norm, without the atan2 (the snippets' *_points entries, whose
 * kernels take γ as sin γ and cos γ; γ → 0 and γ → π keep their precision). */
SLUT_STRUCT_BEGIN(slut_vec3_sincos)
    double sin_angle;
    double cos_angle;
SLUT_STRUCT_END(slut_vec3_sincos);

SLUT_FN slut_vec3_sincos slut_vec3_angle_sincos(slut_vec3 a, slut_vec3 b) {
    double sin_part = slut_vec3_cross_length(a, b), cos_part = slut_vec3_dot(a, b);
    double norm = sqrt(sin_part * sin_part + cos_part * cos_part);
    slut_vec3_sincos r;
    r.sin_angle = sin_part / norm;
    r.cos_angle = cos_part / norm;
    return r;
}

#endif /* SLUT_VEC3_H */
