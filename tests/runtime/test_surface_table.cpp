// The diffuse surface term of Sun et al. 2005 from a surface_G table (scatterlut/surface_table.hpp):
// the table filled by quadrature at the nodes, sampled at random off-node points against
// surface_G_exact; the ends of both axes (θ_s = 0, π/2, π; T = 0, tiny, T_max); E_ss through the
// table against surface_irradiance_exact; bad tables and out-of-domain queries refused; eval's
// "surface" answering "table" with --table of a saved surface_G file (null outside its T domain).
// Then any Phong exponent n: the G_n tables (n = 1, 20, 200, 1000 on T ≤ 100) against surface_G_exact
// at random off-node points (printing the measured maximum), their hard corners, the lobe scale's
// bound at T = 0, the exponent recorded and checked on load.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>
#include <sstream>

#include "cli_runner.hpp"
#include "scatterlut/io.hpp"

#include "scatterlut/surface.hpp"
#include "scatterlut/surface_table.hpp"

extern "C" {
#include "slut_surface_table.h"
}

namespace scatterlut {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTMax = 30.0;
// The accepted relative sampling error of the 64 × 65 table on T ∈ [0, 30]: measured 5.6e-3
// at most over 4000 random points (largest near θ_s = π/2 at large T, where G0 has a kink).
constexpr double kAcceptedRel = 1e-2;

const SurfaceTable &table_64x65() {
    static const SurfaceTable t(surface_G0_table_by_quadrature(kTMax, 64, 65));
    return t;
}

TEST(SurfaceTable, RandomPointsWithinTheAcceptedError) {
    const SurfaceTable &t = table_64x65();
    std::mt19937_64 rng(20260212);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0, sum = 0.0;
    const int points = 1500;
    for (int k = 0; k < points; ++k) {
        // T uniform in the axis's own warp (log1p, scale 0.1): small T as densely as large.
        const double T = kSurfaceG0TScale * std::expm1(unit(rng) * std::log1p(kTMax / kSurfaceG0TScale));
        const double theta = kPi * unit(rng);
        const double exact = surface_G_exact(1, T, theta);
        const double got = t.G0(T, theta);
        ASSERT_TRUE(std::isfinite(got) && got > 0.0) << "T=" << T << " theta=" << theta;
        const double rel = std::fabs(got / exact - 1.0);
        worst = std::max(worst, rel);
        sum += rel;
        EXPECT_LT(rel, kAcceptedRel) << "T=" << T << " theta=" << theta;
    }
    std::printf("surface_G 64x65, T <= %g: sampling error max %.3e, mean %.3e over %d points\n", kTMax, worst,
                sum / points, points);
}

TEST(SurfaceTable, EndsOfBothAxes) {
    const SurfaceTable &t = table_64x65();
    const double thetas[] = {0.0, 1e-9, kPi / 2 - 1e-9, kPi / 2, kPi / 2 + 1e-9, kPi - 1e-9, kPi};
    const double Ts[] = {0.0, 1e-12, 1e-6, 1e-3, 1.0, kTMax - 1e-9, kTMax};
    for (double T : Ts)
        for (double theta : thetas) {
            const double got = t.G0(T, theta);
            ASSERT_TRUE(std::isfinite(got) && got > 0.0) << "T=" << T << " theta=" << theta;
            EXPECT_NEAR(got / surface_G_exact(1, T, theta), 1.0, kAcceptedRel) << "T=" << T << " theta=" << theta;
        }
    // T = 0: the ratio is 1 and G0 the closed form 2π [cos θ_s + E(sin θ_s)] (2π at θ_s = π/2, E(1) = 1).
    EXPECT_NEAR(t.G0(0.0, kPi / 2), 2.0 * kPi, 1e-9);
    EXPECT_NEAR(t.G0(0.0, 0.0), 2.0 * kPi * (1.0 + kPi / 2), 1e-9);
}

TEST(SurfaceTable, AtNodesTheQuadrature) {
    const Table small = surface_G0_table_by_quadrature(5.0, 5, 7);
    const SurfaceTable t(small);
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 5; ++i) {
            const double T = slut_axis_node(&small.axes[0].map, i);
            const double theta = slut_axis_node(&small.axes[1].map, j);
            EXPECT_NEAR(t.G0(T, theta) / surface_G_exact(1, T, theta), 1.0, 1e-12) << i << "," << j;
        }
}

