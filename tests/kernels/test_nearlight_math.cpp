// Tests of kernels/slut_nearlight.h: the near-light integral N(T, g, r, S), its closed-form
// part H, the mean attenuation E = N/H, the parameters from geometry and the closed forms
// of docs/PHYSICS.md §1.2–§1.3. Each test names its reference and says why its tolerance.
//
// The header claims ≤ 1e-10 relative for N and E everywhere (the tables' contract at their
// nodes); the measured errors are ~1e-14, so 1e-10 tolerances leave room for compiler and
// libm differences without hiding a missed boundary layer or peak (those show up as 1e-3
// to 1e+5 errors: N_ref's layer point gives 6e-13 instead of 4.17e-8 when missed).
//
// This file: N, H and E against the references (mpmath, Boost) and the identities of the
// integral (r = 0 is the airlight, large T the distant light, g = r = 1 in closed form). The
// evaluation itself (3-D, lanes, the sweep, limits, parameters, node counts, the layer mesh):
// test_nearlight_math_evaluation.cpp (one test executable, test_nearlight_math).

#include "nearlight_math_test_support.hpp"

// ---------------------------------------------------------------------------------------
// Reference: N_ref.json, mpmath at 30 digits (tests/reference/README.md).
// Tolerance: H is a closed form (angle-difference atan2 form, no cancellation): 1e-14.
// N and E: the header's contract, 1e-10 (see the file comment); the brief asks 1e-9.
TEST(NearLightMath, MatchesMpmathReferencePoints) {
    const auto refs = slut_test::load_N_refs();
    Worst wN, wH, wE;
    for (const auto &p : refs) {
        const double H = slut_nl_H(p.T, p.g, p.S);
        const double N = slut_nl_N(p.T, p.g, p.r, p.S);
        const double E = slut_nl_E(p.T, p.g, p.r, p.S);
        const double eN = slut_test::rel_err(N, p.N), eH = slut_test::rel_err(H, p.H), eE = slut_test::rel_err(E, p.E);
        wN.add(eN, p.T, p.g, p.r, p.S);
        wH.add(eH, p.T, p.g, p.r, p.S);
        wE.add(eE, p.T, p.g, p.r, p.S);
        EXPECT_LE(eH, 1e-14) << "H at T=" << p.T << " g=" << p.g << " S=" << p.S << ": " << H << " vs " << (double)p.H;
        EXPECT_LE(eN, 1e-10) << "N at T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S << ": " << N << " vs " << (double)p.N;
        EXPECT_LE(eE, 1e-10) << "E at T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S << ": " << E << " vs " << (double)p.E;
    }
    std::printf("N_ref.json: %zu points\n", refs.size());
    wN.print("N vs mpmath");
    wH.print("H vs mpmath");
    wE.print("E vs mpmath");
}

// ---------------------------------------------------------------------------------------
// Reference: the same 30-digit points, for the Boost reference itself (so that the
// random comparison below compares against something known to be right).
// Tolerance: long double GK61 at tol 1e-15 reaches ~1e-18; 1e-13 catches a bad break point.
TEST(NearLightMath, BoostReferenceMatchesMpmath) {
    const auto refs = slut_test::load_N_refs();
    Worst wN, wH;
    for (const auto &p : refs) {
        const auto v = slut_ref::nearlight_NHE(p.T, p.g, p.r, p.S);
        const double eN = slut_test::rel_err(v.N, p.N), eH = slut_test::rel_err(v.H, p.H);
        wN.add(eN, p.T, p.g, p.r, p.S);
        wH.add(eH, p.T, p.g, p.r, p.S);
        EXPECT_LE(eN, 1e-13) << "Boost N at T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S;
        EXPECT_LE(eH, 1e-13) << "Boost H at T=" << p.T << " g=" << p.g << " S=" << p.S;
    }
    wN.print("Boost N vs mpmath");
    wH.print("Boost H vs mpmath");
}

