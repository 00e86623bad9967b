#include "scatterlut/nearlight_hg.hpp"

#include "nearlight_query.hpp"
#include "require.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

extern "C" {
#include "slut_nearlight_hg.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

double phase_g_of(const Table &t) {
    require(t.kind == kKindNearLightE3Hg || t.kind == kKindNearLightE4Hg,
            "not an anisotropic near-light table (kind '" + t.kind + "')");
    return table_phase_g(t);
}

// The same values read as the isotropic kind: kind and channel name of nearlight.hpp.
Table isotropic_view(const Table &t) {
    Table v = t;
    const bool e3 = t.kind == kKindNearLightE3Hg;
    v.kind = e3 ? kKindNearLightE3 : kKindNearLightE4;
    require(!v.channels.empty() && v.channels[0].name == (e3 ? "ln_E_over_D" : "ln_E_over_D_B"),
            std::string("anisotropic near-light table channel 0 must be ") +
                (e3 ? "ln_E_over_D" : "ln_E_over_D_B"));
    v.channels[0].name = e3 ? "ln_E" : "ln_E_over_B";
    return v;
}

// Whether the table has the query's parameters (validated; *p: its T, near-light g, r, S).
bool in_table(const NearLightTable &t, const NearLightQuery &q, NearLightParams *p) {
    *p = near_light_params(q);
    return !p->light_below && p->T > 0.0 && t.covers(p->T, p->g, p->r, p->S);
}

// The parameters of the query, checked (nearlight_query.hpp: eye-side refraction as near_light_params).
slut_nl_params geometry(const NearLightQuery &q) {
    check_near_light_query(q);
    return detail::near_light_params_unchecked(q);
}

// q with one channel's coefficients (1/m).
NearLightQuery with_coefficients(NearLightQuery q, double sigma_s_per_m, double sigma_a_per_m) {
    q.sigma_s_per_m = sigma_s_per_m;
    q.sigma_a_per_m = sigma_a_per_m;
    return q;
}

} // namespace

std::string phase_g_text(double phase_g) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", phase_g);
    return text;
}

std::string near_light_hg_file_stem(bool finite_thickness, double phase_g) {
    const std::string airlight = airlight_fg_stem(phase_g); // "airlight_Fg_g<g>"
    return std::string(finite_thickness ? kKindNearLightE4Hg : kKindNearLightE3Hg) +
           airlight.substr(std::char_traits<char>::length(kKindAirlightFg));
}

double near_light_radiance_thin(const NearLightQuery &q, double phase_g) {
    check_phase_g(phase_g);
    const double iso = near_light_radiance_thin(q);
    if (phase_g == 0.0 || !(iso > 0.0) || !std::isfinite(iso)) return iso;
    const slut_nl_params p = geometry(q);
    // The ĥ⁻²-weighted mean of ψ over the path at σ_t = 0: the mean of ψ over the arc of
    // scattering angles the path sweeps (lengths in units of l: s/l), kernels/slut_nearlight_hg.h.
    return iso * slut_hg_nl_thin_psi_mean(phase_g, p.g, p.S_over_T);
}

double near_light_radiance_distant(const NearLightQuery &q, double phase_g) {
    check_phase_g(phase_g);
    const double iso = near_light_radiance_distant(q);
    if (phase_g == 0.0 || !(iso > 0.0) || !std::isfinite(iso)) return iso;
    const slut_nl_params p = geometry(q);
    // ψ at the entry point, cos θ = −ω·ω_l = −g (kernels/slut_nearlight_hg.h).
    return iso * slut_hg_nl_distant_psi(phase_g, p.g);
}

NearLightHgTable::NearLightHgTable(Table table)
    : table_(std::move(table)), phase_g_(phase_g_of(table_)), iso_(isotropic_view(table_)) {}

double NearLightHgTable::divisor(double T, double g, double S) const { return slut_hg_nl_divisor(phase_g_, T, g, S); }

double NearLightHgTable::node_E(const size_t *node) const {
    double p[4];
    iso_.node_params(node, p);
    return divisor(p[0], p[1], p[3]) * iso_.node_E(node);
}

double NearLightHgTable::E(double T, double g, double r, double S) const {
    if (!covers(T, g, r, S)) {
        const double S_over_T = (S > 1e300) ? HUGE_VAL : S / T;
        return slut_hg_nl_E(T > 0.0 ? T : 0.0, g, r, T > 0.0 ? S_over_T : HUGE_VAL, phase_g_, 1.0);
    }
    return divisor(T, g, S) * iso_.E(T, g, r, S);
}

double NearLightHgTable::radiance(const NearLightQuery &q) const {
    NearLightParams p;
    if (!in_table(iso_, q, &p)) return near_light_radiance_exact(q, phase_g_);
    // NearLightTable::radiance is linear in the stored E: E_g/D there.
    return divisor(p.T, p.g, p.S) * iso_.radiance(q);
}

Rgb NearLightHgTable::radiance_rgb(const NearLightQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m) const {
    for (int c = 0; c < 3; ++c)
        require(sigma_s_per_m[c] >= 0.0 && std::isfinite(sigma_s_per_m[c]) && sigma_a_per_m[c] >= 0.0 &&
                    std::isfinite(sigma_a_per_m[c]),
                "sigma_s and sigma_a must be finite and >= 0 (1/m) in every channel");
    return {radiance(with_coefficients(q, sigma_s_per_m[0], sigma_a_per_m[0])),
            radiance(with_coefficients(q, sigma_s_per_m[1], sigma_a_per_m[1])),
            radiance(with_coefficients(q, sigma_s_per_m[2], sigma_a_per_m[2]))};
}

void NearLightHgTable::radiance(const NearLightQuery *queries, size_t count, double *out) const {
    iso_.radiance(queries, count, out); // checks every query before writing
    for (size_t i = 0; i < count; ++i) {
        NearLightParams p;
        out[i] = in_table(iso_, queries[i], &p) ? divisor(p.T, p.g, p.S) * out[i]
                                                : near_light_radiance_exact(queries[i], phase_g_);
    }
}

} // namespace scatterlut
