#include "spot_measure.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "measure_util.hpp"
#include "scatterlut/airlight.hpp"

namespace scatterlut {
namespace {

// NaN (a NaN answer) counts as an infinite error.
double relative(double value, double exact) {
    const double r = std::fabs(value - exact) / exact;
    return std::isnan(r) ? HUGE_VAL : r;
}

// f at the point of [0, s] closest to the light (the view ray's closest approach, clamped to
// the ray): what an engine multiplies an unclipped point light's airlight by.
double falloff_at_closest_approach(const SpotQuery &q) {
    const double dn = std::sqrt(q.view_dir[0] * q.view_dir[0] + q.view_dir[1] * q.view_dir[1] +
                                q.view_dir[2] * q.view_dir[2]);
    double t = 0;
    for (int i = 0; i < 3; ++i) t += (q.light.position_m[i] - q.viewer_m[i]) * q.view_dir[i] / dn;
    t = std::clamp(t, 0.0, q.length_m);
    Vec3 point{};
    for (int i = 0; i < 3; ++i) point[i] = q.viewer_m[i] + t * q.view_dir[i] / dn;
    return spot_falloff(q.light, point); // scatterlut/spot.hpp (0 at the apex of a cone)
}

} // namespace

size_t SpotMeasurement::lit() const {
    size_t n = 0;
    for (const SpotViewErrors &v : views) n += v.lit;
    return n;
}

double SpotMeasurement::table_max() const {
    double m = 0;
    for (const SpotViewErrors &v : views)
        for (double e : v.table) m = std::max(m, e);
    return m;
}

SpotMeasurement measure_spot_lights(const SpotServing &serving, size_t rays_per_view, uint64_t seed) {
    SpotMeasurement out;
    const double g = serving.phase_g;
    const detail::PointLightRadiance exact_point = [g](const AirlightQuery &a) { return airlight_radiance_exact(a, g); };
    for (SpotView view : {SpotView::inside, SpotView::beside, SpotView::along}) {
        const std::vector<SpotQuery> rays =
            sample_spot_queries(serving.media, view, rays_per_view, seed + static_cast<uint64_t>(view));
        if (rays.empty()) continue;
        // Per ray: exact, table, band rule, unclipped, closest-approach falloff.
        std::vector<std::array<double, 5>> v(rays.size());
        parallel_for(static_cast<int>(rays.size()), [&](int i) {
            const SpotQuery &q = rays[static_cast<size_t>(i)];
            const double unclipped = airlight_radiance_exact(
                airlight_query_from_points(q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(), q.length_m,
                                           q.sigma_s_per_m, q.sigma_a_per_m, q.light.intensity_W_per_sr),
                g);
            v[static_cast<size_t>(i)] = {spot_airlight_radiance_exact(q, g), serving.table_radiance(q),
                                         detail::spot_airlight_radiance_from(exact_point, q), unclipped,
                                         unclipped * falloff_at_closest_approach(q)};
        });
        SpotViewErrors e;
        e.view = view;
        e.rays = rays.size();
        for (const auto &r : v) {
            if (!std::isfinite(r[0])) continue; // through the lit apex: no finite radiance to compare
            if (r[0] > 0.0 && r[0] < DBL_MIN) continue; // subnormal: fewer digits than any error measured
            if (r[0] == 0.0) {
                e.dark_answered += r[1] != 0.0;
                continue;
            }
            ++e.lit;
            e.table.push_back(relative(r[1], r[0]));
            e.band_rule.push_back(relative(r[2], r[0]));
            e.unclipped.push_back(relative(r[3], r[0]));
            e.closest_falloff.push_back(relative(r[4], r[0]));
        }
        out.views.push_back(std::move(e));
        out.rays.insert(out.rays.end(), rays.begin(), rays.end());
    }
    return out;
}

} // namespace scatterlut
