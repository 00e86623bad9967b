// The near-light runtime (tables/src/nearlight.cpp): radiance from tables against exact
// (scalar, batch, general lookup), and eval's exact answers against the 30-digit mpmath
// references.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <gtest/gtest.h>

#include "eval.hpp"
#include "generate_nearlight.hpp"
#include "nearlight_reference.hpp"
#include "nearlight_tables.hpp"
#include "opencl_device.hpp"
#include "reference_data.hpp"
#include "scatterlut/airlight.hpp"

extern "C" {
#include "slut_nearlight.h"
}

using slut_test::default_e4;
using slut_test::device;
using slut_test::query_of;
using slut_test::small_table;

// eval's "exact" for N within 1e-8 of every point of N_ref.json (mpmath).
TEST(NearLightEval, ExactMatchesMpmathReference) {
    scatterlut::EvalTables none;
    for (const auto &p : slut_test::load_N_refs()) {
        nlohmann::json q = {{"quantity", "N"}, {"T", p.T}, {"g", p.g}, {"r", p.r}};
        if (std::isinf(p.S)) q["S"] = "inf";
        else q["S"] = p.S;
        const auto a = scatterlut::eval_query(q, none);
        EXPECT_LE(slut_test::rel_err(a["exact"].get<double>(), p.N), 1e-8) << q.dump();
        EXPECT_LE(slut_test::rel_err(a["E"].get<double>(), p.E), 1e-8) << q.dump();
        EXPECT_TRUE(a["table"].is_null());
    }
}

// near_light radiance: exact against physical_ref.json; from tables within the domain the
// tables cover, finite and non-negative; a light below the surface gives 0; a viewer below
// is an error.
TEST(NearLightRadiance, ExactAndTableAgainstPhysicalReference) {
    scatterlut::NearLightTable e3(small_table(false));
    for (const auto &c : slut_test::load_near_light_refs()) {
        const scatterlut::NearLightQuery q = query_of(c);
        EXPECT_LE(slut_test::rel_err(scatterlut::near_light_radiance_exact(q), c.L), 1e-8);
        const double table = e3.radiance(q);
        EXPECT_TRUE(std::isfinite(table) && table >= 0.0);
        const double thin = scatterlut::near_light_radiance_thin(q), distant = scatterlut::near_light_radiance_distant(q);
        EXPECT_TRUE(std::isfinite(thin) && thin >= 0.0 && std::isfinite(distant) && distant >= 0.0);
    }
    scatterlut::NearLightQuery below;
    below.sigma_s_per_m = 1.0;
    below.intensity_W_per_sr = 1.0;
    below.length_m = 1.0;
    below.eye_dir[2] = -1.0;
    EXPECT_THROW(scatterlut::near_light_radiance_exact(below), std::invalid_argument);
}

// The default thick table samples E within 1 % wherever E ≥ 1e-6 (the default plans' target),
// measured by the generator at 20000 random points against the shared quadrature (itself
// checked against Boost above). Off-table points fall back to exact integration.
TEST(NearLightTable, DefaultThickTableWithinOnePercent) {
    const scatterlut::Table t = scatterlut::generate_nearlight_table(device(), scatterlut::NearLightPlan{}, {});
    EXPECT_LE(t.accuracy.sampling_max_rel, 1e-2);
    EXPECT_GT(t.accuracy.sampling_points, 15000u);
    scatterlut::NearLightTable table(t);
    // And at the hard corners (T at both ends, g = −0.99 and 1, r = 0, 1e-12 and r_max).
    const scatterlut::SamplingStats corners = scatterlut::measure_nearlight_corners(table, 20000, 3);
    EXPECT_LE(corners.max_rel, 1e-2) << "worst at T=" << corners.worst_at[0] << " g=" << corners.worst_at[1]
                                     << " r=" << corners.worst_at[2];
    EXPECT_GT(corners.points, 10000u);
    EXPECT_FALSE(table.covers(50.0, 0.9, 1e-4, std::numeric_limits<double>::infinity()));
    EXPECT_LE(slut_test::rel_err(table.E(50.0, 0.9, 1e-4, std::numeric_limits<double>::infinity()),
                                 2.015009384261607074432191e-6L), 1e-8); // off-table: exact (N_ref.json)
}

