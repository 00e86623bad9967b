#include "scatterlut/nearlight.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scatterlut/io.hpp"
#include "scatterlut/sampler.hpp"

extern "C" {
#include "slut_nearlight.h"
}

namespace scatterlut {
namespace {

void require(bool ok, const std::string &message) {
    if (!ok) throw std::invalid_argument(message);
}
// Literal messages: no std::string built on the hot path (radiance checks every query).
void require(bool ok, const char *message) {
    if (!ok) throw std::invalid_argument(message);
}

bool unit_vector(const double *v) {
    const double n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    return std::fabs(n2 - 1.0) < 1e-9;
}

slut_nl_params params(const NearLightQuery &q) {
    check_near_light_query(q);
    double eye_inside[3] = {q.eye_dir[0], q.eye_dir[1], q.eye_dir[2]};
    const double mu_e = q.eye_dir[0] * q.normal[0] + q.eye_dir[1] * q.normal[1] + q.eye_dir[2] * q.normal[2];
    require(mu_e > 0.0, "the viewer is below the surface (eye_dir . normal <= 0)");
    if (q.eta != 1.0) slut_refract_eye_dir(q.normal, q.eye_dir, q.eta, eye_inside);
    slut_nl_params p;
    slut_nl_params_from_geometry(q.normal, eye_inside, q.light_rel_m, q.sigma_s_per_m + q.sigma_a_per_m,
                                 q.length_m, &p);
    if (p.kind == SLUT_NL_VIEWER_BELOW) p.kind = SLUT_NL_LIGHT_BELOW; // refracted to grazing: no light out
    return p;
}

// The Fresnel factor of the exit, 1 without refraction or without `fresnel`.
double exit_transmittance(const NearLightQuery &q) {
    if (!q.fresnel || q.eta == 1.0) return 1.0;
    double inside[3];
    const double cos_i = q.eye_dir[0] * q.normal[0] + q.eye_dir[1] * q.normal[1] + q.eye_dir[2] * q.normal[2];
    const double cos_t = slut_refract_eye_dir(q.normal, q.eye_dir, q.eta, inside);
    return slut_fresnel_transmittance(cos_i, cos_t, q.eta);
}

// σ_s/(4π)·I0·E·(T·H)/l, the form finite as σ_t → 0; +inf where H diverges.
double assemble(const NearLightQuery &q, const slut_nl_params &p, double E) {
    if (p.kind == SLUT_NL_LIGHT_BELOW || !(q.sigma_s_per_m > 0.0) || !(q.intensity_W_per_sr > 0.0) ||
        !(q.length_m > 0.0))
        return 0.0;
    if (!(p.distance_m > 0.0)) return HUGE_VAL;
    const double H_scaled = slut_nl_H_scaled(p.g, p.S_over_T);
    if (!std::isfinite(H_scaled)) return HUGE_VAL;
    return exit_transmittance(q) * q.sigma_s_per_m * SLUT_INV_4PI * q.intensity_W_per_sr * E * H_scaled / p.distance_m;
}

} // namespace

void check_near_light_query(const NearLightQuery &q) {
    require(q.sigma_s_per_m >= 0.0 && std::isfinite(q.sigma_s_per_m), "sigma_s must be finite and >= 0 (1/m)");
    require(q.sigma_a_per_m >= 0.0 && std::isfinite(q.sigma_a_per_m), "sigma_a must be finite and >= 0 (1/m)");
    require(q.intensity_W_per_sr >= 0.0 && std::isfinite(q.intensity_W_per_sr), "intensity must be finite and >= 0 (W/sr)");
    require(q.length_m >= 0.0, "length must be >= 0 (m; inf for a thick medium)");
    require(unit_vector(q.normal), "normal must be a unit vector");
    require(unit_vector(q.eye_dir), "eye_dir must be a unit vector");
    require(q.eta > 0.0 && std::isfinite(q.eta), "eta (relative index of refraction) must be finite and > 0");
    for (int k = 0; k < 3; ++k) require(std::isfinite(q.light_rel_m[k]), "light_pos must be finite");
}

NearLightParams near_light_params(const NearLightQuery &q) {
    const slut_nl_params p = params(q);
    NearLightParams out;
    out.light_below = p.kind != SLUT_NL_OK;
    out.T = p.T;
    out.g = p.g;
    out.r = p.r;
    out.S = p.S;
    return out;
}

double near_light_radiance_exact(const NearLightQuery &q) {
    const slut_nl_params p = params(q);
    return assemble(q, p, p.T > 0.0 ? slut_nl_E(p.T, p.g, p.r, p.S) : 1.0);
}

double near_light_radiance_thin(const NearLightQuery &q) {
    const slut_nl_params p = params(q);
    return assemble(q, p, slut_nl_E_thin(p.r, p.S));
}

double near_light_radiance_distant(const NearLightQuery &q) {
    const slut_nl_params p = params(q);
    if (p.kind != SLUT_NL_OK || !(p.distance_m > 0.0)) return 0.0;
    const double irradiance = q.intensity_W_per_sr / (p.distance_m * p.distance_m); // W/m² at normal incidence
    return exit_transmittance(q) *
           slut_distant_light_radiance(q.sigma_s_per_m, q.sigma_a_per_m, irradiance, p.mu_e, p.mu_l, q.length_m);
}

NearLightTable::NearLightTable(Table table) : table_(std::move(table)) {
    const bool e3 = table_.kind == kKindNearLightE3, e4 = table_.kind == kKindNearLightE4;
    require(e3 || e4, "not a near-light table (kind '" + table_.kind + "')");
    require(table_.quantity_version == kNearLightEQuantityVersion,
            "near-light table quantity version " + std::to_string(table_.quantity_version) + " is not the one (" +
                std::to_string(kNearLightEQuantityVersion) + ") this library knows: regenerate the table");
    require(table_.axes.size() == (e3 ? 3u : 4u), "near-light table has the wrong number of axes");
    require(table_.axes[0].name == "T" && table_.axes[1].name == "g" && table_.axes[2].name == "r" &&
                (e3 || table_.axes[3].name == "q"),
            "near-light table axes must be (T, g, r) or (T, g, r, q)");
    for (size_t a = 0; a < 3; ++a)
        require(table_.axes[a].map.warp != SLUT_WARP_NL_QODDS, "near-light axis " + table_.axes[a].name +
                                                                   " cannot use the slab warp 'nl_qodds'");
    require(e3 || table_.axes[3].map.warp == SLUT_WARP_NL_QODDS, "near-light axis q must use the warp 'nl_qodds'");
    const char *channel = e3 ? "ln_E" : "ln_E_over_B";
    require(!table_.channels.empty() && table_.channels[0].name == channel &&
                table_.channels[0].encoding == Encoding::Log,
            std::string("near-light table channel 0 must be ") + channel + " (log encoded)");
    table_.check_consistent();
    // E ∈ (0, 1] (an attenuation mean): ln E ≤ 0 for E3; E4 stores ln(E/B) with
    // B ≥ e^{−T} (slut_nl_E_base), so ln(E/B) ≤ T at the node's T. Beyond rounding, or
    // below −1e6, a value is no near-light value.
    const size_t stride = table_.channels.size(), n_T = static_cast<size_t>(table_.axes[0].map.count);
    for (size_t i = 0; i < table_.values.size(); i += stride) {
        const double T = slut_axis_node(&table_.axes[0].map, static_cast<int>((i / stride) % n_T));
        const double hi = (e3 ? 0.0 : T) + kLnRoundingSlack;
        require(table_.values[i] >= kMinStoredLn && table_.values[i] <= hi,
                std::string("near-light table: ") + channel + " = " + std::to_string(table_.values[i]) + " at " +
                    detail::describe_value(table_, i) + " is outside the quantity's range (E in (0, 1]: " +
                    (e3 ? "ln E <= 0" : "ln(E/B) <= T") + "): the file is corrupt");
    }
    cache_ = make_sampler_cache(table_);
    values32_ = float_values_if_exact(table_);
}

bool NearLightTable::covers(double T, double g, double r, double S) const {
    auto inside = [](const Axis &a, double p) { return p >= a.map.min && p <= a.map.max; };
    if (!inside(table_.axes[0], T) || !inside(table_.axes[1], g) || !inside(table_.axes[2], r)) return false;
    if (thick_only()) return !std::isfinite(S);
    return std::isfinite(S) && inside(table_.axes[3], S);
}

double NearLightTable::E(double T, double g, double r, double S) const {
    if (!covers(T, g, r, S)) return T > 0.0 ? slut_nl_E(T, g, r, S) : 1.0;
    double unit[4];
    const double p[3] = {T, g, r};
    for (size_t a = 0; a < 3; ++a) unit[a] = slut_unit_from_warped_runtime(&table_.axes[a].map, p[a], cache_.g0[a], cache_.g1[a]);
    if (thick_only()) return std::exp(sample_encoded_at_unit(table_, values32_, unit, 0));
    unit[3] = slut_nl_unit_from_S(&table_.axes[3].map, T, g, S);
    return std::exp(sample_encoded_at_unit(table_, values32_, unit, 0)) * slut_nl_E_base(T, r, S);
}

void NearLightTable::node_params(const size_t *node, double *params) const {
    for (size_t a = 0; a < 3; ++a) params[a] = slut_axis_node(&table_.axes[a].map, static_cast<int>(node[a]));
    params[3] = thick_only() ? HUGE_VAL
                             : slut_nl_S_node(&table_.axes[3].map, params[0], params[1], static_cast<int>(node[3]));
}

double NearLightTable::node_E(const size_t *node) const {
    double p[4];
    node_params(node, p);
    const double stored = std::exp(table_.values[table_.index(node)]);
    return thick_only() ? stored : stored * slut_nl_E_base(p[0], p[2], p[3]);
}

double NearLightTable::radiance(const NearLightQuery &q) const {
    const slut_nl_params p = params(q);
    if (p.kind != SLUT_NL_OK) return 0.0;
    return assemble(q, p, p.T > 0.0 ? E(p.T, p.g, p.r, p.S) : 1.0);
}

} // namespace scatterlut
