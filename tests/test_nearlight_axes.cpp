// The axis maps of the near-light tables (kernels/slut_axes.h, kernels/slut_nearlight.h):
// the loglin T warp and the 4-D table's slab axis q. Each map is a pair param ↔ unit
// coordinate shared by the kernel (nodes), the runtime sampler and the shader snippets;
// these tests pin the pair to each other (round trips), to the texel-centre node
// convention, and the slab map to its definition through the closed-form H.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "reference_data.hpp"
#include "slut_axes.h"
#include "slut_nearlight.h"

namespace {
const double kInf = std::numeric_limits<double>::infinity();
}

// loglin: g(p) = ln p + p/s. Round trips p → x → p and x → p → x to 1e-14 over the T
// axes used (s ∈ [0.1, 10]) and beyond (p from 1e-6 to 1e3); tolerance: a few ulps of
// the ~30 e-folds of the axis, far below any interpolation effect (1e-4 of a cell).
TEST(NearLightAxes, LoglinRoundTrips) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (double s : {0.1, 1.0, 1.5, 10.0}) {
        const slut_axis a = {1e-6, 1e3, s, SLUT_WARP_LOGLIN, 64};
        EXPECT_EQ(slut_param_from_unit(&a, 0.0), a.min);
        EXPECT_EQ(slut_param_from_unit(&a, 1.0), a.max);
        for (int k = 0; k < 2000; ++k) {
            const double x = U(rng);
            const double p = slut_param_from_unit(&a, x);
            EXPECT_NEAR(slut_unit_from_param(&a, p), x, 1e-14) << "s=" << s << " x=" << x;
            const double q = a.min * std::pow(a.max / a.min, U(rng));
            EXPECT_LE(slut_test::rel_err(slut_param_from_unit(&a, slut_unit_from_param(&a, q)), q), 1e-13)
                << "s=" << s << " p=" << q;
        }
        // The inverse solves ln p + p/s = y: checked on the definition, not on the forward map's code.
        for (double p : {1e-6, 0.01, 0.5, 3.0, 999.0}) {
            const double y = std::log(p) + p / s;
            EXPECT_LE(slut_test::rel_err(slut_loglin_inverse(y, s), p), 1e-14) << "s=" << s << " p=" << p;
        }
    }
}

// The slab axis q (warp nl_qodds): σ(T, g, S) = T·(T H∞)·q/(1 − q) with q = H(S)/H(∞).
// Reference: the closed-form H (slut_nl_H, itself tested against mpmath in
// test_nearlight_math) — q computed from H directly, independent of the odds' code.
// Tolerance: both sides are a few closed-form operations (1e-13), but the reference's 1 − q
// cancels as q → 1 (S/T up to 2e4 here), losing ~ε/(1 − q); the code under test does not
// (it takes ∫_S^∞ ĥ⁻² directly), so the tolerance follows the reference's loss.
TEST(NearLightAxes, SlabOddsFollowTheWeightFraction) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int k = 0; k < 5000; ++k) {
        const double T = 1e-3 * std::pow(2e4, U(rng)), g = -0.99 + 1.99 * U(rng), S = 1e-3 * std::pow(2e4, U(rng));
        const double q = slut_nl_H(T, g, S) / slut_nl_H(T, g, kInf);
        const double sigma = slut_nl_depth_odds(T, g, S);
        const double want = T * (T * slut_nl_H(T, g, kInf)) * q / (1.0 - q);
        EXPECT_LE(slut_test::rel_err(sigma, want), 1e-13 + 1e-15 / (1.0 - q)) << "T=" << T << " g=" << g << " S=" << S;
        // The inverse by the law of sines: back to S.
        EXPECT_LE(slut_test::rel_err(slut_nl_S_from_depth_odds(T, g, sigma), S), 1e-12)
            << "T=" << T << " g=" << g << " S=" << S;
    }
    // Limits (derivation in slut_nearlight.h): σ = S exactly at g = 1; σ → S for S ≪ T;
    // σ → S·(θ/sin θ)² for S ≫ T. Tolerances: the next order, S/T·O(1) and T/S·O(1).
    for (double S : {1e-3, 0.7, 20.0}) EXPECT_LE(slut_test::rel_err(slut_nl_depth_odds(2.0, 1.0, S), S), 1e-14);
    for (double g : {-0.99, -0.5, 0.3}) {
        const double th = std::acos(g), k = th / std::sin(th);
        EXPECT_LE(slut_test::rel_err(slut_nl_depth_odds(10.0, g, 1e-6), 1e-6), 1e-5) << g;
        EXPECT_LE(slut_test::rel_err(slut_nl_depth_odds(1e-3, g, 20.0), 20.0 * k * k), 1e-3) << g;
    }
}

