// The airlight math of kernels/slut_airlight.h against references that share none of its
// code: F, its tail and the scaled tail G̃ against the 30-digit mpmath values of
// tests/reference and the Boost.Math quadrature of tests/airlight_reference.hpp; the
// asymptotic forms where they are used; the closed forms' limits.
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <boost/math/special_functions/expint.hpp>
#include <gtest/gtest.h>

#include "airlight_reference.hpp"
#include "generate_airlight.hpp"
#include "reference_data.hpp"
#include "scatterlut/airlight.hpp"

extern "C" {
#include "slut_airlight.h"
}

using slut_test::rel_err;

namespace {

constexpr double kPi = 3.14159265358979323846;

} // namespace

// F and its tail at every reference point (mpmath, 30 digits; every tail, down to 1e-171,
// cross-checked there against its closed form in E_1). Tolerance 1e-12: the panels'
// Gauss–Legendre error is ~1e-14; what remains is rounding in tan v near π/2.
TEST(AirlightMath, FAndTailMatchMpmathReference) {
    double worst = 0;
    for (const auto &p : slut_test::load_F_refs()) {
        SCOPED_TRACE("u=" + std::to_string(p.u) + " v=" + std::to_string(p.v));
        const double F = slut_F_quadrature(p.u, p.v);
        EXPECT_LE(rel_err(F, p.F), 1e-12);
        worst = std::max(worst, rel_err(F, p.F));
        const double tail = slut_tail_quadrature(p.u, p.v);
        if (p.tail < 1e-300L) {
            EXPECT_LE(tail, 1e-300) << "a tail below the double range must underflow to (nearly) 0";
        } else {
            EXPECT_LE(rel_err(tail, p.tail), 1e-12);
            worst = std::max(worst, rel_err(tail, p.tail));
        }
    }
    RecordProperty("worst_rel_err", std::to_string(worst));
}

// F(0, v) = v exactly (the integrand is 1).
TEST(AirlightMath, FAtZeroOpticalDistanceIsV) {
    for (double v : {0.0, 1e-12, 0.3, 1.0, 1.5707963267948966}) EXPECT_EQ(slut_F_quadrature(0.0, v), v);
}

// G̃ by the production rule against Boost on a grid spanning every regime: u from 0 to
// 1e4 (log), w from 1e-9 to π/2. Tolerance 1e-12: both are ~1e-14 quadratures.
TEST(AirlightMath, ScaledTailMatchesBoostOverTheWholeDomain) {
    double worst = 0;
    for (double u : {0.0, 1e-12, 1e-9, 1e-7, 1e-5, 1e-3, 0.03, 0.5, 1.0, 3.0, 17.0, 64.0, 300.0, 1e4}) {
        for (double w : {1e-9, 1e-6, 1e-4, 1e-3, 0.01, 0.1, 0.5, 1.0, 1.4, 1.5707963267948966}) {
            const double got = slut_gs_quadrature(u, w, 1.0);
            const double want = slut_ref::ref_scaled_tail(u, w);
            EXPECT_LE(rel_err(got, want), 1e-12) << "u=" << u << " w=" << w;
            EXPECT_GT(got, 0.0);
            EXPECT_LE(got, 1.0 + 1e-15);
            worst = std::max(worst, rel_err(got, want));
        }
    }
    RecordProperty("worst_rel_err", std::to_string(worst));
}

