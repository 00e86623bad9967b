// The surface front-end in physical units (scatterlut/surface_radiance.hpp): a lit surface
// point's radiance towards the viewer, L = e^{−σ_t D_v} [k_d/π (E_d + E_ss) + k_s (P_d + S_n)].
// References: (1) the same geometry through the exact quadrature (surface_radiance_exact);
// (2) geometries whose angles are known by construction, against the irradiance functions of
// scatterlut/surface.hpp that take θ directly (surface_irradiance_exact, surface_specular_exact,
// the closed forms of E_d and P_d); (3) the limits of docs/PHYSICS.md §1.5 (σ_t → 0: the
// closed form σ_s I0/(2D)[cos θ_s + E(sin θ_s)]; θ_s = π still positive; the light below the
// horizon); (4) never NaN or negative over extreme inputs; bad input refused.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "scatterlut/surface.hpp"
#include "scatterlut/surface_radiance.hpp"
#include "scatterlut/surface_table.hpp"

namespace scatterlut {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTMax = 10.0;
constexpr int kExponent = 20; // the wet lobe's Phong exponent of these tests
// The accepted sampling error of the small G0 and G_20 tables below (24 × 25 on T ≤ 10: small,
// since CTest runs each test in its own process, each filling its tables by quadrature): the
// scattered terms carry it, the direct terms are exact. Measured: the random test prints it.
constexpr double kTableRel = 2e-2;

const SurfaceTable &g0_table() {
    static const SurfaceTable t(surface_G0_table_by_quadrature(kTMax, 24, 25));
    return t;
}

const SurfaceTable &g20_table() {
    static const SurfaceTable t(surface_G_table_by_quadrature(kExponent, kTMax, 24, 25));
    return t;
}

SurfaceTables tables() {
    SurfaceTables t;
    t.diffuse = &g0_table();
    t.specular = &g20_table();
    return t;
}

// A surface point at the origin with normal +z, the light at `light`, the viewer at `viewer`.
SurfaceLighting at_origin(double lx, double ly, double lz, double vx, double vy, double vz, double I0 = 100.0) {
    SurfaceLighting s;
    s.light_m[0] = lx, s.light_m[1] = ly, s.light_m[2] = lz;
    s.viewer_m[0] = vx, s.viewer_m[1] = vy, s.viewer_m[2] = vz;
    s.intensity_W_per_sr = I0;
    return s;
}

SurfaceMaterial material(double kd, double ks, int n = kExponent) {
    SurfaceMaterial m;
    m.diffuse_albedo = kd;
    m.specular_per_sr = ks;
    m.phong_exponent = n;
    return m;
}

void expect_valid(const SurfaceRadiance &r, const char *what) {
    for (double x : {r.diffuse_direct, r.diffuse_scattered, r.specular_direct, r.specular_scattered}) {
        EXPECT_FALSE(std::isnan(x)) << what;
        EXPECT_GE(x, 0.0) << what;
    }
}

// Random geometries on a street (ground z = 0, normal +z; lights 0.5–30 m away, above the
// ground or below it; viewers above), random fog: the table front-end against the exact one.
// The direct terms come from the same closed forms (equal); the scattered terms within the
// table's sampling error.
TEST(SurfaceRadiance, TableAgainstExactOverRandomGeometries) {
    std::mt19937_64 rng(20261202);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst_diffuse = 0.0, worst_total = 0.0;
    const int cases = 300;
    int used = 0;
    for (int k = 0; k < cases; ++k) {
        const double D = 0.5 * std::pow(60.0, unit(rng)); // 0.5 … 30 m
        const double cos_s = 2.0 * unit(rng) - 1.0, phi = 2.0 * kPi * unit(rng);
        const double sin_s = std::sqrt(1.0 - cos_s * cos_s);
        const double Dv = 1.0 + 40.0 * unit(rng), cos_v = 0.05 + 0.95 * unit(rng), phi_v = 2.0 * kPi * unit(rng);
        const double sin_v = std::sqrt(1.0 - cos_v * cos_v);
        SurfaceLighting s = at_origin(D * sin_s * std::cos(phi), D * sin_s * std::sin(phi), D * cos_s,
                                      Dv * sin_v * std::cos(phi_v), Dv * sin_v * std::sin(phi_v), Dv * cos_v);
        const double sigma_s = 0.25 * unit(rng), sigma_a = 0.08 * unit(rng);
        if ((sigma_s + sigma_a) * D > kTMax) continue; // beyond the table: the exact fallback (tested below)
        const SurfaceMaterial m = material(0.6, 0.4);
        const SurfaceRadiance t = surface_radiance(tables(), s, sigma_s, sigma_a, m);
        const SurfaceRadiance e = surface_radiance_exact(s, sigma_s, sigma_a, m);
        expect_valid(t, "table");
        EXPECT_EQ(t.diffuse_direct, e.diffuse_direct);
        EXPECT_EQ(t.specular_direct, e.specular_direct);
        ASSERT_GT(e.diffuse_scattered, 0.0) << "E_ss > 0 at every θ_s (sigma_s > 0)";
        const double rel_d = std::fabs(t.diffuse_scattered / e.diffuse_scattered - 1.0);
        const double rel_s = e.specular_scattered > 0 ? std::fabs(t.specular_scattered / e.specular_scattered - 1.0) : 0;
        const double rel_t = std::fabs(t.total() / e.total() - 1.0);
        EXPECT_LT(rel_d, kTableRel) << "D=" << D << " cos_s=" << cos_s;
        EXPECT_LT(rel_s, kTableRel) << "D=" << D << " cos_s=" << cos_s;
        EXPECT_LT(rel_t, kTableRel);
        worst_diffuse = std::max({worst_diffuse, rel_d, rel_s});
        worst_total = std::max(worst_total, rel_t);
        ++used;
    }
    EXPECT_GE(used, 250); // most geometries inside the table's T domain
    std::printf("surface radiance, G0 and G_20 tables 24x25 (T <= %g) vs exact over %d geometries: scattered terms max rel "
                "%.3e, total max rel %.3e\n",
                kTMax, used, worst_diffuse, worst_total);
}

// Known angles: the light straight above (θ_s = 0), at 60° and below the horizon; the viewer
// on the mirror direction of the light (θ_r = 0) or elsewhere. Against the functions of
// scatterlut/surface.hpp that take θ directly, and the closed forms of the direct terms.
TEST(SurfaceRadiance, KnownAnglesAgainstTheIrradianceFunctions) {
    const double sigma_s = 0.08, sigma_a = 0.02, sigma_t = 0.1, I0 = 250.0, kd = 0.7, ks = 0.25;
    const double D = 6.0, Dv = 9.0;
    const double view = std::exp(-sigma_t * Dv);
    struct Case {
        double theta_s;  // the light's angle from the normal, in the x–z plane
        double theta_v;  // the viewer's, on the other side (θ_v = θ_s: the mirror direction)
        double theta_r;  // the angle between ρ and the light that follows
    };
    const Case cases[] = {{0.0, 0.0, 0.0}, {kPi / 3, kPi / 3, 0.0}, {kPi / 3, kPi / 6, kPi / 6},
                          {2.0, 0.3, 2.0 - 0.3}, {kPi, 0.4, kPi - 0.4}};
    for (const Case &c : cases) {
        SurfaceLighting s = at_origin(D * std::sin(c.theta_s), 0.0, D * std::cos(c.theta_s), -Dv * std::sin(c.theta_v),
                                      0.0, Dv * std::cos(c.theta_v), I0);
        SurfaceQuery q;
        q.sigma_s_per_m = sigma_s;
        q.sigma_a_per_m = sigma_a;
        q.intensity_W_per_sr = I0;
        q.distance_m = D;
        q.theta_rad = c.theta_s;
        const double E_ss = surface_irradiance_exact(q);
        q.theta_rad = c.theta_r;
        const double S_n = surface_specular_exact(q, kExponent);
        const double direct = I0 * std::exp(-sigma_t * D) / (D * D);
        const SurfaceRadiance e = surface_radiance_exact(s, sigma_s, sigma_a, material(kd, ks));
        const SurfaceRadiance t = surface_radiance(tables(), s, sigma_s, sigma_a, material(kd, ks));
        expect_valid(e, "exact");
        const double lit = std::cos(c.theta_s) > 0 ? 1.0 : 0.0;
        EXPECT_NEAR(e.diffuse_direct, view * kd / kPi * direct * std::max(std::cos(c.theta_s), 0.0), 1e-13 * direct);
        EXPECT_NEAR(e.diffuse_scattered / (view * kd / kPi * E_ss), 1.0, 1e-9) << c.theta_s;
        EXPECT_NEAR(e.specular_direct, lit * view * ks * direct * std::pow(std::max(std::cos(c.theta_r), 0.0), kExponent),
                    1e-12 * direct)
            << c.theta_s;
        EXPECT_NEAR(e.specular_scattered / (view * ks * S_n), 1.0, 1e-9) << c.theta_s;
        EXPECT_NEAR(t.diffuse_scattered / e.diffuse_scattered, 1.0, kTableRel);
        EXPECT_NEAR(t.specular_scattered / e.specular_scattered, 1.0, kTableRel);
    }
}

// σ_t → 0: E_ss → σ_s I0/(2D) [cos θ_s + E(sin θ_s)] (docs/PHYSICS.md §1.5, derived there;
// surface_irradiance_no_extinction), and no attenuation of the direct terms or the view.
TEST(SurfaceRadiance, NoExtinctionLimit) {
    const double sigma_s = 1e-12, D = 3.0, I0 = 50.0;
    for (double theta_s : {0.0, 0.7, kPi / 2, 2.2, kPi}) {
        SurfaceLighting s = at_origin(D * std::sin(theta_s), 0.0, D * std::cos(theta_s), 0.0, 2.0, 5.0, I0);
        SurfaceQuery q;
        q.sigma_s_per_m = sigma_s;
        q.intensity_W_per_sr = I0;
        q.distance_m = D;
        q.theta_rad = theta_s;
        const double limit = surface_irradiance_no_extinction(q);
        for (int table = 0; table < 2; ++table) {
            const SurfaceRadiance r = table ? surface_radiance(tables(), s, sigma_s, 0.0, material(1.0, 0.0))
                                            : surface_radiance_exact(s, sigma_s, 0.0, material(1.0, 0.0));
            EXPECT_NEAR(r.diffuse_scattered * kPi / limit, 1.0, table ? 1e-9 : 1e-8) << theta_s;
            EXPECT_NEAR(r.diffuse_direct * kPi, I0 * std::max(std::cos(theta_s), 0.0) / (D * D), 1e-12 * I0);
        }
    }
    // σ_s = 0 exactly: no scattered light at all.
    const SurfaceRadiance r = surface_radiance(tables(), at_origin(0, 0, 2, 0, 1, 1), 0.0, 0.3, material(1.0, 1.0));
    EXPECT_EQ(r.diffuse_scattered, 0.0);
    EXPECT_EQ(r.specular_scattered, 0.0);
    EXPECT_GT(r.diffuse_direct, 0.0);
}

// The light below the horizon (θ_s > π/2) and straight below (θ_s = π): no direct terms, the
// scattered ones positive; the specular direct term is cut even where ρ·ω_l > 0 (the viewer
// grazing, the light just below the horizon), S_n is not (Sun et al. 2005's unclipped lobe).
TEST(SurfaceRadiance, LightBelowTheHorizon) {
    const double sigma_s = 0.2, sigma_a = 0.05;
    // θ_s = π: the light 4 m straight below the point.
    SurfaceLighting below = at_origin(0.0, 0.0, -4.0, 1.0, 0.0, 3.0);
    for (int table = 0; table < 2; ++table) {
        const SurfaceRadiance r = table ? surface_radiance(tables(), below, sigma_s, sigma_a, material(0.5, 0.5))
                                        : surface_radiance_exact(below, sigma_s, sigma_a, material(0.5, 0.5));
        expect_valid(r, "theta_s = pi");
        EXPECT_EQ(r.diffuse_direct, 0.0);
        EXPECT_EQ(r.specular_direct, 0.0);
        EXPECT_GT(r.diffuse_scattered, 0.0);
        EXPECT_GT(r.specular_scattered, 0.0);
    }
    // The light 0.01 rad below the horizon along +x; the viewer grazing from −x (ρ ≈ +x):
    // cos θ_r > 0 but the light is below the surface.
    SurfaceLighting grazing = at_origin(5.0 * std::cos(0.01), 0.0, -5.0 * std::sin(0.01), -8.0, 0.0, 0.5);
    const SurfaceRadiance r = surface_radiance_exact(grazing, sigma_s, sigma_a, material(0.5, 0.5));
    EXPECT_EQ(r.specular_direct, 0.0);
    EXPECT_EQ(r.diffuse_direct, 0.0);
    EXPECT_GT(r.specular_scattered, 0.0);
    EXPECT_GT(r.diffuse_scattered, 0.0);
}

// T beyond the table's axis: the front-end integrates exactly there (equal to the exact form).
TEST(SurfaceRadiance, BeyondTheTableTheQuadrature) {
    SurfaceLighting s = at_origin(3.0, 1.0, 20.0, -2.0, 0.0, 4.0); // D ≈ 20.25 m
    const double sigma_s = 2.0, sigma_a = 0.5;                      // T ≈ 50 > 10
    const SurfaceRadiance t = surface_radiance(tables(), s, sigma_s, sigma_a, material(0.8, 0.3));
    const SurfaceRadiance e = surface_radiance_exact(s, sigma_s, sigma_a, material(0.8, 0.3));
    EXPECT_GT(e.diffuse_scattered, 0.0);
    EXPECT_EQ(t.diffuse_scattered, e.diffuse_scattered);
    EXPECT_EQ(t.specular_scattered, e.specular_scattered);
}

// The viewer below the surface sees its back: 0. RGB: each channel the scalar form with its σ.
TEST(SurfaceRadiance, ViewerBelowAndRgb) {
    const SurfaceRadiance back = surface_radiance(tables(), at_origin(0, 1, 3, 0, 2, -1), 0.1, 0.0, material(1, 1));
    EXPECT_EQ(back.total(), 0.0);
    const SurfaceLighting s = at_origin(2, 1, 3, -1, 2, 4);
    const Rgb ss{0.02, 0.05, 0.3}, sa{0.0, 0.01, 0.1};
    const Rgb t = surface_radiance_rgb(tables(), s, ss, sa, material(0.5, 0.2));
    const Rgb e = surface_radiance_exact_rgb(s, ss, sa, material(0.5, 0.2));
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(t[c], surface_radiance(tables(), s, ss[c], sa[c], material(0.5, 0.2)).total());
        EXPECT_EQ(e[c], surface_radiance_exact(s, ss[c], sa[c], material(0.5, 0.2)).total());
        EXPECT_NEAR(t[c] / e[c], 1.0, kTableRel);
    }
    EXPECT_GT(e[0], e[2]); // the clearer channel is brighter
}

