// The airlight_rational table (kernels/slut_airlight_rational.h; tables/src/airlight_rational.cpp):
// its node values and edge limits against references that share none of its code (Boost.Math
// quadrature of H directly, tests/airlight_reference.hpp; Boost.Math's expint), the sampler
// against a GPU's bilinear filter at texel centres, the radiance against the exact quadrature,
// and the loader's refusals. No device: the tables here are filled on the host by the node
// function (tests/commands/test_airlight_rational_kind.cpp checks the device's).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/math/special_functions/expint.hpp>
#include <gtest/gtest.h>

#include "airlight_reference.hpp"
#include "generate_airlight_rational.hpp"
#include "reference_data.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_rational.hpp"

extern "C" {
#include "slut_airlight_rational.h"
}

using slut_test::rel_err;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// m of the unit coordinate x_m: the header's forward map inverted by bisection (the test's own,
// not the node function's closed inverse).
double m_of(double x_m) {
    if (!(x_m > 0.0)) return 0.0;
    double lo = 0.0, hi = 1.0;
    while (slut_airlight_rational_x_m(hi) < x_m) hi *= 2.0;
    for (int k = 0; k < 2200; ++k) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (slut_airlight_rational_x_m(mid) < x_m ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// e^m E_2(m)·(1 + m): the edge x_t = 1. Boost.Math's expint in long double up to m = 1000; above,
// where e^m E_2(m) would leave even long double's range, its asymptotic series
// e^m E_2(m) = Σ_k (−1)^k (k + 1)!/m^{k+1} (20 terms: the remainder ≤ 22!/m^22 ≤ 1e-45).
double edge_t_limit(double m) {
    if (m == 0.0) return 1.0;
    const long double ml = m;
    if (m <= 1000.0) return static_cast<double>((1 + ml) * std::exp(ml) * boost::math::expint(2, ml));
    long double sum = 0, term = 1 / ml;
    for (int k = 0; k < 20; ++k, term *= -(k + 1) / ml) sum += term;
    return static_cast<double>((1 + ml) * sum);
}

// Ĥ at (x_m, x_t) from tests/airlight_reference.hpp's Gauss–Kronrod of H(u, t) over y (double,
// its own panels): independent of the kernels and of the generator's long-double reference.
double reference_hn(double x_m, double x_t) {
    if (x_m >= 1.0) return 1.0;
    const double m = m_of(x_m);
    if (x_t >= 1.0) return edge_t_limit(m);
    const double t = x_t / (1.0 - x_t), u = m / (1.0 + t);
    const double H = u > 0.0 ? static_cast<double>(slut_ref::detail::scaled_lorentz_exp(u, t, kInf))
                             : std::atan2(1.0, t); // u = 0: arccot t
    return H * (t + 2.0 / kPi + u * (1.0 + t * t));
}

// A table of n_m × n_t nodes filled on the host by the node function (refine 1), rounded to
// float as an f32 file stores it.
scatterlut::Table host_table(int n_m, int n_t) {
    scatterlut::AirlightRationalPlan plan;
    plan.n_m = n_m;
    plan.n_t = n_t;
    scatterlut::Table t = scatterlut::make_airlight_rational_layout(plan);
    const slut_axis &am = t.axes[0].map, &at = t.axes[1].map;
    t.values.resize(t.node_count());
    for (int j = 0; j < n_t; ++j)
        for (int i = 0; i < n_m; ++i)
            t.values[static_cast<size_t>(j) * n_m + i] = static_cast<float>(
                slut_airlight_rational_node(slut_axis_node(&am, i), slut_axis_node(&at, j), 1.0));
    return t;
}

const scatterlut::AirlightRationalTable &table64() {
    static const scatterlut::AirlightRationalTable t(host_table(64, 64));
    return t;
}

// The largest relative interpolation error of table64 over 200000 uniform random unit
// coordinates (the planner's measurement, ten times the points).
double table64_sampling_error() {
    static const double e = scatterlut::measure_airlight_rational_sampling(table64(), 200000, 3).max_rel;
    return e;
}

void expect_refused(scatterlut::Table t, const std::string &needle) {
    try {
        scatterlut::AirlightRationalTable r(std::move(t));
        ADD_FAILURE() << "accepted; expected a refusal mentioning '" << needle << "'";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}

} // namespace

// Every node of a 33 × 33 grid of the unit square (the edges included) and points crowding
// towards the edges: the node function (refine 1, the table's) and the generator's long-double
// reference (validate's) against the test's own quadrature, to 1e-10.
TEST(AirlightRational, NodeValuesMatchAnIndependentReference) {
    std::vector<double> xs;
    for (int i = 0; i <= 32; ++i) xs.push_back(i / 32.0);
    for (double d : {1e-2, 1e-3, 1e-5}) {
        xs.push_back(d);
        xs.push_back(1.0 - d);
    }
    double worst = 0, worst_generator = 0;
    for (double x_m : xs)
        for (double x_t : xs) {
            const double ref = reference_hn(x_m, x_t);
            ASSERT_TRUE(ref >= 0.80 && ref <= 1.29) << "x_m=" << x_m << " x_t=" << x_t << " ref=" << ref;
            const double node = slut_airlight_rational_node(x_m, x_t, 1.0);
            const double generator = scatterlut::reference_airlight_rational(x_m, x_t);
            EXPECT_LE(rel_err(node, ref), 1e-10) << "x_m=" << x_m << " x_t=" << x_t;
            EXPECT_LE(rel_err(generator, ref), 1e-10) << "x_m=" << x_m << " x_t=" << x_t;
            worst = std::max(worst, rel_err(node, ref));
            worst_generator = std::max(worst_generator, rel_err(generator, ref));
        }
    std::printf("node function vs Boost over %zu points: max rel %.2e; the generator's reference: %.2e\n",
                xs.size() * xs.size(), worst, worst_generator);
}

// The edges are the limits: x_m → 1 (u → ∞) gives 1, x_t → 1 (t → ∞ at fixed m) gives
// e^m E_2(m)(1 + m) (Boost.Math's expint); nodes just inside approach them, closer the closer.
TEST(AirlightRational, EdgesAreTheLimitsOfTheNodesJustInside) {
    for (double x_t : {0.0, 0.25, 0.5, 0.75, 0.9}) {
        EXPECT_EQ(slut_airlight_rational_node(1.0, x_t, 1.0), 1.0);
        double previous = HUGE_VAL;
        for (double d : {1e-2, 1e-3, 1e-4, 1e-5}) {
            const double gap = std::fabs(slut_airlight_rational_node(1.0 - d, x_t, 1.0) - 1.0);
            EXPECT_LT(gap, previous) << "x_t=" << x_t << " 1 - x_m=" << d;
            previous = gap;
        }
        EXPECT_LT(previous, 1e-3) << "x_t=" << x_t;
    }
    for (double x_m : {0.0, 0.2, 0.5, 0.8, 0.95}) {
        const double limit = edge_t_limit(m_of(x_m));
        EXPECT_LE(rel_err(slut_airlight_rational_node(x_m, 1.0, 1.0), limit), 1e-13) << "x_m=" << x_m;
        double previous = HUGE_VAL;
        for (double d : {1e-2, 1e-3, 1e-4, 1e-5}) {
            const double gap = rel_err(slut_airlight_rational_node(x_m, 1.0 - d, 1.0), limit);
            EXPECT_LT(gap, previous) << "x_m=" << x_m << " 1 - x_t=" << d;
            previous = gap;
        }
        EXPECT_LT(previous, 1e-3) << "x_m=" << x_m;
    }
    // The corner (1, 1) and the other two: 1 at u = ∞, at u = 0 arccot(t)(t + 2/π) → 1 at
    // both t = 0 and t = ∞.
    EXPECT_EQ(slut_airlight_rational_node(1.0, 1.0, 1.0), 1.0);
    EXPECT_NEAR(slut_airlight_rational_node(0.0, 0.0, 1.0), 1.0, 1e-15);
    EXPECT_NEAR(slut_airlight_rational_node(0.0, 1.0, 1.0), 1.0, 1e-15);
}

// sample() is what a GPU's linear filter returns at the texel-centre coordinates
// tc = (x·(n − 1) + 0.5)/n with clamp-to-edge: the filter's position tc·n − 0.5 = x·(n − 1),
// its cell and fraction, then the bilinear of the four texels (exact weights: the C++ side of
// the comparison a GPU makes with its 8-bit weights).
TEST(AirlightRational, SampleIsTheTexelCentreBilinearFilter) {
    const scatterlut::AirlightRationalTable &t = table64();
    const std::vector<double> &v = t.table().values;
    const int nm = t.m_count(), nt = t.t_count();
    auto texel = [&](int i, int j) {
        i = std::clamp(i, 0, nm - 1);
        j = std::clamp(j, 0, nt - 1);
        return v[static_cast<size_t>(j) * nm + i];
    };
    auto filter = [&](double x_m, double x_t) {
        const double tcm = (std::clamp(x_m, 0.0, 1.0) * (nm - 1) + 0.5) / nm;
        const double tct = (std::clamp(x_t, 0.0, 1.0) * (nt - 1) + 0.5) / nt;
        const double pm = tcm * nm - 0.5, pt = tct * nt - 0.5;
        const int im = static_cast<int>(std::floor(pm)), it = static_cast<int>(std::floor(pt));
        const double fm = pm - im, ft = pt - it;
        return (1 - ft) * ((1 - fm) * texel(im, it) + fm * texel(im + 1, it)) +
               ft * ((1 - fm) * texel(im, it + 1) + fm * texel(im + 1, it + 1));
    };
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> unit(-0.1, 1.1); // some beyond the edges: clamped
    for (int k = 0; k < 5000; ++k) {
        const double x_m = unit(rng), x_t = unit(rng);
        ASSERT_NEAR(t.sample(x_m, x_t), filter(x_m, x_t), 1e-14) << x_m << " " << x_t;
    }
    // At the nodes: the stored values themselves.
    for (int j : {0, 17, nt - 1})
        for (int i : {0, 5, nm - 1})
            EXPECT_EQ(t.sample(i / double(nm - 1), j / double(nt - 1)), texel(i, j)) << i << " " << j;
    EXPECT_THROW(t.sample(std::nan(""), 0.5), std::invalid_argument);
}

// hn(u, t): the axis maps, then the sample; within the table's interpolation error of the
// reference, the edges t = ∞ and u = 0 included.
TEST(AirlightRational, HnIsTheSampleAtTheMappedCoordinates) {
    const scatterlut::AirlightRationalTable &t = table64();
    const double tolerance = 1.25 * table64_sampling_error();
    for (double u : {0.0, 1e-4, 0.03, 0.7, 5.0, 80.0})
        for (double tt : {0.0, 0.01, 0.4, 1.0, 3.0, 50.0, 1e4}) {
            const double x_m = slut_airlight_rational_x_m(u * (1 + tt)), x_t = tt / (1 + tt);
            EXPECT_EQ(t.hn(u, tt), t.sample(x_m, x_t)) << u << " " << tt;
            EXPECT_LE(rel_err(t.hn(u, tt), reference_hn(x_m, x_t)), tolerance) << u << " " << tt;
        }
    EXPECT_EQ(t.hn(0.0, kInf), t.sample(0.0, 1.0));
    EXPECT_EQ(t.hn(2.0, kInf), t.sample(1.0, 1.0)); // m = ∞
    EXPECT_EQ(t.hn(kInf, 0.5), t.sample(1.0, 0.5 / 1.5));
    EXPECT_THROW(t.hn(-1.0, 0.5), std::invalid_argument);
    EXPECT_THROW(t.hn(1.0, std::nan("")), std::invalid_argument);
}

// AirlightRationalTable::radiance against airlight_radiance_exact on 600 random geometries
// (σ_t D log-uniform in [0.01, 50], γ uniform in [0, π] with γ = 0 and γ = π among them, s
// log-uniform in [1e-9, 1e3]·D and infinite; γ = 0 with s < D), and a few hard ones.
// The tolerance, per query: where the tiers take the difference V − F of the two ends' terms
// (V = weight2·Ĥ2, F = weight1·Ĥ1; F ≤ (1 − 1/G) V, G = SLUT_AIRLIGHT_RATIONAL_GAIN) relative
// errors of at most ε on both samples give at most ε (V + F)/(V − F) ≤ (2G − 1) ε on the
// radiance, ε the table's interpolation error (measured at 200000 points, times 1.25 for a
// worse point between them; storage rounding included, as the table holds floats). Where they
// take the short segment's corrected trapezoid instead (no table), 1e-4: that rule's error
// (T⁵ max|g⁗|/720, kernels/slut_airlight_rational.h), measured ≤ 2.6e-5 over 200000 geometries.
TEST(AirlightRational, RadianceMatchesTheExactWithinTheSamplesErrorTimesTheGain) {
    const scatterlut::AirlightRationalTable &t = table64();
    const double eps = 1.25 * table64_sampling_error();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<scatterlut::AirlightQuery> qs;
    for (int k = 0; k < 600; ++k) {
        scatterlut::AirlightQuery q;
        const double optical = 0.01 * std::pow(5000.0, unit(rng)), albedo = 0.05 + 0.95 * unit(rng);
        q.distance_m = std::pow(10.0, -2 + 4 * unit(rng));
        q.sigma_s_per_m = albedo * optical / q.distance_m;
        q.sigma_a_per_m = (1 - albedo) * optical / q.distance_m;
        q.intensity_W_per_sr = std::pow(10.0, -2 + 4 * unit(rng));
        const int shape = k % 10;
        q.gamma_rad = shape == 0 ? 0.0 : shape == 1 ? kPi : kPi * unit(rng);
        q.length_m = shape == 2 || shape == 5 ? kInf : q.distance_m * std::pow(10.0, -9 + 12 * unit(rng));
        if (shape == 0) q.length_m = q.distance_m * std::pow(10.0, -9 + 9 * unit(rng)) * 0.999; // s < D
        qs.push_back(q);
    }
    // Hard ones: s → 0, γ → 0 and π, a ray ending just before the light, the light behind.
    qs.push_back({0.3, 0.1, 1.0, 5.0, 1.0, 1e-12});
    qs.push_back({0.3, 0.1, 1.0, 5.0, 1e-7, 4.999});
    qs.push_back({0.3, 0.1, 1.0, 5.0, 0.0, 4.9999});
    qs.push_back({0.3, 0.1, 1.0, 5.0, kPi - 1e-12, kInf});
    qs.push_back({0.3, 0.1, 1.0, 5.0, kPi, 1e-6});
    qs.push_back({5.0, 5.0, 1.0, 5.0, 0.5, kInf}); // σ_t D = 50
    double worst_difference = 0, worst_gain = 0, worst_segment = 0;
    int segments = 0;
    for (const scatterlut::AirlightQuery &q : qs) {
        const double exact = scatterlut::airlight_radiance_exact(q);
        ASSERT_TRUE(exact > 0.0 && std::isfinite(exact));
        const double got = t.radiance(q);
        const double err = rel_err(got, exact);
        // Which path the shared function takes, from its own set-up.
        const double half = std::fmin(0.5 * q.gamma_rad, SLUT_PIO2_HI);
        double sh, ch;
        slut_sincos_half_angle(half, &sh, &ch);
        const slut_airlight_rational_setup r = slut_airlight_rational_setup_of(
            q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m, 2 * sh * ch,
            SLUT_AIRLIGHT_COS_GAMMA(sh, ch), q.length_m);
        const double V = r.weight2 * t.sample(r.x_m2, r.x_t2), F = r.weight1 * t.sample(r.x_m1, r.x_t1);
        const bool difference = F <= (1.0 - 1.0 / SLUT_AIRLIGHT_RATIONAL_GAIN) * V;
        const std::string where = "sigma_s=" + std::to_string(q.sigma_s_per_m) + " sigma_a=" +
                                  std::to_string(q.sigma_a_per_m) + " D=" + std::to_string(q.distance_m) +
                                  " gamma=" + std::to_string(q.gamma_rad) + " s=" + std::to_string(q.length_m);
        if (difference) {
            const double gain = (V + F) / (V - F);
            EXPECT_LE(gain, 2 * SLUT_AIRLIGHT_RATIONAL_GAIN - 1 + 1e-9) << where;
            EXPECT_LE(err, eps * gain + 1e-12) << where << " gain " << gain;
            worst_difference = std::max(worst_difference, err);
            worst_gain = std::max(worst_gain, err / eps);
        } else {
            ++segments;
            EXPECT_LE(err, 1e-4) << where << " (the segment's rule)";
            worst_segment = std::max(worst_segment, err);
        }
    }
    std::printf("radiance vs exact, %zu queries: two samples max rel %.2e (%.2f x the samples' %.2e), "
                "segment rule (%d queries) max rel %.2e\n",
                qs.size(), worst_difference, worst_gain, eps, segments, worst_segment);
}

// The degenerate queries as airlight_radiance_exact has them, and the batch as a loop.
TEST(AirlightRational, LimitsAndTheBatch) {
    const scatterlut::AirlightRationalTable &t = table64();
    EXPECT_EQ(t.radiance({0.3, 0.1, 1.0, 5.0, 0.0, 6.0}), kInf); // through the light
    EXPECT_EQ(t.radiance({0.3, 0.1, 1.0, 5.0, 0.0, kInf}), kInf);
    EXPECT_EQ(t.radiance({0.0, 0.1, 1.0, 5.0, 1.0, 3.0}), 0.0); // σ_s = 0
    EXPECT_EQ(t.radiance({0.3, 0.1, 0.0, 5.0, 1.0, 3.0}), 0.0); // I0 = 0
    EXPECT_EQ(t.radiance({0.3, 0.1, 1.0, 5.0, 1.0, 0.0}), 0.0); // s = 0
    EXPECT_THROW(t.radiance({-0.3, 0.1, 1.0, 5.0, 1.0, 3.0}), std::invalid_argument);
    EXPECT_THROW(t.radiance({0.3, 0.1, 1.0, 5.0, 4.0, 3.0}), std::invalid_argument);

    std::vector<scatterlut::AirlightQuery> qs = {
        {0.3, 0.1, 1.0, 5.0, 1.0, 3.0}, {0.05, 0.0, 10.0, 30.0, 2.5, kInf}, {1.0, 1.0, 1.0, 2.0, 0.1, 1.9}};
    std::vector<double> out(qs.size(), -1.0);
    t.radiance(qs.data(), qs.size(), out.data());
    for (size_t k = 0; k < qs.size(); ++k) EXPECT_EQ(out[k], t.radiance(qs[k])) << k;
    qs[2].distance_m = -1.0;
    std::vector<double> untouched(qs.size(), -1.0);
    try {
        t.radiance(qs.data(), qs.size(), untouched.data());
        ADD_FAILURE() << "a bad query was accepted";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("query 2: distance"), std::string::npos) << e.what();
    }
    for (double v : untouched) EXPECT_EQ(v, -1.0);
}

// The loader distrusts its file: another kind or version, other axes, another channel, a NaN or
// a value outside [0.5, 2] (naming the node).
TEST(AirlightRational, LoaderRefusesWhatIsNoAirlightRationalTable) {
    const scatterlut::Table good = host_table(8, 6);
    EXPECT_NO_THROW(scatterlut::AirlightRationalTable{good});
    {
        scatterlut::Table t = good;
        t.kind = scatterlut::kKindAirlightF;
        expect_refused(t, "not an airlight_rational table");
    }
    {
        scatterlut::Table t = good;
        t.quantity_version = 2;
        expect_refused(t, "quantity version 2");
    }
    {
        scatterlut::Table t = good;
        std::swap(t.axes[0].name, t.axes[1].name);
        expect_refused(t, "expected the axes (x_m, x_t)");
    }
    {
        scatterlut::Table t = good;
        t.axes[1].map.max = 0.5;
        expect_refused(t, "the x_t axis must be linear on [0, 1]");
    }
    {
        scatterlut::Table t = good;
        t.axes[0].map.warp = SLUT_WARP_LOG1P;
        t.axes[0].map.scale = 1.0;
        expect_refused(t, "the x_m axis must be linear on [0, 1]");
    }
    {
        scatterlut::Table t = good;
        t.axes.push_back(t.axes[1]);
        t.axes[2].name = "extra";
        t.values.resize(t.values.size() * 6, 1.0);
        expect_refused(t, "expected the axes (x_m, x_t)");
    }
    {
        scatterlut::Table t = good;
        t.channels[0].encoding = scatterlut::Encoding::Log;
        expect_refused(t, "expected one linear channel Hn");
    }
    {
        scatterlut::Table t = good;
        t.values.pop_back();
        expect_refused(t, ""); // check_consistent's message
    }
    {
        scatterlut::Table t = good;
        t.values[8 * 3 + 2] = std::nan("");
        expect_refused(t, "node (2, 3)");
    }
    {
        scatterlut::Table t = good;
        t.values[8 * 5 + 7] = 0.4;
        expect_refused(t, "node (7, 5)");
    }
    {
        scatterlut::Table t = good;
        t.values[0] = 2.5;
        expect_refused(t, "node (0, 0)");
    }
    {
        scatterlut::Table t = good;
        t.values[1] = kInf;
        expect_refused(t, "node (1, 0)");
    }
}
