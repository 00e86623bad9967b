#include "scatterlut/airlight.hpp"

#include "airlight_layout.hpp"
#include "require.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "scatterlut/io.hpp"
#include "scatterlut/sampler.hpp"
#include "simd4.hpp"

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

namespace {
// check_airlight_query's conditions: each field of AirlightQuery in a closed range [lo, hi]
// (x > 0 as x ≥ the least subnormal; NaN is in none), with the message its check throws.
// Written once as ranges so that the batch can check its queries' fields as one flat array of
// doubles (check_airlight_queries); query_conditions states them as require.hpp's Conditions.
struct FieldRange {
    double lo, hi;
    const char *message;
};
constexpr double kLargest = std::numeric_limits<double>::max();
constexpr FieldRange kQueryRanges[6] = {
    {0.0, kLargest, "sigma_s must be finite and >= 0 (1/m)"},
    {0.0, kLargest, "sigma_a must be finite and >= 0 (1/m)"},
    {0.0, kLargest, "intensity must be finite and >= 0 (W/sr)"},
    {std::numeric_limits<double>::denorm_min(), kLargest, "distance must be finite and > 0 (m)"},
    {0.0, 3.14159265358979323846 + 1e-15, "gamma must lie in [0, pi] (rad)"},
    {0.0, std::numeric_limits<double>::infinity(), "length must be >= 0 (m; inf allowed)"}};
// The fields in kQueryRanges' order, as the six consecutive doubles of the struct.
static_assert(sizeof(AirlightQuery) == 6 * sizeof(double) && std::is_standard_layout_v<AirlightQuery>);
static_assert(offsetof(AirlightQuery, sigma_s_per_m) == 0 && offsetof(AirlightQuery, sigma_a_per_m) == 8 &&
              offsetof(AirlightQuery, intensity_W_per_sr) == 16 && offsetof(AirlightQuery, distance_m) == 24 &&
              offsetof(AirlightQuery, gamma_rad) == 32 && offsetof(AirlightQuery, length_m) == 40);

inline detail::Condition in_range(double x, const FieldRange &range) {
    const bool holds = (x >= range.lo) & (x <= range.hi); // NaN: false
    return {holds, range.message};
}
inline std::array<detail::Condition, 6> query_conditions(const AirlightQuery &q) {
    return {in_range(q.sigma_s_per_m, kQueryRanges[0]), in_range(q.sigma_a_per_m, kQueryRanges[1]),
            in_range(q.intensity_W_per_sr, kQueryRanges[2]), in_range(q.distance_m, kQueryRanges[3]),
            in_range(q.gamma_rad, kQueryRanges[4]), in_range(q.length_m, kQueryRanges[5])};
}
} // namespace

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

