// A lit surface in physical units under a spot light (scatterlut/spot_surface.hpp): the point
// light's surface terms (surface_radiance.hpp, Sun et al. 2005) with the direct terms masked by
// the falloff f(θ_P) of glTF KHR_lights_punctual and the scattered ones either approximated
// (times f(θ_P), or by the thin-beam model, from the tables) or from the spot's exact E_ss and
// S_n (the reference).
#include "scatterlut/spot_surface.hpp"

#include "require.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

extern "C" {
#include "slut_spot.h"
#include "slut_surface_frontend.h"
#include "slut_vec3.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

constexpr double kPi = 3.14159265358979323846;
constexpr double kAngleMax = kPi + 1e-15; // the double nearest π and rounding above it

bool finite3(const Vec3 &v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

void check_spot_light(const SpotLight &l) {
    require(finite3(l.position_m), "spot light: position must hold finite coordinates (m)");
    require(finite3(l.direction) && slut_vec3_length(slut_vec3_make(l.direction[0], l.direction[1], l.direction[2])) > 0.0,
            "spot light: direction must be finite and non-zero");
    require(l.outer_angle_rad >= 0.0 && l.outer_angle_rad <= kAngleMax, "spot light: outer_angle must lie in [0, pi] (rad)");
    require(l.inner_angle_rad >= 0.0 && l.inner_angle_rad <= kAngleMax, "spot light: inner_angle must lie in [0, pi] (rad)");
    require(l.inner_angle_rad <= l.outer_angle_rad, "spot light: inner_angle must not exceed outer_angle");
    require(std::isfinite(l.intensity_W_per_sr) && l.intensity_W_per_sr >= 0.0,
            "spot light: intensity must be finite and >= 0 (W/sr)");
}

void check(const SpotSurfaceLighting &s, double sigma_s, double sigma_a, const SurfaceMaterial &m) {
    check_spot_light(s.light);
    check_surface_lighting(point_light_of(s), sigma_s, sigma_a, m);
}

// Each product only where its factor is > 0 (an infinite term times 0 stays 0).
double times(double term, double factor) { return factor > 0.0 && term > 0.0 ? term * factor : 0.0; }

slut_surface_geometry geometry_of(const SpotSurfaceLighting &s) {
    const slut_vec3 normal = slut_vec3_make(s.normal[0], s.normal[1], s.normal[2]);
    const slut_vec3 to_light = slut_vec3_make(s.light.position_m[0] - s.point_m[0], s.light.position_m[1] - s.point_m[1],
                                              s.light.position_m[2] - s.point_m[2]);
    const slut_vec3 to_viewer =
        slut_vec3_make(s.viewer_m[0] - s.point_m[0], s.viewer_m[1] - s.point_m[1], s.viewer_m[2] - s.point_m[2]);
    return slut_surface_geometry_make(normal, to_light, to_viewer);
}

// ρ = 2 (n·ω_v) n − ω_v, the mirror direction of the view ray (slut_surface_frontend.h).
Vec3 mirror_of(const SpotSurfaceLighting &s) {
    const slut_vec3 to_viewer =
        slut_vec3_make(s.viewer_m[0] - s.point_m[0], s.viewer_m[1] - s.point_m[1], s.viewer_m[2] - s.point_m[2]);
    const double v = slut_vec3_length(to_viewer);
    const double wv[3] = {to_viewer.x / v, to_viewer.y / v, to_viewer.z / v};
    const double nv = s.normal[0] * wv[0] + s.normal[1] * wv[1] + s.normal[2] * wv[2];
    return {2.0 * nv * s.normal[0] - wv[0], 2.0 * nv * s.normal[1] - wv[1], 2.0 * nv * s.normal[2] - wv[2]};
}

SpotSurfacePoint spot_point(const SpotSurfaceLighting &s, double sigma_s, double sigma_a) {
    SpotSurfacePoint q;
    q.sigma_s_per_m = sigma_s;
    q.sigma_a_per_m = sigma_a;
    q.point_m = {s.point_m[0], s.point_m[1], s.point_m[2]};
    q.light = s.light;
    return q;
}

void check_channels(const Rgb &sigma_s, const Rgb &sigma_a) {
    for (int c = 0; c < 3; ++c)
        if (!(std::isfinite(sigma_s[c]) && sigma_s[c] >= 0.0 && std::isfinite(sigma_a[c]) && sigma_a[c] >= 0.0))
            throw std::invalid_argument("spot surface radiance: sigma_s and sigma_a must be finite and >= 0 in every "
                                        "channel (channel " + std::to_string(c) + ")");
}

} // namespace

SurfaceLighting point_light_of(const SpotSurfaceLighting &s) {
    SurfaceLighting p;
    for (int i = 0; i < 3; ++i) {
        p.point_m[i] = s.point_m[i];
        p.normal[i] = s.normal[i];
        p.viewer_m[i] = s.viewer_m[i];
        p.light_m[i] = s.light.position_m[static_cast<size_t>(i)];
    }
    p.intensity_W_per_sr = s.light.intensity_W_per_sr;
    return p;
}

double spot_falloff_at_point(const SpotLight &light, const double point_m[3]) {
    check_spot_light(light);
    require(std::isfinite(point_m[0]) && std::isfinite(point_m[1]) && std::isfinite(point_m[2]),
            "spot falloff: the point must hold finite coordinates (m)");
    require(point_m[0] != light.position_m[0] || point_m[1] != light.position_m[1] ||
                point_m[2] != light.position_m[2],
            "spot falloff: the point must not sit on the light (distance 0)");
    return spot_falloff(light, {point_m[0], point_m[1], point_m[2]}); // scatterlut/spot.hpp
}

SurfaceRadiance spot_surface_radiance(const SurfaceTables &tables, const SpotSurfaceLighting &s, double sigma_s_per_m,
                                      double sigma_a_per_m, const SurfaceMaterial &m, SpotScatterModel model) {
    check(s, sigma_s_per_m, sigma_a_per_m, m);
    const SurfaceRadiance point = surface_radiance(tables, point_light_of(s), sigma_s_per_m, sigma_a_per_m, m);
    const double f = spot_falloff_at_point(s.light, s.point_m);
    SurfaceRadiance r;
    r.diffuse_direct = times(point.diffuse_direct, f);
    r.specular_direct = times(point.specular_direct, f);
    if (model == SpotScatterModel::falloff) {
        r.diffuse_scattered = times(point.diffuse_scattered, f);
        r.specular_scattered = times(point.specular_scattered, f);
        return r;
    }
    // Thin beam: min(point light's term, the same assembled with e^{−T} G^spot_n(T = 0)), which
    // is the point light's term times min(1, e^{−T} G^spot_n(0)/G_n(T, θ)).
    if (!(point.diffuse_scattered > 0.0) && !(point.specular_scattered > 0.0)) return r;
    const slut_surface_geometry g = geometry_of(s);
    const double T = (sigma_s_per_m + sigma_a_per_m) * g.light_distance_m, extinction = std::exp(-T);
    SpotSurfacePoint q = spot_point(s, sigma_s_per_m, sigma_a_per_m);
    double g_diffuse = 0.0, g_specular = 0.0;
    if (point.diffuse_scattered > 0.0) {
        q.lobe_axis = {s.normal[0], s.normal[1], s.normal[2]};
        g_diffuse = extinction * spot_surface_G_thin(1, q);
    }
    if (point.specular_scattered > 0.0) {
        q.lobe_axis = mirror_of(s);
        g_specular = extinction * spot_surface_G_thin(m.phong_exponent, q);
    }
    const slut_surface_terms thin = slut_surface_assemble(g, sigma_s_per_m, sigma_a_per_m, s.light.intensity_W_per_sr,
                                                          m.diffuse_albedo, m.specular_per_sr, m.phong_exponent,
                                                          g_diffuse, g_specular);
    r.diffuse_scattered = std::min(point.diffuse_scattered, thin.diffuse_scattered);
    r.specular_scattered = std::min(point.specular_scattered, thin.specular_scattered);
    return r;
}

SurfaceRadiance spot_surface_radiance_exact(const SpotSurfaceLighting &s, double sigma_s_per_m, double sigma_a_per_m,
                                            const SurfaceMaterial &m) {
    check(s, sigma_s_per_m, sigma_a_per_m, m);
    const slut_surface_geometry g = geometry_of(s);
    double g_diffuse = 0.0, g_specular = 0.0;
    if (g.kind == SLUT_SURF_OK && sigma_s_per_m > 0.0 && s.light.intensity_W_per_sr > 0.0) {
        SpotSurfacePoint q = spot_point(s, sigma_s_per_m, sigma_a_per_m);
        if (m.diffuse_albedo > 0.0) {
            q.lobe_axis = {s.normal[0], s.normal[1], s.normal[2]};
            g_diffuse = spot_surface_G_exact(1, q);
        }
        if (m.specular_per_sr > 0.0) {
            q.lobe_axis = mirror_of(s);
            g_specular = spot_surface_G_exact(m.phong_exponent, q);
        }
    }
    const slut_surface_terms t = slut_surface_assemble(g, sigma_s_per_m, sigma_a_per_m, s.light.intensity_W_per_sr,
                                                       m.diffuse_albedo, m.specular_per_sr, m.phong_exponent, g_diffuse,
                                                       g_specular);
    const double f = spot_falloff_at_point(s.light, s.point_m);
    SurfaceRadiance r;
    r.diffuse_direct = times(t.diffuse_direct, f);
    r.specular_direct = times(t.specular_direct, f);
    r.diffuse_scattered = t.diffuse_scattered;
    r.specular_scattered = t.specular_scattered;
    return r;
}

Rgb spot_surface_radiance_rgb(const SurfaceTables &tables, const SpotSurfaceLighting &s, const Rgb &sigma_s_per_m,
                              const Rgb &sigma_a_per_m, const SurfaceMaterial &m, SpotScatterModel model) {
    check_channels(sigma_s_per_m, sigma_a_per_m);
    Rgb out{};
    for (int c = 0; c < 3; ++c)
        out[c] = spot_surface_radiance(tables, s, sigma_s_per_m[c], sigma_a_per_m[c], m, model).total();
    return out;
}

Rgb spot_surface_radiance_exact_rgb(const SpotSurfaceLighting &s, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                                    const SurfaceMaterial &m) {
    check_channels(sigma_s_per_m, sigma_a_per_m);
    Rgb out{};
    for (int c = 0; c < 3; ++c)
        out[c] = spot_surface_radiance_exact(s, sigma_s_per_m[c], sigma_a_per_m[c], m).total();
    return out;
}

} // namespace scatterlut