// The default finite-thickness table samples E within 1 % wherever E ≥ 1e-6 (the default
// plans' target), at the generator's 20000 random points (T, g, r at uniform unit coordinates,
// S log-uniform in [S_min, S_max]) and at 20000 hard-corner points (S at S_min and just
// above, S_max, S ≈ −g·T where the far face cuts the 1/ĥ² peak; g = g_min and 1; r = 0,
// 1e-12, r_max; T at both ends), against slut_nl_E (checked against Boost above, mpmath in
// test_nearlight_math). Outside its domain the table integrates exactly.
TEST(NearLightTable, DefaultFiniteTableWithinOnePercent) {
    const scatterlut::Table &t = default_e4();
    EXPECT_LE(t.accuracy.sampling_max_rel, 1e-2);
    EXPECT_GT(t.accuracy.sampling_points, 15000u);
    EXPECT_LE(t.accuracy.integration_max_rel, 1e-10); // tolerance 1e-11: see EveryNodeMatchesBoostReference
    const scatterlut::NearLightTable table(t);
    const scatterlut::SamplingStats corners = scatterlut::measure_nearlight_corners(table, 20000, 3);
    std::printf("default E4: random max %.3e p99 %.3e; corners max %.3e p99 %.3e (%llu points)\n",
                t.accuracy.sampling_max_rel, t.accuracy.sampling_p99_rel, corners.max_rel, corners.p99_rel,
                static_cast<unsigned long long>(corners.points));
    EXPECT_LE(corners.max_rel, 1e-2) << "worst at T=" << corners.worst_at[0] << " g=" << corners.worst_at[1]
                                     << " r=" << corners.worst_at[2] << " S=" << corners.worst_at[3];
    EXPECT_GT(corners.points, 10000u);
    for (double S : {1e-4, 25.0}) { // thinner and thicker than the axis: exact, not clamped
        EXPECT_FALSE(table.covers(2.0, -0.3, 0.1, S));
        EXPECT_LE(slut_test::rel_err(table.E(2.0, -0.3, 0.1, S), slut_nl_E(2.0, -0.3, 0.1, S)), 1e-14);
    }
}

// Radiance from the default 4-D table against exact radiance (near_light_radiance_exact) for
// random finite slabs in physical units — the light above the plane at 0.05–20 m, σ_t
// 0.05–5 /m, paths 0.01–10 m, eye and light directions uniform over the upper hemisphere —
// within 1 % where E ≥ 1e-6 (the table's acceptance; the rest of the radiance is closed
// form), and the finite-length near_light cases of physical_ref.json (mpmath, 30 digits)
// within 1 % (inside the table) or 1e-8 (outside it: exact integration).
TEST(NearLightRadiance, FiniteTableRadianceMatchesExact) {
    const scatterlut::NearLightTable table(default_e4());
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto hemisphere = [&](double *v) {
        const double z = U(rng), phi = 2 * M_PI * U(rng), s = std::sqrt(1 - z * z);
        v[0] = s * std::cos(phi);
        v[1] = s * std::sin(phi);
        v[2] = z;
    };
    int compared = 0, covered = 0;
    double worst = 0;
    for (int k = 0; k < 3000; ++k) {
        scatterlut::NearLightQuery q;
        q.sigma_s_per_m = 0.05 * std::pow(100.0, U(rng));
        q.sigma_a_per_m = q.sigma_s_per_m * U(rng);
        q.intensity_W_per_sr = 10.0;
        hemisphere(q.eye_dir);
        if (q.eye_dir[2] < 1e-3) continue;
        double dir[3];
        hemisphere(dir);
        const double l = 0.05 * std::pow(400.0, U(rng));
        for (int c = 0; c < 3; ++c) q.light_rel_m[c] = l * dir[c];
        q.length_m = 0.01 * std::pow(1000.0, U(rng));
        const scatterlut::NearLightParams p = scatterlut::near_light_params(q);
        if (p.light_below || slut_nl_E(p.T, p.g, p.r, p.S) < 1e-6) continue;
        const double exact = scatterlut::near_light_radiance_exact(q), got = table.radiance(q);
        const double err = slut_test::rel_err(got, exact);
        EXPECT_LE(err, 1e-2) << "T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S;
        worst = std::max(worst, err);
        ++compared;
        covered += table.covers(p.T, p.g, p.r, p.S);
    }
    std::printf("finite slabs: %d compared (%d inside the table), max rel err %.3e\n", compared, covered, worst);
    EXPECT_GT(covered, 1000);
    int finite_cases = 0;
    for (const auto &c : slut_test::load_near_light_refs()) {
        if (!std::isfinite(c.length)) continue;
        const scatterlut::NearLightQuery q = query_of(c);
        const scatterlut::NearLightParams p = scatterlut::near_light_params(q);
        const bool inside = !p.light_below && table.covers(p.T, p.g, p.r, p.S);
        EXPECT_LE(slut_test::rel_err(table.radiance(q), c.L), inside ? 1e-2 : 1e-8)
            << "T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S;
        ++finite_cases;
    }
    EXPECT_GT(finite_cases, 0);
}