// ---------------------------------------------------------------------------------------
// Reference: physical_ref.json near_light cases (direct quadrature of the radiance in
// physical units, not through N), through slut_nl_params_from_geometry:
//   L = σ_s/(4π) · I0 · σ_t · N(T, g, r, S).
// This pins the conventions (eye_dir towards the viewer, light_pos relative to the entry
// point, g = ω·ω_l, r = μ_l/μ_e). Tolerance 1e-8 (brief); the reference has 25 digits.
TEST(NearLightMath, PhysicalReferenceThroughGeometry) {
    const auto refs = slut_test::load_near_light_refs();
    Worst w;
    int zero_cases = 0;
    for (const auto &c : refs) {
        const double sigma_t = c.sigma_s + c.sigma_a;
        slut_nl_params p;
        slut_nl_params_from_geometry(c.normal, c.eye_dir, c.light_pos, sigma_t, c.length, &p);
        ASSERT_NE(p.kind, SLUT_NL_VIEWER_BELOW);
        const double L = slut_nl_radiance_exact(c.sigma_s, c.sigma_a, c.intensity, c.normal, c.eye_dir, c.light_pos, c.length);
        if (c.L == 0) {
            ++zero_cases;
            EXPECT_EQ(p.kind, SLUT_NL_LIGHT_BELOW);
            EXPECT_EQ(L, 0.0);
            continue;
        }
        ASSERT_EQ(p.kind, SLUT_NL_OK);
        // The same radiance by the defining formula σ_s/(4π)·I0·σ_t·N.
        const double L_via_N = c.sigma_s * SLUT_INV_4PI * c.intensity * sigma_t * slut_nl_N(p.T, p.g, p.r, p.S);
        const double e = slut_test::rel_err(L, c.L);
        w.add(e, p.T, p.g, p.r, p.S);
        EXPECT_LE(e, 1e-8) << "case L=" << (double)c.L << " got " << L << " (T=" << p.T << " g=" << p.g << " r=" << p.r
                           << " S=" << p.S << ")";
        EXPECT_LE(slut_test::rel_err(L_via_N, c.L), 1e-8);
    }
    EXPECT_GE(zero_cases, 1);
    std::printf("physical_ref.json: %zu near_light cases (%d with the light below the plane)\n", refs.size(), zero_cases);
    w.print("radiance vs physical_ref");
}

// ---------------------------------------------------------------------------------------
// Reference: the Boost.Math quadrature of tests/nearlight_reference.hpp (independent
// rule, precision and break-point placement), on the hard corners and a few hundred
// random points: T log-uniform in [1e-3, 100], g in [−0.999999, 1] (a third of them
// within 1e-6..1 of −1, a tenth near 1), r ∈ {0} ∪ log-uniform [1e-6, 1e4],
// S ∈ {∞} ∪ log-uniform [1e-6, 100]. Tolerance 1e-10: the header's contract.
TEST(NearLightMath, MatchesBoostReferenceOnCornersAndRandomPoints) {
    struct P { double T, g, r, S; };
    std::vector<P> pts;
    for (double T : {1e-3, 1.0, 100.0})
        for (double g : {-0.999999, -0.9, 0.0, 0.999999, 1.0})
            for (double r : {0.0, 1e-6, 1e-2, 1.0, 1e4})
                for (double S : {kInf, 1e-6, 1e-2, 3.0, 100.0}) pts.push_back({T, g, r, S});
    const size_t corners = pts.size();
    std::mt19937_64 rng(20240601);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int i = 0; i < 400; ++i) {
        double T, g;
        random_hard_T_g(rng, &T, &g);
        const double r = U(rng) < 0.1 ? 0.0 : std::pow(10.0, -6.0 + 10.0 * U(rng));
        const double S = U(rng) < 0.35 ? kInf : std::pow(10.0, -6.0 + 8.0 * U(rng));
        pts.push_back({T, std::max(g, -0.999999), r, S});
    }
    Worst wN, wE;
    int max_nodes = 0;
    long total_nodes = 0, total_ref_evals = 0;
    for (const auto &p : pts) {
        const auto ref = slut_ref::nearlight_NHE(p.T, p.g, p.r, p.S);
        double E = 0;
        const int nodes = slut_nl_E_lanes(p.T, p.g, p.S, &p.r, 1, &E, 1.0);
        const double N = slut_nl_N(p.T, p.g, p.r, p.S);
        max_nodes = std::max(max_nodes, nodes);
        total_nodes += nodes;
        total_ref_evals += ref.evals;
        const double eN = slut_test::rel_err(N, ref.N), eE = slut_test::rel_err(E, ref.E);
        wN.add(eN, p.T, p.g, p.r, p.S);
        wE.add(eE, p.T, p.g, p.r, p.S);
        EXPECT_LE(eN, 1e-10) << "N at T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S << ": " << N << " vs "
                             << (double)ref.N;
        EXPECT_LE(eE, 1e-10) << "E at T=" << p.T << " g=" << p.g << " r=" << p.r << " S=" << p.S;
    }
    std::printf("%zu corners + %zu random points; header nodes per call: mean %.0f, max %d; Boost evals mean %.0f\n",
                corners, pts.size() - corners, (double)total_nodes / pts.size(), max_nodes,
                (double)total_ref_evals / pts.size());
    wN.print("N vs Boost");
    wE.print("E vs Boost");
}