AirlightTable::AirlightTable(Table table) : table_(std::move(table)) {
    detail::check_airlight_layout(table_, kKindAirlightF, kAirlightFQuantityVersion, "ln_Gs", "airlight table",
                                  "an airlight F table");
    detail::check_airlight_domain(table_, "airlight table");
    // G̃ ∈ (0, 1]: a stored ln G̃ above 0 (beyond rounding) or below −1e6 is no airlight value.
    const size_t stride = table_.channels.size();
    for (size_t i = 0; i < table_.values.size(); i += stride)
        if (!(table_.values[i] >= kMinStoredLn && table_.values[i] <= kLnRoundingSlack)) // the message only when it fails
            throw std::invalid_argument("airlight table: ln G~ = " + std::to_string(table_.values[i]) + " at " +
                                        detail::describe_value(table_, i) +
                                        " is outside the quantity's range (G~ in (0, 1]: ln G~ <= 0): the file is corrupt");
    cache_ = make_sampler_cache(table_);
    values32_ = float_values_if_exact(table_);
    u_max_ = table_.axes[0].map.max;
    w_min_ = table_.axes[1].map.min;
    count_u_ = table_.axes[0].map.count;
    count_w_ = table_.axes[1].map.count;
    channels_ = table_.channels.size();
    inv_span_u_ = 1.0 / (cache_.g1[0] - cache_.g0[0]);
    inv_span_w_ = 1.0 / (cache_.g1[1] - cache_.g0[1]);
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

// F = G(u, 0) − G(u, v) where that keeps the table's relative accuracy, the direct
// integral where it would cancel (slut_F_from_tails).
double AirlightTable::F(double u, double v) const {
    if (!(v > 0.0)) return 0.0;
    const double whole = 1.5707963267948966 * scaled_tail(u, 1.5707963267948966, 0.0);
    return std::fmax(slut_F_from_tails(u, v, whole, tail(u, v)), 0.0);
}

double detail::airlight_radiance_portable(const AirlightTable &table, const AirlightQuery &q) {
    return table.radiance_portable(q);
}

// The portable radiance (see AirlightTable::radiance below).
double AirlightTable::radiance_portable(const AirlightQuery &q) const {
    const slut_airlight_geometry g = setup_near_end_unscaled(q);
    if (g.kind != 0) return slut_airlight_from_gs(g, 0.0, 0.0);
    // Beyond plain products (scales or lengths near the ends of the double range): the
    // general path, which multiplies in logarithms where it must (slut_airlight_scaled).
    if (!slut_airlight_scale_is_plain(g, q.distance_m, q.length_m)) return radiance_general(q);
    if (slut_airlight_theta_fits_one_panel(g)) return one_panel_radiance(g);
    return two_sample_radiance(g);
}

// The scalar path without the fast paths' folding: the geometry with its scale (and its
// logarithm where the scale is not a normal double), then one θ-panel or the two samples.
double AirlightTable::radiance_general(const AirlightQuery &q) const {
    slut_airlight_geometry g = setup_near_end(q);
    if (g.kind != 0) return slut_airlight_from_gs(g, 0.0, 0.0);
    if (slut_airlight_theta_fits_one_panel(g))
        return slut_airlight_scaled(
            g, slut_airlight_theta_integral_one_panel(g.c, g.cos_half, g.sin_half, g.tan_dv) / g.sin_gamma);
    g = slut_airlight_setup_far_end(g);
    const double at_u = unit_u(g.u);
    const double gs2 = scaled_tail_at(at_u, g.u, g.w2, g.a2);
    const double gs1 = g.w1 > 0.0 ? scaled_tail_at(at_u, g.u, g.w1, g.a1) : 0.0;
    return slut_airlight_from_gs(g, gs2, gs1);
}

#if SLUT_HAVE_SIMD4
namespace {
using simd4::v4d;

// slut_airlight_theta_integral_one_panel's six nodes as two 4-lane vectors (the last two
// lanes weight 0), e^{−σ_t D} folded into the node exponentials: the same sum in 2 vector
// exps instead of 7 scalar ones and a third of the divides. tan dv comes as a quotient
// tan_num/tan_den as well: the exponents −c·t/(sin w2 − t·cos w2) are taken as
// −c·t′/(tan_den·sin w2 − t′·cos w2) with t′ = t·tan_den from tan_num, so that their divide
// does not wait for tan dv's (AirlightScalar4 passes the triangle's two sides; the portable
// path tan dv and 1, the kernel's expression).
// (always inline: AirlightScalar4's call too; one_panel_radiance4 below for the portable path)
SLUT_SIMD4_TARGET inline __attribute__((always_inline)) double
one_panel_radiance4_inline(const slut_airlight_geometry &g, double tan_num, double tan_den) {
    const v4d x0 = {-slut_gl6_x[0], -slut_gl6_x[1], -slut_gl6_x[2], slut_gl6_x[0]};
    const v4d x1 = {slut_gl6_x[1], slut_gl6_x[2], 0.0, 0.0};
    const v4d w0 = {slut_gl6_w[0], slut_gl6_w[1], slut_gl6_w[2], slut_gl6_w[0]};
    const v4d w1 = {slut_gl6_w[1], slut_gl6_w[2], 0.0, 0.0};
    const double half_len = 0.5 * g.tan_dv, half_num = 0.5 * tan_num, sin_den = tan_den * g.cos_half;
    const v4d n0 = half_num * (1.0 + x0), n1 = half_num * (1.0 + x1);
    const v4d e0 = -g.c * n0 / (sin_den - n0 * g.sin_half) - g.optical_distance;
    const v4d e1 = -g.c * n1 / (sin_den - n1 * g.sin_half) - g.optical_distance;
    const v4d t0 = half_len * (1.0 + x0), t1 = half_len * (1.0 + x1);
    const v4d f = w0 / (1.0 + t0 * t0) * simd4::exp4(e0) + w1 / (1.0 + t1 * t1) * simd4::exp4(e1);
    // half_len/sin γ first: at γ → 0 both are ~1e-300, and the sum carries e^{−σ_t D}, so
    // half_len·sum would underflow where the radiance does not.
    return g.scale_unattenuated * ((half_len / g.sin_gamma) * ((f[0] + f[1]) + (f[2] + f[3])));
}
SLUT_SIMD4_TARGET double one_panel_radiance4(const slut_airlight_geometry &g) {
    return one_panel_radiance4_inline(g, g.tan_dv, 1.0);
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

#if SLUT_HAVE_SIMD4
// slut_airlight_theta_integral_rule(c, w2, dv, 0) with each panel's eight node exps as two
// 4-lane exps and its two sines and cosines as one 4-lane sin and cos: the same panels,
// nodes, weights and stopping rule.
SLUT_SIMD4_TARGET double theta_rule8_simd(double c, double w2, double dv) {
    if (dv <= 0.0) return 0.0;
    if (c <= 0.0) return dv;
    const v4d x_low = {-slut_gl8_x[0], -slut_gl8_x[1], -slut_gl8_x[2], -slut_gl8_x[3]};
    const v4d x_high = {slut_gl8_x[0], slut_gl8_x[1], slut_gl8_x[2], slut_gl8_x[3]};
    const v4d weight = {slut_gl8_w[0], slut_gl8_w[1], slut_gl8_w[2], slut_gl8_w[3]};
    const double sin_w2 = std::sin(w2);
    double delta = w2, remaining = dv, sum = 0.0;
    for (int panel = 0; panel < 20000 && remaining > 0.0; ++panel) {
        const double theta = dv - remaining;
        const v4d angles = {delta, theta, 0.0, 0.0};
        const v4d sines = simd4::sin4(angles), cosines = simd4::cos4(angles);
        const double sd = sines[0], st = sines[1], cd = cosines[0], ct = cosines[1];
        const double rate = c * sin_w2 / (sd * sd);
        const double f_start = std::exp(-c * st / sd);
        if (panel > 0 && f_start <= 1e-17 * sum * rate) break;
        const double h = std::fmin(remaining, std::fmin(0.25 * delta, 4.0 / rate));
        const double half_len = 0.5 * std::tan(h);
        const v4d t_low = half_len + half_len * x_low, t_high = half_len + half_len * x_high;
        const v4d f = simd4::exp4(-c * (st + t_low * ct) / (sd - t_low * cd)) / (1.0 + t_low * t_low) +
                      simd4::exp4(-c * (st + t_high * ct) / (sd - t_high * cd)) / (1.0 + t_high * t_high);
        const v4d part = weight * f;
        sum += half_len * ((part[0] + part[1]) + (part[2] + part[3]));
        remaining -= h;
        delta -= h;
    }
    return sum;
}
#endif

double theta_rule8(double c, double w2, double dv) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return theta_rule8_simd(c, w2, dv);
#endif
    return slut_airlight_theta_integral_rule(c, w2, dv, 0);
}

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
inline __attribute__((always_inline)) double AirlightTable::ln_gs_at(int cell_u, double frac_u,
                                                                        double unit_w) const {
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
        g = slut_airlight_set_scale(g);
        g = slut_airlight_setup_far_end(g);
        const double at_u = unit_u(g.u);
        const double gs2 = scaled_tail_at(at_u, g.u, g.w2, g.a2);
        const double gs1 = g.w1 > 0.0 ? scaled_tail_at(at_u, g.u, g.w1, g.a1) : 0.0;
        return slut_airlight_from_gs(g, gs2, gs1);
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
    g = slut_airlight_set_scale(g);
    return g.scale * (theta_rule8(g.c, g.w2, slut_airlight_dv(g)) / g.sin_gamma);
}

#if SLUT_HAVE_SIMD4
namespace {
// a ≤ b ? if_true : if_false without a branch (a blend). The geometry's tests (x ≥ 0, y ≥ 0,
// γ/2 ≤ π/4) go either way at random across queries: as branches they mispredict often.
SLUT_SIMD4_TARGET inline double select_le(double a, double b, double if_true, double if_false) {
    const __m128d mask = _mm_cmp_sd(_mm_set_sd(a), _mm_set_sd(b), _CMP_LE_OQ);
    return _mm_cvtsd_f64(_mm_blendv_pd(_mm_set_sd(if_false), _mm_set_sd(if_true), mask));
}

// The elementwise functions the set-up below needs, for one query (double) and four (v4d).
inline double sqrt_of(double x) { return std::sqrt(x); }
inline double abs_of(double x) { return std::fabs(x); }
inline double max_of(double x, double y) { return std::max(x, y); }
SLUT_SIMD4_TARGET inline simd4::v4d sqrt_of(simd4::v4d x) { return simd4::sqrt4(x); }
SLUT_SIMD4_TARGET inline simd4::v4d abs_of(simd4::v4d x) { return simd4::abs4(x); }
SLUT_SIMD4_TARGET inline simd4::v4d max_of(simd4::v4d x, double y) { return simd4::max4(x, simd4::splat(y)); }

// slut_airlight_setup_near_end_unscaled's geometry from the sine and cosine of γ/2 (moderate
// lengths: s, D ≤ 1e100; its formulas from kernels/slut_airlight.h's SLUT_AIRLIGHT_* macros)
// for the scalar call's vector path (AirlightScalar4, Real = double) and the batch
// (AirlightBatch, four queries in a v4d): the same expressions, so the same values.
template <class Real>
struct NearEnd {
    Real sin_gamma, cos_gamma; // of γ, sin γ ≥ 1e-300 (on the axis: the one-panel rule's length / sin γ stays finite)
    Real u, c;                 // σ_t D sin γ; 2 σ_t D sin(γ/2)
    Real d_far;                // the far end's distance from the light, m
    Real x, ds;                // the far end: x = s − D cos γ (> 0: past the light's foot), ds = D sin γ
    Real y, ss;                // the light: y = D − s cos γ (> 0: ahead of the far end), ss = s sin γ
    Real dx, dy;               // d + |x|, d + |y|: d + x for x ≥ 0 and d − x below (never cancels)
};
template <class Real>
SLUT_SIMD4_TARGET inline NearEnd<Real> near_end(Real optical_distance, Real D, Real s, Real sin_half, Real cos_half) {
    NearEnd<Real> g;
    g.sin_gamma = max_of(2.0 * sin_half * cos_half, SLUT_TINY);
    g.cos_gamma = SLUT_AIRLIGHT_COS_GAMMA(sin_half, cos_half);
    g.u = optical_distance * g.sin_gamma;
    g.c = 2.0 * optical_distance * sin_half;
    g.d_far = sqrt_of(SLUT_AIRLIGHT_FAR_DISTANCE2(s, D, sin_half));
    g.x = s - D * g.cos_gamma;
    g.ds = D * g.sin_gamma;
    g.y = D - s * g.cos_gamma;
    g.ss = s * g.sin_gamma;
    g.dx = g.d_far + abs_of(g.x);
    g.dy = g.d_far + abs_of(g.y);
    return g;
}
// σ_t Δ ≥ 0 (the far end's extra attenuation e^{−σ_t Δ}, SLUT_AIRLIGHT_DELTA).
template <class Real>
SLUT_SIMD4_TARGET inline Real optical_delta_of(Real sigma_t, Real D, Real s, const NearEnd<Real> &g) {
    return sigma_t * max_of(SLUT_AIRLIGHT_DELTA(s, D, g.cos_gamma, g.d_far), 0.0);
}
} // namespace

// The one-panel rule's six node exponentials as one 8-lane exp where the CPU has AVX-512
// (libmvec's _ZGVeN8v_exp, ≤ 4 ulp like the 4-lane one): one_panel_radiance4's nodes, weights
// and order of additions (lanes 0–3 its first vector, 4–7 its second).
namespace {
typedef double v8d __attribute__((vector_size(64)));
} // namespace
extern "C" __attribute__((target("avx512f"))) v8d _ZGVeN8v_exp(v8d);
namespace {
bool has_avx512f() {
    static const bool yes = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f") != 0;
    }();
    return yes;
}
// The geometry's fields as arguments (registers), not a slut_airlight_geometry in memory.
__attribute__((target("avx512f,avx2,fma"))) __attribute__((noinline)) double
one_panel_radiance8(double c, double cos_half, double sin_half, double tan_dv, double optical_distance,
                    double scale_unattenuated, double sin_gamma) {
    const v8d x = {-slut_gl6_x[0], -slut_gl6_x[1], -slut_gl6_x[2], slut_gl6_x[0], slut_gl6_x[1], slut_gl6_x[2], 0.0, 0.0};
    const v8d w = {slut_gl6_w[0], slut_gl6_w[1], slut_gl6_w[2], slut_gl6_w[0], slut_gl6_w[1], slut_gl6_w[2], 0.0, 0.0};
    const double half_len = 0.5 * tan_dv;
    const v8d t = half_len * (1.0 + x);
    const v8d e = -c * t / (cos_half - t * sin_half) - optical_distance;
    const v8d f = w / (1.0 + t * t) * _ZGVeN8v_exp(e);
    return scale_unattenuated *
           ((half_len / sin_gamma) * (((f[0] + f[4]) + (f[1] + f[5])) + ((f[2] + f[6]) + (f[3] + f[7]))));
}
} // namespace

// AirlightTable::radiance where the CPU has AVX2 and FMA: radiance_portable's paths (the
// one-panel θ-rule, the two table samples, the 8-point θ-rule where they cancel) with the
// geometry of slut_airlight_setup_near_end_unscaled and slut_sincos_half_angle written
// without branches on the geometry (blends; |x| + d in place of the two signs' d ± x) and
// its independent divides, square roots and transcendentals as 4-lane vector operations:
// one divide for tan w1 and tan dv (each with its reciprocal: the two signs' quotients),
// one atan for w1 and dv, one divide for the three warps' arguments and 1/sin γ, one log
// for the three warps, one exp for the two decodes and e^{−σ_t D} (and the one-panel rule's
// six exps as one 8-lane exp where the CPU has AVX-512). The same formulas but for the warps'
// arguments and the one-panel exponents' divide, both taken from the triangle's sides so as
// not to wait on another quotient (see there), and FMA contraction: 1e-12 against the
// portable path, test ScalarRadianceMatchesThePortablePath. Queries outside its plain range
// take the portable path.
// eight_lanes: the one-panel rule on 8 lanes (only where the CPU has AVX-512F), else on 4.
struct AirlightScalar4 {
    SLUT_SIMD4_TARGET static double radiance(const AirlightTable &t, const AirlightQuery &q, bool eight_lanes) {
        using simd4::v4d;
        // query_conditions (check_airlight_query's) as one test; where one fails the check throws, naming the field.
        if (!detail::all_hold(query_conditions(q))) check_airlight_query(q);
        const double sigma_s = q.sigma_s_per_m, intensity = q.intensity_W_per_sr, D = q.distance_m, s = q.length_m;
        const double sigma_t = sigma_s + q.sigma_a_per_m;
        const double optical_distance = sigma_t * D;
        const double scale_unattenuated = sigma_s * SLUT_INV_4PI * intensity * 2.0 / D;
        // The finite radiance (σ_s, I0, s > 0; γ > 0: not on the axis, where the ray may pass
        // through the light), a finite ray and plain products (slut_airlight_scale_is_plain);
        // the rest: the portable path. One branch for all of it.
        const bool plain = (sigma_s > 0.0) & (intensity > 0.0) & (q.gamma_rad > 0.0) & (s >= 1e-100) & (s <= 1e100) &
                           (D >= 1e-100) & (D <= 1e100) & (scale_unattenuated >= 1e-100) &
                           (scale_unattenuated <= 1e100) & (optical_distance <= 300.0);
        if (!plain) return t.radiance_portable(q);
        // slut_sincos_half_angle (h ≤ π/4: the Taylor forms at h, else at π/2 − h, swapped).
        const double half = std::min(0.5 * q.gamma_rad, SLUT_PIO2_HI);
        const double w2 = slut_pio2_minus(half);
        const double quarter = 0.78539816339744828;
        double sin_reduced, cos_reduced;
        slut_sincos_quarter(select_le(half, quarter, half, w2), &sin_reduced, &cos_reduced);
        const double sin_half = select_le(half, quarter, sin_reduced, cos_reduced);
        const double cos_half = select_le(half, quarter, cos_reduced, sin_reduced);
        const NearEnd<double> geometry = near_end(optical_distance, D, s, sin_half, cos_half);
        const double sin_gamma = geometry.sin_gamma, u = geometry.u, c = geometry.c, d_far = geometry.d_far;
        const double x = geometry.x, ds = geometry.ds, y = geometry.y, ss = geometry.ss;
        const double dx = geometry.dx, dy = geometry.dy;
        // tan w1 = ds/(d + x) or (d − x)/ds, tan dv likewise with y and ss.
        const v4d ratios = v4d{ds, dx, ss, dy} / v4d{dx, ds, dy, ss};
        const double tan_w1 = select_le(0.0, x, ratios[0], ratios[1]);
        const double tan_dv = select_le(0.0, y, ratios[2], ratios[3]);
        if (SLUT_AIRLIGHT_THETA_FITS_ONE_PANEL(tan_dv, w2, c, cos_half)) {
            if (eight_lanes)
                return one_panel_radiance8(c, cos_half, sin_half, tan_dv, optical_distance, scale_unattenuated, sin_gamma);
            slut_airlight_geometry g;
            g.c = c;
            g.cos_half = cos_half;
            g.sin_half = sin_half;
            g.tan_dv = tan_dv;
            g.optical_distance = optical_distance;
            g.scale_unattenuated = scale_unattenuated;
            g.sin_gamma = sin_gamma;
            return one_panel_radiance4_inline(g, select_le(0.0, y, ss, dy), select_le(0.0, y, dy, ss));
        }
        if (!t.fast_lookup_) return t.radiance_portable(q);
        const double optical_delta = optical_delta_of(sigma_t, D, s, geometry);
        const v4d angles = simd4::atan4(v4d{tan_w1, tan_dv, 0.0, 0.0}); // w1, dv
        const double w1 = angles[0];
        if (!(w1 >= t.w_min_) || !(u > 0.0) || u > t.u_max_) return t.radiance_portable(q); // asymptotic forms
        // The warps: u's LOG1P (Goldberg's form) and the two ends' ASINH_COT, whose argument
        // cot w + √(1 + cot² w) is taken from the triangle instead of from cot w = a/u (the
        // portable path's quotient and square root after it): at the viewer cot w2 = tan(γ/2),
        // so the argument is (1 + sin(γ/2))/cos(γ/2); at the far end cot w1 = dx/ds (x ≥ 0) or
        // ds/dx, and with √(dx² + ds²) = √(2·d·dx) (d² = x² + ds²) it is (dx + √(2·d·dx))/ds or
        // (ds + √(2·d·dx))/dx. One divide for the three arguments and 1/sin γ, its square root
        // beside the divide for tan w1 and tan dv, not after it: a few ulps from the portable
        // path's arguments.
        const double hypotenuse = std::sqrt((d_far + d_far) * dx);
        const double far_num = select_le(0.0, x, dx, ds), far_den = select_le(0.0, x, ds, dx);
        const slut_axis &axis_u = t.table_.axes[0].map;
        const v4d quotients = v4d{u - axis_u.min, 1.0 + sin_half, far_num + hypotenuse, 1.0} /
                              v4d{axis_u.scale, cos_half, far_den, sin_gamma};
        const double x_u = quotients[0], one_plus_x_u = 1.0 + x_u, inv_sin_gamma = quotients[3];
        const v4d logs = simd4::log4(v4d{one_plus_x_u, quotients[1], quotients[2], 1.0});
        const double goldberg = one_plus_x_u == 1.0 ? 1.0 : x_u / (one_plus_x_u - 1.0);
        const double g_u = one_plus_x_u == 1.0 ? x_u : logs[0] * goldberg;
        // The unit coordinates with the spans' reciprocals (once per table: a product in place
        // of a divide on the way to the cells; an ulp from the portable path's quotient).
        const v4d units = (v4d{g_u, -logs[1], -logs[2], 1.0} - v4d{t.cache_.g0[0], t.cache_.g0[1], t.cache_.g0[1], 0.0}) *
                          v4d{t.inv_span_u_, t.inv_span_w_, t.inv_span_w_, 1.0};
        const double unit_u = u >= axis_u.max ? 1.0 : units[0];
        int cell_u;
        double frac_u;
        slut_cell_from_unit(unit_u, t.count_u_, &cell_u, &frac_u);
        const double ln2 = t.ln_gs_at(cell_u, frac_u, units[1]), ln1 = t.ln_gs_at(cell_u, frac_u, units[2]);
        const v4d e = simd4::exp4(v4d{ln2 - optical_distance, ln1 - optical_distance - optical_delta, -optical_distance, 0.0});
        const double viewer_term = (w2 * inv_sin_gamma) * e[0], far_term = (w1 * inv_sin_gamma) * e[1];
        if (far_term <= 0.5 * viewer_term) return scale_unattenuated * (viewer_term - far_term);
        // The two terms would cancel: slut_airlight_from_gs's θ-integral.
        return (scale_unattenuated * e[2]) * (theta_rule8_simd(c, w2, angles[1]) / sin_gamma);
    }
};
#endif

// A segment short enough for one panel takes the θ-integral directly (6 exps, more
// accurate than the table and cheaper than two lookups); the others the two table samples
// (slut_airlight_from_gs, which still integrates where they would cancel).
double AirlightTable::radiance(const AirlightQuery &q) const {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return AirlightScalar4::radiance(*this, q, has_avx512f());
#endif
    return radiance_portable(q);
}

double detail::airlight_radiance_four_lanes(const AirlightTable &table, const AirlightQuery &q) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return AirlightScalar4::radiance(table, q, false);
#endif
    return table.radiance_portable(q);
}