// A query with σ_s log-uniform in 0.05–5 /m, σ_a uniform in [0, σ_s) and the given I0 (W/sr);
// the geometry left to the caller.
scatterlut::NearLightQuery random_medium_query(std::mt19937_64 &rng, double intensity_W_per_sr) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    scatterlut::NearLightQuery q;
    q.sigma_s_per_m = 0.05 * std::pow(100.0, U(rng));
    q.sigma_a_per_m = q.sigma_s_per_m * U(rng);
    q.intensity_W_per_sr = intensity_W_per_sr;
    return q;
}

// The batch radiance is the scalar radiance per query (to 1e-12 relative: libmvec's ≤ 4 ulp
// exp/expm1/log/atan where the scalar path has libm's), for batch sizes around the 4-lane
// blocks, on the default thick and finite tables (f32: the float copy) and the small f64 ones,
// over thick and finite slabs in and out of each table, with refraction and Fresnel on some,
// a light below the plane, zero length, no scattering, the light at the entry point (+inf) and
// g = +0 exactly (the eye ray perpendicular to the light direction).
TEST(NearLightTable, BatchMatchesScalarPerQuery) {
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto hemisphere = [&](double *v) {
        const double z = 0.02 + 0.98 * U(rng), phi = 2 * M_PI * U(rng), s = std::sqrt(1 - z * z);
        v[0] = s * std::cos(phi);
        v[1] = s * std::sin(phi);
        v[2] = z;
    };
    std::vector<scatterlut::NearLightQuery> queries;
    for (int k = 0; k < 3000; ++k) {
        scatterlut::NearLightQuery q = random_medium_query(rng, 10.0);
        hemisphere(q.eye_dir);
        double dir[3];
        hemisphere(dir);
        if (k % 50 == 7) dir[2] = -dir[2]; // the light below the plane: 0
        const double l = 0.05 * std::pow(400.0, U(rng));
        for (int c = 0; c < 3; ++c) q.light_rel_m[c] = l * dir[c];
        q.length_m = (k % 2) ? std::numeric_limits<double>::infinity() : 0.01 * std::pow(1000.0, U(rng));
        if (k % 7 == 3) {
            q.eta = 1.33;
            q.fresnel = (k % 14 == 3);
        }
        if (k % 101 == 5) { // g = +0 exactly (e·l = −ls² + ls²): the H integral's den = 0 case (π/(2w))
            const double h = std::sqrt(0.5);
            q.eye_dir[0] = h, q.eye_dir[1] = 0.0, q.eye_dir[2] = h;
            q.light_rel_m[0] = -l * h, q.light_rel_m[1] = 0.0, q.light_rel_m[2] = l * h;
            q.eta = 1.0;
        }
        if (k % 97 == 11) q.length_m = 0.0;
        if (k % 97 == 12) q.sigma_s_per_m = 0.0;
        if (k % 97 == 13) q.light_rel_m[0] = q.light_rel_m[1] = q.light_rel_m[2] = 0.0;
        queries.push_back(q);
    }
    const scatterlut::Table e3 = scatterlut::generate_nearlight_table(device(), scatterlut::NearLightPlan{}, {});
    const scatterlut::NearLightTable tables[] = {scatterlut::NearLightTable(e3), scatterlut::NearLightTable(default_e4()),
                                                 scatterlut::NearLightTable(small_table(false)),
                                                 scatterlut::NearLightTable(small_table(true))};
    for (const auto &table : tables) {
        int covered = 0;
        for (size_t count : {size_t{0}, size_t{1}, size_t{3}, size_t{4}, size_t{6}, size_t{9}, queries.size()}) {
            std::vector<double> out(count + 1, -1.0);
            table.radiance(queries.data(), count, out.data());
            EXPECT_EQ(out[count], -1.0) << "wrote past the end";
            for (size_t i = 0; i < count; ++i) {
                const double want = table.radiance(queries[i]);
                if (std::isinf(want) || want == 0.0) {
                    EXPECT_EQ(out[i], want) << i;
                    continue;
                }
                const scatterlut::NearLightParams p = scatterlut::near_light_params(queries[i]);
                EXPECT_LE(slut_test::rel_err(out[i], want), 1e-12)
                    << "count " << count << " query " << i << ": T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S;
                if (count == queries.size()) covered += table.covers(p.T, p.g, p.r, p.S);
            }
        }
        EXPECT_GT(covered, 200) << table.table().kind; // the vector lanes were exercised
    }
}

