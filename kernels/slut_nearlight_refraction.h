/* scatterlut — the eye ray through the surface of the medium: Snell's cos θ_t, the refracted
 * direction and the unpolarised Fresnel transmittance of the exit (docs/PHYSICS.md §1.3).
 *
 * Compiled as OpenCL C, as C++ (the runtime library) and, whole, as GLSL/HLSL in float (the
 * near-light snippet); written in the shared subset (kernels/slut_compat.h): vectors as the
 * struct slut_vec3 by value (kernels/slut_vec3.h), the array form for C callers in the
 * `#ifndef SLUT_SHADER` block.
 */
#ifndef SLUT_NEARLIGHT_REFRACTION_H
#define SLUT_NEARLIGHT_REFRACTION_H

#include "slut_compat.h"
#include "slut_vec3.h"

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

/* The eye ray refracted into the medium (docs/PHYSICS.md §1.3): eye_dir ω = unit vector from O
 * towards the viewer (outside), normal n the outward normal, eta = n_medium/n_outside > 0.
 * dir is the unit vector ω_t pointing from O back along the refracted ray (so the point at
 * depth x is O − x ω_t, the same convention as eye_dir), cos_t = ω_t·n (≥ 0,
 * slut_refracted_cos): ω_t = (ω − μ_e n)/η + cos θ_t n, of unit length by Snell (normalised
 * all the same, against rounding). */
SLUT_STRUCT_BEGIN(slut_refracted_ray)
    slut_vec3 dir; /* ω_t */
    double cos_t;  /* cos θ_t = ω_t·n */
SLUT_STRUCT_END(slut_refracted_ray);

SLUT_FN slut_refracted_ray slut_refract_eye(slut_vec3 normal, slut_vec3 eye_dir, double eta) {
    slut_refracted_ray t;
    double mu_e = slut_vec3_dot(eye_dir, normal);
    t.cos_t = slut_refracted_cos(mu_e, eta);
    double x = (eye_dir.x - mu_e * normal.x) / eta + t.cos_t * normal.x;
    double y = (eye_dir.y - mu_e * normal.y) / eta + t.cos_t * normal.y;
    double z = (eye_dir.z - mu_e * normal.z) / eta + t.cos_t * normal.z;
    double inv = 1.0 / sqrt(x * x + y * y + z * z);
    t.dir = slut_vec3_make(x * inv, y * inv, z * inv);
    return t;
}

/* The Fresnel factor of the exit towards the viewer (slut_fresnel_transmittance with cos θ_i =
 * ω·n and cos θ_t = slut_refracted_cos): 1 without refraction (eta = 1) or where fresnel is 0. */
SLUT_FN double slut_exit_transmittance(slut_vec3 normal, slut_vec3 eye_dir, double eta, int fresnel) {
    if (fresnel == 0 || eta == 1.0) return 1.0;
    double cos_i = slut_vec3_dot(eye_dir, normal);
    return slut_fresnel_transmittance(cos_i, slut_refracted_cos(cos_i, eta), eta);
}

#ifndef SLUT_SHADER
/* slut_refract_eye for 3-element arrays: writes ω_t to out, returns cos θ_t. */
SLUT_FN double slut_refract_eye_dir(const double *normal, const double *eye_dir, double eta, double *out) {
    slut_refracted_ray t = slut_refract_eye(slut_vec3_make(normal[0], normal[1], normal[2]),
                                            slut_vec3_make(eye_dir[0], eye_dir[1], eye_dir[2]), eta);
    out[0] = t.dir.x;
    out[1] = t.dir.y;
    out[2] = t.dir.z;
    return t.cos_t;
}
#endif /* !SLUT_SHADER */

#endif /* SLUT_NEARLIGHT_REFRACTION_H */