// n = 1: the G0 table serves the lobe too (G_1 = G0 at θ_r).
TEST(SurfaceRadiance, ExponentOneFromTheG0Table) {
    SurfaceTables both;
    both.diffuse = &g0_table();
    both.specular = &g0_table();
    const SurfaceLighting s = at_origin(2, 1, 3, -1, 2, 4);
    const SurfaceRadiance t = surface_radiance(both, s, 0.1, 0.02, material(0.5, 0.4, 1));
    const SurfaceRadiance e = surface_radiance_exact(s, 0.1, 0.02, material(0.5, 0.4, 1));
    EXPECT_NEAR(t.specular_scattered / e.specular_scattered, 1.0, kTableRel);
    EXPECT_NEAR(t.diffuse_scattered / e.diffuse_scattered, 1.0, kTableRel);
}

// Extreme inputs: never NaN, never negative (+∞ allowed only where I0/D² overflows).
TEST(SurfaceRadiance, NeverNaNOrNegative) {
    const double ds[] = {1e-300, 1e-9, 1e-3, 1.0, 1e3, 1e150};
    const double sigmas[] = {0.0, 1e-300, 1e-6, 1.0, 1e6, 1e300};
    for (double D : ds)
        for (double sigma : sigmas)
            for (double c : {1.0, 1e-9, 0.0, -1e-9, -1.0}) {
                SurfaceLighting s = at_origin(D * std::sqrt(1.0 - c * c), 0.0, D * c, -1.0, 0.0, 1.0);
                const SurfaceRadiance r = surface_radiance(tables(), s, sigma, 0.5 * sigma, material(0.7, 0.3));
                expect_valid(r, "extreme");
                if (D >= 1e-3) {
                    EXPECT_TRUE(std::isfinite(r.total())) << D << " " << sigma << " " << c;
                }
            }
}

