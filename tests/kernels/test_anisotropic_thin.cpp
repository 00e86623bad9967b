// The thin-medium and distant-light forms of the Henyey–Greenstein airlight and near light
// (kernels/slut_phase_arc.h, kernels/slut_airlight_hg_bracket.h): the phase's mean over an arc
// against the elliptic-integral closed form, and the forms in their limits. Part of the
// test_anisotropic executable (anisotropic_test_support.hpp).

#include "anisotropic_test_support.hpp"

namespace {

// ∫_0^φ ψ_a(t) dt for a ≥ 0 (the peak at t = 0) in closed form, long double, from the
// elliptic integral of the second kind (Boost.Math ellint_2, modulus k_m = 2√a/(1 + a)):
// with Q = 1 + a² − 2a cos t = (1 + a)² − 4a cos²(t/2),
//   ∫ Q^{−3/2} dt = (4a sin t/√Q + ∫ √Q dt)/(1 − a²)²,
//   ∫_0^φ √Q dt = 2(1 + a)·[E(k_m) − E(π/2 − φ/2 | k_m)],
// so ∫_0^φ ψ_a = (4a sin φ/√Q + 2(1 + a)[E(k_m) − E(π/2 − φ/2 | k_m)])/(1 − a²). Shares
// nothing with kernels/slut_phase_arc.h's rule.
real ref_psi_primitive(real a, real phi) {
    const real pio2 = 1.5707963267948966192313216916397514L;
    const real sh = std::sin(phi / 2), Q = (1 - a) * (1 - a) + 4 * a * sh * sh;
    const real km = 2 * std::sqrt(a) / (1 + a);
    const real E = boost::math::ellint_2(km) - boost::math::ellint_2(km, pio2 - phi / 2);
    return (4 * a * std::sin(phi) / std::sqrt(Q) + 2 * (1 + a) * E) / ((1 - a) * (1 + a));
}

// The mean of ψ_g over θ ∈ [θ0, θ1] from the closed form (ψ_g(θ) = ψ_{−g}(π − θ) for g < 0). The
// difference of the primitives cancels by ~1/((1 − |g|)²(θ1 − θ0)): long double keeps that
// below 1e-14 for the arcs ≥ 0.01 it is used on.
double ref_psi_arc_mean(double g, double theta0, double theta1) {
    const real pi = 3.14159265358979323846264338327950288L;
    const real lo = g >= 0 ? (real)theta0 : pi - theta1, hi = g >= 0 ? (real)theta1 : pi - theta0;
    return (double)((ref_psi_primitive(std::fabs((real)g), hi) - ref_psi_primitive(std::fabs((real)g), lo)) / (hi - lo));
}

} // namespace

// kernels/slut_phase_arc.h's fixed rule (≤ 48 points) for the mean of ψ_g over an arc of
// scattering angle, against the elliptic-integral closed form: arcs from 0.01 to π anywhere in
// [0, π], the peak's end included, every g of kG (|g| up to 0.99). Measured worst 8.2e-14.
TEST(PhaseArcMean, FixedRuleMatchesTheEllipticIntegral) {
    double worst = 0;
    int n = 0;
    for (double g : kG)
        for (int i = 0; i <= 40; ++i)
            for (int j = i + 1; j <= 40; ++j) {
                const double t0 = kPi * i / 40 * (i % 2 ? 1.0 : 0.999), t1 = std::min(kPi, kPi * j / 40 + 0.01);
                const double got = slut_hg_psi_arc_mean(g, t0, t1), want = ref_psi_arc_mean(g, t0, t1);
                worst = std::max(worst, rel(got, want));
                ++n;
                EXPECT_LT(rel(got, want), 1e-12) << "g " << g << " arc [" << t0 << ", " << t1 << "]";
            }
    // A zero-length arc is ψ at its point; g = 0 is 1.
    EXPECT_EQ(slut_hg_psi_arc_mean(0.0, 0.3, 2.0), 1.0);
    EXPECT_LT(rel(slut_hg_psi_arc_mean(0.8, 0.7, 0.7), slut_hg_psi(0.8, std::cos(0.7))), 1e-15);
    std::printf("phase arc mean vs the elliptic closed form: %d arcs, worst %.2e\n", n, worst);
    RecordProperty("worst_rel_err", std::to_string(worst));
}

// The near-light thin form's phase factor (slut_hg_nl_thin_psi_mean, the fixed rule the C++
// near_light_radiance_thin(q, g) and the GPU snippet share) against the adaptive double
// quadrature it replaced, slut_hg_nl_E at σ_t = 0 (the ĥ⁻²-weighted mean of ψ over the path):
// the near-light cosine over [−1, 1] (close to both ends), s/l from 1e-6 to 1e4 and thick,
// g ∈ {−0.99, −0.9, −0.5, 0.3, 0.8, 0.95, 0.99}. Bound 1e-12 (measured worst 8e-14:
// docs/PHYSICS.md §1.4).
TEST(AnisotropicNearLight, ThinPhaseMeanMatchesTheQuadrature) {
    double worst = 0;
    int n = 0;
    for (double G : kG)
        for (int ig = 0; ig <= 120; ++ig) {
            double gn = -1 + 2.0 * ig / 120;
            if (ig == 0) gn = -1 + 1e-6;
            if (ig == 120) gn = 1 - 1e-6;
            for (int is = 0; is <= 50; ++is) {
                const double s = is == 50 ? HUGE_VAL : std::pow(10.0, -6 + 10.0 * is / 49);
                const double got = slut_hg_nl_thin_psi_mean(G, gn, s), want = slut_hg_nl_E(0.0, gn, 1.0, s, G, 1.0);
                worst = std::max(worst, rel(got, want));
                ++n;
                EXPECT_LT(rel(got, want), 1e-12) << "G " << G << " g " << gn << " s/l " << s;
            }
        }
    std::printf("near-light thin phase mean vs slut_hg_nl_E(T = 0): %d points, worst %.2e\n", n, worst);
    RecordProperty("worst_rel_err", std::to_string(worst));
}

