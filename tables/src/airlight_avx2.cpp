// AirlightTable::radiance (one query) where the CPU has AVX2 and FMA (AirlightScalar4), and the
// portable path's steps on 4-lane vectors (airlight_simd.hpp: the one-panel θ-rule, the 8-point
// θ-rule, the two-sample path's logs and exps). The library is built for the baseline x86-64:
// the code here carries SLUT_SIMD4_TARGET and runs only where simd4::available().
#include "scatterlut/airlight.hpp"

#include "airlight_lookup.hpp"
#include "airlight_near_end.hpp"
#include "airlight_query_ranges.hpp"
#include "airlight_simd.hpp"
#include "require.hpp"

#include <algorithm>
#include <cmath>

#include "simd4.hpp"

extern "C" {
#include "slut_airlight.h"
}

namespace scatterlut {

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
// (always inline: AirlightScalar4's call too; detail::airlight_one_panel_radiance4 below for the
// portable path)
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

// a ≤ b ? if_true : if_false without a branch (a blend). The geometry's tests (x ≥ 0, y ≥ 0,
// γ/2 ≤ π/4) go either way at random across queries: as branches they mispredict often.
SLUT_SIMD4_TARGET inline double select_le(double a, double b, double if_true, double if_false) {
    const __m128d mask = _mm_cmp_sd(_mm_set_sd(a), _mm_set_sd(b), _CMP_LE_OQ);
    return _mm_cvtsd_f64(_mm_blendv_pd(_mm_set_sd(if_false), _mm_set_sd(if_true), mask));
}
} // namespace

// The portable path's one-panel rule (AirlightTable::one_panel_radiance) on 4 lanes.
SLUT_SIMD4_TARGET double detail::airlight_one_panel_radiance4(const slut_airlight_geometry &g) {
    return one_panel_radiance4_inline(g, g.tan_dv, 1.0);
}

// The two-sample path's logs and exps (AirlightTable::two_sample_radiance) as one 4-lane log and exp.
SLUT_SIMD4_TARGET void detail::airlight_logs3_simd(double a, double b, double c, double *la, double *lb, double *lc) {
    const v4d l = simd4::log4(v4d{a, b, c, 1.0});
    *la = l[0];
    *lb = l[1];
    *lc = l[2];
}
SLUT_SIMD4_TARGET void detail::airlight_exps2_simd(double a, double b, double *ea, double *eb) {
    const v4d e = simd4::exp4(v4d{a, b, 0.0, 0.0});
    *ea = e[0];
    *eb = e[1];
}

// slut_airlight_theta_integral_rule(c, w2, dv, 0) with each panel's eight node exps as two
// 4-lane exps and its two sines and cosines as one 4-lane sin and cos: the same panels,
// nodes, weights and stopping rule.
SLUT_SIMD4_TARGET double detail::airlight_theta_rule8_simd(double c, double w2, double dv) {
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
                return detail::airlight_one_panel_radiance8(c, cos_half, sin_half, tan_dv, optical_distance,
                                                            scale_unattenuated, sin_gamma);
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
        return (scale_unattenuated * e[2]) * (detail::airlight_theta_rule8_simd(c, w2, angles[1]) / sin_gamma);
    }
};
#endif

// A segment short enough for one panel takes the θ-integral directly (6 exps, more
// accurate than the table and cheaper than two lookups); the others the two table samples
// (slut_airlight_from_gs, which still integrates where they would cancel).
double AirlightTable::radiance(const AirlightQuery &q) const {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return AirlightScalar4::radiance(*this, q, detail::airlight_cpu_has_avx512f());
#endif
    return radiance_portable(q);
}

double detail::airlight_radiance_four_lanes(const AirlightTable &table, const AirlightQuery &q) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return AirlightScalar4::radiance(table, q, false);
#endif
    return table.radiance_portable(q);
}

} // namespace scatterlut
