// The spot airlight from the point-light airlight tables (scatterlut/spot.hpp,
// tables/src/spot_table.cpp; docs/SPOT.md): against the exact spot airlight on random cones and
// rays, split into the band rule's own error (the table path with the exact point-light radiance
// in place of the table's) and the whole table path (isotropic table, and an anisotropic table of
// g = 0.6, both filled by quadrature here), beside the point-light table's own error on the
// same rays. Also the point light (θ_o = θ_i = π) and the RGB entry points.
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "airlight_quadrature_table.hpp"
#include "generate_airlight.hpp"
#include "scatterlut/spot.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_airlight_hg.h"
#include "slut_axes.h"
}

namespace {

using scatterlut::SpotQuery;
using scatterlut::Vec3;

double rel(double a, double b) {
    if (a == b) return 0.0;
    return std::fabs(a - b) / std::fabs(b);
}

const scatterlut::AirlightTable &iso_table() {
    static const scatterlut::AirlightTable table(slut_test::airlight_quadrature_table(0.0, 256, 128));
    return table;
}
const scatterlut::AirlightHgTable &hg_table() {
    static const scatterlut::AirlightHgTable table(slut_test::airlight_quadrature_table(0.6, 256, 128));
    return table;
}

Vec3 unit(Vec3 v) {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return {v[0] / n, v[1] / n, v[2] / n};
}

// A soft cone (θ_i < θ_o) seen from inside, beside or along the beam (k % 3); every fourth
// ray infinite.
SpotQuery random_spot(std::mt19937_64 &rng, int k) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto random_unit = [&] { return unit({2 * U(rng) - 1, 2 * U(rng) - 1, 2 * U(rng) - 1 + 1e-3}); };
    SpotQuery q;
    q.sigma_s_per_m = 0.02 + 0.3 * U(rng);
    q.sigma_a_per_m = 0.1 * U(rng);
    q.light.position_m = {0, 0, 4};
    q.light.direction = random_unit();
    q.light.outer_angle_rad = 0.2 + 1.2 * U(rng);
    q.light.inner_angle_rad = q.light.outer_angle_rad * 0.8 * U(rng);
    q.light.intensity_W_per_sr = 1;
    const Vec3 n = unit(q.light.direction);
    const double r = 1 + 10 * U(rng);
    if (k % 3 == 2) q.viewer_m = {r * n[0] + 0.2 * U(rng), r * n[1], 4 + r * n[2]};
    else q.viewer_m = {10 * U(rng) - 5, 10 * U(rng) - 5, 10 * U(rng) - 1};
    q.view_dir = k % 3 == 2 ? Vec3{-n[0] + 0.1 * U(rng), -n[1], -n[2]} : random_unit();
    q.length_m = k % 4 == 0 ? std::numeric_limits<double>::infinity() : 1 + 30 * U(rng);
    return q;
}

TEST(SpotAirlightTable, BandRuleAndTablesAgainstExact) {
    std::mt19937_64 rng(32);
    double worst_rule = 0, worst_iso = 0, worst_hg = 0, worst_point_iso = 0, worst_point_hg = 0;
    int lit = 0;
    const scatterlut::detail::PointLightRadiance exact_point = [](const scatterlut::AirlightQuery &a) {
        return scatterlut::airlight_radiance_exact(a);
    };
    for (int k = 0; k < 600; ++k) {
        const SpotQuery q = random_spot(rng, k);
        const double exact = scatterlut::spot_airlight_radiance_exact(q);
        const double exact_hg = scatterlut::spot_airlight_radiance_exact(q, 0.6);
        if (!(exact > 0.0)) {
            EXPECT_EQ(scatterlut::spot_airlight_radiance(iso_table(), q), 0.0);
            continue;
        }
        ++lit;
        const double rule = scatterlut::detail::spot_airlight_radiance_from(exact_point, q);
        const double iso = scatterlut::spot_airlight_radiance(iso_table(), q);
        const double hg = scatterlut::spot_airlight_radiance(hg_table(), q);
        EXPECT_TRUE(std::isfinite(iso) && iso >= 0.0 && std::isfinite(hg) && hg >= 0.0) << k;
        worst_rule = std::fmax(worst_rule, rel(rule, exact));
        worst_iso = std::fmax(worst_iso, rel(iso, exact));
        worst_hg = std::fmax(worst_hg, rel(hg, exact_hg));
        // The point light's own table error on the same ray (the floor under the spot's).
        const scatterlut::AirlightQuery p = scatterlut::airlight_query_from_points(
            q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(), q.length_m, q.sigma_s_per_m,
            q.sigma_a_per_m, 1);
        worst_point_iso = std::fmax(worst_point_iso, rel(iso_table().radiance(p), scatterlut::airlight_radiance_exact(p)));
        worst_point_hg =
            std::fmax(worst_point_hg, rel(hg_table().radiance(p), scatterlut::airlight_radiance_exact(p, 0.6)));
    }
    std::printf("spot from tables, %d lit rays: band rule (exact point radiance) %.2e; isotropic table %.2e "
                "(point light on the same rays %.2e); g = 0.6 table %.2e (point light %.2e)\n",
                lit, worst_rule, worst_iso, worst_point_iso, worst_hg, worst_point_hg);
    EXPECT_GE(lit, 200);
    EXPECT_LE(worst_rule, 3e-5); // measured 1.1e-5
    EXPECT_LE(worst_iso, 1e-3);  // measured 3.9e-4, the 256 × 128 table's own 3.7e-4 on the same rays
    EXPECT_LE(worst_hg, 1e-3);
}

