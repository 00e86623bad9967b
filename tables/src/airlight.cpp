// AirlightTable (scatterlut/airlight.hpp): the table's checks, its lookups (G̃, the tail, F),
// and the portable radiance path (radiance_portable: libm and the kernels' functions, on CPUs
// without AVX2 and for the cases the vector paths leave). Its steps take their 4-lane forms
// where the CPU has AVX2 and FMA (airlight_simd.hpp, airlight_avx2.cpp). The query's checks and
// the radiances without a table: airlight_query.cpp; the scalar radiance's AVX2 path:
// airlight_avx2.cpp (and airlight_avx512.cpp); the batch: airlight_batch.cpp.
#include "scatterlut/airlight.hpp"

#include "airlight_layout.hpp"
#include "airlight_lookup.hpp"
#include "airlight_simd.hpp"
#include "require.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "scatterlut/io.hpp"
#include "scatterlut/sampler.hpp"
#include "simd4.hpp"

extern "C" {
#include "slut_airlight.h"
}

namespace scatterlut {

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

// The portable radiance (see AirlightTable::radiance, airlight_avx2.cpp).
double AirlightTable::radiance_portable(const AirlightQuery &q) const {
    const slut_airlight_geometry g = detail::airlight_query_near_end(q);
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
    slut_airlight_geometry g = slut_airlight_set_scale(detail::airlight_query_near_end(q));
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

double AirlightTable::one_panel_radiance(const slut_airlight_geometry &g) const {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return detail::airlight_one_panel_radiance4(g);
#endif
    return g.scale_unattenuated * std::exp(-g.optical_distance) *
           (slut_airlight_theta_integral_one_panel(g.c, g.cos_half, g.sin_half, g.tan_dv) / g.sin_gamma);
}

namespace {
double theta_rule8(double c, double w2, double dv) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return detail::airlight_theta_rule8_simd(c, w2, dv);
#endif
    return slut_airlight_theta_integral_rule(c, w2, dv, 0);
}

void logs3(double a, double b, double c, double *la, double *lb, double *lc) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return detail::airlight_logs3_simd(a, b, c, la, lb, lc);
#endif
    *la = std::log(a);
    *lb = std::log(b);
    *lc = std::log(c);
}

void exps2(double a, double b, double *ea, double *eb) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return detail::airlight_exps2_simd(a, b, ea, eb);
#endif
    *ea = std::exp(a);
    *eb = std::exp(b);
}
} // namespace

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

} // namespace scatterlut