TEST(SurfaceTable, IrradianceAgainstExact) {
    const SurfaceTable &t = table_64x65();
    SurfaceQuery q;
    q.sigma_s_per_m = 0.3;
    q.sigma_a_per_m = 0.05;
    q.intensity_W_per_sr = 100.0;
    q.distance_m = 7.0;
    for (double theta : {0.0, 1.0, kPi / 2, 2.5, kPi}) {
        q.theta_rad = theta;
        const double exact = surface_irradiance_exact(q);
        EXPECT_NEAR(t.irradiance(q) / exact, 1.0, kAcceptedRel) << theta;
    }
    q.sigma_s_per_m = 0.0;
    EXPECT_EQ(t.irradiance(q), 0.0);
}

TEST(SurfaceTable, OutOfDomainRefused) {
    const SurfaceTable &t = table_64x65();
    EXPECT_THROW(t.G0(kTMax * 1.001, 1.0), std::invalid_argument);
    EXPECT_THROW(t.G0(-1e-9, 1.0), std::invalid_argument);
    EXPECT_THROW(t.G0(std::numeric_limits<double>::quiet_NaN(), 1.0), std::invalid_argument);
    EXPECT_THROW(t.G0(1.0, kPi + 1e-6), std::invalid_argument);
    EXPECT_THROW(t.G0(1.0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    SurfaceQuery q;
    q.sigma_s_per_m = 1.0;
    q.intensity_W_per_sr = 1.0;
    q.distance_m = 100.0; // T = 100 > 30
    EXPECT_THROW(t.irradiance(q), std::invalid_argument);
}

TEST(SurfaceTable, BadTablesRefused) {
    const Table good = surface_G0_table_by_quadrature(2.0, 3, 3);
    Table t = good;
    t.kind = "airlight_F";
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.values[4] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.values[4] = 0.5; // ratio e^0.5 > 1: G0 above its no-extinction bound
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.axes[0].map.warp = SLUT_WARP_LOG; // ln 0 at T = 0
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.axes[0].map.scale = 0.0;
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.values[2] = -2e6; // below any double's logarithm
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.channels[0].encoding = Encoding::Linear;
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    EXPECT_THROW(surface_G0_layout(10.0, 8, 8), std::invalid_argument); // even θ_s count
    EXPECT_THROW(surface_G0_layout(0.0, 8, 9), std::invalid_argument);
    EXPECT_THROW(surface_G0_layout(std::numeric_limits<double>::infinity(), 8, 9), std::invalid_argument);
}

TEST(SurfaceTable, EvalAnswersTableWithASavedFile) {
    const std::string path = slut_test::temp_stem("surface_G") + ".slut";
    save_binary(surface_G0_table_by_quadrature(kTMax, 64, 65), path);
    std::ostringstream input;
    const double thetas[] = {0.0, 0.7, kPi / 2, 2.2, kPi};
    for (double theta : thetas) // T = (0.3 + 0.1)·20 = 8: inside [0, 30]
        input << nlohmann::json{{"quantity", "surface"}, {"sigma_s", 0.3}, {"sigma_a", 0.1}, {"intensity", 50.0},
                                {"distance", 20.0}, {"theta_s", theta}}
                     .dump()
              << "\n";
    // T = 0.4·100 = 40 > 30: outside the table.
    input << nlohmann::json{{"quantity", "surface"}, {"sigma_s", 0.3}, {"sigma_a", 0.1}, {"intensity", 50.0},
                            {"distance", 100.0}, {"theta_s", 1.0}}
                 .dump()
          << "\n";
    const auto r = slut_test::run_scatterlut("eval --table " + path, input.str());
    std::remove(path.c_str());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = slut_test::json_lines(r.out);
    ASSERT_EQ(lines.size(), 6u);
    for (size_t i = 0; i < 5; ++i) {
        const auto &a = lines[i];
        ASSERT_TRUE(a.at("table").is_number() && a.at("exact").is_number()) << a.dump();
        const double table = a.at("table").get<double>(), exact = a.at("exact").get<double>();
        EXPECT_GT(table, 0.0) << a.dump();
        EXPECT_NEAR(table / exact, 1.0, kAcceptedRel) << a.dump();
    }
    EXPECT_TRUE(lines[5].at("table").is_null()) << lines[5].dump();
    EXPECT_TRUE(lines[5].at("exact").is_number()) << lines[5].dump();
}


// --- Any Phong exponent n: G_n tables (surface_G_layout / surface_G_table_by_quadrature) ---------

// The scale of a G_n table at T = 0 is the narrow-lobe form N_n(θ) (kernels/slut_surface_table.h):
// G_n(0, θ)/N_n(θ) must stay within [e^{-0.2}, e^{kSurfaceGnMaxLnRatio}] for every n ≥ 2, which
// is what SurfaceTable's load check of the stored ln ratio (≤ kSurfaceGnMaxLnRatio) relies on:
// extinction only lowers G_n (G_n(T, θ) ≤ e^{−T} G_n(0, θ)). Measured: at most 1.156 (n = 2,
// θ ≈ 0.95), at least 0.92 (n = 2, θ = 0).
TEST(SurfaceGnTable, TheLobeScaleBoundsGnAtZeroExtinction) {
    double lo = 1e300, hi = 0.0;
    const auto check = [&](int n, double theta) {
        const double ratio = surface_G_exact(n, 0.0, theta) / slut_surface_G_scale(n, 0.0, theta);
        lo = std::min(lo, ratio);
        hi = std::max(hi, ratio);
        EXPECT_LE(std::log(ratio), kSurfaceGnMaxLnRatio) << "n=" << n << " theta=" << theta;
        EXPECT_GE(std::log(ratio), -0.2) << "n=" << n << " theta=" << theta;
    };
    for (int n : {2, 3, 5, 10, 20, 50, 200, 1000}) {
        const double width = 1.0 / std::sqrt(n + 1.0);
        // Half the points within 3 lobe widths of θ = 0, half over the rest of [0, π].
        for (int k = 0; k <= 24; ++k)
            check(n, k <= 12 ? 3.0 * width * k / 12.0 : 3.0 * width + (kPi - 3.0 * width) * (k - 12) / 12.0);
    }
    // n = 10000 away from 0.005 < θ < 0.2 only: there surface_G_exact takes ~8 s of CPU per point.
    for (double theta : {0.0, 0.5, 1.0, 2.0, kPi}) check(10000, theta);
    std::printf("G_n(0, theta)/N_n(theta), n = 2 ... 10000: in [%.4f, %.4f]\n", lo, hi);
}

struct GnCase {
    int exponent;
    int T_count, theta_count;
};

// The G_n tables the precision tests measure, on T ∈ [0, kGnTMax], and the accepted relative
// sampling error: a bound from measurement (each test prints its measured maximum).
// Measured (this test's output): n = 1: 7.5e-3 at 48 × 97 (T → 0 near θ_s = π; 1.3e-2 at 48 × 49, at
// the kink θ_s = π/2 for large T); n = 20, 200, 1000: 2.9e-3, 2.7e-3, 3.7e-3 at 48 × 49.
constexpr double kGnTMax = 100.0;
constexpr double kGnAcceptedRel = 1e-2;

// A point uniform in an axis's own warp (log1p or linear): as densely near 0 as the nodes are.
double uniform_in_warp(const slut_axis &a, double unit) {
    return a.warp == SLUT_WARP_LOG1P ? a.scale * std::expm1(unit * std::log1p((a.max - a.min) / a.scale))
                                     : a.min + unit * (a.max - a.min);
}

// The table of case c filled by quadrature, against surface_G_exact at 400 random off-node points
// and at the hard corners (T → 0 and T_max; θ → 0, π/2, π): positive, finite, within kGnAcceptedRel.
void check_gn_table(const GnCase &c) {
    const SurfaceTable t(surface_G_table_by_quadrature(c.exponent, kGnTMax, c.T_count, c.theta_count));
    ASSERT_EQ(t.exponent(), c.exponent);
    std::mt19937_64 rng(20261202 + c.exponent);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0, worst_T = 0.0, worst_theta = 0.0;
    const auto check = [&](double T, double theta) {
        const double exact = surface_G_exact(c.exponent, T, theta);
        const double got = t.G(T, theta);
        ASSERT_TRUE(std::isfinite(got) && got > 0.0) << "n=" << c.exponent << " T=" << T << " theta=" << theta;
        const double rel = std::fabs(got / exact - 1.0);
        if (rel > worst) worst = rel, worst_T = T, worst_theta = theta;
        EXPECT_LT(rel, kGnAcceptedRel) << "n=" << c.exponent << " T=" << T << " theta=" << theta;
    };
    const int points = 400;
    for (int k = 0; k < points; ++k) {
        const double T = uniform_in_warp(t.table().axes[0].map, unit(rng));
        // Every other point uniform in θ itself (the far lobe), the others in the axis's warp (near 0).
        const double theta = k % 2 ? kPi * unit(rng) : uniform_in_warp(t.table().axes[1].map, unit(rng));
        check(T, theta);
    }
    for (double T : {0.0, 1e-12, 1e-6, 1e-3, 1.0, 30.0, kGnTMax - 1e-9, kGnTMax})
        for (double theta : {0.0, 1e-12, 1e-6, 1e-3, kPi / 2, kPi - 1e-6, kPi - 1e-12, kPi}) check(T, theta);
    std::printf("surface_G n=%d %dx%d, T <= %g: sampling error max %.3e (T=%.4g, theta=%.4g) over %d random "
                "points and 64 corners\n",
                c.exponent, c.T_count, c.theta_count, kGnTMax, worst, worst_T, worst_theta, points);
}

// One test per exponent (each fills its own table: n = 1000 takes the longest, ~30 s of CPU).
TEST(SurfaceGnTable, Exponent1WithinTheAcceptedError) { check_gn_table({1, 48, 97}); }
TEST(SurfaceGnTable, Exponent20WithinTheAcceptedError) { check_gn_table({20, 48, 49}); }
TEST(SurfaceGnTable, Exponent200WithinTheAcceptedError) { check_gn_table({200, 48, 49}); }
TEST(SurfaceGnTable, Exponent1000WithinTheAcceptedError) { check_gn_table({1000, 48, 49}); }

// Why the θ_r axis is warped: the same n = 200 table at 48 × 49 with a practically linear θ_r axis
// (log1p with scale 1e6: node spacings within 3e-6 of each other) against the layout's (scale
// 1/√201), both at the same random points. Measured: 3.9e-2 linear, 2.7e-3 warped.
TEST(SurfaceGnTable, TheWarpedThetaAxisBeatsALinearOne) {
    const int n = 200, T_count = 48, theta_count = 49;
    const SurfaceTable warped(surface_G_table_by_quadrature(n, kGnTMax, T_count, theta_count));
    Table flat = surface_G_layout(n, kGnTMax, T_count, theta_count);
    flat.axes[1].map.scale = 1e6;
    flat.values.resize(flat.node_count());
    for (int j = 0; j < theta_count; ++j)
        for (int i = 0; i < T_count; ++i) {
            const double T = slut_axis_node(&flat.axes[0].map, i), theta = slut_axis_node(&flat.axes[1].map, j);
            flat.values[static_cast<size_t>(j) * T_count + i] = surface_G_encode(n, T, theta, surface_G_exact(n, T, theta));
        }
    const SurfaceTable linear(flat);
    std::mt19937_64 rng(20261203);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst_warped = 0.0, worst_linear = 0.0;
    for (int k = 0; k < 200; ++k) {
        const double T = uniform_in_warp(warped.table().axes[0].map, unit(rng));
        const double theta = k % 2 ? kPi * unit(rng) : uniform_in_warp(warped.table().axes[1].map, unit(rng));
        const double exact = surface_G_exact(n, T, theta);
        worst_warped = std::max(worst_warped, std::fabs(warped.G(T, theta) / exact - 1.0));
        worst_linear = std::max(worst_linear, std::fabs(linear.G(T, theta) / exact - 1.0));
    }
    std::printf("surface_G n=%d %dx%d: sampling error max %.3e with the log1p theta_r axis, %.3e with a linear one\n",
                n, T_count, theta_count, worst_warped, worst_linear);
    EXPECT_LT(worst_warped, worst_linear);
}

TEST(SurfaceGnTable, AtNodesTheQuadratureAndTheExponentRecorded) {
    const Table small = surface_G_table_by_quadrature(20, 5.0, 5, 6);
    EXPECT_EQ(small.extra.at(kSurfaceExponentKey), "20");
    EXPECT_EQ(small.axes[1].name, "theta_r");
    EXPECT_EQ(small.axes[1].map.warp, SLUT_WARP_LOG1P);
    const SurfaceTable t(small);
    EXPECT_EQ(t.exponent(), 20);
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 5; ++i) {
            const double T = slut_axis_node(&small.axes[0].map, i);
            const double theta = slut_axis_node(&small.axes[1].map, j);
            EXPECT_NEAR(t.G(T, theta) / surface_G_exact(20, T, theta), 1.0, 1e-12) << i << "," << j;
        }
    // The diffuse functions are the exponent-1 case, value for value.
    const Table g0 = surface_G0_table_by_quadrature(5.0, 5, 7), g1 = surface_G_table_by_quadrature(1, 5.0, 5, 7);
    EXPECT_EQ(g0.values, g1.values);
    EXPECT_EQ(g0.extra.at(kSurfaceExponentKey), "1");
    EXPECT_EQ(table_surface_exponent(g0), 1);
}

TEST(SurfaceGnTable, SpecularAgainstExactAndTheDiffuseCallsRefused) {
    const SurfaceTable t(surface_G_table_by_quadrature(20, kGnTMax, 48, 49));
    SurfaceQuery q;
    q.sigma_s_per_m = 0.3;
    q.sigma_a_per_m = 0.05;
    q.intensity_W_per_sr = 100.0;
    q.distance_m = 7.0;
    for (double theta : {0.0, 0.01, 0.1, 1.0, kPi / 2, 2.5, kPi}) {
        q.theta_rad = theta;
        EXPECT_NEAR(t.specular(q) / surface_specular_exact(q, 20), 1.0, kGnAcceptedRel) << theta;
    }
    EXPECT_THROW(t.irradiance(q), std::invalid_argument); // E_ss needs exponent 1
    EXPECT_THROW(t.G0(1.0, 1.0), std::invalid_argument);
    q.distance_m = 1000.0; // T = 350 > 100
    EXPECT_THROW(t.specular(q), std::invalid_argument);
    // The exponent-1 table answers S_1 = σ_s I0/(4π D) G_1(T, θ_r) too.
    const SurfaceTable &d = table_64x65();
    q.distance_m = 7.0;
    q.theta_rad = 1.0;
    EXPECT_NEAR(d.specular(q) / surface_specular_exact(q, 1), 1.0, kAcceptedRel);
}

TEST(SurfaceGnTable, RoundTripKeepsTheExponent) {
    const std::string path = slut_test::temp_stem("surface_G_n20") + ".slut";
    save_binary(surface_G_table_by_quadrature(20, 5.0, 4, 5), path);
    const Table back = load_table(path);
    std::remove(path.c_str());
    const SurfaceTable t(back);
    EXPECT_EQ(t.exponent(), 20);
    const double T = slut_axis_node(&back.axes[0].map, 2), theta = slut_axis_node(&back.axes[1].map, 3);
    EXPECT_NEAR(t.G(T, theta) / surface_G_exact(20, T, theta), 1.0, 1e-12); // a node, stored in f64
}

TEST(SurfaceGnTable, BadExponentsAndMismatchesRefused) {
    EXPECT_THROW(surface_G_layout(0, 10.0, 8, 9), std::invalid_argument);
    EXPECT_THROW(surface_G_layout(kSurfaceMaxExponent + 1, 10.0, 8, 9), std::invalid_argument);
    EXPECT_THROW(surface_G_layout(20, 10.0, 8, 2), std::invalid_argument);
    EXPECT_THROW(surface_G_layout(20, 701.0, 8, 9), std::invalid_argument); // e^{−T} no longer a normal double
    EXPECT_NO_THROW(surface_G_layout(20, 10.0, 8, 8));                       // n > 1: no kink, any count ≥ 3
    const Table good = surface_G_table_by_quadrature(20, 2.0, 3, 4);
    Table t = good;
    for (const char *text : {"0", "10001", "-3", "20x", "2.5", "", " 20", "99999999999999999999"}) {
        t.extra[kSurfaceExponentKey] = text;
        EXPECT_THROW(SurfaceTable{t}, std::invalid_argument) << "'" << text << "'";
    }
    t = good;
    t.extra.erase(kSurfaceExponentKey);
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.extra[kSurfaceExponentKey] = "1"; // says diffuse: theta_r, log1p, ln_Gn_ratio do not match
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    Table d = surface_G0_table_by_quadrature(2.0, 3, 3);
    d.extra[kSurfaceExponentKey] = "20"; // says a lobe: theta_s, linear, ln_G0_ratio do not match
    EXPECT_THROW(SurfaceTable{d}, std::invalid_argument);
    t = good;
    t.axes[1].map.warp = SLUT_WARP_LINEAR;
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.axes[1].map.scale = std::numeric_limits<double>::infinity();
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.values[3] = kSurfaceGnMaxLnRatio + 0.01; // above G_n(0, θ)'s largest ratio to N_n
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
    t = good;
    t.values[3] = std::numeric_limits<double>::infinity();
    EXPECT_THROW(SurfaceTable{t}, std::invalid_argument);
}

} // namespace
} // namespace scatterlut
