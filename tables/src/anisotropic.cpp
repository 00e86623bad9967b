#include "scatterlut/anisotropic.hpp"

#include "nearlight_query.hpp"
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

// The anisotropic airlight of one channel (q validated, phase_g ≠ 0): the kernel's
// (slut_hg_airlight_radiance_half) with the half angle taken from γ/2 itself.
double airlight_hg(const AirlightQuery &q, double phase_g) {
    const double half = std::fmin(0.5 * q.gamma_rad, SLUT_PIO2_HI);
    return slut_hg_airlight_radiance_half(q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m,
                                          std::sin(half), std::cos(half), q.length_m, phase_g, 1.0);
}

// The near light of one channel (q validated, phase_g ≠ 0): the parameters and the exit's
// Fresnel factor as the isotropic near light's (nearlight_query.hpp: eye-side refraction
// included), E_g by quadrature, σ_s/(4π)·I0·E_g·(T·H)/l assembled by slut_nl_assemble
// (kernels/slut_nearlight_frontend.h).
double near_light_hg(const NearLightQuery &q, double phase_g) {
    const slut_nl_params p = detail::near_light_params_unchecked(q);
    // E_g by quadrature only where slut_nl_assemble multiplies by it (light, and a finite H).
    const bool lit = p.kind == SLUT_NL_OK && q.sigma_s_per_m > 0.0 && q.intensity_W_per_sr > 0.0 && q.length_m > 0.0 &&
                     p.distance_m > 0.0 && std::isfinite(slut_nl_H_scaled(p.g, p.S_over_T));
    const double E = lit ? slut_hg_nl_E(p.T, p.g, p.r, p.S_over_T, phase_g, 1.0) : 0.0;
    return slut_nl_assemble(p, q.sigma_s_per_m, q.intensity_W_per_sr, q.length_m,
                            detail::near_light_exit_transmittance(q), E);
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
    return slut_hg_airlight_from_bracket_at(q.sigma_s_per_m, q.intensity_W_per_sr, q.distance_m, optical_distance, B);
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
