// The planner's and the report's spot-light measurement (host/src/spot_measure.cpp) and the
// rays it draws (scene_queries.cpp, sample_spot_queries): each view is the geometry it names,
// and the measurement tells a right table path from wrong ones. No device: the "tables" here
// are the exact spot airlight, its band rule on the exact point light, and the unclipped light.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "scene.hpp"
#include "scene_queries.hpp"
#include "spot_measure.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/spot.hpp"

namespace {

using scatterlut::SpotQuery;
using scatterlut::SpotView;

const scatterlut::Scene &spots_scene() {
    static const scatterlut::Scene s =
        scatterlut::load_scene_file(std::string(SLUT_SOURCE_DIR) + "/examples/scenes/fog_spots.toml");
    return s;
}

double dot(const scatterlut::Vec3 &a, const scatterlut::Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const scatterlut::Vec3 &a) { return std::sqrt(dot(a, a)); }

// cos of the angle between the axis and the direction light → viewer.
double cos_theta_of_viewer(const SpotQuery &q) {
    scatterlut::Vec3 w{};
    for (int i = 0; i < 3; ++i) w[i] = q.viewer_m[i] - q.light.position_m[i];
    return dot(w, q.light.direction) / (norm(w) * norm(q.light.direction));
}

TEST(SpotMeasure, ViewsAreTheGeometriesTheyName) {
    for (SpotView view : {SpotView::inside, SpotView::beside, SpotView::along}) {
        const auto rays = scatterlut::sample_spot_queries(spots_scene(), view, 400, 5);
        ASSERT_EQ(rays.size(), 400u) << scatterlut::spot_view_name(view);
        size_t entering = 0, infinite = 0;
        for (const SpotQuery &q : rays) {
            EXPECT_NO_THROW(scatterlut::check_spot_query(q));
            const double c = cos_theta_of_viewer(q), c_outer = std::cos(q.light.outer_angle_rad);
            const double D = norm(q.viewer_m);
            EXPECT_TRUE(D >= 1.0 - 1e-12 && D <= 40.0 + 1e-12) << D; // the lights' distance ranges
            if (view == SpotView::inside) {
                EXPECT_GE(c, c_outer - 1e-12);
            }
            if (view == SpotView::beside) {
                EXPECT_LT(c, c_outer + 1e-12);
            }
            if (view == SpotView::along) {
                EXPECT_GT(std::fabs(c), 1 - 1e-12); // on the axis line
                const double along = std::fabs(dot(q.view_dir, q.light.direction)) / norm(q.view_dir);
                EXPECT_GE(along, std::cos(q.light.outer_angle_rad) - 1e-12);
            }
            infinite += std::isinf(q.length_m);
            const scatterlut::SpotRay r = scatterlut::spot_ray_pieces(SpotQuery{q.sigma_s_per_m, q.sigma_a_per_m,
                                                                                q.viewer_m, q.view_dir, HUGE_VAL, q.light});
            entering += !r.pieces.empty();
        }
        // Beside: every ray is aimed at a point of the beam, so its line enters it.
        if (view == SpotView::beside) {
            EXPECT_EQ(entering, rays.size());
        } else {
            EXPECT_GT(entering, rays.size() / 3) << scatterlut::spot_view_name(view);
        }
        EXPECT_GT(infinite, rays.size() / 8);
        EXPECT_LT(infinite, rays.size() * 3 / 8);
    }
    // The two lights in turn; a scene without spots draws none.
    const auto both = scatterlut::sample_spot_queries(spots_scene(), SpotView::inside, 2, 5);
    EXPECT_NE(both[0].light.intensity_W_per_sr, both[1].light.intensity_W_per_sr);
    const scatterlut::Scene street =
        scatterlut::load_scene_file(std::string(SLUT_SOURCE_DIR) + "/examples/scenes/fog_street.toml");
    EXPECT_TRUE(scatterlut::sample_spot_queries(street, SpotView::inside, 10, 5).empty());
}

scatterlut::SpotMeasurement measure_with(std::function<double(const SpotQuery &)> table) {
    scatterlut::SpotServing s{spots_scene(), 0.0, std::move(table)};
    return scatterlut::measure_spot_lights(s, 60, 3);
}

TEST(SpotMeasure, TellsTheRightAnswerFromWrongOnes) {
    // The exact spot airlight as the "table": no error; the views and their lit rays counted.
    const auto exact = measure_with([](const SpotQuery &q) { return scatterlut::spot_airlight_radiance_exact(q); });
    ASSERT_EQ(exact.views.size(), 3u);
    EXPECT_EQ(exact.rays.size(), 180u);
    EXPECT_EQ(exact.table_max(), 0.0);
    size_t dark = 0;
    for (const auto &v : exact.views) {
        EXPECT_GT(v.lit, 10u) << scatterlut::spot_view_name(v.view);
        EXPECT_EQ(v.dark_answered, 0u);
        dark += v.rays - v.lit;
        // The band rule alone (docs/SPOT.md: within 1.1e-5 of the exact spot airlight).
        for (double e : v.band_rule) EXPECT_LE(e, 1e-4);
    }
    EXPECT_GT(dark, 0u); // some rays miss the beams: the dark rays are checked too
    // The point light without its cone lights the rays beside the beam from everywhere.
    const auto unclipped = measure_with([](const SpotQuery &q) {
        return scatterlut::airlight_radiance_exact(scatterlut::airlight_query_from_points(
            q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(), q.length_m, q.sigma_s_per_m,
            q.sigma_a_per_m, q.light.intensity_W_per_sr));
    });
    EXPECT_GT(unclipped.table_max(), 1.0);
    size_t wrongly_lit = 0;
    for (const auto &v : unclipped.views) wrongly_lit += v.dark_answered;
    EXPECT_GT(wrongly_lit, 0u);
    // A NaN answer is an infinite error, not a skipped ray.
    const auto nan = measure_with([](const SpotQuery &) { return std::nan(""); });
    EXPECT_TRUE(std::isinf(nan.table_max()));
    // A 1e-3 bias is measured as 1e-3.
    const auto biased =
        measure_with([](const SpotQuery &q) { return (1 + 1e-3) * scatterlut::spot_airlight_radiance_exact(q); });
    EXPECT_NEAR(biased.table_max(), 1e-3, 1e-12);
}

} // namespace
