#include "scatterlut/airlight_hg.hpp"

#include "airlight_layout.hpp"
#include "require.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "scatterlut/io.hpp"

extern "C" {
#include "slut_airlight_hg.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

} // namespace

std::string airlight_fg_stem(double phase_g) {
    char text[40];
    for (int digits = 1; digits <= 17; ++digits) { // the shortest text that reads back as g
        std::snprintf(text, sizeof text, "%.*g", digits, phase_g);
        if (std::strtod(text, nullptr) == phase_g) break;
    }
    return std::string(kKindAirlightFg) + "_g" + text;
}

double table_phase_g(const Table &table) {
    const auto it = table.extra.find(kPhaseGKey);
    require(it != table.extra.end(), "table of kind '" + table.kind + "' records no \"" + kPhaseGKey + "\"");
    char *end = nullptr;
    const double g = std::strtod(it->second.c_str(), &end);
    require(end != it->second.c_str() && *end == '\0',
            std::string("\"") + kPhaseGKey + "\" = '" + it->second + "' is not a number");
    check_phase_g(g);
    return g;
}

AirlightHgTable::AirlightHgTable(Table table) : table_(std::move(table)) {
    detail::check_airlight_layout(table_, kKindAirlightFg, kAirlightFgQuantityVersion, "ln_Gs_g",
                                  "anisotropic airlight table", "an anisotropic airlight table");
    g_ = table_phase_g(table_);
    require(g_ != 0.0, "anisotropic airlight table with phase.g = 0: the isotropic table (airlight_F) serves g = 0");
    detail::check_airlight_domain(table_, "anisotropic airlight table");
    // G̃_g ∈ (0, ψ_max(g)]: ln G̃_g ≤ ln ψ_max (beyond rounding) and above −1e6.
    const double ln_max = std::log(slut_hg_psi_max(g_));
    const size_t stride = table_.channels.size();
    for (size_t i = 0; i < table_.values.size(); i += stride)
        if (!(table_.values[i] >= kMinStoredLn && table_.values[i] <= ln_max + kLnRoundingSlack)) // the message only when it fails
            throw std::invalid_argument("anisotropic airlight table: ln G~_g = " + std::to_string(table_.values[i]) +
                                        " at " + detail::describe_value(table_, i) +
                                        " is outside the quantity's range (ln G~_g <= ln psi_max = " +
                                        std::to_string(ln_max) + "): the file is corrupt");
    cache_ = make_sampler_cache(table_);
    u_max_ = table_.axes[0].map.max;
    w_min_ = table_.axes[1].map.min;
}

double AirlightHgTable::scaled_tail(double u, double w) const {
    if (w < w_min_) return slut_hg_gs_small_w(w, u * (std::cos(w) / std::sin(w)), g_);
    if (u > u_max_) return slut_hg_gs_beyond_u_max(u, w, g_);
    const double params[2] = {u, w};
    return sample(table_, cache_, params, 0);
}

double AirlightHgTable::radiance(const AirlightQuery &q) const {
    // The isotropic runtime's front-end (the query checked; u, w2, w1, e^{−σ_t Δ} without
    // cancellation, slut_airlight.h): only G̃_g and the fallback integral are the phase's.
    const slut_airlight_geometry geo = slut_airlight_setup_far_end(detail::airlight_query_near_end(q));
    if (geo.kind == 1) return 0.0;      // no scattering, no light or no ray; or σ_t D beyond the double range
    if (geo.kind == 2) return HUGE_VAL; // the ray passes through the light
    const double s_over_D = SLUT_ISFINITE(q.length_m) ? q.length_m / q.distance_m : HUGE_VAL;
    // The bracket B_g (slut_hg_airlight_bracket's) from two table samples where that is sound:
    // w2 G̃_g(u, w2) − e^{−σ_t Δ} w1 G̃_g(u, w1) over sin γ, where the second term is at most half the first.
    double B = -1.0;
    if (geo.sin_gamma >= 1e-6) {
        const double a = geo.w2 * scaled_tail(geo.u, geo.w2);
        const double b = geo.w1 > 0.0 ? geo.far_attenuation * geo.w1 * scaled_tail(geo.u, geo.w1) : 0.0;
        if (std::isfinite(a) && std::isfinite(b) && b <= 0.5 * a && a > 0.0) B = (a - b) / geo.sin_gamma;
    }
    if (B < 0.0) B = slut_hg_airlight_bracket(geo.optical_distance, geo.sin_half, geo.cos_half, s_over_D, g_, 1.0);
    return airlight_radiance_from_bracket(q, geo.optical_distance, B);
}

Rgb AirlightHgTable::radiance_rgb(const AirlightQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m) const {
    return per_channel(q, sigma_s_per_m, sigma_a_per_m, [this](const AirlightQuery &one) { return radiance(one); });
}

double airlight_hg_radiance_thin(const AirlightQuery &q, double phase_g) {
    check_phase_g(phase_g);
    check_airlight_query(q);
    // kernels/slut_airlight_hg.h: the isotropic bracket at σ_t = 0 times the phase's mean over the arc.
    return slut_hg_airlight_radiance_thin(q.sigma_s_per_m, q.intensity_W_per_sr, q.distance_m, std::sin(q.gamma_rad),
                                          std::cos(q.gamma_rad), q.length_m, phase_g);
}

double airlight_hg_radiance_distant(const AirlightQuery &q, double phase_g) {
    check_phase_g(phase_g);
    check_airlight_query(q);
    return slut_hg_airlight_radiance_distant(q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m,
                                             std::sin(q.gamma_rad), std::cos(q.gamma_rad), q.length_m, phase_g);
}

} // namespace scatterlut