// ------------------------------------------------------------------ batch radiance

namespace {
#if SLUT_HAVE_SIMD4
// Whether every field of queries[0 … count) lies in its kQueryRanges range: the queries as
// one flat array of 6·count doubles, two queries (three 4-lane vectors) per step against the
// ranges laid out with the same period, the comparisons' masks and-ed. Reads the queries'
// bytes (trivially copyable doubles), not their fields: no shuffle per query. (Each query's
// conditions folded with all_hold, eleven scalar compare-and-set steps, took ~8 % of the
// batch's time: bench/README.md, "The airlight batch's check and lookups".)
SLUT_SIMD4_TARGET bool every_field_in_range(const AirlightQuery *queries, size_t count) {
    using simd4::v4d;
    using simd4::v4l;
    v4d lo[3], hi[3];
    for (int k = 0; k < 12; ++k) {
        lo[k / 4][k % 4] = kQueryRanges[k % 6].lo;
        hi[k / 4][k % 4] = kQueryRanges[k % 6].hi;
    }
    const unsigned char *bytes = reinterpret_cast<const unsigned char *>(queries);
    v4l in_range = {-1, -1, -1, -1};
    size_t i = 0;
    for (; i + 2 <= count; i += 2) {
        for (int k = 0; k < 3; ++k) {
            v4d x;
            std::memcpy(&x, bytes + i * sizeof(AirlightQuery) + static_cast<size_t>(k) * sizeof(v4d), sizeof(v4d));
            in_range &= (x >= lo[k]) & (x <= hi[k]);
        }
    }
    bool all = !simd4::any(~in_range);
    if (i < count) all &= detail::all_hold(query_conditions(queries[i]));
    return all;
}
#endif

// Every query's conditions before the first is computed; where one fails, the first failing
// query named by its index (check_airlight_query per query, require_every_query).
void check_airlight_queries(const AirlightQuery *queries, size_t count) {
    const auto holds = [](const AirlightQuery &q) { return detail::all_hold(query_conditions(q)); };
    const auto check = [](const AirlightQuery &q) { check_airlight_query(q); };
#if SLUT_HAVE_SIMD4
    if (simd4::available()) {
        if (!every_field_in_range(queries, count)) detail::require_every_query(queries, count, holds, check);
        return;
    }
#endif
    detail::require_every_query(queries, count, holds, check);
}
} // namespace

