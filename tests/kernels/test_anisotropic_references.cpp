// The Henyey–Greenstein airlight and near light against the 30-digit mpmath values of
// tests/reference/hg_ref.json, and never NaN or negative on extreme inputs. Part of the
// test_anisotropic executable (anisotropic_test_support.hpp).

#include "anisotropic_test_support.hpp"

// tests/reference/hg_ref.json (make_reference.py: mpmath, two quadrature routes per value plus
// the ξ form of the airlight and the r = 0 airlight identity, agreeing to ≤ 1e-41): every
// g ∈ {−0.9, −0.5, 0, 0.3, 0.8, 0.95, 0.99}, hard geometries included (γ = 1e-3 and π − 1e-6,
// an infinite ray, σ_t → 0, a dense medium; a grazing light, a light on the plane).
TEST(AnisotropicReferences, ExactMatchesMpmath) {
    const nlohmann::json file = slut_test::load_json("hg_ref.json");
    double worst_air = 0, worst_near = 0, worst_boost = 0;
    int n_air = 0, n_near = 0;
    for (const auto &c : file.at("cases")) {
        const double g = c.at("phase_g").get<double>();
        const long double want = slut_test::ref_number(c.at("L"));
        const double length = (double)slut_test::ref_number(c.at("length"));
        if (c.at("quantity") == "airlight") {
            const scatterlut::AirlightQuery q =
                air_query(c.at("sigma_s").get<double>(), c.at("sigma_a").get<double>(), c.at("intensity").get<double>(),
                          c.at("distance").get<double>(), c.at("gamma").get<double>(), length);
            const double got = scatterlut::airlight_radiance_exact(q, g);
            const double e = (double)(std::fabs(got - want) / want);
            worst_air = std::max(worst_air, e);
            EXPECT_LT(e, 1e-12) << c.dump();
            // The Boost reference of the tests above, on the same cases.
            const double boost = ref_airlight_hg(q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m,
                                                 q.gamma_rad, q.length_m, g);
            worst_boost = std::max(worst_boost, (double)(std::fabs(boost - want) / want));
            ++n_air;
        } else {
            scatterlut::NearLightQuery q;
            q.sigma_s_per_m = c.at("sigma_s").get<double>();
            q.sigma_a_per_m = c.at("sigma_a").get<double>();
            q.intensity_W_per_sr = c.at("intensity").get<double>();
            for (int k = 0; k < 3; ++k) {
                q.normal[k] = c.at("normal")[k].get<double>();
                q.eye_dir[k] = c.at("eye_dir")[k].get<double>();
                q.light_rel_m[k] = c.at("light_pos")[k].get<double>();
            }
            q.length_m = length;
            const double got = scatterlut::near_light_radiance_exact(q, g);
            const double e = (want == 0) ? std::fabs(got) : (double)(std::fabs(got - want) / want);
            worst_near = std::max(worst_near, e);
            EXPECT_LT(e, 1e-12) << c.dump();
            ++n_near;
        }
    }
    EXPECT_EQ(n_air, 42);
    EXPECT_EQ(n_near, 28);
    EXPECT_LT(worst_boost, 1e-12);
    std::printf("hg_ref.json: airlight %d cases worst %.2e (Boost reference %.2e), near light %d cases worst %.2e\n",
                n_air, worst_air, worst_boost, n_near, worst_near);
    RecordProperty("worst_rel_err", std::to_string(std::max(worst_air, worst_near)));
}

// Extreme inputs: never NaN, never negative, whatever the scale (lengths 1e-200 … 1e200,
// coefficients 0 … 1e100, γ at and near 0 and π, |g| up to 0.999999).
TEST(AnisotropicReferences, NeverNaNOrNegativeOnExtremeInputs) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto scale = [&](double lo, double hi) { return std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * U(rng)); };
    const double gs[] = {-0.999999, -0.99, -0.3, 0.5, 0.95, 0.999999};
    int finite = 0;
    for (int i = 0; i < 3000; ++i) {
        const double g = gs[i % 6];
        const double D = scale(1e-200, 1e200);
        double gamma = kPi * U(rng);
        if (i % 5 == 0) gamma = (i % 10 == 0) ? 0.0 : kPi;
        if (i % 5 == 1) gamma = scale(1e-300, 1e-3);
        if (i % 5 == 2) gamma = kPi - scale(1e-16, 1e-3);
        const double s = (i % 4 == 0) ? HUGE_VAL : D * scale(1e-12, 1e12);
        const double ss = (i % 9 == 0) ? 0.0 : scale(1e-100, 1e100) / D, sa = (i % 3 == 0) ? 0.0 : scale(1e-100, 1e100) / D;
        const double L = scatterlut::airlight_radiance_exact(air_query(ss, sa, scale(1e-10, 1e10), D, gamma, s), g);
        ASSERT_FALSE(std::isnan(L)) << "g " << g << " D " << D << " gamma " << gamma << " s " << s << " ss " << ss << " sa " << sa;
        ASSERT_GE(L, 0.0);
        finite += std::isfinite(L);

        scatterlut::NearLightQuery q;
        q.sigma_s_per_m = ss;
        q.sigma_a_per_m = sa;
        q.intensity_W_per_sr = 1;
        const double el = 0.01 + 1.5 * U(rng);
        q.eye_dir[0] = std::cos(el);
        q.eye_dir[2] = std::sin(el);
        const double az = 2 * kPi * U(rng), inc = (i % 7 == 0) ? 0.0 : 1.5 * U(rng);
        q.light_rel_m[0] = D * std::cos(az) * std::cos(inc);
        q.light_rel_m[1] = D * std::sin(az) * std::cos(inc);
        q.light_rel_m[2] = D * std::sin(inc);
        q.length_m = s;
        const double N = scatterlut::near_light_radiance_exact(q, g);
        ASSERT_FALSE(std::isnan(N)) << "g " << g << " D " << D << " s " << s << " ss " << ss << " sa " << sa;
        ASSERT_GE(N, 0.0);
    }
    EXPECT_GT(finite, 2000);
}
