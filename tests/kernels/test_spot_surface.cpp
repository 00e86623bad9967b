// A surface point lit by a spot light through the medium, exact (scatterlut/spot_surface.hpp,
// tables/src/spot_surface.cpp; docs/SPOT.md "Surfaces lit by a spot"): the triple integral over
// the medium around the light against
//  (1) the point light (θ_i = θ_o = π) of surface.hpp, whose G_n is a different integral (over
//      directions from P, about the direction to the light, with Sun et al. 2005's A(T, γ) and
//      the azimuthal kernels in closed form): n = 1, 20, 200 over T and θ;
//  (2) an independent brute force: Boost.Math adaptive Gauss–Kronrod (31 points) over the
//      directions ω from P (polar angle about the direction to the light, azimuth) of the
//      spot's exact airlight along the infinite ray from P (spot_airlight_radiance_exact) times
//      max(ℓ·ω, 0)^n sin χ: no cone algebra, no break points;
//  (3) limits and properties (no beam, no scattering, the glow outside the beam, monotone in
//      the cone, the soft cone between its hard inner and outer cones, scale invariance);
//  (4) bad input refused, naming the field.
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "scatterlut/spot.hpp"
#include "scatterlut/spot_surface.hpp"
#include "scatterlut/surface.hpp"

namespace {

using scatterlut::SpotSurfacePoint;
using scatterlut::Vec3;

constexpr double kPi = 3.14159265358979323846;

double rel(double a, double b) { return a == b ? 0.0 : std::fabs(a - b) / std::fabs(b); }
double dot(const Vec3 &a, const Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 add(const Vec3 &a, double k, const Vec3 &b) { return {a[0] + k * b[0], a[1] + k * b[1], a[2] + k * b[2]}; }
Vec3 scale(double k, const Vec3 &a) { return {k * a[0], k * a[1], k * a[2]}; }
Vec3 cross(const Vec3 &a, const Vec3 &b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 unit(const Vec3 &a) { return scale(1.0 / std::sqrt(dot(a, a)), a); }

// A spot at a skew position and axis (no coordinate axis special); P at spot angle θ_P and
// distance D from the light; the lobe axis at angle `lobe_angle` from the direction P → light,
// tilted towards `tilt` (any vector not along that direction). σ_t D = T, σ_s = 0.7 σ_t.
struct SpotScene {
    double outer = kPi, inner = kPi, theta_P = 0.1, D = 2.0, T = 1.0, lobe_angle = 0.5;
    Vec3 tilt{0.3, 0.2, 1.0};
    Vec3 azimuth{1.0, 0.0, 0.0}; // the side P lies on, seen from the axis
    SpotSurfacePoint point() const {
        SpotSurfacePoint q;
        q.light.position_m = {0.3, -1.1, 1.4};
        q.light.direction = {0.4, 2.0, 0.6}; // not unit: the library normalises
        q.light.outer_angle_rad = outer;
        q.light.inner_angle_rad = inner;
        q.light.intensity_W_per_sr = 3.0;
        const Vec3 m = unit(q.light.direction), across = unit(cross(m, azimuth));
        const Vec3 to_point = add(scale(std::cos(theta_P), m), std::sin(theta_P), across);
        q.point_m = add(q.light.position_m, D, to_point);
        q.sigma_s_per_m = 0.7 * T / D;
        q.sigma_a_per_m = 0.3 * T / D;
        const Vec3 to_light = scale(-1.0, to_point), side = unit(cross(to_light, tilt));
        q.lobe_axis = scale(1.7, add(scale(std::cos(lobe_angle), to_light), std::sin(lobe_angle), side));
        return q;
    }
};

// The brute force (2): ∫ L_in(P, ω) max(ℓ·ω, 0)^n dω over the sphere, ω = cos χ ω_l + sin χ u(φ).
double brute_force(const SpotSurfacePoint &q, int n, double tol, int depth) {
    const Vec3 wl = unit(add(q.light.position_m, -1.0, q.point_m)), l = unit(q.lobe_axis);
    Vec3 e1 = add(l, -dot(l, wl), wl);
    if (dot(e1, e1) < 1e-20) e1 = std::fabs(wl[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    e1 = unit(add(e1, -dot(e1, wl), wl));
    const Vec3 e2 = cross(wl, e1);
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    const auto over_chi = [&](double phi) {
        const Vec3 u = add(scale(std::cos(phi), e1), std::sin(phi), e2);
        return GK::integrate(
            [&](double chi) {
                const Vec3 w = add(scale(std::cos(chi), wl), std::sin(chi), u);
                const double lobe = dot(w, l);
                if (!(lobe > 0.0)) return 0.0;
                scatterlut::SpotQuery s;
                s.sigma_s_per_m = q.sigma_s_per_m;
                s.sigma_a_per_m = q.sigma_a_per_m;
                s.viewer_m = q.point_m;
                s.view_dir = w;
                s.length_m = std::numeric_limits<double>::infinity();
                s.light = q.light;
                return scatterlut::spot_airlight_radiance_exact(s) * std::pow(lobe, n) * std::sin(chi);
            },
            0.0, kPi, depth, tol);
    };
    return GK::integrate(over_chi, 0.0, kPi, depth, tol) + GK::integrate(over_chi, kPi, 2.0 * kPi, depth, tol);
}

// ---------------------------------------------------------------- (1) the point light
TEST(SpotSurfaceExact, PointLightLimitIsSurfaceGExact) {
    double worst = 0.0;
    int checked = 0;
    for (int n : {1, 20, 200})
        for (double T : {0.0, 0.01, 1.0, 10.0})
            for (double theta : {0.0, 0.3, 1.2, kPi / 2, 2.5, kPi}) {
                if (n == 200 && (theta == 1.2 || theta == 2.5)) continue; // the slowest; 0.3 and π/2 remain
                SpotScene s;
                s.T = T;
                s.lobe_angle = theta;
                s.theta_P = 0.7;
                const SpotSurfacePoint q = s.point();
                const double got = scatterlut::spot_surface_G_exact(n, q);
                const double want = scatterlut::surface_G_exact(n, T, theta);
                const double err = rel(got, want);
                worst = std::fmax(worst, err);
                ++checked;
                EXPECT_LE(err, 5e-8) << "n " << n << " T " << T << " theta " << theta << ": " << got << " vs " << want;
            }
    std::printf("spot surface at theta_o = pi vs surface_G_exact: %d cases (n = 1, 20, 200; T = 0 ... 10), worst %.2e\n",
                checked, worst);
}

TEST(SpotSurfaceExact, PointLightLimitInPhysicalUnits) {
    SpotScene s;
    s.lobe_angle = 1.0;
    const SpotSurfacePoint q = s.point();
    scatterlut::SurfaceQuery p;
    p.sigma_s_per_m = q.sigma_s_per_m;
    p.sigma_a_per_m = q.sigma_a_per_m;
    p.intensity_W_per_sr = q.light.intensity_W_per_sr;
    p.distance_m = s.D;
    p.theta_rad = 1.0;
    EXPECT_LE(rel(scatterlut::spot_surface_irradiance_exact(q), scatterlut::surface_irradiance_exact(p)), 5e-8);
    EXPECT_LE(rel(scatterlut::spot_surface_specular_exact(q, 20), scatterlut::surface_specular_exact(p, 20)), 5e-8);
}

// ---------------------------------------------------------------- (2) brute force
TEST(SpotSurfaceExact, MatchesBruteForceOverDirections) {
    struct Case {
        const char *what;
        int n;
        double T, outer, inner, theta_P, lobe_angle;
    };
    const Case cases[] = {
        {"inside, soft cone", 1, 1.0, 0.4, 0.3, 0.1, 0.5},
        {"inside, hard cone", 1, 1.0, 0.4, 0.4, 0.1, 0.5},
        {"in the falloff band, dense", 1, 3.0, 0.4, 0.2, 0.35, 2.0},
        {"outside, thin medium", 1, 0.01, 0.4, 0.4, 0.6, 0.5},
        {"narrow beam, on the axis", 1, 1.0, 0.05, 0.02, 0.0, 1.0},
        {"outside a wide soft beam (theta_o > pi/2)", 1, 1.0, 2.5, 1.0, 2.8, 0.3},
        {"Phong lobe n = 20, inside", 20, 1.0, 0.4, 0.3, 0.2, 0.3},
    };
    double worst = 0.0;
    for (const Case &c : cases) {
        SpotScene s;
        s.T = c.T;
        s.outer = c.outer;
        s.inner = c.inner;
        s.theta_P = c.theta_P;
        s.lobe_angle = c.lobe_angle;
        const SpotSurfacePoint q = s.point();
        const double got = scatterlut::spot_surface_specular_exact(q, c.n);
        const double want = brute_force(q, c.n, 1e-8, 12);
        ASSERT_GT(want, 0.0) << c.what;
        const double err = rel(got, want);
        worst = std::fmax(worst, err);
        EXPECT_LE(err, 1e-6) << c.what << ": " << got << " vs brute force " << want;
    }
    std::printf("spot surface vs brute force over directions of the exact spot airlight: %zu cases, worst %.2e\n",
                sizeof(cases) / sizeof(cases[0]), worst);
}

// ---------------------------------------------------------------- (3) limits and properties
TEST(SpotSurfaceExact, NoBeamNoScatteringNoLight) {
    SpotScene s;
    s.outer = s.inner = 0.0;
    EXPECT_EQ(scatterlut::spot_surface_G_exact(1, s.point()), 0.0);
    s.outer = s.inner = 0.5;
    SpotSurfacePoint q = s.point();
    q.sigma_s_per_m = 0.0;
    EXPECT_EQ(scatterlut::spot_surface_irradiance_exact(q), 0.0);
    q = s.point();
    q.light.intensity_W_per_sr = 0.0;
    EXPECT_EQ(scatterlut::spot_surface_irradiance_exact(q), 0.0);
    // Every light path is at least D: e^{−T} underflows, and so does G (0, finite, no NaN).
    s.T = 1e4;
    const double g = scatterlut::spot_surface_G_exact(1, s.point());
    EXPECT_EQ(g, 0.0);
}

TEST(SpotSurfaceExact, GlowOutsideTheBeamAndProperties) {
    SpotScene s;
    s.outer = s.inner = 0.3;
    s.theta_P = 0.6; // outside: the direct light is 0, the scattered light is not
    s.lobe_angle = 0.8;
    const double outside = scatterlut::spot_surface_G_exact(1, s.point());
    EXPECT_GT(outside, 0.0);
    // Physical units: σ_s I0/(4π D) · G.
    const SpotSurfacePoint q = s.point();
    EXPECT_LE(rel(scatterlut::spot_surface_irradiance_exact(q),
                  q.sigma_s_per_m * q.light.intensity_W_per_sr / (4 * kPi * s.D) * outside),
              1e-14);
    // A wider cone lights more of the medium: G grows with θ_o up to the point light's.
    double previous = 0.0;
    for (double outer : {0.1, 0.3, 0.8, 1.6, 2.5, kPi}) {
        s.outer = s.inner = outer;
        const double g = scatterlut::spot_surface_G_exact(1, s.point());
        EXPECT_GT(g, previous) << "theta_o " << outer;
        previous = g;
    }
    // A soft cone lies between its hard inner and outer cones (f between their indicators).
    s.theta_P = 0.2;
    s.outer = 0.5, s.inner = 0.5;
    const double hard_outer = scatterlut::spot_surface_G_exact(1, s.point());
    s.outer = 0.25, s.inner = 0.25;
    const double hard_inner = scatterlut::spot_surface_G_exact(1, s.point());
    s.outer = 0.5, s.inner = 0.25;
    const double soft = scatterlut::spot_surface_G_exact(1, s.point());
    EXPECT_GT(soft, hard_inner);
    EXPECT_LT(soft, hard_outer);
    // G is dimensionless: the same geometry 10× larger with σ 10× smaller gives the same G.
    s.D = 2.0;
    const double g1 = scatterlut::spot_surface_G_exact(1, s.point());
    s.D = 20.0;
    EXPECT_LE(rel(scatterlut::spot_surface_G_exact(1, s.point()), g1), 1e-7);
}

TEST(SpotSurfaceExact, SurfaceFacingAwayFromTheBeamSeesLittle) {
    // P outside a narrow beam, beside it: the normal towards the beam sees its glow, the normal
    // away from it only what the beam scatters backwards past P's horizon.
    SpotScene s;
    s.outer = s.inner = 0.2;
    s.theta_P = 0.5;
    SpotSurfacePoint towards = s.point();
    const Vec3 m = unit(towards.light.direction);
    const Vec3 foot = add(towards.light.position_m, dot(add(towards.point_m, -1.0, towards.light.position_m), m), m);
    towards.lobe_axis = add(foot, -1.0, towards.point_m); // from P to the axis
    SpotSurfacePoint away = towards;
    away.lobe_axis = scale(-1.0, towards.lobe_axis);
    const double g_towards = scatterlut::spot_surface_G_exact(1, towards), g_away = scatterlut::spot_surface_G_exact(1, away);
    EXPECT_GT(g_towards, 20.0 * g_away);
    EXPECT_GT(g_away, 0.0);
}

// ---------------------------------------------------------------- (4) bad input
TEST(SpotSurfaceExact, RefusesBadInputNamingTheField) {
    const auto refuses = [](const SpotSurfacePoint &q, int n, const std::string &word) {
        try {
            scatterlut::spot_surface_G_exact(n, q);
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
            return;
        }
        ADD_FAILURE() << "accepted bad input (" << word << ")";
    };
    SpotScene s;
    s.outer = 0.5, s.inner = 0.3;
    const SpotSurfacePoint good = s.point();
    EXPECT_NO_THROW(scatterlut::spot_surface_G_exact(1, good));
    SpotSurfacePoint q = good;
    q.sigma_s_per_m = -1.0;
    refuses(q, 1, "sigma_s");
    q = good;
    q.sigma_a_per_m = std::numeric_limits<double>::quiet_NaN();
    refuses(q, 1, "sigma_a");
    q = good;
    q.point_m[1] = std::numeric_limits<double>::infinity();
    refuses(q, 1, "point");
    q = good;
    q.lobe_axis = {0, 0, 0};
    refuses(q, 1, "lobe_axis");
    q = good;
    q.light.direction = {0, 0, 0};
    refuses(q, 1, "direction");
    q = good;
    q.light.outer_angle_rad = 3.2;
    refuses(q, 1, "outer_angle");
    q = good;
    q.light.inner_angle_rad = -0.1;
    refuses(q, 1, "inner_angle");
    q = good;
    q.light.inner_angle_rad = 0.6;
    refuses(q, 1, "inner_angle must not exceed");
    q = good;
    q.light.intensity_W_per_sr = -2.0;
    refuses(q, 1, "intensity");
    q = good;
    q.point_m = q.light.position_m;
    refuses(q, 1, "distance 0");
    refuses(good, 0, "exponent");
    refuses(good, scatterlut::kSurfaceMaxExponent + 1, "exponent");
    EXPECT_THROW(scatterlut::spot_surface_irradiance_exact(q), std::invalid_argument);
    EXPECT_THROW(scatterlut::spot_surface_specular_exact(good, 0), std::invalid_argument);
}

} // namespace