#if SLUT_HAVE_SIMD4
// Four queries at a time. Each block of four is set up in 4-lane vectors (the arithmetic of
// slut_airlight_setup_near_end_unscaled, restated lane-wise; sin and cos of γ/2 by the kernel's
// SLUT_SIN_QUARTER and SLUT_COS_QUARTER, as slut_sincos_half_angle);
// each query then joins one of two queues by its path (AirlightTable::radiance's test
// slut_airlight_theta_fits_one_panel), and a queue holding four runs its path on all four
// lanes: the one-panel θ-rule (6 vector exps per four queries) or the two table samples (a
// vector atan, three vector logs, two vector exps and eight cell gathers per query). So no
// lane computes a path it does not take. Queries the vectors do not serve (zero radiance,
// the ray through the light, an infinite ray, an end beyond the table, the cancelling case)
// take the scalar radiance(q), which handles them all.
struct AirlightBatch {
    struct Lanes { // one queue: up to 4 pending queries (structure of arrays)
        double c[4], sin_half[4], cos_half[4], tan_dv[4], optical_distance[4], scale_unattenuated[4], sin_gamma[4];
        double u[4], far_num[4], far_den[4], two_d_dx[4], w2[4], tan_w1[4], optical_delta[4];
        size_t index[4];
        int size = 0;
    };