// A bad query anywhere in a batch: std::invalid_argument naming the first bad one's index and
// what is wrong with it, nothing written (the viewer below the surface alone; then a field
// check failing before it).
TEST(NearLightTable, BatchChecksEveryQueryBeforeWriting) {
    const scatterlut::NearLightTable table(small_table(false));
    std::vector<scatterlut::NearLightQuery> queries(7);
    for (auto &q : queries) {
        q.sigma_s_per_m = 0.5;
        q.intensity_W_per_sr = 1.0;
        q.length_m = std::numeric_limits<double>::infinity();
        q.light_rel_m[0] = 0.3;
    }
    queries[5].eye_dir[2] = -1.0; // the viewer below the surface
    for (const auto &[bad_index, what] : {std::pair<int, const char *>{5, "viewer is below"}, {2, "sigma_a"}}) {
        if (bad_index == 2) queries[2].sigma_a_per_m = -1.0;
        std::vector<double> out(queries.size(), -1.0);
        try {
            table.radiance(queries.data(), queries.size(), out.data());
            ADD_FAILURE() << "no exception";
        } catch (const std::invalid_argument &e) {
            const std::string message = e.what();
            EXPECT_NE(message.find("query " + std::to_string(bad_index) + ":"), std::string::npos) << message;
            EXPECT_NE(message.find(what), std::string::npos) << message;
        }
        for (double v : out) EXPECT_EQ(v, -1.0);
    }
}

// The 4-D table's scalar radiance packs its transcendentals into vector lanes where the CPU
// allows (nearlight.cpp); it must equal the general assembly σ_s/(4π)·I0·E·(T·H)/l from the
// public lookup NearLightTable::E and slut_nl_H_scaled to 1e-12 relative (rounding only).
TEST(NearLightTable, FiniteRadianceMatchesTheGeneralLookup) {
    const scatterlut::NearLightTable table(default_e4());
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int covered = 0;
    for (int k = 0; k < 3000; ++k) {
        scatterlut::NearLightQuery q;
        q.sigma_s_per_m = 0.05 * std::pow(100.0, U(rng));
        q.sigma_a_per_m = q.sigma_s_per_m * U(rng);
        q.intensity_W_per_sr = 3.0;
        const double z = 0.02 + 0.98 * U(rng), phi = 2 * M_PI * U(rng);
        q.eye_dir[0] = std::sqrt(1 - z * z) * std::cos(phi);
        q.eye_dir[1] = std::sqrt(1 - z * z) * std::sin(phi);
        q.eye_dir[2] = z;
        const double zl = U(rng), phil = 2 * M_PI * U(rng), l = 0.05 * std::pow(400.0, U(rng));
        q.light_rel_m[0] = l * std::sqrt(1 - zl * zl) * std::cos(phil);
        q.light_rel_m[1] = l * std::sqrt(1 - zl * zl) * std::sin(phil);
        q.light_rel_m[2] = l * zl;
        q.length_m = 0.01 * std::pow(1000.0, U(rng));
        const scatterlut::NearLightParams p = scatterlut::near_light_params(q);
        if (p.light_below) continue;
        const double distance = std::sqrt(q.light_rel_m[0] * q.light_rel_m[0] + q.light_rel_m[1] * q.light_rel_m[1] +
                                          q.light_rel_m[2] * q.light_rel_m[2]);
        const double want = q.sigma_s_per_m / (4 * M_PI) * q.intensity_W_per_sr * table.E(p.T, p.g, p.r, p.S) *
                            slut_nl_H_scaled(p.g, q.length_m / distance) / distance;
        EXPECT_LE(slut_test::rel_err(table.radiance(q), want), 1e-12) << "T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S;
        covered += table.covers(p.T, p.g, p.r, p.S);
    }
    EXPECT_GT(covered, 1000);
}