// e^a E_n(a) against Boost's expint(n, a) (a different algorithm), 1e-13.
TEST(AirlightMath, ScaledExponentialIntegralMatchesBoost) {
    for (int n : {1, 2, 4})
        for (double a : {1e-8, 1e-3, 0.2, 0.999, 1.0, 1.5, 7.0, 40.0, 700.0}) {
            const long double want = std::exp((long double)a) * boost::math::expint(n, (long double)a);
            EXPECT_LE(rel_err(slut_exp_expint(n, a), want), 1e-13) << "n=" << n << " a=" << a;
        }
    EXPECT_EQ(slut_exp_expint(2, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(slut_exp_expint(4, 0.0), 1.0 / 3.0);
}

// Beyond the table: the small-w form (error ≤ w⁴/5) and Watson's series for large u
// (≲ 8!/u^8) are exact to far better than any table. Checked against Boost at the
// edges where the runtime switches to them and beyond.
TEST(AirlightMath, AsymptoticFormsMatchBoostWhereTheyAreUsed) {
    for (double w : {1e-3, 3e-4, 1e-5, 1e-8})
        for (double u : {0.0, 1e-9, 1e-6, 1e-3, 0.1, 1.0, 30.0, 64.0, 1e3}) {
            const double a = u * std::cos(w) / std::sin(w);
            EXPECT_LE(rel_err(slut_gs_small_w(w, a), slut_ref::ref_scaled_tail(u, w)), 1e-11) << "u=" << u << " w=" << w;
        }
    for (double u : {64.0, 100.0, 1e3, 1e5})
        for (double w : {1e-8, 1e-3, 0.1, 0.7, 1.2, 1.5707963267948966})
            EXPECT_LE(rel_err(slut_gs_large_u(u, w), slut_ref::ref_scaled_tail(u, w)), std::max(3e-6 * std::pow(64.0 / u, 4), 1e-14))
                << "u=" << u << " w=" << w;
}

// The closed forms engines use (Macklin 2010; airlight_radiance_no_extinction and its
// × e^{−σ_t D} variant). Their limits in closed form, independent of the implementation:
//  γ = π/2, s = ∞: ∫_0^∞ dx/(x² + D²) = π/(2D);  γ = π: s/(D(D + s));
//  γ = 0, s < D: s/(D(D − s)), continuous from γ > 0;  γ = 0, s ≥ D: +inf (never NaN);
//  γ = 0, s = ∞: +inf;  γ = π, s = ∞: 1/D;  s = 0, σ_s = 0, I0 = 0: 0.
TEST(AirlightClosedForm, LimitsAreFiniteAndCorrect) {
    const double p = 1.0 / (4 * kPi), inf = std::numeric_limits<double>::infinity();
    const double ss = 0.3, sa = 0.1, I = 2.0;
    auto no_ext = [&](double D, double gamma, double s) {
        return scatterlut::airlight_radiance_no_extinction({ss, sa, I, D, gamma, s});
    };
    auto attenuated = [&](double D, double gamma, double s) {
        return scatterlut::airlight_radiance_no_extinction_attenuated({ss, sa, I, D, gamma, s});
    };
    const double k = ss * p * I;
    EXPECT_LE(rel_err(no_ext(3.0, kPi / 2, inf), k * kPi / 6.0), 1e-15);
    EXPECT_LE(rel_err(no_ext(3.0, kPi, 5.0), k * 5.0 / (3.0 * 8.0)), 1e-15);
    EXPECT_LE(rel_err(no_ext(3.0, kPi - 1e-9, 5.0), k * 5.0 / (3.0 * 8.0)), 1e-15);
    EXPECT_LE(rel_err(no_ext(3.0, kPi, inf), k / 3.0), 1e-15);
    EXPECT_LE(rel_err(no_ext(5.0, 0.0, 2.0), k * 2.0 / (5.0 * 3.0)), 1e-15);
    EXPECT_LE(rel_err(no_ext(5.0, 1e-12, 2.0), k * 2.0 / (5.0 * 3.0)), 1e-12);
    EXPECT_LE(rel_err(no_ext(5.0, 1e-300, 2.0), k * 2.0 / (5.0 * 3.0)), 1e-15);
    EXPECT_TRUE(std::isinf(no_ext(5.0, 0.0, 5.0)));
    EXPECT_TRUE(std::isinf(no_ext(5.0, 0.0, 6.0)));
    EXPECT_TRUE(std::isinf(no_ext(5.0, 0.0, inf)));
    EXPECT_TRUE(std::isinf(attenuated(5.0, 0.0, 6.0)));
    EXPECT_TRUE(std::isinf(scatterlut::airlight_radiance_no_extinction_attenuated({500.0, 500.0, 1.0, 5.0, 0.0, 6.0})));
    // Just off the axis through the light: finite, large, and the angle form's value.
    for (double gamma : {1e-6, 1e-12, 1e-200}) {
        const double D = 5.0, s = 6.0, h = D * std::sin(gamma);
        const double want = k * (kPi - std::atan(s * h / (D * (s - D * std::cos(gamma))))) / h;
        const double got = no_ext(D, gamma, s);
        EXPECT_TRUE(std::isfinite(got)) << gamma;
        EXPECT_LE(rel_err(got, want), 1e-13) << gamma;
    }
    // The subtended angle Δφ/h at a generic geometry, both sides of den = 0 (Δφ = π/2).
    for (double s : {1.0, 3.0 / std::cos(1.1) - 1e-9, 3.0 / std::cos(1.1), 3.0 / std::cos(1.1) + 1e-9, 20.0}) {
        const double D = 3.0, gamma = 1.1;
        const double want = k * std::atan2(s * D * std::sin(gamma), D * D - s * D * std::cos(gamma)) / (D * std::sin(gamma));
        EXPECT_LE(rel_err(no_ext(D, gamma, s), want), 1e-14) << s;
    }
    EXPECT_EQ(no_ext(3.0, 1.0, 0.0), 0.0);
    EXPECT_EQ(scatterlut::airlight_radiance_no_extinction({0.0, 0.1, 1.0, 5.0, 0.0, 6.0}), 0.0);
    EXPECT_EQ(scatterlut::airlight_radiance_no_extinction_attenuated({0.3, 0.1, 0.0, 5.0, 0.0, 6.0}), 0.0);
    EXPECT_LE(rel_err(attenuated(3.0, kPi, 5.0), k * 5.0 / 24.0 * std::exp(-0.4 * 3.0)), 1e-15);
    EXPECT_THROW(scatterlut::airlight_radiance_no_extinction({-1.0, 0.1, 1.0, 2.0, 1.0, 3.0}), std::invalid_argument);
    EXPECT_THROW(scatterlut::airlight_radiance_no_extinction_attenuated({0.1, 0.1, 1.0, 0.0, 1.0, 3.0}),
                 std::invalid_argument);
}

// Against the exact radiance on random geometries: L_0·e^{−σ_t(2s + D)} ≤ L ≤ L_0·e^{−σ_t D}
// ≤ L_0 (D ≤ x + d(x) ≤ 2x + D), so as σ_t → 0 both closed forms agree with exact to
// σ_t·(2s + D); at σ_t = 1e-12 /m that is ≤ 1e-9 here. With real fog they are far off.
TEST(AirlightClosedForm, BracketsExactAndAgreesAsExtinctionVanishes) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n = 0; n < 2000; ++n) {
        const double D = std::pow(10.0, -1 + 3 * unit(rng)), gamma = 1e-4 + (kPi - 2e-4) * unit(rng);
        const double s = D * std::pow(10.0, -3 + 4 * unit(rng));
        for (double sigma_t : {1e-12, 1e-3, 0.05, 1.0}) {
            const scatterlut::AirlightQuery q{0.8 * sigma_t, 0.2 * sigma_t, 1.5, D, gamma, s};
            const double exact = scatterlut::airlight_radiance_exact(q);
            const double L0 = scatterlut::airlight_radiance_no_extinction(q);
            const double La = scatterlut::airlight_radiance_no_extinction_attenuated(q);
            if (!std::isfinite(exact)) continue;
            const double slack = 1e-12; // the exact quadrature's ~1e-13 and the closed form's rounding
            EXPECT_LE(exact, La * (1 + slack)) << "D=" << D << " gamma=" << gamma << " s=" << s;
            EXPECT_LE(La, L0 * (1 + slack));
            EXPECT_GE(exact, L0 * std::exp(-sigma_t * (2 * s + D)) * (1 - slack));
            if (sigma_t == 1e-12) {
                EXPECT_LE(rel_err(L0, exact), sigma_t * (2 * s + D) + slack);
                EXPECT_LE(rel_err(La, exact), sigma_t * (2 * s + D) + slack);
            }
        }
    }
}