    const AirlightTable &table;
    const AirlightQuery *queries;
    double *out;

    Lanes theta_rule; // two-sample queries whose ends' terms cancel: the 8-point θ-rule

    SLUT_SIMD4_TARGET void run(size_t count) {
        Lanes one_panel, two_sample;
        for (size_t first = 0; first < count; first += 4) {
            size_t index[4];
            for (int l = 0; l < 4; ++l) index[l] = first + static_cast<size_t>(l) < count ? first + static_cast<size_t>(l) : first;
            setup_block(index, one_panel, two_sample);
        }
        if (one_panel.size > 0) flush_one_panel(one_panel);
        if (two_sample.size > 0) flush_two_sample(two_sample);
        if (theta_rule.size > 0) flush_theta_rule(theta_rule);
    }

    static void push(Lanes &to, const Lanes &from, int k) {
        const int n = to.size++;
        to.index[n] = from.index[k];
        to.c[n] = from.c[k];
        to.sin_half[n] = from.sin_half[k];
        to.cos_half[n] = from.cos_half[k];
        to.tan_dv[n] = from.tan_dv[k];
        to.optical_distance[n] = from.optical_distance[k];
        to.scale_unattenuated[n] = from.scale_unattenuated[k];
        to.sin_gamma[n] = from.sin_gamma[k];
        to.u[n] = from.u[k];
        to.far_num[n] = from.far_num[k];
        to.far_den[n] = from.far_den[k];
        to.two_d_dx[n] = from.two_d_dx[k];
        to.w2[n] = from.w2[k];
        to.tan_w1[n] = from.tan_w1[k];
        to.optical_delta[n] = from.optical_delta[k];
    }

