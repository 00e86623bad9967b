#include "scatterlut/airlight.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scatterlut/io.hpp"
#include "scatterlut/sampler.hpp"

extern "C" {
#include "slut_airlight.h"
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

// From the half angle h = γ/2 (clamped to π/2 against the rounding the check allows):
// w2 = π/2 − h exactly, sin h and cos h by slut_sincos_half_angle (no libm call). The far
// end's angles and attenuation are left to slut_airlight_setup_far_end.
slut_airlight_geometry setup_near_end(const AirlightQuery &q) {
    check_airlight_query(q);
    const double half = std::fmin(0.5 * q.gamma_rad, SLUT_PIO2_HI);
    double sin_half, cos_half;
    slut_sincos_half_angle(half, &sin_half, &cos_half);
    slut_airlight_geometry g;
    slut_airlight_setup_near_end(q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m, sin_half,
                                 cos_half, slut_pio2_minus(half), q.length_m, &g);
    return g;
}

slut_airlight_geometry setup(const AirlightQuery &q) {
    slut_airlight_geometry g = setup_near_end(q);
    slut_airlight_setup_far_end_and_dv(&g);
    return g;
}

} // namespace

void check_airlight_query(const AirlightQuery &q) {
    auto non_negative = [](double x) { return x >= 0.0 && !std::isnan(x); };
    require(non_negative(q.sigma_s_per_m) && std::isfinite(q.sigma_s_per_m), "sigma_s must be finite and >= 0 (1/m)");
    require(non_negative(q.sigma_a_per_m) && std::isfinite(q.sigma_a_per_m), "sigma_a must be finite and >= 0 (1/m)");
    require(non_negative(q.intensity_W_per_sr) && std::isfinite(q.intensity_W_per_sr), "intensity must be finite and >= 0 (W/sr)");
    require(q.distance_m > 0.0 && std::isfinite(q.distance_m), "distance must be finite and > 0 (m)");
    require(q.gamma_rad >= 0.0 && q.gamma_rad <= 3.14159265358979323846 + 1e-15,
            "gamma must lie in [0, pi] (rad)");
    require(non_negative(q.length_m), "length must be >= 0 (m; inf allowed)");
}

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
    const double cross[3] = {view_dir[1] * to_light[2] - view_dir[2] * to_light[1],
                             view_dir[2] * to_light[0] - view_dir[0] * to_light[2],
                             view_dir[0] * to_light[1] - view_dir[1] * to_light[0]};
    const double sin_part = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
    const double cos_part = view_dir[0] * to_light[0] + view_dir[1] * to_light[1] + view_dir[2] * to_light[2];
    AirlightQuery q;
    q.sigma_s_per_m = sigma_s_per_m;
    q.sigma_a_per_m = sigma_a_per_m;
    q.intensity_W_per_sr = intensity_W_per_sr;
    q.distance_m = std::sqrt(distance2);
    q.gamma_rad = std::atan2(sin_part, cos_part);
    q.length_m = length_m;
    return q;
}

double airlight_radiance_exact(const AirlightQuery &q) {
    const slut_airlight_geometry g = setup(q);
    return slut_airlight_exact(&g);
}

AirlightTable::AirlightTable(Table table) : table_(std::move(table)) {
    require(table_.kind == kKindAirlightF, "not an airlight F table (kind '" + table_.kind + "')");
    require(table_.quantity_version == kAirlightFQuantityVersion,
            "airlight table quantity version " + std::to_string(table_.quantity_version) +
                " is not the one this library knows (" + std::to_string(kAirlightFQuantityVersion) + ")");
    require(table_.axes.size() == 2 && table_.axes[0].name == "u" && table_.axes[1].name == "w",
            "airlight table must have axes (u, w)");
    require(!table_.channels.empty() && table_.channels[0].name == "ln_Gs" &&
                table_.channels[0].encoding == Encoding::Log,
            "airlight table channel 0 must be ln_Gs (log encoded)");
    table_.check_consistent();
    require(table_.axes[0].map.min == 0.0, "airlight table u axis must start at 0");
    require(std::fabs(table_.axes[1].map.max - 1.5707963267948966) < 1e-12,
            "airlight table w axis must end at pi/2");
    // G̃ ∈ (0, 1]: a stored ln G̃ above 0 (beyond rounding) or below −1e6 is no airlight value.
    const size_t stride = table_.channels.size();
    for (size_t i = 0; i < table_.values.size(); i += stride)
        require(table_.values[i] >= kMinStoredLn && table_.values[i] <= kLnRoundingSlack,
                "airlight table: ln G~ = " + std::to_string(table_.values[i]) + " at " +
                    detail::describe_value(table_, i) +
                    " is outside the quantity's range (G~ in (0, 1]: ln G~ <= 0): the file is corrupt");
    cache_ = make_sampler_cache(table_);
    values32_ = float_values_if_exact(table_);
    u_max_ = table_.axes[0].map.max;
    w_min_ = table_.axes[1].map.min;
}

