// The Henyey–Greenstein near light (kernels/slut_nearlight_hg.h, tables/src/anisotropic.cpp) against
// Boost.Math quadrature, and its identities: g = 0 is today's path, r = 0 is the airlight with the same g;
// RGB channels and limits. Part of the test_anisotropic executable (anisotropic_test_support.hpp).

#include "anisotropic_test_support.hpp"

TEST(AnisotropicNearLight, EMatchesBoostQuadrature) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    double worst = 0, worst_refine = 0;
    int n = 0;
    for (double G : kG)
        for (int i = 0; i < 40; ++i) {
            const double T = std::exp(std::log(1e-3) + std::log(1e5) * U(rng));
            double gn = -1 + 2 * U(rng);
            if (i % 5 == 0) gn = -1 + std::exp(-12 * U(rng)); // the near-singular peak
            if (i % 5 == 1) gn = 1 - std::exp(-12 * U(rng));
            const double r = (i % 7 == 0) ? 0.0 : std::exp(std::log(1e-6) + std::log(1e10) * U(rng));
            const double S = (i % 3 == 0) ? HUGE_VAL : std::exp(std::log(1e-6) + std::log(1e8) * U(rng));
            if (gn < -0.999999) gn = -0.999999;
            const double S_over_T = std::isinf(S) ? HUGE_VAL : S / T;
            const double got = slut_hg_nl_E(T, gn, r, S_over_T, G, 1.0);
            const slut_ref::NearLightValue want = ref_nearlight_hg(T, gn, r, S, G);
            worst = std::max(worst, rel(got, (double)want.E));
            worst_refine = std::max(worst_refine, rel(got, slut_hg_nl_E(T, gn, r, S_over_T, G, 2.5)));
            ++n;
            EXPECT_LT(rel(got, (double)want.E), 1e-12) << "G " << G << " T " << T << " g " << gn << " r " << r << " S " << S;
        }
    std::printf("anisotropic E vs Boost: %d points, worst %.2e (vs the 2.5× finer mesh %.2e)\n", n, worst, worst_refine);
    RecordProperty("worst_rel_err", std::to_string(worst));
}

// At g_hg = 0 the HG march is slut_nl_E's integral (its own mesh); the entry point hands
// phase_g = 0 to near_light_radiance_exact (bit for bit).
TEST(AnisotropicNearLight, ZeroGIsTodaysPath) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    double worst = 0;
    for (int i = 0; i < 500; ++i) {
        const double T = std::exp(std::log(1e-3) + std::log(1e5) * U(rng)), gn = -0.999 + 1.998 * U(rng);
        const double r = std::exp(std::log(1e-4) + std::log(1e8) * U(rng));
        const double S = (i % 3 == 0) ? HUGE_VAL : std::exp(std::log(1e-4) + std::log(1e6) * U(rng));
        worst = std::max(worst, rel(slut_hg_nl_E(T, gn, r, std::isinf(S) ? HUGE_VAL : S / T, 0.0, 1.0), slut_nl_E(T, gn, r, S)));
    }
    EXPECT_LT(worst, 1e-12);
    scatterlut::NearLightQuery q;
    q.sigma_s_per_m = 0.4;
    q.sigma_a_per_m = 0.1;
    q.intensity_W_per_sr = 3;
    q.light_rel_m[0] = 1;
    q.light_rel_m[2] = 2;
    q.eye_dir[0] = 0.6;
    q.eye_dir[2] = 0.8;
    q.length_m = 3;
    EXPECT_EQ(scatterlut::near_light_radiance_exact(q, 0.0), scatterlut::near_light_radiance_exact(q));
    RecordProperty("worst_rel_err", std::to_string(worst));
}

