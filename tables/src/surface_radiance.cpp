#include "scatterlut/surface_radiance.hpp"

#include "require.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

extern "C" {
#include "slut_surface_frontend.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

constexpr double kGUnderflowT = 760.0; // optical distance beyond which G_n < 1e-320

bool finite3(const double v[3]) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }
bool finite_non_negative(double x) { return std::isfinite(x) && x >= 0.0; }

slut_vec3 rel(const double a[3], const double origin[3]) {
    return slut_vec3_make(a[0] - origin[0], a[1] - origin[1], a[2] - origin[2]);
}

slut_surface_geometry geometry(const SurfaceLighting &s) {
    return slut_surface_geometry_make(slut_vec3_make(s.normal[0], s.normal[1], s.normal[2]), rel(s.light_m, s.point_m),
                                      rel(s.viewer_m, s.point_m));
}

SurfaceRadiance from_terms(const slut_surface_terms &t) {
    SurfaceRadiance r;
    r.diffuse_direct = t.diffuse_direct;
    r.diffuse_scattered = t.diffuse_scattered;
    r.specular_direct = t.specular_direct;
    r.specular_scattered = t.specular_scattered;
    return r;
}

// G of `exponent` at (T, θ): from the table inside its T axis, else by quadrature.
double G_from(const SurfaceTable &table, double T, double theta) {
    if (T <= table.T_max()) return table.G(T, theta);
    return surface_G_exact(table.exponent(), T, theta);
}

// The radiance with G_1 = g_of(false, 1, T, θ_s) and G_n = g_of(true, n, T, θ_r); the G's are computed only for the
// terms that need them (k_d > 0, k_s > 0, light and viewer valid, σ_s I0 > 0).
template <class GOf>
SurfaceRadiance assemble(const SurfaceLighting &s, double sigma_s, double sigma_a, const SurfaceMaterial &m,
                         GOf g_of) {
    check_surface_lighting(s, sigma_s, sigma_a, m);
    const slut_surface_geometry g = geometry(s);
    double g_diffuse = 0.0, g_specular = 0.0;
    const double T = (sigma_s + sigma_a) * g.light_distance_m;
    // Beyond kGUnderflowT every G underflows (G ≤ G0(0, 0) e^{−T} = (π² + 2π) e^{−T} < 1e-320):
    // 0 without a quadrature (T may be +inf there).
    if (g.kind == SLUT_SURF_OK && sigma_s > 0.0 && s.intensity_W_per_sr > 0.0 && T <= kGUnderflowT) {
        if (m.diffuse_albedo > 0.0) g_diffuse = g_of(false, 1, T, g.theta_s);
        if (m.specular_per_sr > 0.0) g_specular = g_of(true, m.phong_exponent, T, g.theta_r);
    }
    return from_terms(slut_surface_assemble(g, sigma_s, sigma_a, s.intensity_W_per_sr, m.diffuse_albedo,
                                            m.specular_per_sr, m.phong_exponent, g_diffuse, g_specular));
}

void check_channels(const Rgb &sigma_s, const Rgb &sigma_a) {
    for (int c = 0; c < 3; ++c)
        if (!(finite_non_negative(sigma_s[c]) && finite_non_negative(sigma_a[c])))
            throw std::invalid_argument("surface radiance: sigma_s and sigma_a must be finite and >= 0 in every "
                                        "channel (channel " + std::to_string(c) + ")");
}

} // namespace