// The table regime from (u, w, a = u·cot w): for u > 0 the w axis's ASINH_COT warp is
// −asinh(a/u), which skips the cos, sin and log of the warp in w (u = 0 has no cot w in a).
// unit_u is u's unit coordinate (one per u: the radiance's two ends share it).
double AirlightTable::scaled_tail_at(double unit_u, double u, double w, double a) const {
    switch (slut_gs_regime(u, w, u_max_, w_min_)) {
    case SLUT_GS_LARGE_U: return slut_gs_large_u(u, w);
    case SLUT_GS_SMALL_W: return slut_gs_small_w(w, a);
    default: {
        const slut_axis &axis_w = table_.axes[1].map;
        const double unit[2] = {
            unit_u, u > 0.0 ? (slut_warp_asinh_cot_from_cot(a / u) - cache_.g0[1]) / (cache_.g1[1] - cache_.g0[1])
                            : slut_unit_from_warped_runtime(&axis_w, w, cache_.g0[1], cache_.g1[1])};
        return std::exp(sample_encoded_at_unit(table_, values32_, unit, 0));
    }
    }
}

double AirlightTable::unit_u(double u) const {
    return slut_unit_from_warped_runtime(&table_.axes[0].map, u, cache_.g0[0], cache_.g1[0]);
}

double AirlightTable::scaled_tail(double u, double w, double a) const { return scaled_tail_at(unit_u(u), u, w, a); }

// a = u·cot w is needed only below w_min (slut_gs_small_w): computed there alone.
double AirlightTable::scaled_tail(double u, double w) const {
    if (slut_gs_regime(u, w, u_max_, w_min_) == SLUT_GS_TABLE) {
        const double params[2] = {u, w};
        return sample(table_, cache_, params, 0);
    }
    return scaled_tail(u, w, u * std::cos(w) / std::sin(w));
}

double AirlightTable::tail(double u, double v) const {
    const double w = slut_pio2_minus(v);
    if (w <= 0.0) return 0.0;
    const double tan_v = slut_tan_v(v, w);
    return std::exp(-u * tan_v) * w * scaled_tail(u, w, u * tan_v);
}

// F = G(u, 0) − G(u, v) where that keeps the table's relative accuracy, the direct
// integral where it would cancel (slut_F_from_tails).
double AirlightTable::F(double u, double v) const {
    if (!(v > 0.0)) return 0.0;
    const double whole = 1.5707963267948966 * scaled_tail(u, 1.5707963267948966, 0.0);
    return std::fmax(slut_F_from_tails(u, v, whole, tail(u, v)), 0.0);
}

// A segment short enough for one panel takes the θ-integral directly (6 exps, more
// accurate than the table and cheaper than two lookups); the others the two table samples
// (slut_airlight_from_gs, which still integrates where they would cancel).
double AirlightTable::radiance(const AirlightQuery &q) const {
    slut_airlight_geometry g = setup_near_end(q);
    if (g.kind != 0) return slut_airlight_from_gs(&g, 0.0, 0.0);
    if (slut_airlight_theta_fits_one_panel(&g))
        return slut_airlight_scaled(
            &g, slut_airlight_theta_integral_one_panel(g.c, g.cos_half, g.sin_half, g.tan_dv) / g.sin_gamma);
    slut_airlight_setup_far_end(&g);
    const double at_u = unit_u(g.u);
    const double gs2 = scaled_tail_at(at_u, g.u, g.w2, g.a2);
    const double gs1 = g.w1 > 0.0 ? scaled_tail_at(at_u, g.u, g.w1, g.a1) : 0.0;
    return slut_airlight_from_gs(&g, gs2, gs1);
}

} // namespace scatterlut