// ---------------------------------------------------------------------------------------
// Reference: docs/PHYSICS.md §1.2, special case r = 0. With r = 0 the whole light path is inside,
// k = h, and N is the airlight integral of §1.1 with cos γ = −g (γ = angle between the view
// direction and the direction from the viewer to the light, d² = x² + D² − 2xD cos γ):
//   ∫_0^s e^{−σ_t (x + d(x))}/d(x)² dx = σ_t · N(σ_t D, −cos γ, 0, σ_t s).
// The left side is integrated here directly in physical units (Boost GK61, break points
// at the closest approach x_c = D cos γ and x_c ± D sin γ·2^k). Also compared with the
// airlight header's own exact evaluation (slut_airlight_exact: "the two tables must agree
// here"). Tolerance 1e-10: both sides claim ≤ 1e-13.
TEST(NearLightMath, ZeroRIsTheAirlightIntegral) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    Worst w_direct, w_airlight;
    for (int i = 0; i < 120; ++i) {
        const double sigma_s = std::pow(10.0, -2.0 + 2.5 * U(rng)), sigma_a = sigma_s * U(rng);
        const double sigma_t = sigma_s + sigma_a;
        const double D = std::pow(10.0, -1.5 + 2.5 * U(rng)); // viewer–light distance, m
        const double pick = U(rng);
        const double gamma = pick < 0.3 ? std::pow(10.0, -3.0 + 3.0 * U(rng)) // light nearly ahead: the peak
                             : pick < 0.4 ? SLUT_PI - std::pow(10.0, -3.0 + 3.0 * U(rng))
                                          : SLUT_PI * U(rng);
        const double s = U(rng) < 0.3 ? 2e3 / sigma_t : std::pow(10.0, -2.0 + 3.0 * U(rng)); // "∞": e^{−2000}
        // g is rounded to double once and both sides use exactly that value: near g = −1 the
        // integral's sensitivity to g is ~1/(1 − |g|), so a 1e-16 rounding would cost 1e-12.
        const double g = -std::cos(gamma);
        const real cg = -(real)g, sgm = std::sqrt((1 - std::fabs(cg)) * (1 + std::fabs(cg))), st = sigma_t;
        // d(x)² = x² + D² − 2xD cos γ, written as (x − D cos γ)² + (D sin γ)² (the same number
        // without the cancellation near the closest approach, which would leave the integrand
        // noisy at ~1e-19/sin²γ and keep the adaptive quadrature from converging).
        auto airlight = [=](real x) {
            const real dx = x - (real)D * cg, b = (real)D * sgm;
            const real d2 = dx * dx + b * b;
            return std::exp(-st * (x + std::sqrt(d2))) / d2;
        };
        std::vector<real> br{(real)D * cg};
        for (int k = -2; k <= 40; ++k) {
            br.push_back((real)D * cg + (real)D * sgm * std::ldexp(real(1), k));
            br.push_back((real)D * cg - (real)D * sgm * std::ldexp(real(1), k));
        }
        for (int k = -4; k <= 8; ++k) br.push_back(std::ldexp(real(1), k) / st);
        const real direct = slut_ref::integrate_with_breaks(airlight, br, (real)s, 1e-15L, nullptr);
        const double T = sigma_t * D, S = sigma_t * s;
        const double via_N = sigma_t * slut_nl_N(T, g, 0.0, S);
        const double e = slut_test::rel_err(via_N, direct);
        w_direct.add(e, T, g, 0.0, S);
        EXPECT_LE(e, 1e-10) << "T=" << T << " g=" << g << " S=" << S << ": " << via_N << " vs " << (double)direct;

        const slut_airlight_geometry geo = slut_airlight_setup(sigma_s, sigma_a, 1.0, D, (double)sgm, (double)cg, s);
        const double L_air = slut_airlight_exact(geo);
        const double L_near = sigma_s * SLUT_INV_4PI * via_N;
        const double e2 = slut_test::rel_err(L_near, L_air);
        w_airlight.add(e2, T, g, 0.0, S);
        EXPECT_LE(e2, 1e-10) << "vs slut_airlight_exact: T=" << T << " g=" << g << " S=" << S;
    }
    w_direct.print("sigma_t N(r=0) vs airlight quad");
    w_airlight.print("vs slut_airlight_exact");
}

