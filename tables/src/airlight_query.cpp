// The airlight query (scatterlut/airlight.hpp) without a table: its check, its geometry's near
// end (the front-end both airlight runtimes share), the query from points, and the radiances
// that need no table (the exact quadrature, the closed forms without extinction).
#include "scatterlut/airlight.hpp"

#include "airlight_query_ranges.hpp"
#include "require.hpp"

#include <cmath>

extern "C" {
#include "slut_airlight.h"
#include "slut_vec3.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

// From the half angle h = γ/2 (clamped to π/2 against the rounding the check allows):
// w2 = π/2 − h exactly, sin h and cos h by slut_sincos_half_angle (no libm call). The far
// end's angles and attenuation are left to slut_airlight_setup_far_end, and g.scale's
// e^{−σ_t D} to the caller (slut_airlight_setup_near_end_unscaled).
slut_airlight_geometry setup_near_end_unscaled(const AirlightQuery &q) {
    check_airlight_query(q);
    const double half = 0.5 * q.gamma_rad < SLUT_PIO2_HI ? 0.5 * q.gamma_rad : SLUT_PIO2_HI;
    double sin_half, cos_half;
    slut_sincos_half_angle(half, &sin_half, &cos_half);
    return slut_airlight_setup_near_end_unscaled(q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr,
                                                 q.distance_m, sin_half, cos_half, slut_pio2_minus(half), q.length_m);
}

slut_airlight_geometry setup_near_end(const AirlightQuery &q) {
    return slut_airlight_set_scale(setup_near_end_unscaled(q));
}

slut_airlight_geometry setup(const AirlightQuery &q) { return slut_airlight_setup_far_end_and_dv(setup_near_end(q)); }

} // namespace

slut_airlight_geometry detail::airlight_query_near_end(const AirlightQuery &q) { return setup_near_end_unscaled(q); }

void check_airlight_query(const AirlightQuery &q) { detail::require_each(query_conditions(q)); }

AirlightQuery airlight_query_from_points(const double viewer_m[3], const double view_dir[3],
                                         const double light_m[3], double length_m,
                                         double sigma_s_per_m, double sigma_a_per_m,
                                         double intensity_W_per_sr) {
    double to_light[3], dir_len2 = 0.0, distance2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        to_light[k] = light_m[k] - viewer_m[k];
        distance2 += to_light[k] * to_light[k];
        dir_len2 += view_dir[k] * view_dir[k];
    }
    require(dir_len2 > 0.0, "view direction must be non-zero");
    // γ = atan2(|d × l|, d · l): accurate at both ends, unlike acos of the dot product.
    const double gamma = slut_vec3_angle(slut_vec3_make(view_dir[0], view_dir[1], view_dir[2]),
                                         slut_vec3_make(to_light[0], to_light[1], to_light[2]));
    AirlightQuery q;
    q.sigma_s_per_m = sigma_s_per_m;
    q.sigma_a_per_m = sigma_a_per_m;
    q.intensity_W_per_sr = intensity_W_per_sr;
    q.distance_m = std::sqrt(distance2);
    q.gamma_rad = gamma;
    q.length_m = length_m;
    return q;
}

double airlight_radiance_exact(const AirlightQuery &q) {
    const slut_airlight_geometry g = setup(q);
    return slut_airlight_exact(g);
}

namespace {
// sin γ and cos γ from the half angle (slut_sincos_half_angle: no libm call; cos γ as
// (cos − sin)(cos + sin) of γ/2, no cancellation near γ = π/2).
void sincos_gamma(const AirlightQuery &q, double *sin_gamma, double *cos_gamma) {
    check_airlight_query(q);
    const double half = std::fmin(0.5 * q.gamma_rad, SLUT_PIO2_HI);
    double sin_half, cos_half;
    slut_sincos_half_angle(half, &sin_half, &cos_half);
    *sin_gamma = 2.0 * sin_half * cos_half;
    *cos_gamma = SLUT_AIRLIGHT_COS_GAMMA(sin_half, cos_half);
}
} // namespace

double airlight_radiance_no_extinction(const AirlightQuery &q) {
    double sin_gamma, cos_gamma;
    sincos_gamma(q, &sin_gamma, &cos_gamma);
    return slut_airlight_no_extinction(q.sigma_s_per_m, q.intensity_W_per_sr, q.distance_m, sin_gamma, cos_gamma,
                                       q.length_m);
}

double airlight_radiance_no_extinction_attenuated(const AirlightQuery &q) {
    double sin_gamma, cos_gamma;
    sincos_gamma(q, &sin_gamma, &cos_gamma);
    return slut_airlight_no_extinction_attenuated(q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr,
                                                  q.distance_m, sin_gamma, cos_gamma, q.length_m);
}

} // namespace scatterlut