// The airlight's closed forms with the phase (kernels/slut_airlight_hg.h, the C++ entry points
// airlight_hg_radiance_thin / _distant):
//  - the thin bracket (the isotropic one times the phase's mean over the ray's arc) equals the
//    adaptive quadrature of the segment's integral at σ_t = 0, slut_hg_airlight_bracket(0, …),
//    within 1e-12 (γ from 1e-9 to π, s/D from 1e-5 to 1e3 and infinite);
//  - each is the exact radiance (Boost.Math quadrature of the physical integral) in its limit:
//    thin at σ_t (D + s) = 1e-9 (1e-8), distant at D = 1e5 s, σ_t D = 1 (1e-4: first order in s/D);
//  - the thin form never falls below the exact radiance (it drops the extinction).
TEST(AnisotropicAirlight, ThinAndDistantFormsInTheirLimits) {
    double worst_bracket = 0, worst_thin = 0, worst_distant = 0;
    for (double g : kG) {
        for (int ig = 0; ig <= 100; ++ig)
            for (int is = 0; is <= 30; ++is) {
                const double gamma = ig == 0 ? 1e-9 : kPi * ig / 100;
                const double sp = is == 30 ? HUGE_VAL : std::pow(10.0, -5 + 8.0 * is / 29);
                double sh = 0, ch = 0;
                slut_hg_half_angles(std::sin(gamma), std::cos(gamma), &sh, &ch);
                const double got = slut_hg_airlight_bracket_thin(sh, ch, sp, g);
                const double want = slut_hg_airlight_bracket(0.0, sh, ch, sp, g, 1.0);
                worst_bracket = std::max(worst_bracket, rel(got, want));
                EXPECT_LT(rel(got, want), 1e-12) << "g " << g << " gamma " << gamma << " s/D " << sp;
            }
        for (double gamma : {1e-3, 0.4, 1.6, 3.0, kPi - 1e-4}) {
            const double D = 3.0;
            for (double s : {0.01, 2.0, 40.0}) {
                const double st = 1e-9 / (D + s);
                const double thin = scatterlut::airlight_hg_radiance_thin(air_query(st, 0.0, 2.0, D, gamma, s), g);
                const double exact = ref_airlight_hg(st, 0.0, 2.0, D, gamma, s, g);
                worst_thin = std::max(worst_thin, rel(thin, exact));
                EXPECT_LT(rel(thin, exact), 1e-8) << "g " << g << " gamma " << gamma << " s " << s;
                const double dense = scatterlut::airlight_hg_radiance_thin(air_query(0.3, 0.1, 2.0, D, gamma, s), g);
                EXPECT_GE(dense, ref_airlight_hg(0.3, 0.1, 2.0, D, gamma, s, g)) << "g " << g << " gamma " << gamma;
            }
            const double s_far = 0.5, D_far = 5e4;
            // σ_t D = 1, σ_t s = 1e-5 (the distant form keeps the extinction along both legs).
            const double distant =
                scatterlut::airlight_hg_radiance_distant(air_query(1.5e-5, 0.5e-5, 2.0, D_far, gamma, s_far), g);
            const double exact = ref_airlight_hg(1.5e-5, 0.5e-5, 2.0, D_far, gamma, s_far, g);
            ASSERT_GT(exact, 0.0);
            worst_distant = std::max(worst_distant, rel(distant, exact));
            EXPECT_LT(rel(distant, exact), 1e-4) << "g " << g << " gamma " << gamma;
        }
    }
    // Zero limits and a ray through the light.
    EXPECT_EQ(scatterlut::airlight_hg_radiance_thin(air_query(0.0, 0.1, 2.0, 3.0, 0.5, 1.0), 0.8), 0.0);
    EXPECT_EQ(scatterlut::airlight_hg_radiance_distant(air_query(0.2, 0.1, 2.0, 3.0, 0.5, 0.0), 0.8), 0.0);
    EXPECT_TRUE(std::isinf(scatterlut::airlight_hg_radiance_thin(air_query(0.2, 0.1, 2.0, 3.0, 0.0, 5.0), -0.5)));
    std::printf("airlight thin bracket vs the adaptive one %.2e; thin vs exact at sigma_t (D + s) = 1e-9 %.2e; "
                "distant vs exact at D = 1e5 s %.2e\n",
                worst_bracket, worst_thin, worst_distant);
    RecordProperty("worst_rel_err", std::to_string(worst_bracket));
}
