// The spot light's airlight (scatterlut/spot.hpp, tables/src/spot.cpp, kernels/slut_spot.h;
// docs/PHYSICS.md §1.6) against an independent brute-force reference: Boost.Math adaptive
// Gauss–Kronrod of the physical integrand
//   σ_s p_g(θ_scatter) I0 f(θ(x)) e^{−σ_t (x + d(x))} / d(x)²
// over the whole ray, f evaluated pointwise from the positions (glTF's formula in cos θ, no
// versines), the ray cut at its closest approach to the light and where θ − θ_o or θ − θ_i
// changes sign on a fine scan (bisected; no ray–cone algebra), in the angle φ seen from the
// light (t = t* + h tan φ) so that close passes and infinite rays are proper integrals.
// Then the limits (the point light, a missed beam, rays through the apex), bad input, RGB.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "scatterlut/spot.hpp"
#include "spot_geometry.hpp"

namespace {

using scatterlut::SpotQuery;
using scatterlut::Vec3;

using spot_geometry::kPi;

double rel(double a, double b) {
    if (a == b) return 0.0;
    return std::fabs(a - b) / std::fabs(b);
}
using spot_geometry::dot;
using spot_geometry::add;
using spot_geometry::cross;
using spot_geometry::base_query;
using spot_geometry::norm;
using spot_geometry::unit;

// ---------------------------------------------------------------- the reference
struct Reference {
    const SpotQuery &q;
    double g;
    Vec3 o, d, L, n;
    double t_star, h;
    // The spot angle θ at depth t, by atan2 of the positions.
    double spot_angle(double t) const {
        const Vec3 w = add(add(o, t, d), -1.0, L);
        return std::atan2(norm(cross(n, w)), dot(n, w));
    }
    double falloff(double t) const {
        const double theta = spot_angle(t), to = q.light.outer_angle_rad, ti = q.light.inner_angle_rad;
        if (to == 0.0) return 0.0;
        if (ti == to) return theta <= to ? 1.0 : 0.0;
        const double x = (std::cos(theta) - std::cos(to)) / (std::cos(ti) - std::cos(to));
        const double c = std::fmin(std::fmax(x, 0.0), 1.0);
        return c * c;
    }
    double integrand_t(double t) const {
        const Vec3 w = add(add(o, t, d), -1.0, L);
        const double dist = norm(w);
        const double cos_scatter = -dot(w, d) / dist; // light→point · point→viewer
        const double phase = (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * cos_scatter, 1.5));
        const double st = q.sigma_s_per_m + q.sigma_a_per_m;
        return q.sigma_s_per_m * phase * q.light.intensity_W_per_sr * falloff(t) * std::exp(-st * (t + dist)) /
               (dist * dist);
    }
    double t_of(double phi) const { return t_star + h * std::tan(phi); }
    double integrand_phi(double phi) const {
        const double c = std::cos(phi);
        return integrand_t(t_of(phi)) * h / (c * c);
    }
    // Zeros of spot_angle − α on (p0, p1) in φ, by scan and bisection.
    void crossings(double alpha, double p0, double p1, std::vector<double> &out) const {
        const int n_scan = 4000;
        double prev = p0, fprev = spot_angle(t_of(p0)) - alpha;
        for (int i = 1; i <= n_scan; ++i) {
            const double p = p0 + (p1 - p0) * i / n_scan, fp = spot_angle(t_of(p)) - alpha;
            if ((fprev < 0) != (fp < 0)) {
                double lo = prev, hi = p;
                for (int k = 0; k < 200 && hi - lo > 1e-17; ++k) {
                    const double m = 0.5 * (lo + hi);
                    if (((spot_angle(t_of(m)) - alpha) < 0) == (fprev < 0)) lo = m;
                    else hi = m;
                }
                out.push_back(0.5 * (lo + hi));
            }
            prev = p;
            fprev = fp;
        }
    }
    double value() const {
        const double p0 = std::atan2(-t_star, h);
        const double p1 = std::isinf(q.length_m) ? kPi / 2 : std::atan2(q.length_m - t_star, h);
        std::vector<double> cuts{p0, p1};
        if (p0 < 0 && p1 > 0) cuts.push_back(0.0);
        crossings(q.light.outer_angle_rad, p0, p1, cuts);
        crossings(q.light.inner_angle_rad, p0, p1, cuts);
        std::sort(cuts.begin(), cuts.end());
        double sum = 0;
        for (size_t i = 0; i + 1 < cuts.size(); ++i) {
            if (!(cuts[i + 1] > cuts[i])) continue;
            sum += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
                [this](double phi) { return integrand_phi(phi); }, cuts[i], cuts[i + 1], 15, 1e-11);
        }
        return sum;
    }
};