void check_surface_lighting(const SurfaceLighting &s, double sigma_s_per_m, double sigma_a_per_m,
                            const SurfaceMaterial &m) {
    require(finite3(s.point_m), "surface radiance: point_m must be finite");
    require(finite3(s.normal), "surface radiance: normal must be finite");
    const double n2 = s.normal[0] * s.normal[0] + s.normal[1] * s.normal[1] + s.normal[2] * s.normal[2];
    if (!(std::fabs(n2 - 1.0) <= 2e-6)) // (the message built only on failure: this runs per query)
        throw std::invalid_argument("surface radiance: normal must be a unit vector (|n|^2 = " + std::to_string(n2) +
                                    ")");
    require(finite3(s.light_m), "surface radiance: light_m must be finite");
    require(finite3(s.viewer_m), "surface radiance: viewer_m must be finite");
    const slut_surface_geometry g = geometry(s);
    require(std::isfinite(g.light_distance_m) && g.light_distance_m > 0.0,
            "surface radiance: the light must not sit on the surface point (distance 0)");
    require(std::isfinite(g.view_distance_m) && g.view_distance_m > 0.0,
            "surface radiance: the viewer must not sit on the surface point (distance 0)");
    require(finite_non_negative(s.intensity_W_per_sr), "surface radiance: intensity_W_per_sr must be finite and >= 0");
    require(finite_non_negative(sigma_s_per_m), "surface radiance: sigma_s must be finite and >= 0");
    require(finite_non_negative(sigma_a_per_m), "surface radiance: sigma_a must be finite and >= 0");
    require(finite_non_negative(m.diffuse_albedo), "surface radiance: diffuse_albedo (k_d) must be finite and >= 0");
    require(finite_non_negative(m.specular_per_sr), "surface radiance: specular_per_sr (k_s) must be finite and >= 0");
    if (!(m.phong_exponent >= 1 && m.phong_exponent <= kSurfaceMaxExponent))
        throw std::invalid_argument("surface radiance: phong_exponent must lie in [1, " +
                                    std::to_string(kSurfaceMaxExponent) + "], not " + std::to_string(m.phong_exponent));
}

SurfaceRadiance surface_radiance(const SurfaceTables &tables, const SurfaceLighting &s, double sigma_s_per_m,
                                 double sigma_a_per_m, const SurfaceMaterial &m) {
    require(m.diffuse_albedo == 0.0 || tables.diffuse != nullptr,
            "surface radiance: diffuse_albedo > 0 needs the diffuse (G0) table");
    require(m.specular_per_sr == 0.0 || tables.specular != nullptr,
            "surface radiance: specular_per_sr > 0 needs a specular table of the material's exponent");
    if (m.diffuse_albedo > 0.0 && tables.diffuse->exponent() != 1)
        throw std::invalid_argument("surface radiance: the diffuse table is of exponent " +
                                    std::to_string(tables.diffuse->exponent()) + ", expected 1 (G0)");
    if (m.specular_per_sr > 0.0 && tables.specular->exponent() != m.phong_exponent)
        throw std::invalid_argument("surface radiance: the specular table is of exponent " +
                                    std::to_string(tables.specular->exponent()) + ", the material's exponent is " +
                                    std::to_string(m.phong_exponent));
    return assemble(s, sigma_s_per_m, sigma_a_per_m, m, [&](bool lobe, int, double T, double theta) {
        return G_from(lobe ? *tables.specular : *tables.diffuse, T, theta);
    });
}

SurfaceRadiance surface_radiance_exact(const SurfaceLighting &s, double sigma_s_per_m, double sigma_a_per_m,
                                       const SurfaceMaterial &m) {
    return assemble(s, sigma_s_per_m, sigma_a_per_m, m,
                    [](bool, int exponent, double T, double theta) { return surface_G_exact(exponent, T, theta); });
}

Rgb surface_radiance_rgb(const SurfaceTables &tables, const SurfaceLighting &s, const Rgb &sigma_s_per_m,
                         const Rgb &sigma_a_per_m, const SurfaceMaterial &m) {
    check_channels(sigma_s_per_m, sigma_a_per_m);
    Rgb out{};
    for (int c = 0; c < 3; ++c) out[c] = surface_radiance(tables, s, sigma_s_per_m[c], sigma_a_per_m[c], m).total();
    return out;
}

Rgb surface_radiance_exact_rgb(const SurfaceLighting &s, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                               const SurfaceMaterial &m) {
    check_channels(sigma_s_per_m, sigma_a_per_m);
    Rgb out{};
    for (int c = 0; c < 3; ++c) out[c] = surface_radiance_exact(s, sigma_s_per_m[c], sigma_a_per_m[c], m).total();
    return out;
}

} // namespace scatterlut
