// The diffuse surface term of Sun et al. 2005 from a surface_G table (scatterlut/surface_table.hpp):
// the table filled by quadrature at the nodes, sampled at random off-node points against
// surface_G_exact; the ends of both axes (θ_s = 0, π/2, π; T = 0, tiny, T_max); E_ss through the
// table against surface_irradiance_exact; bad tables and out-of-domain queries refused; eval's
// "surface" answering "table" with --table of a saved surface_G file (null outside its T domain).
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

} // namespace
} // namespace scatterlut
