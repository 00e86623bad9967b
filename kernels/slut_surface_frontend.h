/* scatterlut — the front-end of Sun et al. 2005's surface terms: the angles and distances of a
 * lit surface point from positions, and the radiance it sends towards the viewer assembled
 * from the dimensionless G_n (docs/PHYSICS.md §1.5; G from a table or from the quadrature).
 *
 * Compiled as C++ (the runtime library's scatterlut/surface_radiance.hpp) and, whole, as
 * GLSL/HLSL in float (the surface snippet); written in the shared subset (kernels/slut_compat.h).
 *
 * Geometry (vectors relative to the surface point P, in m; n the unit normal on the viewer's side):
 *   D   = |light − P|,  ω_l = (light − P)/D        (the direction FROM P TO THE LIGHT)
 *   D_v = |viewer − P|, ω_v = (viewer − P)/D_v     (from P to the viewer)
 *   cos θ_s = n·ω_l (θ_s > π/2: the light is below the surface's horizon)
 *   ρ = 2 (n·ω_v) n − ω_v, the mirror direction of the view ray (unit);  cos θ_r = ρ·ω_l.
 * The angles are taken as atan2(|a × b|, a·b) (slut_vec3_angle), accurate at 0 and at π
 * (acos of a dot product loses half the digits there).
 *
 * Radiance towards the viewer, W/(m²·sr), with T = σ_t D, I0 in W/sr, σ in 1/m:
 *   E_d   = I0 e^{−T} max(cos θ_s, 0)/D²                       direct irradiance
 *   E_ss  = σ_s I0/(4π D) · G_1(T, θ_s)                         scattered irradiance (G_1 = G0)
 *   P_d   = I0 e^{−T} max(cos θ_r, 0)^n/D²  if cos θ_s > 0, else 0   direct specular
 *   S_n   = σ_s I0/(4π D) · G_n(T, θ_r)                         specular lobe (not horizon-clipped)
 *   L     = e^{−σ_t D_v} [ k_d/π (E_d + E_ss) + k_s (P_d + S_n) ]
 * k_d the diffuse albedo (dimensionless); k_s the Phong coefficient in 1/sr of the
 * unnormalised lobe max(cos θ_r, 0)^n (Sun et al. 2005's form; an energy-conserving lobe of
 * specular albedo ρ_s sets k_s = ρ_s (n + 2)/(2π)). The direct specular term is cut where the
 * light is below the horizon (the surface shadows its own lamp, as E_d is cut); S_n is not
 * (as Sun et al. 2005 define it). The view ray's own airlight is not included: the caller adds
 * it (AirlightTable, the airlight snippet). */
#ifndef SLUT_SURFACE_FRONTEND_H
#define SLUT_SURFACE_FRONTEND_H

#include "slut_compat.h"
#include "slut_vec3.h"

#define SLUT_SURF_OK 0            /* a valid geometry                                            */
#define SLUT_SURF_VIEWER_BELOW 1  /* n·ω_v ≤ 0: the viewer sees the surface's back: radiance 0  */
#define SLUT_SURF_AT_LIGHT 2      /* D = 0: the light sits on the point (the radiance diverges)  */
#define SLUT_SURF_AT_VIEWER 3     /* D_v = 0: no view direction                                  */

SLUT_STRUCT_BEGIN(slut_surface_geometry)
    int kind;                /* SLUT_SURF_*                                   */
    double light_distance_m; /* D                                             */
    double view_distance_m;  /* D_v                                           */
    double cos_theta_s;      /* n·ω_l                                         */
    double theta_s;          /* rad, [0, π]                                   */
    double cos_theta_r;      /* ρ·ω_l                                         */
    double theta_r;          /* rad, [0, π]                                   */
SLUT_STRUCT_END(slut_surface_geometry);

/* The geometry of a surface point (see the top of this file): normal = unit normal n,
 * light_rel_m = light − P, viewer_rel_m = viewer − P (m). */
SLUT_FN slut_surface_geometry slut_surface_geometry_make(slut_vec3 normal, slut_vec3 light_rel_m,
                                                         slut_vec3 viewer_rel_m) {
    slut_surface_geometry g;
    g.kind = SLUT_SURF_OK;
    g.light_distance_m = slut_vec3_length(light_rel_m);
    g.view_distance_m = slut_vec3_length(viewer_rel_m);
    g.cos_theta_s = 0.0;
    g.theta_s = 0.0;
    g.cos_theta_r = 0.0;
    g.theta_r = 0.0;
    if (!(g.light_distance_m > 0.0)) {
        g.kind = SLUT_SURF_AT_LIGHT;
        return g;
    }
    if (!(g.view_distance_m > 0.0)) {
        g.kind = SLUT_SURF_AT_VIEWER;
        return g;
    }
    double l = g.light_distance_m, v = g.view_distance_m;
    slut_vec3 wl = slut_vec3_make(light_rel_m.x / l, light_rel_m.y / l, light_rel_m.z / l);
    slut_vec3 wv = slut_vec3_make(viewer_rel_m.x / v, viewer_rel_m.y / v, viewer_rel_m.z / v);
    g.cos_theta_s = slut_clamp(slut_vec3_dot(normal, wl), -1.0, 1.0);
    g.theta_s = slut_vec3_angle(normal, wl);
    double nv = slut_vec3_dot(normal, wv);
    if (!(nv > 0.0)) {
        g.kind = SLUT_SURF_VIEWER_BELOW;
        return g;
    }
    slut_vec3 rho = slut_vec3_make(2.0 * nv * normal.x - wv.x, 2.0 * nv * normal.y - wv.y, 2.0 * nv * normal.z - wv.z);
    g.cos_theta_r = slut_clamp(slut_vec3_dot(rho, wl), -1.0, 1.0);
    g.theta_r = slut_vec3_angle(rho, wl);
    return g;
}