double reference(const SpotQuery &q, double g) {
    Reference r{q, g, q.viewer_m, unit(q.view_dir), q.light.position_m, unit(q.light.direction), 0, 0};
    const Vec3 lo = add(r.L, -1.0, r.o);
    r.t_star = dot(lo, r.d);
    r.h = norm(cross(r.d, lo));
    return r.value();
}

// ---------------------------------------------------------------- random geometries
// (spot_geometry.hpp: the viewer inside the beam, beside it, on (near) the axis looking along
// it, or in the beam looking away from the light; every third ray infinite; k % 5 == 0 a hard cone)
using spot_geometry::Geometry;
using spot_geometry::random_geometry;

TEST(SpotAirlight, ExactMatchesBoostQuadratureOnRandomGeometries) {
    std::mt19937_64 rng(20240532);
    double worst[4] = {0, 0, 0, 0};
    int zero = 0, checked = 0;
    for (int k = 0; k < 400; ++k) {
        const Geometry G = random_geometry(rng, k);
        const double got = scatterlut::spot_airlight_radiance_exact(G.q, G.g), want = reference(G.q, G.g);
        ASSERT_TRUE(std::isfinite(got)) << k;
        ASSERT_GE(got, 0.0) << k;
        if (want == 0.0) {
            EXPECT_EQ(got, 0.0) << k;
            ++zero;
            continue;
        }
        const double err = rel(got, want);
        worst[G.kind] = std::fmax(worst[G.kind], err);
        ++checked;
        EXPECT_LE(err, 1e-8) << "case " << k << " kind " << G.kind << " got " << got << " want " << want;
    }
    std::printf("spot exact vs Boost: %d geometries (%d unlit), worst: inside %.2e, beside %.2e, along %.2e, "
                "apex behind %.2e\n",
                checked, zero, worst[0], worst[1], worst[2], worst[3]);
}

TEST(SpotAirlight, FullConeIsThePointLight) {
    std::mt19937_64 rng(7);
    double worst = 0;
    for (int k = 0; k < 200; ++k) {
        Geometry G = random_geometry(rng, k);
        G.q.light.outer_angle_rad = G.q.light.inner_angle_rad = kPi;
        const scatterlut::AirlightQuery p = scatterlut::airlight_query_from_points(
            G.q.viewer_m.data(), G.q.view_dir.data(), G.q.light.position_m.data(), G.q.length_m, G.q.sigma_s_per_m,
            G.q.sigma_a_per_m, G.q.light.intensity_W_per_sr);
        const double point = scatterlut::airlight_radiance_exact(p, G.g);
        const double spot = scatterlut::spot_airlight_radiance_exact(G.q, G.g);
        worst = std::fmax(worst, rel(spot, point));
        EXPECT_LE(rel(spot, point), 1e-13) << k;
        // A hard cone that holds the whole ray is the point light too (one piece from the viewer).
        G.q.light.outer_angle_rad = G.q.light.inner_angle_rad = 3.1;
        const Vec3 to_viewer = add(G.q.viewer_m, -1.0, G.q.light.position_m);
        G.q.light.direction = to_viewer;
        G.q.view_dir = to_viewer; // straight away from the light: θ = 0 all along
        const scatterlut::AirlightQuery a = scatterlut::airlight_query_from_points(
            G.q.viewer_m.data(), G.q.view_dir.data(), G.q.light.position_m.data(), G.q.length_m, G.q.sigma_s_per_m,
            G.q.sigma_a_per_m, G.q.light.intensity_W_per_sr);
        EXPECT_LE(rel(scatterlut::spot_airlight_radiance_exact(G.q, G.g), scatterlut::airlight_radiance_exact(a, G.g)),
                  1e-13)
            << k;
    }
    std::printf("θ_o = θ_i = π vs the point light: worst %.2e\n", worst);
}

TEST(SpotAirlight, MissedBeamIsExactlyZero) {
    SpotQuery q = base_query();
    q.light.direction = {0, 0, 1}; // pointing up, away from the ray below
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q, 0.0), 0.0);
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q, 0.7), 0.0);
    q.light.direction = {0, 0, -1};
    q.length_m = 1.0; // the ray ends before the beam (which reaches z = 0 at x ∈ [5 − 4 tan 0.6, …])
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q, 0.0), 0.0);
    q.length_m = 20;
    q.light.outer_angle_rad = q.light.inner_angle_rad = 0.0; // no solid angle
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q, 0.3), 0.0);
    q = base_query();
    q.sigma_s_per_m = 0;
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q), 0.0);
    q = base_query();
    q.length_m = 0;
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q), 0.0);
}

