// The near-light tables end to end: the OpenCL kernel against the independent Boost
// reference (tests/nearlight_reference.hpp), the r = 0 identity between the near-light
// and the airlight quantities, radiance from tables against exact, and eval's answers
// against the 30-digit mpmath references.
#include <cmath>
#include <limits>
#include <random>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <gtest/gtest.h>

#include "eval.hpp"
#include "generate_nearlight.hpp"
#include "nearlight_reference.hpp"
#include "opencl_device.hpp"
#include "reference_data.hpp"
#include "scatterlut/airlight.hpp"

extern "C" {
#include "slut_nearlight.h"
}

namespace {

scatterlut::Device &device() {
    static scatterlut::Device d("");
    return d;
}

const scatterlut::Table &small_table(bool finite) {
    static const auto make = [](bool fin) {
        scatterlut::NearLightPlan plan;
        plan.finite_thickness = fin;
        plan.n_T = 9;
        plan.n_g = 11;
        plan.n_r = 20; // two lane groups, the second partial
        plan.n_S = 5;
        plan.storage = scatterlut::Storage::F64;
        return scatterlut::generate_nearlight_table(device(), plan, scatterlut::Provenance{});
    };
    static const scatterlut::Table e3 = make(false), e4 = make(true);
    return finite ? e4 : e3;
}

} // namespace

// Every node of a 3-D and a 4-D table against Boost Gauss–Kronrod with break points:
// ≤ 1e-8 relative (the bound; we expect ~1e-14).
TEST(NearLightKernel, EveryNodeMatchesBoostReference) {
    for (bool finite : {false, true}) {
        const scatterlut::Table &t = small_table(finite);
        const scatterlut::NearLightTable table(t);
        double worst = 0;
        size_t node[4] = {0, 0, 0, 0};
        const size_t n_axes = t.axes.size();
        for (size_t flat = 0; flat < t.node_count(); ++flat) {
            size_t rest = flat;
            for (size_t a = 0; a < n_axes; ++a) {
                node[a] = rest % static_cast<size_t>(t.axes[a].map.count);
                rest /= static_cast<size_t>(t.axes[a].map.count);
            }
            double at[4]; // T, g, r, S (+inf in a thick table) by the table's own axis maps
            table.node_params(node, at);
            const double T = at[0], g = at[1], r = at[2], S = at[3];
            // S = 0: N and H vanish; E is their limit, the attenuation at the entry point:
            // e^{−T} for r = 0 (the whole light path inside), 1 for r > 0.
            const double want = S == 0.0 ? (r == 0.0 ? std::exp(-T) : 1.0)
                                         : static_cast<double>(slut_ref::nearlight_NHE(T, g, r, S).E);
            const double got = table.node_E(node);
            const double err = slut_test::rel_err(got, want);
            ASSERT_LE(err, 1e-8) << "T=" << T << " g=" << g << " r=" << r << " S=" << S;
            worst = std::max(worst, err);
        }
        std::printf("%s: %zu nodes, max rel err vs Boost %.2e\n", t.kind.c_str(), t.node_count(), worst);
        EXPECT_LE(t.accuracy.integration_max_rel, 1e-12);
    }
}

// r = 0 (the light in the surface plane, its whole path inside): N is the airlight
// integral with cos γ = −g, per unit σ_s p I0 σ_t: N = σ_t^{-1}·L_air/(σ_s p I0) with
// D = T/σ_t. Two independent computations (slut_nearlight.h's E·H and the airlight θ-integral) agree.
TEST(NearLightIdentity, ZeroRIsTheAirlight) {
    for (double T : {0.05, 1.0, 7.0})
        for (double g : {-0.9, -0.3, 0.0, 0.6, 0.99})
            for (double S : {0.5, 4.0, std::numeric_limits<double>::infinity()}) {
                const double N = slut_nl_E(T, g, 0.0, S) * slut_nl_H(T, g, S);
                scatterlut::AirlightQuery q{1.0, 0.0, 4.0 * M_PI, T, std::acos(-g), S}; // σ_t = 1: D = T, s = S
                const double L = scatterlut::airlight_radiance_exact(q);
                EXPECT_LE(slut_test::rel_err(N, L), 1e-11) << "T=" << T << " g=" << g << " S=" << S;
            }
}

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
        scatterlut::NearLightQuery q;
        q.sigma_s_per_m = c.sigma_s;
        q.sigma_a_per_m = c.sigma_a;
        q.intensity_W_per_sr = c.intensity;
        for (int k = 0; k < 3; ++k) {
            q.normal[k] = c.normal[k];
            q.eye_dir[k] = c.eye_dir[k];
            q.light_rel_m[k] = c.light_pos[k];
        }
        q.length_m = c.length;
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

