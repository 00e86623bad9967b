#include "scatterlut/airlight.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scatterlut/sampler.hpp"
#include "simd4.hpp"

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
// end's angles and attenuation are left to slut_airlight_setup_far_end, and g.scale's
// e^{−σ_t D} to the caller (slut_airlight_setup_near_end_unscaled).
slut_airlight_geometry setup_near_end_unscaled(const AirlightQuery &q) {
    check_airlight_query(q);
    const double half = 0.5 * q.gamma_rad < SLUT_PIO2_HI ? 0.5 * q.gamma_rad : SLUT_PIO2_HI;
    double sin_half, cos_half;
    slut_sincos_half_angle(half, &sin_half, &cos_half);
    slut_airlight_geometry g;
    slut_airlight_setup_near_end_unscaled(q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m,
                                          sin_half, cos_half, slut_pio2_minus(half), q.length_m, &g);
    return g;
}

void set_scale(slut_airlight_geometry *g) {
    if (g->kind == 0) g->scale = g->scale_unattenuated * std::exp(-g->optical_distance);
}

slut_airlight_geometry setup_near_end(const AirlightQuery &q) {
    slut_airlight_geometry g = setup_near_end_unscaled(q);
    set_scale(&g);
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

namespace {
// sin γ and cos γ from the half angle (slut_sincos_half_angle: no libm call; cos γ as
// (cos − sin)(cos + sin) of γ/2, no cancellation near γ = π/2).
void sincos_gamma(const AirlightQuery &q, double *sin_gamma, double *cos_gamma) {
    check_airlight_query(q);
    const double half = std::fmin(0.5 * q.gamma_rad, SLUT_PIO2_HI);
    double sin_half, cos_half;
    slut_sincos_half_angle(half, &sin_half, &cos_half);
    *sin_gamma = 2.0 * sin_half * cos_half;
    *cos_gamma = (cos_half - sin_half) * (cos_half + sin_half);
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
    cache_ = make_sampler_cache(table_);
    values32_ = float_values_if_exact(table_);
    u_max_ = table_.axes[0].map.max;
    w_min_ = table_.axes[1].map.min;
    count_u_ = table_.axes[0].map.count;
    count_w_ = table_.axes[1].map.count;
    channels_ = table_.channels.size();
    fast_lookup_ = !values32_.empty() && table_.axes[0].map.warp == SLUT_WARP_LOG1P &&
                   table_.axes[1].map.warp == SLUT_WARP_ASINH_COT;
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

double AirlightTable::F(double u, double v) const {
    if (v <= 0.0) return 0.0;
    const double whole = 1.5707963267948966 * scaled_tail(u, 1.5707963267948966, 0.0);
    return std::fmax(whole - tail(u, v), 0.0);
}

// A segment short enough for one panel takes the θ-integral directly (6 exps, more
// accurate than the table and cheaper than two lookups); the others the two table samples
// (slut_airlight_from_gs, which still integrates where they would cancel).
double AirlightTable::radiance(const AirlightQuery &q) const {
    const slut_airlight_geometry g = setup_near_end_unscaled(q);
    if (g.kind != 0) return slut_airlight_from_gs(&g, 0.0, 0.0);
    if (slut_airlight_theta_fits_one_panel(&g)) return one_panel_radiance(g);
    return two_sample_radiance(g);
}

#if SLUT_HAVE_SIMD4
namespace {
using simd4::v4d;

// slut_airlight_theta_integral_one_panel's six nodes as two 4-lane vectors (the last two
// lanes weight 0), e^{−σ_t D} folded into the node exponentials: the same sum in 2 vector
// exps instead of 7 scalar ones and a third of the divides.
SLUT_SIMD4_TARGET double one_panel_radiance4(const slut_airlight_geometry &g) {
    const v4d x0 = {-slut_gl6_x[0], -slut_gl6_x[1], -slut_gl6_x[2], slut_gl6_x[0]};
    const v4d x1 = {slut_gl6_x[1], slut_gl6_x[2], 0.0, 0.0};
    const v4d w0 = {slut_gl6_w[0], slut_gl6_w[1], slut_gl6_w[2], slut_gl6_w[0]};
    const v4d w1 = {slut_gl6_w[1], slut_gl6_w[2], 0.0, 0.0};
    const double half_len = 0.5 * g.tan_dv;
    const v4d t0 = half_len * (1.0 + x0), t1 = half_len * (1.0 + x1);
    const v4d e0 = -g.c * t0 / (g.cos_half - t0 * g.sin_half) - g.optical_distance;
    const v4d e1 = -g.c * t1 / (g.cos_half - t1 * g.sin_half) - g.optical_distance;
    const v4d f = w0 / (1.0 + t0 * t0) * simd4::exp4(e0) + w1 / (1.0 + t1 * t1) * simd4::exp4(e1);
    return g.scale_unattenuated * (half_len * ((f[0] + f[1]) + (f[2] + f[3])) / g.sin_gamma);
}
} // namespace
#endif

double AirlightTable::one_panel_radiance(const slut_airlight_geometry &g) const {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return one_panel_radiance4(g);
#endif
    return g.scale_unattenuated * std::exp(-g.optical_distance) *
           (slut_airlight_theta_integral_one_panel(g.c, g.cos_half, g.sin_half, g.tan_dv) / g.sin_gamma);
}

namespace {
#if SLUT_HAVE_SIMD4
SLUT_SIMD4_TARGET void logs3_simd(double a, double b, double c, double *la, double *lb, double *lc) {
    const v4d l = simd4::log4(v4d{a, b, c, 1.0});
    *la = l[0];
    *lb = l[1];
    *lc = l[2];
}
SLUT_SIMD4_TARGET void exps2_simd(double a, double b, double *ea, double *eb) {
    const v4d e = simd4::exp4(v4d{a, b, 0.0, 0.0});
    *ea = e[0];
    *eb = e[1];
}
#endif

void logs3(double a, double b, double c, double *la, double *lb, double *lc) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return logs3_simd(a, b, c, la, lb, lc);
#endif
    *la = std::log(a);
    *lb = std::log(b);
    *lc = std::log(c);
}

void exps2(double a, double b, double *ea, double *eb) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return exps2_simd(a, b, ea, eb);
#endif
    *ea = std::exp(a);
    *eb = std::exp(b);
}
} // namespace

// ln G̃ at unit coordinates from the float copy: sample_encoded_at_unit's 2-D case (the
// same lerps in the same order: identical values) with the u cell given.
double AirlightTable::ln_gs_at(int cell_u, double frac_u, double unit_w) const {
    int cell_w;
    double frac_w;
    slut_cell_from_unit(unit_w, count_w_, &cell_w, &frac_w);
    const float *v = values32_.data() + (static_cast<size_t>(cell_w) * static_cast<size_t>(count_u_) +
                                         static_cast<size_t>(cell_u)) * channels_;
    const size_t row = static_cast<size_t>(count_u_) * channels_;
    auto lerp = [](double lower, double upper, double f) {
        return f == 0.0 ? lower : f == 1.0 ? upper : lower + f * (upper - lower);
    };
    const double lower = lerp(v[0], v[row], frac_w), upper = lerp(v[channels_], v[row + channels_], frac_w);
    return lerp(lower, upper, frac_u);
}

// Both ends from the table (slut_airlight_from_gs's sum, its cancellation test and its
// fallback) with fewer transcendentals: the u warp (LOG1P, Goldberg's form) and the two w
// warps (−ln(a/u + √(1 + (a/u)²))) as one 4-lane log, the decoding exps with e^{−σ_t D} and
// e^{−σ_t Δ} folded in (one 4-lane exp instead of four exps). Where an end leaves the
// table (u > u_max, w1 < w_min: the asymptotic forms), for an infinite ray, f64 storage or
// another u warp: the general path.
double AirlightTable::two_sample_radiance(const slut_airlight_geometry &geometry) const {
    slut_airlight_geometry g = geometry;
    const double w1 = SLUT_ISFINITE(g.optical_delta) ? std::atan(g.tan_w1) : 0.0;
    if (!fast_lookup_ || !SLUT_ISFINITE(g.optical_delta) || !(w1 >= w_min_) || !(g.u > 0.0) || g.u > u_max_) {
        set_scale(&g);
        slut_airlight_setup_far_end(&g);
        const double at_u = unit_u(g.u);
        const double gs2 = scaled_tail_at(at_u, g.u, g.w2, g.a2);
        const double gs1 = g.w1 > 0.0 ? scaled_tail_at(at_u, g.u, g.w1, g.a1) : 0.0;
        return slut_airlight_from_gs(&g, gs2, gs1);
    }
    const slut_axis &axis_u = table_.axes[0].map;
    const double x_u = (g.u - axis_u.min) / axis_u.scale, one_plus_x_u = 1.0 + x_u;
    const double cot2 = g.a2 / g.u, cot1 = g.a1 / g.u;
    const double arg2 = cot2 + std::sqrt(1.0 + cot2 * cot2), arg1 = cot1 + std::sqrt(1.0 + cot1 * cot1);
    double log_u, log2, log1;
    logs3(one_plus_x_u, arg2, arg1, &log_u, &log2, &log1);
    double unit_u;
    if (!(g.u > axis_u.min)) unit_u = 0.0;
    else if (g.u >= axis_u.max) unit_u = 1.0;
    else unit_u = ((one_plus_x_u == 1.0 ? x_u : log_u * (x_u / (one_plus_x_u - 1.0))) - cache_.g0[0]) /
                  (cache_.g1[0] - cache_.g0[0]);
    int cell_u;
    double frac_u;
    slut_cell_from_unit(unit_u, count_u_, &cell_u, &frac_u);
    const double span_w = cache_.g1[1] - cache_.g0[1];
    const double ln2 = ln_gs_at(cell_u, frac_u, (-log2 - cache_.g0[1]) / span_w);
    const double ln1 = ln_gs_at(cell_u, frac_u, (-log1 - cache_.g0[1]) / span_w);
    double e2, e1;
    exps2(ln2 - g.optical_distance, ln1 - g.optical_distance - g.optical_delta, &e2, &e1);
    const double viewer_term = (g.w2 / g.sin_gamma) * e2, far_term = (w1 / g.sin_gamma) * e1;
    if (far_term <= 0.5 * viewer_term) return g.scale_unattenuated * (viewer_term - far_term);
    set_scale(&g);
    return g.scale * (slut_airlight_theta_integral_rule(g.c, g.w2, slut_airlight_dv(&g), 0) / g.sin_gamma);
}

} // namespace scatterlut