    SLUT_SIMD4_TARGET void setup_block(const size_t *index, Lanes &one_panel, Lanes &two_sample) {
        using simd4::v4d;
        using simd4::v4l;
        v4d sigma_s, sigma_a, intensity, D, gamma, s;
        for (int l = 0; l < 4; ++l) {
            const AirlightQuery &q = queries[index[l]];
            sigma_s[l] = q.sigma_s_per_m;
            sigma_a[l] = q.sigma_a_per_m;
            intensity[l] = q.intensity_W_per_sr;
            D[l] = q.distance_m;
            gamma[l] = q.gamma_rad;
            s[l] = q.length_m;
        }
        const v4d zero = simd4::splat(0.0);
        const v4d half = simd4::min4(0.5 * gamma, simd4::splat(SLUT_PIO2_HI));
        const v4d w2 = (SLUT_PIO2_HI - half) + SLUT_PIO2_LO;
        // slut_sincos_half_angle lane-wise (the scalar call's sines: its Taylor forms at h ≤ π/4,
        // else at π/2 − h, swapped), not libmvec's sin and cos: two vector calls fewer.
        const v4l low = half <= simd4::splat(0.78539816339744828);
        const v4d h = simd4::select(low, half, w2), z = h * h, z2 = z * z, z4 = z2 * z2;
        const v4d sin_h = SLUT_SIN_QUARTER(h, z, z2, z4), cos_h = SLUT_COS_QUARTER(z, z2, z4);
        const v4d sin_half = simd4::select(low, sin_h, cos_h), cos_half = simd4::select(low, cos_h, sin_h);
        const v4d sigma_t = sigma_s + sigma_a;
        const v4d scale_unattenuated = sigma_s * SLUT_INV_4PI * intensity * 2.0 / D;
        const v4d optical_distance = sigma_t * D;
        const NearEnd<v4d> geometry = near_end(optical_distance, D, s, sin_half, cos_half);
        const v4d sin_gamma = geometry.sin_gamma, u = geometry.u, c = geometry.c, d_far = geometry.d_far;
        const v4d x = geometry.x, ds = geometry.ds, y = geometry.y, ss = geometry.ss;
        const v4d dx = geometry.dx, dy = geometry.dy;
        // tan w1 = ds/(d + x) or (d − x)/ds, tan dv likewise with y and ss, each one divide of
        // the selected sides (the same values as the scalar call's). The far end's warp
        // argument takes the same sides (flush_two_sample).
        const v4l x_ahead = x >= zero, y_ahead = y >= zero;
        const v4d far_num = simd4::select(x_ahead, dx, ds), far_den = simd4::select(x_ahead, ds, dx);
        const v4d two_d_dx = (d_far + d_far) * dx;
        const v4d tan_w1 = far_den / far_num;
        const v4d tan_dv = simd4::select(y_ahead, ss, dy) / simd4::select(y_ahead, dy, ss);
        const v4d optical_delta = optical_delta_of(sigma_t, D, s, geometry);
        // Lanes for the vectors: kind 0 (σ_s, I0, s > 0), finite s, γ/2 > 0 (not through the light).
        // And the plain-product range of slut_airlight_scale_is_plain (the rest: radiance_general).
        const v4d lo = simd4::splat(1e-100), hi = simd4::splat(1e100);
        const v4l regular = (sigma_s > zero) & (intensity > zero) & (s > zero) & (s <= simd4::splat(SLUT_INFINITE_ABOVE)) &
                            (sin_half > zero) & (scale_unattenuated >= lo) & (scale_unattenuated <= hi) &
                            (optical_distance <= simd4::splat(300.0)) & (D >= lo) & (D <= hi) & (s >= lo) & (s <= hi);
        const v4l fits = SLUT_AIRLIGHT_THETA_FITS_ONE_PANEL(tan_dv, w2, c, cos_half);
        for (int l = 0; l < 4; ++l) {
            if (l > 0 && index[l] == index[0]) break; // the padding of the last block
            if (!regular[l]) {
                out[index[l]] = table.radiance(queries[index[l]]);
                continue;
            }
            Lanes &queue = fits[l] ? one_panel : two_sample;
            const int k = queue.size++;
            queue.index[k] = index[l];
            queue.c[k] = c[l];
            queue.sin_half[k] = sin_half[l];
            queue.cos_half[k] = cos_half[l];
            queue.tan_dv[k] = tan_dv[l];
            queue.optical_distance[k] = optical_distance[l];
            queue.scale_unattenuated[k] = scale_unattenuated[l];
            queue.sin_gamma[k] = sin_gamma[l];
            queue.u[k] = u[l];
            queue.far_num[k] = far_num[l];
            queue.far_den[k] = far_den[l];
            queue.two_d_dx[k] = two_d_dx[l];
            queue.w2[k] = w2[l];
            queue.tan_w1[k] = tan_w1[l];
            queue.optical_delta[k] = optical_delta[l];
            if (queue.size == 4) {
                if (fits[l]) flush_one_panel(queue);
                else flush_two_sample(queue);
            }
        }
    }