TEST(SpotAirlightTable, PointLightAndRgb) {
    SpotQuery q;
    q.sigma_s_per_m = 0.1;
    q.sigma_a_per_m = 0.02;
    q.viewer_m = {0, 0, 0};
    q.view_dir = {1, 0, 0.2};
    q.length_m = 25;
    q.light.position_m = {6, 1, 3};
    q.light.direction = {0, 0, -1};
    q.light.outer_angle_rad = q.light.inner_angle_rad = 3.14159265358979323846;
    q.light.intensity_W_per_sr = 2;
    const scatterlut::AirlightQuery p = scatterlut::airlight_query_from_points(
        q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(), 25, 0.1, 0.02, 2);
    EXPECT_EQ(scatterlut::spot_airlight_radiance(iso_table(), q), iso_table().radiance(p));
    EXPECT_EQ(scatterlut::spot_airlight_radiance(hg_table(), q), hg_table().radiance(p));
    q.light.outer_angle_rad = 0.7;
    q.light.inner_angle_rad = 0.4;
    const scatterlut::Rgb ss{0.05, 0.1, 0.2}, sa{0, 0.01, 0.02};
    const scatterlut::Rgb got = scatterlut::spot_airlight_radiance_rgb(hg_table(), q, ss, sa);
    for (int c = 0; c < 3; ++c) {
        SpotQuery one = q;
        one.sigma_s_per_m = ss[c];
        one.sigma_a_per_m = sa[c];
        EXPECT_EQ(got[c], scatterlut::spot_airlight_radiance(hg_table(), one));
        EXPECT_LE(rel(got[c], scatterlut::spot_airlight_radiance_exact(one, 0.6)), 2e-3);
    }
}


// Band pieces many extinction lengths long: a ray from behind the light, past it and along the
// beam, enters the falloff band 1 km away and stays in it to infinity (found by `report`'s view
// "along" on examples/scenes/fog_spots.toml, where one 8-point rule over the whole piece was off
// by 39 %: the rest R(t) falls by e^{-42} across it). Cut into sub-pieces of a few optical
// depths and ended in closed form, the rule holds its error however long the piece, in thin
// and in dense fog, on both forms of the parts (f rising along the ray, and falling).
TEST(SpotAirlightTable, LongBandPiecesKeepTheirDigits) {
    const scatterlut::detail::PointLightRadiance exact_point = [](const scatterlut::AirlightQuery &a) {
        return scatterlut::airlight_radiance_exact(a);
    };
    SpotQuery q;
    q.sigma_s_per_m = 0.04;
    q.sigma_a_per_m = 0.002;
    q.viewer_m = {0, 28.9925315, -8.69775945};
    q.view_dir = {0.178692764, -0.911228883, 0.37112103};
    q.length_m = std::numeric_limits<double>::infinity();
    q.light.position_m = {0, 0, 0};
    q.light.direction = {0, -0.957826, 0.287348};
    q.light.outer_angle_rad = 0.20944;
    q.light.inner_angle_rad = 0.139626;
    q.light.intensity_W_per_sr = 2000;
    for (double scale : {1.0, 0.1, 5.0}) {
        SpotQuery d = q;
        d.sigma_s_per_m *= scale;
        d.sigma_a_per_m *= scale;
        const double exact = scatterlut::spot_airlight_radiance_exact(d);
        ASSERT_GT(exact, 0.0) << scale;
        EXPECT_NEAR(scatterlut::detail::spot_airlight_radiance_from(exact_point, d), exact, 1e-5 * exact) << scale;
    }
    // The same band crossed the other way (f falling along the ray): from far inside the beam
    // back towards the light's rear.
    SpotQuery back = q;
    const double far_m = 3000;
    for (int i = 0; i < 3; ++i) {
        back.viewer_m[i] = q.viewer_m[i] + far_m * q.view_dir[i];
        back.view_dir[i] = -q.view_dir[i];
    }
    back.length_m = far_m;
    const double exact = scatterlut::spot_airlight_radiance_exact(back);
    ASSERT_GT(exact, 0.0);
    EXPECT_NEAR(scatterlut::detail::spot_airlight_radiance_from(exact_point, back), exact, 1e-5 * exact);
}

} // namespace