// ---------------------------------------------------------------------------------------
// Reference: docs/PHYSICS.md §1.2, distant-light limit (Gath 2008 eq. 5). Removing the fall-off means
// T²·N: for t = O(1) and T → ∞, 1/ĥ² → 1/T² and ĥ·t/(t + T r) → c t, c = 1/r, so
//   T² N → ∫_0^S e^{−(1+c)t} dt = (1 − e^{−(1+c)S})/(1+c)   (slut_distant_light_factor).
// First-order correction (expand ĥ = T + t g + t²(1−g²)/(2T), q = t/(Tr) − t²/(Tr)²):
//   T² N = I0 − [(g c − c²) I2 + 2 g I1]/T + O(T^{−2}),  Ik = ∫_0^S t^k e^{−(1+c)t} dt.
// Tolerances: the uncorrected limit within 1.05·|first-order term|; the corrected value
// within 2e-8 at T = 1e5 (second-order terms ~(c + 1)²·10/T² here).
TEST(NearLightMath, LargeTWithoutFallOffIsTheDistantLightForm) {
    Worst w1, w2;
    for (double g : {-0.9, 0.0, 0.7, 1.0})
        for (double r : {0.2, 1.0, 5.0})
            for (double S : {0.5, 3.0, kInf}) {
                const double c = 1.0 / r, a = 1.0 + c;
                const double eaS = std::isinf(S) ? 0.0 : std::exp(-a * S);
                const double aS = std::isinf(S) ? 0.0 : a * S;
                const double I0 = (1.0 - eaS) / a;
                const double I1 = (1.0 - eaS * (1.0 + aS)) / (a * a);
                const double I2 = (2.0 - eaS * (2.0 + 2.0 * aS + aS * aS)) / (a * a * a);
                const double first = -((g * c - c * c) * I2 + 2.0 * g * I1);
                EXPECT_NEAR(I0, slut_distant_light_factor(r, S), 1e-15);
                for (double T : {1e4, 1e5}) {
                    const double scaled = T * T * slut_nl_N(T, g, r, S);
                    const double e_limit = std::fabs(scaled - I0) / I0;
                    const double e_first = std::fabs(scaled - (I0 + first / T)) / I0;
                    w1.add(e_limit, T, g, r, S);
                    if (T == 1e5) w2.add(e_first, T, g, r, S);
                    EXPECT_LE(e_limit, 1.05 * std::fabs(first) / (T * I0) + 1e-12) << "T=" << T << " g=" << g << " r=" << r << " S=" << S;
                    if (T == 1e5) {
                        EXPECT_LE(e_first, 2e-8) << "g=" << g << " r=" << r << " S=" << S;
                    }
                }
            }
    w1.print("T^2 N vs distant-light limit");
    w2.print("... with the 1/T term, T=1e5");
}

// ---------------------------------------------------------------------------------------
// Reference: exact closed form at g = 1, r = 1. Then ĥ = t + T and ĥ t/(t + T) = t, so the
// fall-off-free integrand is e^{−2t}, exactly the distant-light form (1 − e^{−2S})/2, and
//   N = ∫_0^S e^{−2t}/(t+T)² dt = e^{2T}[E_2(2T)/T − E_2(2(T+S))/(T+S)]
// (∫_x^∞ e^{−2u}u^{−2} du = E_2(2x)/x), E_2 from Boost.Math in long double so that the
// difference keeps ~1e-14 for small S. Tolerance 1e-12: both sides ≤ 1e-13.
TEST(NearLightMath, GEqualsOneREqualsOneClosedForm) {
    Worst w;
    for (double T : {1e-3, 0.1, 0.5, 2.0, 10.0, 50.0})
        for (double S : {1e-5, 0.3, 2.0, 10.0, kInf}) {
            const real Tl = T;
            real exact = std::exp(2 * Tl) * boost::math::expint(2, 2 * Tl) / Tl;
            if (!std::isinf(S)) {
                const real TS = Tl + (real)S;
                exact -= std::exp(2 * Tl) * boost::math::expint(2, 2 * TS) / TS;
            }
            const double N = slut_nl_N(T, 1.0, 1.0, S);
            const double e = slut_test::rel_err(N, exact);
            w.add(e, T, 1.0, 1.0, S);
            EXPECT_LE(e, 1e-12) << "T=" << T << " S=" << S;
        }
    EXPECT_NEAR(slut_distant_light_factor(1.0, 0.7), 0.5 * (1.0 - std::exp(-1.4)), 1e-16);
    w.print("N(g=1,r=1) vs E_2 closed form");
}