    // A partial queue's unused lanes repeat lane 0 (finite, never stored).
    static void pad(Lanes &q) {
        for (int k = q.size; k < 4; ++k) {
            q.c[k] = q.c[0];
            q.sin_half[k] = q.sin_half[0];
            q.cos_half[k] = q.cos_half[0];
            q.tan_dv[k] = q.tan_dv[0];
            q.optical_distance[k] = q.optical_distance[0];
            q.scale_unattenuated[k] = q.scale_unattenuated[0];
            q.sin_gamma[k] = q.sin_gamma[0];
            q.u[k] = q.u[0];
            q.far_num[k] = q.far_num[0];
            q.far_den[k] = q.far_den[0];
            q.two_d_dx[k] = q.two_d_dx[0];
            q.w2[k] = q.w2[0];
            q.tan_w1[k] = q.tan_w1[0];
            q.optical_delta[k] = q.optical_delta[0];
        }
    }

    // slut_airlight_theta_integral_one_panel on four queries (the same nodes in the same
    // order), times scale = scale_unattenuated·e^{−σ_t D} folded into the exponentials.
    SLUT_SIMD4_TARGET void flush_one_panel(Lanes &q) {
        using simd4::v4d;
        pad(q);
        const v4d c = simd4::load4(q.c), sin_w2 = simd4::load4(q.cos_half), cos_w2 = simd4::load4(q.sin_half);
        const v4d optical_distance = simd4::load4(q.optical_distance);
        const v4d half_len = 0.5 * simd4::load4(q.tan_dv);
        v4d sum = simd4::splat(0.0);
        for (int k = 0; k < 6; ++k) {
            const double node = (k < 3) ? -slut_gl6_x[k] : slut_gl6_x[k - 3];
            const v4d t = half_len * (1.0 + node);
            const v4d exponent = -c * t / (sin_w2 - t * cos_w2) - optical_distance;
            sum += (slut_gl6_w[k < 3 ? k : k - 3] / (1.0 + t * t)) * simd4::exp4(exponent);
        }
        const v4d L = simd4::load4(q.scale_unattenuated) * ((half_len / simd4::load4(q.sin_gamma)) * sum); // as one_panel_radiance4
        for (int k = 0; k < q.size; ++k) out[q.index[k]] = L[k];
        q.size = 0;
    }

    // slut_cell_from_unit on four lanes: each lane's lower node (index[k]) and fraction (a
    // NaN lane clamps to node 0: never an index outside the table).
    SLUT_SIMD4_TARGET static simd4::v4d cells4(simd4::v4d unit, int count, int index[4]) {
        const simd4::v4d position =
            simd4::min4(simd4::max4(unit, simd4::splat(0.0)), simd4::splat(1.0)) * static_cast<double>(count - 1);
        const __m128i lower = _mm_min_epi32(_mm256_cvttpd_epi32(position), _mm_set1_epi32(count - 2));
        _mm_storeu_si128(reinterpret_cast<__m128i *>(index), lower);
        return position - _mm256_cvtepi32_pd(lower);
    }
    // A lerp as AirlightTable::ln_gs_at's (the nodes' values exactly at f = 0 and f = 1).
    SLUT_SIMD4_TARGET static simd4::v4d lerp4(simd4::v4d lower, simd4::v4d upper, simd4::v4d f) {
        const simd4::v4d inside = lower + f * (upper - lower);
        return simd4::select(f == 0.0, lower, simd4::select(f == 1.0, upper, inside));
    }
    // The ln G̃ of four queries' samples (AirlightTable::ln_gs_at): each lane's cell given, the
    // four corners' floats loaded one by one, the lerps on the lanes.
    SLUT_SIMD4_TARGET static simd4::v4d ln_gs_in_cells4(const AirlightTable &t, const int cell_u[4], simd4::v4d frac_u,
                                                       const int cell_w[4], simd4::v4d frac_w) {
        using simd4::v4d;
        const size_t channels = t.channels_, row = static_cast<size_t>(t.count_u_) * channels;
        const float *v[4];
        for (int k = 0; k < 4; ++k)
            v[k] = t.values32_.data() +
                   (static_cast<size_t>(cell_w[k]) * static_cast<size_t>(t.count_u_) + static_cast<size_t>(cell_u[k])) * channels;
        v4d corner[4]; // (w, u) lower-lower, upper-lower, lower-upper, upper-upper
        const size_t offsets[4] = {0, row, channels, row + channels};
        for (int c = 0; c < 4; ++c) {
            const size_t o = offsets[c];
            corner[c] = _mm256_cvtps_pd(_mm_setr_ps(v[0][o], v[1][o], v[2][o], v[3][o]));
        }
        return lerp4(lerp4(corner[0], corner[1], frac_w), lerp4(corner[2], corner[3], frac_w), frac_u);
    }
    // AirlightTable::ln_gs_at for both ends of four queries (one u cell per query). (Query by
    // query, the cells and lerps took ~10 % of the batch's time: bench/README.md, "The
    // airlight batch's check and lookups".)
    SLUT_SIMD4_TARGET static void ln_gs_at4(const AirlightTable &t, simd4::v4d unit_u, simd4::v4d unit_w2,
                                            simd4::v4d unit_w1, simd4::v4d *ln2, simd4::v4d *ln1) {
        int cell_u[4], cell_w2[4], cell_w1[4];
        const simd4::v4d frac_u = cells4(unit_u, t.count_u_, cell_u);
        *ln2 = ln_gs_in_cells4(t, cell_u, frac_u, cell_w2, cells4(unit_w2, t.count_w_, cell_w2));
        *ln1 = ln_gs_in_cells4(t, cell_u, frac_u, cell_w1, cells4(unit_w1, t.count_w_, cell_w1));
    }