// The thick medium's T·H on the scalar radiance's fast path (angle_over_sine: θ/sin θ from one
// divide and fdlibm's atan polynomial, the reduction folded into the divide) against
// atan2(sin θ, cos θ)/sin θ in long double from the same two doubles: within 4 ulp (2^-53
// relative each) over cos θ uniform in [−1, 1], near ±1 and 0, and on both sides of the
// reduction's breaks t = sin θ/|cos θ| or its inverse = 7/16, 11/16 and 1; the kernel's
// exact limits at cos θ = ±1 and 0.
TEST(NearLightTable, ThickAngleOverSineWithinUlpsOfTheReference) {
    std::vector<double> cosines;
    std::mt19937_64 rng(43);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int k = 0; k < 200000; ++k) cosines.push_back(U(rng));
    for (int e = 1; e <= 16; ++e)
        for (const double c : {1.0 - std::pow(10.0, -e), std::pow(10.0, -e)}) {
            cosines.push_back(c);
            cosines.push_back(-c);
        }
    for (const double t : {7.0 / 16.0, 11.0 / 16.0, 1.0})
        for (const double ratio : {t, 1.0 / t}) { // sin θ/|cos θ| = ratio at |cos θ| = 1/√(1 + ratio²)
            double c = 1.0 / std::sqrt(1.0 + ratio * ratio);
            for (int k = 0; k < 8; ++k) c = std::nextafter(c, 0.0);
            for (int k = 0; k < 16; ++k, c = std::nextafter(c, 1.0)) {
                cosines.push_back(c);
                cosines.push_back(-c);
            }
        }
    double worst = 0.0, worst_at = 0.0;
    for (const double g : cosines) {
        const double sg = slut_nl_sin_from_cos(g);
        const long double want = std::atan2(static_cast<long double>(sg), static_cast<long double>(g)) / sg;
        const double got = scatterlut::detail::near_light_angle_over_sine(g, sg);
        const double ulps = static_cast<double>(std::fabs((got - want) / want)) / 0x1p-53;
        if (!(ulps <= worst)) worst = ulps, worst_at = g;
    }
    EXPECT_LE(worst, 4.0) << "at cos = " << worst_at;
    std::printf("angle_over_sine: worst %.2f ulp at cos = %.17g over %zu cosines\n", worst, worst_at, cosines.size());
    EXPECT_EQ(scatterlut::detail::near_light_angle_over_sine(1.0, 0.0), slut_nl_H_scaled(1.0, HUGE_VAL));
    EXPECT_EQ(scatterlut::detail::near_light_angle_over_sine(-1.0, 0.0), HUGE_VAL);
    EXPECT_EQ(slut_nl_H_scaled(-1.0, HUGE_VAL), HUGE_VAL);
    EXPECT_NEAR(scatterlut::detail::near_light_angle_over_sine(0.0, 1.0), M_PI / 2, 1e-16);
    EXPECT_NEAR(scatterlut::detail::near_light_angle_over_sine(-0.0, 1.0), M_PI / 2, 1e-16);
}

