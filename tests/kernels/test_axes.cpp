// The axis maps (kernels/slut_axes.h, the slab axis of kernels/slut_nearlight.h): each map
// is a pair param ↔ unit coordinate shared by the kernels (nodes), the runtime samplers and
// the shader snippets. These tests pin the pair to each other (round trips), to the
// texel-centre node convention, the clamp beyond the ends, and the slab map to its
// definition through the closed-form H.
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>


extern "C" {
#include "slut_airlight.h"
}

#include "reference_data.hpp"
#include "slut_axes.h"
#include "slut_nearlight.h"

namespace {
const double kInf = std::numeric_limits<double>::infinity();
}

// Axis maps round-trip (parameter → unit → parameter), end nodes are exact, and the
// texel-centre convention puts node i at texture coordinate (i + 0.5)/count.
TEST(AxisMaps, RoundTripAndTexelCentres) {
    const slut_axis axes[] = {{0.0, 64.0, 1e-7, SLUT_WARP_LOG1P, 512},
                              {1e-3, SLUT_PIO2_HI, 0.0, SLUT_WARP_ASINH_COT, 256},
                              {1e-3, 100.0, 0.0, SLUT_WARP_LOG, 33},
                              {-1.0, 1.0, 0.0, SLUT_WARP_SQRT1P, 65},
                              {-2.0, 3.0, 0.0, SLUT_WARP_LINEAR, 9}};
    for (const auto &a : axes) {
        EXPECT_EQ(slut_axis_node(&a, 0), a.min);
        EXPECT_EQ(slut_axis_node(&a, a.count - 1), a.max);
        for (int i = 0; i < a.count; ++i) {
            const double p = slut_axis_node(&a, i);
            const double x = slut_unit_from_param(&a, p);
            EXPECT_NEAR(x, double(i) / (a.count - 1), 1e-12) << "warp " << a.warp << " node " << i;
            EXPECT_NEAR(slut_texcoord_from_unit(x, a.count), (i + 0.5) / a.count, 1e-12);
            if (i > 0) {
                EXPECT_GT(p, slut_axis_node(&a, i - 1)) << "nodes must increase";
            }
            const double back = slut_param_from_unit(&a, x);
            EXPECT_LE(std::fabs(back - p), 1e-12 * std::max(std::fabs(p), 1e-3)) << "warp " << a.warp;
        }
        int i0;
        double f;
        slut_cell_from_unit(1.0, a.count, &i0, &f);
        EXPECT_EQ(i0, a.count - 2);
        EXPECT_EQ(f, 1.0);
        slut_cell_from_unit(-0.5, a.count, &i0, &f); // clamp, never wrap
        EXPECT_EQ(i0, 0);
        EXPECT_EQ(f, 0.0);
    }
}

// Beyond its ends every axis clamps to its end node, whatever the warp does there: LOG1P
// is undefined below min − scale (the default near-light T axis starts at 1.26 with
// scale 0.3), LOG at p ≤ 0; NaN goes to the first node. Found by the near-light shader
// test: a T below 0.96 gave a NaN unit coordinate and an index outside the table.
TEST(AxisMaps, BeyondTheEndsClampToTheEndNodes) {
    const slut_axis axes[] = {{1.26, 12.6, 0.3, SLUT_WARP_LOG1P, 17},
                              {1e-3, 100.0, 0.0, SLUT_WARP_LOG, 9},
                              {1e-3, SLUT_PIO2_HI, 0.0, SLUT_WARP_ASINH_COT, 9},
                              {-0.99, 1.0, 0.0, SLUT_WARP_SQRT1P, 9},
                              {-2.0, 3.0, 0.0, SLUT_WARP_LINEAR, 9}};
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = HUGE_VAL;
    for (const auto &a : axes) {
        for (double below : {a.min - 1.0, a.min - 1e3, -inf, nan}) {
            EXPECT_EQ(slut_unit_from_param(&a, below), 0.0) << "warp " << a.warp << " p " << below;
            int i0;
            double f;
            slut_cell_from_unit(slut_unit_from_param(&a, below), a.count, &i0, &f);
            EXPECT_EQ(i0, 0);
            EXPECT_EQ(f, 0.0);
        }
        for (double above : {a.max + 1.0, a.max * 1e3 + 1e3, inf}) EXPECT_EQ(slut_unit_from_param(&a, above), 1.0);
    }
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