TEST(SpotAirlight, RaysThroughTheApex) {
    SpotQuery q = base_query();
    q.viewer_m = {5, 0, 0};
    q.view_dir = {0, 0, 1}; // up the axis into the light: lit before it
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q), HUGE_VAL);
    q.length_m = 3; // ends before the light: f = 1 all along, the point light's finite value
    const scatterlut::AirlightQuery p = scatterlut::airlight_query_from_points(
        q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(), 3, 0.1, 0.05, 3);
    EXPECT_LE(rel(scatterlut::spot_airlight_radiance_exact(q), scatterlut::airlight_radiance_exact(p)), 1e-15);
    q.viewer_m = {5, 0, 6};
    q.view_dir = {0, 0, -1}; // down through the apex from above: dark before, lit after
    q.length_m = 20;
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q), HUGE_VAL);
    q.view_dir = {1, 0, 0};
    q.viewer_m = {0, 0, 4}; // horizontally through the apex: θ = π/2 on both sides, outside
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q), 0.0);
    q.viewer_m = {5, 0, 4}; // starting at the light, looking sideways: outside
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q), 0.0);
    q.light.outer_angle_rad = q.light.inner_angle_rad = 2.0; // the same ray now lit: +inf
    EXPECT_EQ(scatterlut::spot_airlight_radiance_exact(q), HUGE_VAL);
}

// Degenerate cones and grazing rays: finite, ≥ 0 and the reference's value.
TEST(SpotAirlight, DegenerateConesAndGrazingRays) {
    double worst = 0;
    const double angles[] = {1e-6, 0.01, kPi / 2, kPi / 2 + 1e-9, 2.0, kPi - 1e-6, kPi};
    for (double to : angles) {
        for (int soft = 0; soft < 2; ++soft) {
            for (int ray = 0; ray < 4; ++ray) {
                SpotQuery q = base_query();
                q.light.outer_angle_rad = to;
                q.light.inner_angle_rad = soft ? 0.5 * to : to;
                if (ray == 1) { // parallel to a generator of the cone, 1 m below the apex (A = 0)
                    q.view_dir = {std::sin(to), 0, -std::cos(to)};
                    q.viewer_m = {4, 0.5, 3};
                }
                if (ray == 2) q.length_m = HUGE_VAL;
                if (ray == 3) { // on the cone itself: the generator from the apex
                    q.viewer_m = {5 + std::sin(to), 0, 4 - std::cos(to)};
                    q.view_dir = {std::sin(to), 0, -std::cos(to)};
                }
                SpotQuery in_plane = q;
                in_plane.viewer_m = {4, 0.5, 4};
                in_plane.view_dir = {1, 0.1, 0};
                const double plane = scatterlut::spot_airlight_radiance_exact(in_plane, 0.4);
                ASSERT_TRUE(std::isfinite(plane) && plane >= 0.0) << to << " " << soft << " " << ray;
                const double got = scatterlut::spot_airlight_radiance_exact(q, 0.4);
                ASSERT_TRUE(std::isfinite(got) && got >= 0.0) << to << " " << soft << " " << ray << " " << got;
                // On the boundary f itself jumps; in the apex's plane, for θ_o ≈ π/2, the answer
                // turns on the last bit of the direction (both are only checked for finiteness).
                if (ray == 3) continue;
                const double want = reference(q, 0.4);
                const double err = want == 0.0 ? std::fabs(got) : rel(got, want);
                worst = std::fmax(worst, err);
                EXPECT_LE(err, 1e-8) << to << " " << soft << " " << ray << " got " << got << " want " << want;
            }
        }
    }
    std::printf("degenerate cones vs Boost: worst %.2e\n", worst);
}

