#include "scatterlut/anisotropic.hpp"

#include "require.hpp"

#include <cmath>
#include <stdexcept>

extern "C" {
#include "slut_airlight_hg.h"
#include "slut_nearlight_hg.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

// The anisotropic airlight of one channel (q validated, phase_g ≠ 0).
double airlight_hg(const AirlightQuery &q, double phase_g) {
    const double half = std::fmin(0.5 * q.gamma_rad, SLUT_PIO2_HI);
    const double sin_half = std::sin(half), cos_half = std::cos(half);
    const double sigma_t = q.sigma_s_per_m + q.sigma_a_per_m;
    if (!(q.sigma_s_per_m > 0.0) || !(q.intensity_W_per_sr > 0.0) || !(q.length_m > 0.0)) return 0.0;
    if (!(sigma_t * q.distance_m < 1e300)) return 0.0;
    const double s_over_D = (q.length_m > 1e300) ? HUGE_VAL : q.length_m / q.distance_m;
    return airlight_radiance_from_bracket(
        q, sigma_t * q.distance_m,
        slut_hg_airlight_bracket(sigma_t * q.distance_m, sin_half, cos_half, s_over_D, phase_g, 1.0));
}

// The near light of one channel (q validated, phase_g ≠ 0): the parameters as
// near_light_params (eye-side refraction included), E_g by quadrature, σ_s/(4π)·I0·E_g·(T·H)/l
// assembled by slut_nl_assemble (kernels/slut_nearlight_frontend.h).
double near_light_hg(const NearLightQuery &q, double phase_g) {
    double eye_inside[3] = {q.eye_dir[0], q.eye_dir[1], q.eye_dir[2]};
    const double mu_e = q.eye_dir[0] * q.normal[0] + q.eye_dir[1] * q.normal[1] + q.eye_dir[2] * q.normal[2];
    require(mu_e > 0.0, "the viewer is below the surface (eye_dir . normal <= 0)");
    double transmittance = 1.0;
    if (q.eta != 1.0) {
        const double cos_t = slut_refract_eye_dir(q.normal, q.eye_dir, q.eta, eye_inside);
        if (q.fresnel) transmittance = slut_fresnel_transmittance(mu_e, cos_t, q.eta);
    }
    slut_nl_params p;
    slut_nl_params_from_geometry(q.normal, eye_inside, q.light_rel_m, q.sigma_s_per_m + q.sigma_a_per_m, q.length_m,
                                 &p);
    // E_g by quadrature only where slut_nl_assemble multiplies by it (light, and a finite H).
    const bool lit = p.kind == SLUT_NL_OK && q.sigma_s_per_m > 0.0 && q.intensity_W_per_sr > 0.0 && q.length_m > 0.0 &&
                     p.distance_m > 0.0 && std::isfinite(slut_nl_H_scaled(p.g, p.S_over_T));
    const double E = lit ? slut_hg_nl_E(p.T, p.g, p.r, p.S_over_T, phase_g, 1.0) : 0.0;
    return slut_nl_assemble(p, q.sigma_s_per_m, q.intensity_W_per_sr, q.length_m, transmittance, E);
}

} // namespace

void check_phase_g(double phase_g) {
    require(std::isfinite(phase_g) && std::fabs(phase_g) <= 0.999999,
            "phase_g (Henyey-Greenstein asymmetry) must be finite and within [-0.999999, 0.999999]");
}

void check_rgb_coefficients(const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m) {
    for (double s : sigma_s_per_m)
        require(s >= 0.0 && std::isfinite(s), "sigma_s must be finite and >= 0 (1/m) in every channel");
    for (double s : sigma_a_per_m)
        require(s >= 0.0 && std::isfinite(s), "sigma_a must be finite and >= 0 (1/m) in every channel");
}

double airlight_radiance_from_bracket(const AirlightQuery &q, double optical_distance, double B) {
    if (!(B > 0.0)) return 0.0;
    if (!std::isfinite(B)) return HUGE_VAL;
    const double scale =
        q.sigma_s_per_m * SLUT_INV_4PI * q.intensity_W_per_sr * 2.0 / q.distance_m * std::exp(-optical_distance);
    if (scale >= SLUT_DBL_MIN_NORMAL && scale <= 1e300) return scale * B;
    return std::exp(std::log(q.sigma_s_per_m) + std::log(SLUT_INV_4PI * 2.0) + std::log(q.intensity_W_per_sr) -
                    std::log(q.distance_m) - optical_distance + std::log(B));
}

namespace {

// The radiance of one channel with the phase: g = 0 the isotropic function's (bit for bit),
// else the query checked (the isotropic function's checks) and the anisotropic one's.
template <class Query>
double with_phase(const Query &q, double phase_g, double (*isotropic)(const Query &), void (*check)(const Query &),
                  double (*anisotropic)(const Query &, double)) {
    check_phase_g(phase_g);
    if (phase_g == 0.0) return isotropic(q);
    check(q);
    return anisotropic(q, phase_g);
}

} // namespace

double airlight_radiance_exact(const AirlightQuery &q, double phase_g) {
    return with_phase<AirlightQuery>(q, phase_g, airlight_radiance_exact, check_airlight_query, airlight_hg);
}

Rgb airlight_radiance_exact_rgb(const AirlightQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                                double phase_g) {
    return per_channel(q, sigma_s_per_m, sigma_a_per_m,
                       [phase_g](const AirlightQuery &one) { return airlight_radiance_exact(one, phase_g); });
}

double near_light_radiance_exact(const NearLightQuery &q, double phase_g) {
    return with_phase<NearLightQuery>(q, phase_g, near_light_radiance_exact, check_near_light_query, near_light_hg);
}

Rgb near_light_radiance_exact_rgb(const NearLightQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                                  double phase_g) {
    return per_channel(q, sigma_s_per_m, sigma_a_per_m,
                       [phase_g](const NearLightQuery &one) { return near_light_radiance_exact(one, phase_g); });
}

} // namespace scatterlut