/* The scale of the scattered terms E_ss and S_n (see the top of this file): σ_s I0/(4π D),
 * W/m² per unit of the dimensionless G_n, for σ_s in 1/m, I0 in W/sr, D in m (formed as
 * σ_s·I0·(1/4π)/D, in that order: every caller gets the same bits). */
SLUT_FN double slut_surface_scattered_scale(double sigma_s_per_m, double intensity_W_per_sr, double D) {
    return sigma_s_per_m * intensity_W_per_sr * SLUT_INV_4PI / D;
}

/* The direct irradiance at normal incidence, W/m²: I0 e^{−T}/D² for I0 in W/sr, T = σ_t D the
 * optical distance to the light, D in m; 0 where e^{−T} underflows (so that D → 0 there gives
 * 0, never 0·∞). E_d is it times max(cos θ_s, 0), P_d times the lobe max(cos θ_r, 0)^n. */
SLUT_FN double slut_surface_direct_normal(double intensity_W_per_sr, double T, double D) {
    double light_att = exp(-T);
    return (light_att > 0.0) ? intensity_W_per_sr * light_att / (D * D) : 0.0;
}

/* The four terms of the radiance towards the viewer, W/(m²·sr), each already attenuated by
 * e^{−σ_t D_v} and weighted by k_d/π or k_s (see the top of this file). */
SLUT_STRUCT_BEGIN(slut_surface_terms)
    double diffuse_direct;     /* e^{−σ_t D_v} k_d/π E_d  */
    double diffuse_scattered;  /* e^{−σ_t D_v} k_d/π E_ss */
    double specular_direct;    /* e^{−σ_t D_v} k_s P_d    */
    double specular_scattered; /* e^{−σ_t D_v} k_s S_n    */
SLUT_STRUCT_END(slut_surface_terms);

/* The terms from the geometry and the two dimensionless integrals G_1(σ_t D, θ_s) (g_diffuse)
 * and G_n(σ_t D, θ_r) (g_specular; n = exponent ≥ 1). All 0 for a viewer below the surface,
 * a viewer at the point, or no light (I0 = 0); +∞ (diffuse_direct, the other terms 0) for a
 * light on the point. Never negative for inputs ≥ 0. */
SLUT_FN slut_surface_terms slut_surface_assemble(slut_surface_geometry g, double sigma_s_per_m, double sigma_a_per_m,
                                                 double intensity_W_per_sr, double k_d, double k_s_per_sr,
                                                 int exponent, double g_diffuse, double g_specular) {
    slut_surface_terms t;
    t.diffuse_direct = 0.0;
    t.diffuse_scattered = 0.0;
    t.specular_direct = 0.0;
    t.specular_scattered = 0.0;
    if (g.kind == SLUT_SURF_AT_LIGHT && intensity_W_per_sr > 0.0) {
        t.diffuse_direct = SLUT_HUGE_VAL;
        return t;
    }
    if (g.kind != SLUT_SURF_OK || !(intensity_W_per_sr > 0.0)) return t;
    double sigma_t = sigma_s_per_m + sigma_a_per_m;
    double D = g.light_distance_m;
    double view = exp(-sigma_t * g.view_distance_m);
    double direct = slut_surface_direct_normal(intensity_W_per_sr, sigma_t * D, D); /* W/m² */
    double scattered = slut_surface_scattered_scale(sigma_s_per_m, intensity_W_per_sr, D); /* × G: W/m² */
    double kd = view * k_d * (1.0 / SLUT_PI);
    double ks = view * k_s_per_sr;
    /* Each product only where its factors are > 0, so that an overflowing factor (D → 0)
     * times a zero weight gives 0, never NaN. */
    if (kd > 0.0 && g.cos_theta_s > 0.0) t.diffuse_direct = kd * g.cos_theta_s * direct;
    if (kd > 0.0 && g_diffuse > 0.0 && scattered > 0.0) t.diffuse_scattered = kd * g_diffuse * scattered;
    if (ks > 0.0 && g.cos_theta_s > 0.0 && g.cos_theta_r > 0.0) {
        double lobe = pow(g.cos_theta_r, SLUT_DOUBLE(exponent));
        if (lobe > 0.0) t.specular_direct = ks * lobe * direct;
    }
    if (ks > 0.0 && g_specular > 0.0 && scattered > 0.0) t.specular_scattered = ks * g_specular * scattered;
    return t;
}

/* The radiance, the sum of the four terms. */
SLUT_FN double slut_surface_terms_total(slut_surface_terms t) {
    return t.diffuse_direct + t.diffuse_scattered + t.specular_direct + t.specular_scattered;
}

#endif /* SLUT_SURFACE_FRONTEND_H */