// The default thick table samples E within 1 % wherever E ≥ 1e-6 (the target),
// measured by the generator at 20000 random points against the shared quadrature (itself
// checked against Boost above). Off-table points fall back to exact integration.
TEST(NearLightTable, DefaultThickTableWithinOnePercent) {
    const scatterlut::Table t = scatterlut::generate_nearlight_table(device(), scatterlut::NearLightPlan{}, {});
    EXPECT_LE(t.accuracy.sampling_max_rel, 1e-2);
    EXPECT_GT(t.accuracy.sampling_points, 15000u);
    scatterlut::NearLightTable table(t);
    EXPECT_FALSE(table.covers(50.0, 0.9, 1e-4, std::numeric_limits<double>::infinity()));
    EXPECT_LE(slut_test::rel_err(table.E(50.0, 0.9, 1e-4, std::numeric_limits<double>::infinity()),
                                 2.015009384261607074432191e-6L), 1e-8); // off-table: exact (N_ref.json)
}

// Eye-side refraction: the radiance along the refracted ray by explicit 3-D quadrature
// (point P = O − x ω_t; the light path below the plane is |P − light|·depth/(depth + height))
// times the unpolarised Fresnel transmittance, against near_light_radiance_exact with
// eta and fresnel. Boost Gauss–Kronrod with break points at e-folds; 1e-9.
TEST(NearLightRefraction, MatchesExplicitQuadratureAlongTheRefractedRay) {
    const double eta = 1.45, sigma_s = 0.8, sigma_a = 0.3, sigma_t = sigma_s + sigma_a, I0 = 2.0;
    const double n[3] = {0, 0, 1};
    const double c = std::cos(0.9), sn = std::sin(0.9);
    const double eye[3] = {sn, 0, c};
    const double light[3] = {-0.4, 0.3, 0.5};
    for (double s : {0.7, std::numeric_limits<double>::infinity()}) {
        // ω_t by Snell's law, written out independently of the header.
        const double sin_t = sn / eta, cos_t = std::sqrt(1 - sin_t * sin_t);
        const double wt[3] = {sin_t, 0, cos_t};
        auto integrand = [&](double x) {
            const double P[3] = {-x * wt[0], -x * wt[1], -x * wt[2]};
            const double d[3] = {light[0] - P[0], light[1] - P[1], light[2] - P[2]};
            const double h = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const double depth = -P[2], height = light[2];
            const double inside = h * depth / (depth + height);
            return std::exp(-sigma_t * (x + inside)) / (h * h);
        };
        const double end = std::isinf(s) ? 60.0 / sigma_t : s;
        double integral = 0;
        for (double a = 0; a < end; a += 0.25) {
            const double b = std::min(end, a + 0.25);
            integral += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(integrand, a, b, 15, 1e-14);
        }
        const double rs = (c - eta * cos_t) / (c + eta * cos_t), rp = (eta * c - cos_t) / (eta * c + cos_t);
        const double fresnel = 1 - 0.5 * (rs * rs + rp * rp);
        const double want = fresnel * sigma_s / (4 * M_PI) * I0 * integral;
        scatterlut::NearLightQuery q;
        q.sigma_s_per_m = sigma_s;
        q.sigma_a_per_m = sigma_a;
        q.intensity_W_per_sr = I0;
        for (int k = 0; k < 3; ++k) {
            q.normal[k] = n[k];
            q.eye_dir[k] = eye[k];
            q.light_rel_m[k] = light[k];
        }
        q.length_m = s;
        q.eta = eta;
        q.fresnel = true;
        EXPECT_LE(slut_test::rel_err(scatterlut::near_light_radiance_exact(q), want), 1e-9) << "s=" << s;
        q.fresnel = false;
        EXPECT_LE(slut_test::rel_err(scatterlut::near_light_radiance_exact(q), want / fresnel), 1e-9) << "s=" << s;
    }
}