TEST(SurfaceRadiance, BadInputRefused) {
    const SurfaceLighting ok = at_origin(0, 0, 2, 0, 1, 1);
    auto refused = [&](SurfaceLighting s, double ss, double sa, SurfaceMaterial m, SurfaceTables t) {
        EXPECT_THROW(surface_radiance(t, s, ss, sa, m), std::invalid_argument);
    };
    SurfaceLighting s = ok;
    s.normal[2] = 2.0;
    refused(s, 0.1, 0.0, material(1, 0), tables());
    s = ok;
    s.point_m[0] = std::nan("");
    refused(s, 0.1, 0.0, material(1, 0), tables());
    s = ok;
    s.light_m[2] = 0.0; // the light on the point
    refused(s, 0.1, 0.0, material(1, 0), tables());
    s = ok;
    s.viewer_m[1] = 0.0, s.viewer_m[2] = 0.0;
    refused(s, 0.1, 0.0, material(1, 0), tables());
    refused(ok, -0.1, 0.0, material(1, 0), tables());
    refused(ok, 0.1, INFINITY, material(1, 0), tables());
    refused(ok, 0.1, 0.0, material(-1, 0), tables());
    refused(ok, 0.1, 0.0, material(1, 1, 0), tables());
    refused(ok, 0.1, 0.0, material(1, 0, kSurfaceMaxExponent + 1), tables());
    refused(ok, 0.1, 0.0, material(1, 0), SurfaceTables{});       // k_d > 0 without a G0 table
    refused(ok, 0.1, 0.0, material(0, 1), SurfaceTables{});       // k_s > 0 without a G_n table
    refused(ok, 0.1, 0.0, material(0, 1, 200), tables());         // a G_n table of another exponent
    SurfaceTables swapped;
    swapped.diffuse = &g20_table(); // a G_20 table as the diffuse one
    swapped.specular = &g20_table();
    refused(ok, 0.1, 0.0, material(1, 0), swapped);
    const Rgb bad{0.1, -1.0, 0.1}, zero{0, 0, 0};
    EXPECT_THROW(surface_radiance_rgb(tables(), ok, bad, zero, material(1, 0)), std::invalid_argument);
    try {
        surface_radiance(tables(), ok, 0.1, 0.0, material(1, 0, 0));
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("phong_exponent"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace scatterlut