TEST(SpotAirlight, BadInputNamesTheField) {
    auto message = [](const SpotQuery &q) -> std::string {
        try {
            scatterlut::spot_airlight_radiance_exact(q);
        } catch (const std::invalid_argument &e) {
            return e.what();
        }
        return "";
    };
    SpotQuery q = base_query();
    q.view_dir = {0, 0, 0};
    EXPECT_NE(message(q).find("view_dir"), std::string::npos);
    q = base_query();
    q.light.direction = {0, 0, 0};
    EXPECT_NE(message(q).find("spot_dir"), std::string::npos);
    q = base_query();
    q.light.inner_angle_rad = 0.7;
    EXPECT_NE(message(q).find("inner_angle"), std::string::npos);
    q = base_query();
    q.light.outer_angle_rad = 3.5;
    EXPECT_NE(message(q).find("outer_angle"), std::string::npos);
    q = base_query();
    q.light.outer_angle_rad = NAN;
    EXPECT_NE(message(q).find("outer_angle"), std::string::npos);
    q = base_query();
    q.viewer_m[1] = NAN;
    EXPECT_NE(message(q).find("viewer"), std::string::npos);
    q = base_query();
    q.light.position_m[2] = HUGE_VAL;
    EXPECT_NE(message(q).find("light_pos"), std::string::npos);
    q = base_query();
    q.length_m = NAN;
    EXPECT_NE(message(q).find("length"), std::string::npos);
    q = base_query();
    q.sigma_a_per_m = -1;
    EXPECT_NE(message(q).find("sigma_a"), std::string::npos);
    q = base_query();
    EXPECT_THROW(scatterlut::spot_airlight_radiance_exact(q, 1.0), std::invalid_argument);
}

TEST(SpotAirlight, RgbIsOneScalarQueryPerChannel) {
    const SpotQuery q = base_query();
    const scatterlut::Rgb ss{0.02, 0.1, 0.4}, sa{0.0, 0.05, 0.2};
    const scatterlut::Rgb got = scatterlut::spot_airlight_radiance_exact_rgb(q, ss, sa, 0.5);
    for (int c = 0; c < 3; ++c) {
        SpotQuery one = q;
        one.sigma_s_per_m = ss[c];
        one.sigma_a_per_m = sa[c];
        EXPECT_EQ(got[c], scatterlut::spot_airlight_radiance_exact(one, 0.5));
    }
    EXPECT_THROW(scatterlut::spot_airlight_radiance_exact_rgb(q, {0.1, -1, 0.1}, sa, 0.0), std::invalid_argument);
}

// spot_falloff(light, point): glTF's f(θ) = clamp((cos θ − cos θ_o)/(cos θ_i − cos θ_o), 0, 1)²
// towards a point, against the formula in cosines at angles away from the edges' rounding; 1 on
// the axis and everywhere for the point light, 0 outside the cone and behind the light; the
// light's fields checked.
TEST(SpotFalloff, GltfFalloffTowardsAPoint) {
    scatterlut::SpotLight l;
    l.position_m = {1, 2, 3};
    l.direction = {0, -2, 0}; // not unit
    l.outer_angle_rad = 0.6;
    l.inner_angle_rad = 0.3;
    l.intensity_W_per_sr = 10;
    const auto at_angle = [&](double theta, double r) {
        return scatterlut::Vec3{1 + r * std::sin(theta), 2 - r * std::cos(theta), 3};
    };
    for (double theta : {0.0, 0.1, 0.29, 0.31, 0.45, 0.59, 0.61, 1.5, 3.0}) {
        const double c = std::cos(theta), co = std::cos(0.6), ci = std::cos(0.3);
        const double x = std::clamp((c - co) / (ci - co), 0.0, 1.0);
        EXPECT_NEAR(scatterlut::spot_falloff(l, at_angle(theta, 7.5)), x * x, 1e-12) << theta;
    }
    EXPECT_EQ(scatterlut::spot_falloff(l, at_angle(0.0, 1e-9)), 1.0);
    EXPECT_EQ(scatterlut::spot_falloff(l, l.position_m), 0.0); // the apex of a cone: no direction, no light
    scatterlut::SpotLight point = l;
    point.outer_angle_rad = point.inner_angle_rad = M_PI;
    for (double theta : {0.0, 1.0, 3.14159})
        EXPECT_EQ(scatterlut::spot_falloff(point, at_angle(theta, 2.0)), 1.0) << theta;
    EXPECT_EQ(scatterlut::spot_falloff(point, point.position_m), 1.0);
    scatterlut::SpotLight bad = l;
    bad.direction = {0, 0, 0};
    EXPECT_THROW(scatterlut::spot_falloff(bad, {0, 0, 0}), std::invalid_argument);
    bad = l;
    bad.inner_angle_rad = 0.7;
    EXPECT_THROW(scatterlut::spot_falloff(bad, {0, 0, 0}), std::invalid_argument);
    EXPECT_THROW(scatterlut::spot_falloff(l, {0, NAN, 0}), std::invalid_argument);
}

} // namespace
