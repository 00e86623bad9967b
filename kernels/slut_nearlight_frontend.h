/* scatterlut — the near-light front-end: the parameters (T, g, r, S) from a geometry in
 * physical units, their kind codes, and the radiance assembled from E.
 *
 * Symbols and sign conventions: kernels/slut_nearlight.h and docs/PHYSICS.md §1.2. Compiled as
 * OpenCL C, as C++ (the runtime library's NearLightTable and free functions, the host) and,
 * whole, as GLSL/HLSL in float (the near-light snippet's front-end); written in the shared
 * subset (kernels/slut_compat.h) except the array form in the `#ifndef SLUT_SHADER` block.
 */
#ifndef SLUT_NEARLIGHT_FRONTEND_H
#define SLUT_NEARLIGHT_FRONTEND_H

#include "slut_compat.h"
#include "slut_nearlight_closed.h"     /* slut_nl_H_scaled (the assembly) */
#include "slut_nearlight_refraction.h" /* slut_vec3, slut_refract_eye */

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
/* The same with T·H given (H_scaled = slut_nl_H_scaled(p.g, p.S_over_T)): for a caller that
 * computes it while the table's cell is fetched (the runtime's thick radiance). 1/l is a
 * divide of its own, which does not wait for E and T·H, the values that arrive last (the
 * runtime's thick radiance 1.07× faster than with the divide by l after them; bench/README.md,
 * "Issue #18's 3-D call"), and the product takes it last: the factors before it are 0 where
 * E is (σ_s/l may overflow: 1e202/1e-154), and 1/l is finite (l = √(x² + y² + z²) is 0 or
 * above 1e-162 in double, 1e-23 in float). */
SLUT_FN double slut_nl_assemble_given_H(slut_nl_params p, double sigma_s_per_m, double intensity_w_sr,
                                        double length_m, double transmittance, double E, double H_scaled) {
    if (p.kind != SLUT_NL_OK || !(sigma_s_per_m > 0.0) || !(intensity_w_sr > 0.0) || !(length_m > 0.0))
        return 0.0;
    if (!(p.distance_m > 0.0)) return SLUT_HUGE_VAL;
    if (!SLUT_ISFINITE(H_scaled)) return SLUT_HUGE_VAL;
    double inv_distance = 1.0 / p.distance_m;
    return transmittance * sigma_s_per_m * SLUT_INV_4PI * intensity_w_sr * E * H_scaled * inv_distance;
}
SLUT_FN double slut_nl_assemble(slut_nl_params p, double sigma_s_per_m, double intensity_w_sr, double length_m,
                                double transmittance, double E) {
    return slut_nl_assemble_given_H(p, sigma_s_per_m, intensity_w_sr, length_m, transmittance, E,
                                    slut_nl_H_scaled(p.g, p.S_over_T));
}

/* (T, g, r, S) of a geometry seen through the surface: the eye ray refracted into the medium
 * where eta = n_medium/n_outside ≠ 1 (slut_refract_eye), then slut_nl_params_from_dots on the
 * dot products of the vectors (normal n, eye_dir ω, light_rel_m as there). Refracted, μ_e of
 * the ray inside is cos θ_t itself (ω_t·n = cos θ_t by Snell), not the dot product of the
 * refracted vector, which loses its relative precision as cos θ_t → 0 (near the critical
 * angle for η < 1: in float an absolute error ~6e-8 on cos θ_t = 0.017 is 4e-6). A viewer
 * outside whose ray refracts to grazing (cos θ_t = 0) sees no light from the medium:
 * SLUT_NL_LIGHT_BELOW (radiance 0), not SLUT_NL_VIEWER_BELOW. The front-end of the runtime
 * library (tables/src/nearlight.cpp) and of the near-light snippet. */
SLUT_FN slut_nl_params slut_nl_params_seen(slut_vec3 normal, slut_vec3 eye_dir, slut_vec3 light_rel_m,
                                           double sigma_t_per_m, double length_m, double eta) {
    slut_vec3 eye = eye_dir;
    double mu_e = slut_vec3_dot(eye_dir, normal);
    int viewer_outside = (mu_e > 0.0) ? 1 : 0;
    if (eta != 1.0 && viewer_outside != 0) {
        slut_refracted_ray inside = slut_refract_eye(normal, eye_dir, eta);
        eye = inside.dir;
        mu_e = inside.cos_t;
    }
    slut_nl_params p = slut_nl_params_from_dots(sqrt(slut_vec3_dot(light_rel_m, light_rel_m)), mu_e,
                                                slut_vec3_dot(light_rel_m, normal), slut_vec3_dot(light_rel_m, eye),
                                                sigma_t_per_m, length_m);
    if (viewer_outside != 0 && p.kind == SLUT_NL_VIEWER_BELOW) p.kind = SLUT_NL_LIGHT_BELOW;
    return p;
}

#ifndef SLUT_SHADER
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
#endif /* !SLUT_SHADER */

#endif /* SLUT_NEARLIGHT_FRONTEND_H */