// Unit coordinate round trips on the default slab axis [1e-3, 20] at random (T, g), the ends
// exact, node i at unit i/(count − 1) (the texel-centre convention: texture coordinate
// slut_texcoord_from_unit), and at g = 1 the map is the LOG warp in S.
TEST(NearLightAxes, SlabAxisRoundTripsAndNodes) {
    const slut_axis a = {1e-3, 20.0, 0.0, SLUT_WARP_NL_QODDS, 40};
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int k = 0; k < 3000; ++k) {
        const double T = 1e-3 * std::pow(2e4, U(rng)), g = -0.99 + 1.99 * U(rng);
        EXPECT_EQ(slut_nl_S_from_unit(&a, T, g, 0.0), a.min);
        EXPECT_EQ(slut_nl_S_from_unit(&a, T, g, 1.0), a.max);
        const double x = U(rng);
        EXPECT_NEAR(slut_nl_unit_from_S(&a, T, g, slut_nl_S_from_unit(&a, T, g, x)), x, 1e-12)
            << "T=" << T << " g=" << g << " x=" << x;
        const double S = a.min * std::pow(a.max / a.min, U(rng));
        EXPECT_LE(slut_test::rel_err(slut_nl_S_from_unit(&a, T, g, slut_nl_unit_from_S(&a, T, g, S)), S), 1e-12)
            << "T=" << T << " g=" << g << " S=" << S;
        const int i = static_cast<int>(U(rng) * a.count) % a.count;
        EXPECT_NEAR(slut_nl_unit_from_S(&a, T, g, slut_nl_S_node(&a, T, g, i)), i / double(a.count - 1), 1e-12);
        // Monotone: more slab, larger coordinate.
        EXPECT_LT(slut_nl_unit_from_S(&a, T, g, S), slut_nl_unit_from_S(&a, T, g, S * 1.001));
    }
    const slut_axis log_axis = {1e-3, 20.0, 0.0, SLUT_WARP_LOG, 40};
    for (double S : {1e-3, 0.02, 1.0, 19.0})
        EXPECT_NEAR(slut_nl_unit_from_S(&a, 3.0, 1.0, S), slut_unit_from_param(&log_axis, S), 1e-14) << S;
}

// The value base B of the 4-D table (E = B·e^{stored}): positive, ≤ 1, and its limits:
// B = 1 at T = 0; B → e^{−T} for r = 0; B → e^{−T} + (1 − e^{−T})·r/S·… in thin slabs
// (E_thin's own limits, test_nearlight_math); finite for S = ∞ (S_eff = T).
TEST(NearLightAxes, ValueBaseIsAPositiveClosedForm) {
    EXPECT_EQ(slut_nl_E_base(0.0, 0.3, 1.0), 1.0);
    for (double T : {1e-3, 1.0, 20.0}) {
        EXPECT_LE(slut_test::rel_err(slut_nl_E_base(T, 0.0, 2.0), std::exp(-T)), 1e-15);
        for (double r : {0.0, 1e-9, 0.5, 1e3})
            for (double S : {1e-3, 1.0, 20.0, kInf}) {
                const double B = slut_nl_E_base(T, r, S);
                EXPECT_TRUE(B > 0.0 && B <= 1.0) << T << " " << r << " " << S;
            }
    }
}