    // AirlightTable::two_sample_radiance on four queries.
    SLUT_SIMD4_TARGET void flush_two_sample(Lanes &q) {
        using simd4::v4d;
        using simd4::v4l;
        pad(q);
        const AirlightTable &t = table;
        const v4d u = simd4::load4(q.u), w2 = simd4::load4(q.w2), sin_gamma = simd4::load4(q.sin_gamma);
        const v4d optical_distance = simd4::load4(q.optical_distance);
        const v4d w1 = simd4::atan4(simd4::load4(q.tan_w1));
        const v4l in_table = (w1 >= simd4::splat(t.w_min_)) & (u <= simd4::splat(t.u_max_));
        double viewer[4], far[4];
        if (t.fast_lookup_) {
            const slut_axis &axis_u = t.table_.axes[0].map;
            // The two ends' ASINH_COT arguments cot w + √(1 + cot² w) from the triangle, as the
            // scalar call: (1 + sin(γ/2))/cos(γ/2) at the viewer, (dx + √(2·d·dx))/ds or
            // (ds + √(2·d·dx))/dx at the far end.
            const v4d x_u = (u - axis_u.min) / axis_u.scale, one_plus_x_u = 1.0 + x_u;
            const v4d arg2 = (1.0 + simd4::load4(q.sin_half)) / simd4::load4(q.cos_half);
            const v4d arg1 = (simd4::load4(q.far_num) + simd4::sqrt4(simd4::load4(q.two_d_dx))) / simd4::load4(q.far_den);
            const v4d log_u = simd4::log4(one_plus_x_u);
            const v4d log2 = simd4::log4(arg2);
            const v4d log1 = simd4::log4(arg1);
            const v4d g_u = simd4::select(one_plus_x_u == 1.0, x_u, log_u * (x_u / (one_plus_x_u - 1.0)));
            // The unit coordinates with the spans' reciprocals, as the scalar call.
            v4d unit_u = (g_u - t.cache_.g0[0]) * t.inv_span_u_;
            unit_u = simd4::select(u <= axis_u.min, simd4::splat(0.0), unit_u);
            unit_u = simd4::select(u >= axis_u.max, simd4::splat(1.0), unit_u);
            const v4d unit_w2 = (-log2 - t.cache_.g0[1]) * t.inv_span_w_, unit_w1 = (-log1 - t.cache_.g0[1]) * t.inv_span_w_;
            v4d ln2, ln1;
            ln_gs_at4(t, unit_u, unit_w2, unit_w1, &ln2, &ln1);
            const v4d e2 = simd4::exp4(ln2 - optical_distance);
            const v4d e1 = simd4::exp4(ln1 - optical_distance - simd4::load4(q.optical_delta));
            const v4d inv_sin_gamma = 1.0 / sin_gamma;
            simd4::store4(viewer, (w2 * inv_sin_gamma) * e2);
            simd4::store4(far, (w1 * inv_sin_gamma) * e1);
        }
        for (int k = 0; k < q.size; ++k) {
            const size_t i = q.index[k];
            if (!t.fast_lookup_ || !in_table[k] || !(u[k] > 0.0)) {
                out[i] = t.radiance(queries[i]); // an end beyond the table (asymptotic forms): the scalar path
            } else if (far[k] <= 0.5 * viewer[k]) {
                out[i] = q.scale_unattenuated[k] * (viewer[k] - far[k]);
            } else {
                push(theta_rule, q, k);
                if (theta_rule.size == 4) flush_theta_rule(theta_rule);
            }
        }
        q.size = 0;
    }

    // slut_airlight_theta_integral_rule(c, w2, dv, 0) on four queries: the same panels (their
    // length from each lane's own pole distance and decay rate), lane by lane masked off as
    // it reaches its end or its remainder bound, 8 Gauss points per panel.
    SLUT_SIMD4_TARGET void flush_theta_rule(Lanes &q) {
        using simd4::v4d;
        using simd4::v4l;
        pad(q);
        const v4d zero = simd4::splat(0.0);
        const v4d c = simd4::load4(q.c), w2 = simd4::load4(q.w2);
        const v4d dv = simd4::atan4(simd4::load4(q.tan_dv));
        const v4d sin_w2 = simd4::sin4(w2);
        v4d delta = w2, remaining = dv, sum = zero;
        v4l active = remaining > zero;
        for (int panel = 0; panel < 20000 && simd4::any(active); ++panel) {
            const v4d theta = dv - remaining;
            const v4d sd = simd4::sin4(delta), cd = simd4::cos4(delta), st = simd4::sin4(theta), ct = simd4::cos4(theta);
            const v4d rate = c * sin_w2 / (sd * sd);
            const v4d f_start = simd4::exp4(-c * st / sd);
            if (panel > 0) active &= ~(f_start <= 1e-17 * sum * rate);
            const v4d h = simd4::min4(remaining, simd4::min4(0.25 * delta, 4.0 / rate));
            const v4d half_len = 0.5 * simd4::tan4(h);
            v4d part = zero;
            for (int k = 0; k < 4; ++k) {
                for (int side = -1; side <= 1; side += 2) {
                    const v4d t = half_len + (double)side * half_len * slut_gl8_x[k];
                    part += slut_gl8_w[k] * simd4::exp4(-c * (st + t * ct) / (sd - t * cd)) / (1.0 + t * t);
                }
            }
            sum = simd4::select(active, sum + half_len * part, sum);
            remaining = simd4::select(active, remaining - h, remaining);
            delta = simd4::select(active, delta - h, delta);
            active &= remaining > zero;
        }
        const v4d scale = simd4::load4(q.scale_unattenuated) * simd4::exp4(-simd4::load4(q.optical_distance));
        const v4d L = scale * (sum / simd4::load4(q.sin_gamma));
        for (int k = 0; k < q.size; ++k) out[q.index[k]] = L[k];
        q.size = 0;
    }
};
#endif

void AirlightTable::radiance(const AirlightQuery *queries, size_t count, double *out) const {
    check_airlight_queries(queries, count);
#if SLUT_HAVE_SIMD4
    if (simd4::available()) {
        AirlightBatch{*this, queries, out, {}}.run(count);
        return;
    }
#endif
    for (size_t i = 0; i < count; ++i) out[i] = radiance(queries[i]);
}

} // namespace scatterlut
