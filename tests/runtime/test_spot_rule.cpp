// The GPU snippets' spot rule (kernels/slut_spot_rule.h; docs/SPOT.md "On the GPU") in double,
// with the exact point-light airlight in place of a table's (scatterlut::detail::
// spot_airlight_radiance_gpu_rule): the rule's own error against the exact spot airlight
// (spot_airlight_radiance_exact), per population, at the tolerances docs/SPOT.md states; hard
// cones and the limits (the point light, no solid angle, rays through the apex, γ = 0 and π);
// and the runtime's batch calls (bit for bit the scalar calls) and spot_query_from_points.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "airlight_quadrature_table.hpp"
#include "generate_airlight.hpp"
#include "scatterlut/spot.hpp"
#include "spot_geometry.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_airlight_hg.h"
#include "slut_axes.h"
#include "slut_spot_rule.h"
}

namespace {

using scatterlut::SpotQuery;
using scatterlut::Vec3;
using spot_geometry::base_query;
using spot_geometry::kPi;

double rel(double a, double b) {
    if (a == b) return 0.0;
    return std::fabs(a - b) / std::fabs(b);
}

double rule(const SpotQuery &q, double g) {
    return scatterlut::detail::spot_airlight_radiance_gpu_rule(
        [g](const scatterlut::AirlightQuery &a) { return scatterlut::airlight_radiance_exact(a, g); }, q, g);
}

// Whether the ray reaches the inner cone (the estimator), and the band's optical length Λ.
struct RayClass {
    bool reaches_core = false;
    double band_optical_length = 0;
};
RayClass classify(const SpotQuery &q) {
    auto v = [](const Vec3 &a) { return slut_vec3_make(a[0], a[1], a[2]); };
    const slut_spot_ray ray = slut_spot_ray_of(v(q.viewer_m), v(q.view_dir), v(q.light.position_m),
                                               v(q.light.direction), q.light.outer_angle_rad,
                                               q.light.inner_angle_rad, q.length_m);
    RayClass c;
    c.reaches_core = slut_spot_interval_of(ray).has_core != 0;
    c.band_optical_length = spot_geometry::band_optical_length(q);
    return c;
}

struct Errors {
    std::vector<double> e;
    void add(double x) { e.push_back(x); }
    double max() const { return e.empty() ? 0.0 : *std::max_element(e.begin(), e.end()); }
    double quantile(double p) const {
        if (e.empty()) return 0.0;
        std::vector<double> s = e;
        std::sort(s.begin(), s.end());
        return s[static_cast<size_t>(p * static_cast<double>(s.size() - 1))];
    }
};

// The rule against the exact spot airlight on one population: every query within
// rule_tolerance, relative to the spot's radiance for θ_o ≤ π/2, to the point light's radiance
// of the whole ray (T) beyond (where the dark cone's light is subtracted from T); the errors
// printed by Λ and class.
void run_population(const char *name, const spot_geometry::Ranges &R, int n, unsigned seed, double phase_g_or_nan,
                    size_t min_core, size_t min_band_only) {
    std::mt19937_64 rng(seed);
    Errors core, band_only, by_length[3], wide, thick;
    int unlit = 0;
    for (int k = 0; k < n; ++k) {
        const spot_geometry::Geometry G = spot_geometry::random_geometry(rng, k, R);
        const double g = std::isnan(phase_g_or_nan) ? G.g : phase_g_or_nan;
        const double exact = scatterlut::spot_airlight_radiance_exact(G.q, g);
        const double got = rule(G.q, g);
        ASSERT_TRUE(got >= 0.0 && !std::isnan(got)) << name << " " << k << ": " << got;
        if (std::isinf(exact)) {
            EXPECT_EQ(got, exact) << name << " " << k;
            continue;
        }
        const RayClass c = classify(G.q);
        const spot_geometry::RuleTolerance tol = spot_geometry::rule_tolerance(G.q, g);
        if (tol.relative_to_whole) {
            const scatterlut::AirlightQuery p = scatterlut::airlight_query_from_points(
                G.q.viewer_m.data(), G.q.view_dir.data(), G.q.light.position_m.data(), G.q.length_m,
                G.q.sigma_s_per_m, G.q.sigma_a_per_m, G.q.light.intensity_W_per_sr);
            const double whole = scatterlut::airlight_radiance_exact(p, g);
            const double e = whole > 0.0 ? std::fabs(got - exact) / whole : std::fabs(got - exact);
            (G.q.light.outer_angle_rad > 0.5 * kPi ? wide : thick).add(e);
            EXPECT_LE(e, tol.tol) << name << " " << k << " (relative to the whole ray's " << whole << "): got " << got
                                  << ", exact " << exact;
            continue;
        }
        if (exact == 0.0) {
            EXPECT_EQ(got, 0.0) << name << " " << k;
            ++unlit;
            continue;
        }
        const double e = rel(got, exact);
        (c.reaches_core ? core : band_only).add(e);
        const double L = c.band_optical_length;
        by_length[L <= 2 ? 0 : L <= 4 ? 1 : 2].add(e);
        EXPECT_LE(e, tol.tol) << name << " " << k << ": Λ = " << L << (c.reaches_core ? ", reaches the core" : ", band only")
                          << ": got " << got << ", exact " << exact;
    }
    std::printf("%s: Λ ≤ 8: reaches the inner cone n=%zu max %.2e p99 %.2e median %.2e | band only n=%zu max %.2e "
                "p99 %.2e | by Λ: <=2 n=%zu max %.2e, <=4 n=%zu max %.2e, <=8 n=%zu max %.2e | relative to the whole "
                "ray's point light: Λ > 8 n=%zu max %.2e, theta_o > pi/2 n=%zu max %.2e | unlit %d\n",
                name, core.e.size(), core.max(), core.quantile(0.99), core.quantile(0.5), band_only.e.size(),
                band_only.max(), band_only.quantile(0.99), by_length[0].e.size(), by_length[0].max(),
                by_length[1].e.size(), by_length[1].max(), by_length[2].e.size(), by_length[2].max(), thick.e.size(),
                thick.max(), wide.e.size(), wide.max(), unlit);
    EXPECT_GE(core.e.size(), min_core) << name;
    EXPECT_GE(band_only.e.size(), min_band_only) << name;
}

TEST(SpotRule, AgainstTheExactAirlightOnTypicalSoftCones) {
    const spot_geometry::Ranges typical = spot_geometry::typical_ranges();
    run_population("typical cones, g = 0", typical, 1200, 71, 0.0, 400, 40);
    run_population("typical cones, g = 0.85", typical, 1200, 72, 0.85, 400, 40);
    run_population("typical cones, g = -0.5", typical, 600, 73, -0.5, 200, 20);
}

TEST(SpotRule, AgainstTheExactAirlightOnAnyCone) {
    // test_spot's population: θ_o up to 2.75, bands up to 0.95 θ_o, σ_t up to 0.8/m, g in
    // [−0.3, 0.85], a hard cone every fifth query.
    run_population("any cone (test_spot's population)", spot_geometry::Ranges(), 1600, 20240532,
                   std::numeric_limits<double>::quiet_NaN(), 400, 40);
}

TEST(SpotRule, HardConesAreThePointLightOnTheirInterval) {
    // A hard cone within glTF's range has no band: the rule is the point light's radiance of the
    // lit interval, to the exact airlight's own precision.
    std::mt19937_64 rng(5);
    spot_geometry::Ranges narrow;
    narrow.outer_max = 0.5 * kPi;
    double worst = 0;
    int n = 0;
    for (int k = 0; k < 600; ++k) {
        const spot_geometry::Geometry G = spot_geometry::random_geometry(rng, k, narrow);
        if (k % 5 != 0) continue; // k % 5 == 0: hard cones
        const double exact = scatterlut::spot_airlight_radiance_exact(G.q, G.g);
        if (!(exact > 0.0) || std::isinf(exact)) continue;
        worst = std::fmax(worst, rel(rule(G.q, G.g), exact));
        ++n;
    }
    std::printf("hard cones: %d lit, worst %.2e\n", n, worst);
    EXPECT_GE(n, 40);
    EXPECT_LE(worst, 1e-11);
}

TEST(SpotRule, Limits) {
    // θ_o = θ_i = π: the point light (the one interval is the whole ray).
    std::mt19937_64 rng(9);
    for (int k = 0; k < 100; ++k) {
        spot_geometry::Geometry G = spot_geometry::random_geometry(rng, k);
        G.q.light.outer_angle_rad = G.q.light.inner_angle_rad = kPi;
        const scatterlut::AirlightQuery p = scatterlut::airlight_query_from_points(
            G.q.viewer_m.data(), G.q.view_dir.data(), G.q.light.position_m.data(), G.q.length_m, G.q.sigma_s_per_m,
            G.q.sigma_a_per_m, G.q.light.intensity_W_per_sr);
        EXPECT_LE(rel(rule(G.q, G.g), scatterlut::airlight_radiance_exact(p, G.g)), 1e-12) << k;
        // θ_o = π with a softer inside: f = ((1 + cos θ)/(1 + cos θ_i))² off the inner cone; the
        // whole ray is the interval, D the inner cone's complement (error relative to T).
        G.q.light.inner_angle_rad = 1.0;
        const double exact = scatterlut::spot_airlight_radiance_exact(G.q, G.g);
        const double whole = scatterlut::airlight_radiance_exact(p, G.g);
        if (std::isfinite(exact) && exact > 0.0) {
            EXPECT_LE(std::fabs(rule(G.q, G.g) - exact) / whole, spot_geometry::rule_tolerance(G.q, G.g).tol) << k;
        }
    }
    SpotQuery q = base_query();
    q.light.outer_angle_rad = q.light.inner_angle_rad = 0.0; // no solid angle
    EXPECT_EQ(rule(q, 0.0), 0.0);
    q = base_query();
    q.light.direction = {0, 0, 1}; // the beam points away from the ray
    EXPECT_EQ(rule(q, 0.3), 0.0);
    // Rays through the apex: up the axis into the light (lit before it): +inf; ending short of
    // it: the point light's value; down through it from above (dark, then lit): +inf; sideways
    // through it (θ = π/2 on both sides, outside the beam): 0.
    q = base_query();
    q.viewer_m = {5, 0, 0};
    q.view_dir = {0, 0, 1};
    EXPECT_EQ(rule(q, 0.0), HUGE_VAL);
    q.length_m = 3;
    const scatterlut::AirlightQuery p = scatterlut::airlight_query_from_points(
        q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(), 3, 0.1, 0.05, 3);
    EXPECT_LE(rel(rule(q, 0.0), scatterlut::airlight_radiance_exact(p)), 1e-13);
    q.viewer_m = {5, 0, 6};
    q.view_dir = {0, 0, -1};
    q.length_m = 20;
    EXPECT_EQ(rule(q, 0.0), HUGE_VAL);
    q.view_dir = {1, 0, 0};
    q.viewer_m = {0, 0, 4};
    EXPECT_EQ(rule(q, 0.0), 0.0);
    q.light.outer_angle_rad = 2.0; // the same ray in a beam wider than π/2, soft (θ_i = 0.3):
    q.light.inner_angle_rad = 0.3; // f = ((cos θ − cos θ_o)/(cos θ_i − cos θ_o))² at θ = π/2
    EXPECT_EQ(rule(q, 0.0), HUGE_VAL);
    // γ = 0 short of the light and γ = π (looking away), inside and beside a soft beam: finite,
    // ≥ 0, the exact value within the rule's tolerance.
    for (const Vec3 &viewer : {Vec3{5, 0, -3}, Vec3{5, 3, 0}, Vec3{1, 0, 0}}) {
        for (double sign : {1.0, -1.0}) {
            q = base_query();
            q.viewer_m = viewer;
            q.view_dir = spot_geometry::add({0, 0, 0}, sign, spot_geometry::add(q.light.position_m, -1.0, viewer));
            q.length_m = 0.5 * spot_geometry::norm(q.view_dir);
            const double got = rule(q, 0.5), want = scatterlut::spot_airlight_radiance_exact(q, 0.5);
            EXPECT_TRUE(std::isfinite(got) && got >= 0.0) << viewer[0] << " " << sign;
            EXPECT_LE(want == 0.0 ? got : rel(got, want), 3e-3) << viewer[0] << " " << viewer[1] << " " << sign;
        }
    }
}

// ---------------------------------------------------------------- the runtime's calls

TEST(SpotBatch, EqualsTheScalarCallBitForBit) {
    const scatterlut::AirlightTable iso(slut_test::airlight_quadrature_table(0.0, 96, 48));
    const scatterlut::AirlightHgTable hg(slut_test::airlight_quadrature_table(0.6, 96, 48));
    std::mt19937_64 rng(11);
    std::vector<SpotQuery> qs;
    for (int k = 0; k < 120; ++k) qs.push_back(spot_geometry::random_geometry(rng, k).q);
    std::vector<double> a(qs.size()), b(qs.size());
    scatterlut::spot_airlight_radiance(iso, qs.data(), qs.size(), a.data());
    scatterlut::spot_airlight_radiance(hg, qs.data(), qs.size(), b.data());
    int lit = 0;
    for (size_t i = 0; i < qs.size(); ++i) {
        const double s_iso = scatterlut::spot_airlight_radiance(iso, qs[i]);
        const double s_hg = scatterlut::spot_airlight_radiance(hg, qs[i]);
        EXPECT_EQ(std::memcmp(&a[i], &s_iso, sizeof(double)), 0) << i << ": " << a[i] << " vs " << s_iso;
        EXPECT_EQ(std::memcmp(&b[i], &s_hg, sizeof(double)), 0) << i << ": " << b[i] << " vs " << s_hg;
        lit += s_iso > 0.0;
    }
    EXPECT_GE(lit, 40);
    const scatterlut::Rgb ss{0.02, 0.1, 0.3}, sa{0.0, 0.01, 0.05};
    std::vector<scatterlut::Rgb> c(qs.size()), d(qs.size());
    scatterlut::spot_airlight_radiance_rgb(iso, qs.data(), qs.size(), ss, sa, c.data());
    scatterlut::spot_airlight_radiance_rgb(hg, qs.data(), qs.size(), ss, sa, d.data());
    for (size_t i = 0; i < qs.size(); ++i) {
        const scatterlut::Rgb s_iso = scatterlut::spot_airlight_radiance_rgb(iso, qs[i], ss, sa);
        const scatterlut::Rgb s_hg = scatterlut::spot_airlight_radiance_rgb(hg, qs[i], ss, sa);
        EXPECT_EQ(std::memcmp(c[i].data(), s_iso.data(), sizeof s_iso), 0) << i;
        EXPECT_EQ(std::memcmp(d[i].data(), s_hg.data(), sizeof s_hg), 0) << i;
    }
    // A bad query: named by its index, nothing written.
    qs[57].light.inner_angle_rad = qs[57].light.outer_angle_rad + 0.1;
    std::vector<double> untouched(qs.size(), -7.0);
    try {
        scatterlut::spot_airlight_radiance(iso, qs.data(), qs.size(), untouched.data());
        ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("query 57: inner_angle"), std::string::npos) << e.what();
    }
    for (double x : untouched) EXPECT_EQ(x, -7.0);
    std::vector<scatterlut::Rgb> untouched_rgb(qs.size(), scatterlut::Rgb{-7.0, -7.0, -7.0});
    EXPECT_THROW(scatterlut::spot_airlight_radiance_rgb(hg, qs.data(), qs.size(), ss, sa, untouched_rgb.data()),
                 std::invalid_argument);
    for (const scatterlut::Rgb &x : untouched_rgb) EXPECT_EQ(x[0], -7.0);
    qs[57].light.inner_angle_rad = 0.0;
    EXPECT_THROW(scatterlut::spot_airlight_radiance_rgb(iso, qs.data(), qs.size(), {0.1, -1.0, 0.1}, sa, c.data()),
                 std::invalid_argument);
}