// r = 0 (the light in the surface plane): the near light is the airlight with D = l,
// cos γ = −g_nl and the same g_hg, for every g_hg.
TEST(AnisotropicNearLight, ZeroRIsTheAirlightWithTheSameG) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    double worst = 0;
    int checked = 0;
    for (double G : kG)
        for (int i = 0; i < 40; ++i) {
            const double l = std::exp(-2 + 4 * U(rng)), gamma = 1e-3 + (kPi - 2e-3) * U(rng);
            const double s = (i % 4 == 0) ? HUGE_VAL : l * std::exp(-5 + 7 * U(rng));
            const double ss = std::exp(-5 + 5 * U(rng)), sa = ss * U(rng);
            // The view ray goes into the medium along −ω, so the viewer→light direction makes
            // the angle γ with −ω: g_nl = ω·ω_l = −cos γ.
            scatterlut::NearLightQuery q;
            q.sigma_s_per_m = ss;
            q.sigma_a_per_m = sa;
            q.intensity_W_per_sr = 2;
            q.normal[0] = 0; q.normal[1] = 0; q.normal[2] = 1;
            const double th = 0.3 + 1.0 * U(rng); // eye elevation
            q.eye_dir[0] = std::cos(th); q.eye_dir[1] = 0; q.eye_dir[2] = std::sin(th);
            // a light in the plane z = 0 at angle γ from −ω's direction, seen from O: solve in the plane
            // spanned by −ω and a horizontal unit vector e ⊥ ω: ω_l = cos γ (−ω) + sin γ e, needs ω_l·n = 0.
            // Use instead: horizontal ω_l with ω·ω_l = −cos γ ⇒ ω_l = (a, b, 0), a cos th = −cos γ.
            const double a = -std::cos(gamma) / std::cos(th);
            if (std::fabs(a) >= 1) continue;
            const double b = std::sqrt((1 - a) * (1 + a));
            q.light_rel_m[0] = l * a; q.light_rel_m[1] = l * b; q.light_rel_m[2] = 0;
            q.length_m = s;
            const double gn = (q.eye_dir[0] * q.light_rel_m[0]) / l;
            const double near = scatterlut::near_light_radiance_exact(q, G);
            const double air = scatterlut::airlight_radiance_exact(air_query(ss, sa, 2, l, std::acos(-gn), s), G);
            worst = std::max(worst, rel(near, air));
            ++checked;
            EXPECT_LT(rel(near, air), 1e-11) << "G " << G << " gamma " << gamma << " s " << s;
        }
    EXPECT_GT(checked, 100);
    std::printf("r = 0 identity: %d geometries, worst %.2e\n", checked, worst);
    RecordProperty("worst_rel_err", std::to_string(worst));
}

TEST(AnisotropicNearLight, RgbClearAndDenseChannelsAndLimits) {
    scatterlut::NearLightQuery q;
    q.intensity_W_per_sr = 4;
    q.light_rel_m[0] = 0.5;
    q.light_rel_m[2] = 1.5;
    q.eye_dir[0] = 0.8;
    q.eye_dir[2] = 0.6;
    q.length_m = HUGE_VAL;
    for (double G : kG) {
        const Rgb L = scatterlut::near_light_radiance_exact_rgb(q, Rgb{0.0, 1e-9, 50.0}, Rgb{0.0, 0.0, 20.0}, G);
        EXPECT_EQ(L[0], 0.0);
        EXPECT_TRUE(L[1] > 0 && std::isfinite(L[1]));
        EXPECT_TRUE(L[2] > 0 && std::isfinite(L[2]));
        // σ_t → 0 is finite with a finite slab (∫ψ/h² along the ray).
        scatterlut::NearLightQuery slab = q;
        slab.length_m = 2.0;
        const Rgb Ls = scatterlut::near_light_radiance_exact_rgb(slab, Rgb{1e-12, 1e-6, 1.0}, Rgb{0, 0, 0}, G);
        EXPECT_LT(rel(Ls[0] / 1e-12, Ls[1] / 1e-6), 1e-5);
        // a light below the plane: 0
        scatterlut::NearLightQuery below = q;
        below.light_rel_m[2] = -0.5;
        EXPECT_EQ(scatterlut::near_light_radiance_exact(below, G), 0.0);
    }
}
