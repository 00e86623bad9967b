// The runtime's cheaper forms (kernels/slut_fastmath.h, slut_unit_from_warped_runtime in
// kernels/slut_axes.h) against the definitions they replace: libm's log1p, sin and cos,
// and the exact warps of slut_unit_from_warped. References: glibc's functions (≤ 1 ulp,
// correctly rounded in practice for these) and the generator's own unit map; tolerances in
// ulps of the result, named at each check.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

extern "C" {
#include "slut_axes.h"
#include "slut_fastmath.h"
}

namespace {

constexpr double kUlp = std::numeric_limits<double>::epsilon(); // 2^−52

double ulps(double got, double want) {
    if (got == want) return 0.0;
    return std::fabs(got - want) / (kUlp * std::fabs(want));
}

// Goldberg's log1p: ≤ 4 ulps (his bound is 5ε for a log within ½ ulp; glibc's log is
// within 1 ulp) from x = −0.999 to 1e300, including the smallest x, where it must return
// x itself (1 + x rounds to 1).
TEST(FastMath, Log1pGoldbergMatchesLibm) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0;
    for (int k = 0; k < 200000; ++k) {
        const double x = unit(rng) < 0.8 ? std::pow(10.0, -20 + 320 * unit(rng)) : -0.999 * unit(rng);
        worst = std::max(worst, ulps(slut_log1p_goldberg(x), std::log1p(x)));
    }
    EXPECT_LE(worst, 4.0);
    EXPECT_EQ(slut_log1p_goldberg(0.0), 0.0);
    EXPECT_EQ(slut_log1p_goldberg(1e-300), 1e-300);
    EXPECT_EQ(slut_log1p_goldberg(1e-17), 1e-17);
    EXPECT_TRUE(std::isnan(slut_log1p_goldberg(std::nan(""))));
    EXPECT_EQ(slut_log1p_goldberg(HUGE_VAL), HUGE_VAL);
    RecordProperty("worst_ulps", std::to_string(worst));
}

// sin and cos of a half angle h ∈ [0, π/2]: ≤ 2 ulps (the Taylor remainders are ≤ 6e-17
// relative; the rest is the rounding of the sums), exact at h = 0, the complement at π/2 giving
// cos = π/2 − fl(π/2) to full precision, and monotone on a dense grid (sin increasing,
// cos decreasing: the airlight's w2 = π/2 − h and the geometry's signs rely on it).
TEST(FastMath, SinCosHalfAngleMatchLibm) {
    double worst_sin = 0, worst_cos = 0, last_sin = -1, last_cos = 2;
    bool monotone = true;
    const int n = 400000;
    for (int k = 0; k <= n; ++k) {
        const double h = SLUT_PIO2_HI * k / n;
        double s, c;
        slut_sincos_half_angle(h, &s, &c);
        if (h > 0) worst_sin = std::max(worst_sin, ulps(s, std::sin(h)));
        worst_cos = std::max(worst_cos, ulps(c, std::cos(h)));
        monotone = monotone && s >= last_sin && c <= last_cos;
        last_sin = s;
        last_cos = c;
    }
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int k = 0; k < 100000; ++k) { // small angles: the relative error of sin
        const double h = std::pow(10.0, -12 + 12 * unit(rng)) * 0.7;
        double s, c;
        slut_sincos_half_angle(h, &s, &c);
        worst_sin = std::max(worst_sin, ulps(s, std::sin(h)));
        worst_cos = std::max(worst_cos, ulps(c, std::cos(h)));
    }
    EXPECT_LE(worst_sin, 2.0);
    EXPECT_LE(worst_cos, 2.0);
    EXPECT_TRUE(monotone);
    double s, c;
    slut_sincos_half_angle(0.0, &s, &c);
    EXPECT_EQ(s, 0.0);
    EXPECT_EQ(c, 1.0);
    slut_sincos_half_angle(SLUT_PIO2_HI, &s, &c);
    EXPECT_EQ(s, 1.0);
    EXPECT_LE(ulps(c, SLUT_PIO2_LO), 1.0); // cos(fl(π/2)) = π/2 − fl(π/2) to 1e-33
    RecordProperty("worst_ulps_sin", std::to_string(worst_sin));
    RecordProperty("worst_ulps_cos", std::to_string(worst_cos));
}

