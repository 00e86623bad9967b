// AirlightTable::radiance for a batch of queries: every query checked first (where the CPU has
// AVX2, all their fields as one flat array of doubles), then, where the CPU has AVX2 and FMA,
// four queries at a time (AirlightBatch); elsewhere the scalar radiance query by query.
#include "scatterlut/airlight.hpp"

#include "airlight_near_end.hpp"
#include "airlight_query_ranges.hpp"
#include "require.hpp"

#include <cmath>
#include <cstddef>
#include <cstring>

#include "simd4.hpp"

extern "C" {
#include "slut_airlight.h"
}

namespace scatterlut {

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