// The 3-D table's scalar radiance takes a vector fast path where the CPU allows (nearlight.cpp:
// the axis warps as one vector call, the cell gathered before H); it must equal the general
// assembly transmittance·σ_s/(4π)·I0·E·(T·H)/l from the public lookup NearLightTable::E,
// slut_nl_H_scaled and slut_exit_transmittance to 1e-12 relative (libmvec's log against libm's),
// and give exactly 0 or +inf where that does: on the default table (f32, warps loglin, sqrt1p,
// log1p) and a small f32 one whose g axis is log1p, over random geometries and hostile ones:
// the light below the plane, in the plane (r = 0), at the entry point, on the view ray (g = ±1),
// a grazing eye, T → 0, outside the table, refraction with and without Fresnel, zero scattering.
TEST(NearLightTable, ThickRadianceMatchesTheGeneralLookup) {
    scatterlut::NearLightPlan log1p_g;
    log1p_g.n_T = 12;
    log1p_g.n_g = 14;
    log1p_g.n_r = 10;
    log1p_g.g_warp = SLUT_WARP_LOG1P;
    log1p_g.g_scale = 0.02;
    const scatterlut::NearLightTable tables[] = {
        scatterlut::NearLightTable(scatterlut::generate_nearlight_table(device(), scatterlut::NearLightPlan{}, {})),
        scatterlut::NearLightTable(scatterlut::generate_nearlight_table(device(), log1p_g, {}))};
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::vector<scatterlut::NearLightQuery> queries;
    for (int k = 0; k < 4000; ++k) {
        scatterlut::NearLightQuery q = random_medium_query(rng, 2.0);
        const double z = (k % 11 == 5) ? 1e-7 : 0.02 + 0.98 * U(rng), phi = 2 * M_PI * U(rng);
        q.eye_dir[0] = std::sqrt(1 - z * z) * std::cos(phi);
        q.eye_dir[1] = std::sqrt(1 - z * z) * std::sin(phi);
        q.eye_dir[2] = z;
        double zl = U(rng);
        if (k % 13 == 1) zl = -zl;  // below the plane: 0
        if (k % 13 == 2) zl = 0.0;  // in the plane: r = 0
        const double phil = 2 * M_PI * U(rng), l = 0.05 * std::pow(400.0, U(rng));
        q.light_rel_m[0] = l * std::sqrt(1 - zl * zl) * std::cos(phil);
        q.light_rel_m[1] = l * std::sqrt(1 - zl * zl) * std::sin(phil);
        q.light_rel_m[2] = l * zl;
        if (k % 13 == 3)
            for (int c = 0; c < 3; ++c) q.light_rel_m[c] = l * q.eye_dir[c]; // g = 1
        if (k % 13 == 4) q.light_rel_m[0] = q.light_rel_m[1] = q.light_rel_m[2] = 0.0; // at O: +inf
        if (k % 13 == 6) q.sigma_s_per_m = q.sigma_a_per_m = 1e-12;                  // T → 0
        if (k % 13 == 7) q.sigma_a_per_m = 1e3;                                       // T beyond the table
        if (k % 13 == 8) q.sigma_s_per_m = 0.0;
        if (k % 7 == 2) {
            q.eta = (k % 14 == 2) ? 1.5 : 0.75;
            q.fresnel = (k % 21 == 2) || (k % 21 == 9);
        }
        q.length_m = std::numeric_limits<double>::infinity();
        queries.push_back(q);
    }
    for (const auto &table : tables) {
        int covered = 0, zero = 0, infinite = 0;
        for (const auto &q : queries) {
            const scatterlut::NearLightParams p = scatterlut::near_light_params(q);
            const double got = table.radiance(q);
            if (p.light_below || q.sigma_s_per_m == 0.0) {
                EXPECT_EQ(got, 0.0);
                ++zero;
                continue;
            }
            const double distance = std::sqrt(q.light_rel_m[0] * q.light_rel_m[0] + q.light_rel_m[1] * q.light_rel_m[1] +
                                              q.light_rel_m[2] * q.light_rel_m[2]);
            const double H_scaled = slut_nl_H_scaled(p.g, HUGE_VAL);
            if (!(distance > 0.0) || !std::isfinite(H_scaled)) {
                EXPECT_EQ(got, HUGE_VAL);
                ++infinite;
                continue;
            }
            const double transmittance = slut_exit_transmittance(
                slut_vec3_make(q.normal[0], q.normal[1], q.normal[2]),
                slut_vec3_make(q.eye_dir[0], q.eye_dir[1], q.eye_dir[2]), q.eta, q.fresnel ? 1 : 0);
            const double E = p.T > 0.0 ? table.E(p.T, p.g, p.r, p.S) : 1.0;
            const double want = transmittance * q.sigma_s_per_m / (4 * M_PI) * q.intensity_W_per_sr * E * H_scaled / distance;
            EXPECT_LE(slut_test::rel_err(got, want), 1e-12)
                << table.table().kind << " T=" << p.T << " g=" << p.g << " r=" << p.r << " eta=" << q.eta;
            covered += table.covers(p.T, p.g, p.r, p.S);
        }
        EXPECT_GT(covered, 1000);
        EXPECT_GT(zero, 300);
        EXPECT_GT(infinite, 100);
    }
}