// The runtime unit map against the exact one on axes of every one-parameter warp the
// tables use (LOG1P with its log spacing reached and not reached, LOGLIN, SQRT1P, LOG,
// ASINH_COT, LINEAR): the difference in x ≤ 4e-16 + 4 ulps of the warp's range
// (Goldberg's ≤ 4 ulps in g, divided by g1 − g0); the ends exactly 0 and 1, below and
// above them and for NaN clamped exactly; every node's x within 1e-13 of i/(count − 1)
// (node positions are hit: the interpolation weight of a neighbour stays ≤ 1e-13·(count−1));
// and non-decreasing on a dense sweep.
TEST(FastMath, RuntimeUnitMapMatchesExactWarps) {
    const slut_axis axes[] = {
        {0.0, 48.0, 0.05, SLUT_WARP_LOG1P, 160},      // airlight u: log spacing above 0.05
        {0.0, 0.5, 2.0, SLUT_WARP_LOG1P, 64},         // x ≤ 1 everywhere: log1p throughout
        {0.0, 1e4, 1e-3, SLUT_WARP_LOG1P, 64},        // near-light r
        {1e-3, 700.0, 8.0, SLUT_WARP_LOGLIN, 80},     // near-light T
        {-1.0, 1.0, 0.0, SLUT_WARP_SQRT1P, 32},       // near-light g
        {1e-4, 10.0, 0.0, SLUT_WARP_LOG, 40},
        {1e-3, 1.5707963267948966, 0.0, SLUT_WARP_ASINH_COT, 128},
        {-2.0, 3.0, 0.0, SLUT_WARP_LINEAR, 17},
    };
    for (const slut_axis &a : axes) {
        double g0, g1;
        slut_axis_warped_ends(&a, &g0, &g1);
        const double tol_x = 4e-16 + 4 * kUlp * std::fmax(std::fabs(g0), std::fabs(g1)) / std::fabs(g1 - g0);
        double worst = 0, last = -1;
        bool monotone = true;
        const int n = 100000;
        for (int k = 0; k <= n; ++k) {
            const double p = slut_param_from_unit(&a, static_cast<double>(k) / n);
            const double fast = slut_unit_from_warped_runtime(&a, p, g0, g1);
            worst = std::max(worst, std::fabs(fast - slut_unit_from_warped(&a, p, g0, g1)));
            monotone = monotone && fast >= last;
            last = fast;
        }
        double worst_node = 0;
        for (int i = 0; i < a.count; ++i) {
            const double x = slut_unit_from_warped_runtime(&a, slut_axis_node(&a, i), g0, g1);
            worst_node = std::max(worst_node, std::fabs(x * (a.count - 1) - i));
        }
        SCOPED_TRACE("warp " + std::to_string(a.warp));
        EXPECT_LE(worst, tol_x);
        EXPECT_LE(worst_node, 1e-13 * (a.count - 1));
        EXPECT_TRUE(monotone);
        EXPECT_EQ(slut_unit_from_warped_runtime(&a, a.min, g0, g1), 0.0);
        EXPECT_EQ(slut_unit_from_warped_runtime(&a, a.max, g0, g1), 1.0);
        EXPECT_EQ(slut_unit_from_warped_runtime(&a, a.min - 1.0, g0, g1), 0.0);
        EXPECT_EQ(slut_unit_from_warped_runtime(&a, a.max + 1.0, g0, g1), 1.0);
        EXPECT_EQ(slut_unit_from_warped_runtime(&a, std::nan(""), g0, g1), 0.0);
    }
}

} // namespace