TEST(SpotQueryFromPoints, FillsEveryFieldAndChecks) {
    const double viewer[3] = {1, 2, 3}, dir[3] = {0, 0, 2}, light[3] = {4, 5, 6}, axis[3] = {0, -1, 0};
    const SpotQuery q = scatterlut::spot_query_from_points(viewer, dir, light, axis, 0.7, 0.2, 12.0, 0.05, 0.01, 8.0);
    EXPECT_EQ(q.viewer_m, (Vec3{1, 2, 3}));
    EXPECT_EQ(q.view_dir, (Vec3{0, 0, 2}));
    EXPECT_EQ(q.light.position_m, (Vec3{4, 5, 6}));
    EXPECT_EQ(q.light.direction, (Vec3{0, -1, 0}));
    EXPECT_EQ(q.light.outer_angle_rad, 0.7);
    EXPECT_EQ(q.light.inner_angle_rad, 0.2);
    EXPECT_EQ(q.length_m, 12.0);
    EXPECT_EQ(q.sigma_s_per_m, 0.05);
    EXPECT_EQ(q.sigma_a_per_m, 0.01);
    EXPECT_EQ(q.light.intensity_W_per_sr, 8.0);
    const double zero[3] = {0, 0, 0};
    try {
        scatterlut::spot_query_from_points(viewer, dir, light, zero, 0.7, 0.2, 12.0, 0.05, 0.01, 8.0);
        ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("spot_dir"), std::string::npos) << e.what();
    }
    EXPECT_THROW(scatterlut::spot_query_from_points(viewer, dir, light, axis, 0.7, 0.9, 12.0, 0.05, 0.01, 8.0),
                 std::invalid_argument);
}

} // namespace
