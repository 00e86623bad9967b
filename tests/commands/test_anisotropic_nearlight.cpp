// The anisotropic (Henyey–Greenstein) near-light tables end to end: the OpenCL kernel
// (kernels/nearlight_Eg.cl) at every node against Boost Gauss–Kronrod with the phase, the
// runtime sampler (NearLightHgTable) against the exact radiance near_light_radiance_exact(q, g)
// where the attenuation is ≥ 1e-6, the r = 0 identity with the anisotropic airlight, the hard
// corners, RGB, and the closed forms' limits.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "eval.hpp"
#include "generate_nearlight.hpp"
#include "opencl_device.hpp"
#include "plan.hpp"
#include "scene.hpp"
#include "reference_quadrature.hpp"
#include "scatterlut/anisotropic.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/nearlight_hg.hpp"

extern "C" {
#include "slut_nearlight.h"
#include "slut_nearlight_hg.h"
}

namespace {

using scatterlut::NearLightHgTable;
using scatterlut::NearLightPlan;
using scatterlut::NearLightQuery;
using scatterlut::Table;

const double kPhaseGs[] = {-0.9, -0.5, 0.3, 0.8, 0.95};


scatterlut::Device &device() {
    static scatterlut::Device d("");
    return d;
}

NearLightPlan plan_of(bool finite, double phase_g, int n_T, int n_g, int n_r, int n_S) {
    NearLightPlan plan = scatterlut::default_near_light_plan(finite);
    plan.phase_g = phase_g;
    plan.T_min = 1e-2;
    plan.T_max = 10.0;
    plan.g_min = -0.99;
    plan.g_max = scatterlut::near_light_hg_g_max(phase_g, finite);
    plan.r_max = 2.0; // a view angle up to 60°
    plan.S_min = 1e-2;
    plan.S_max = 10.0;
    plan.n_T = n_T;
    plan.n_g = n_g;
    plan.n_r = n_r;
    plan.n_S = n_S;
    plan.storage = scatterlut::Storage::F32;
    return plan;
}

// A small table of each kind and g (every node checked) and a production-like one (radiance).
const Table &small_table(bool finite, double phase_g) {
    static std::map<std::pair<bool, double>, Table> cache;
    auto key = std::make_pair(finite, phase_g);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    NearLightPlan plan = plan_of(finite, phase_g, 7, 9, 6, 5);
    plan.storage = scatterlut::Storage::F64;
    return cache[key] = scatterlut::generate_nearlight_table(device(), plan, scatterlut::Provenance{});
}

const Table &radiance_table(bool finite, double phase_g) {
    static std::map<std::pair<bool, double>, Table> cache;
    auto key = std::make_pair(finite, phase_g);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    // The default plans' counts (docs/NEARLIGHT.md) over the domain of plan_of.
    const NearLightPlan defaults = scatterlut::default_near_light_plan(finite);
    const NearLightPlan plan = plan_of(finite, phase_g, defaults.n_T, defaults.n_g, defaults.n_r, defaults.n_S);
    const auto t0 = std::chrono::steady_clock::now();
    Table t = scatterlut::generate_nearlight_table(device(), plan, scatterlut::Provenance{});
    std::printf("%s g = %g: %zu nodes in %.2f s; integration %.2e, sampling max %.2e p99 %.2e\n", t.kind.c_str(),
                phase_g, t.node_count(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                t.accuracy.integration_max_rel, t.accuracy.sampling_max_rel, t.accuracy.sampling_p99_rel);
    return cache[key] = std::move(t);
}

} // namespace

// Every node of a 3-D and a 4-D table per g against Boost Gauss–Kronrod with the phase
// (host/src/reference_quadrature.cpp): ≤ 1e-9 relative (the kernel's tolerance is 1e-11).
TEST(AnisotropicNearLightKernel, EveryNodeMatchesBoostReference) {
    for (double phase_g : kPhaseGs)
        for (bool finite : {false, true}) {
            const Table &t = small_table(finite, phase_g);
            ASSERT_EQ(t.extra.at("phase.g"), scatterlut::phase_g_text(phase_g));
            ASSERT_EQ(t.kind, finite ? scatterlut::kKindNearLightE4Hg : scatterlut::kKindNearLightE3Hg);
            const NearLightHgTable table(t);
            ASSERT_EQ(table.phase_g(), phase_g);
            double worst = 0, worst_at[4] = {0, 0, 0, 0};
            size_t node[4] = {0, 0, 0, 0};
            for (size_t flat = 0; flat < t.node_count(); ++flat) {
                size_t rest = flat;
                for (size_t a = 0; a < t.axes.size(); ++a) {
                    node[a] = rest % static_cast<size_t>(t.axes[a].map.count);
                    rest /= static_cast<size_t>(t.axes[a].map.count);
                }
                double p[4];
                table.node_params(node, p);
                const double ref = scatterlut::reference_near_light_E(p[0], p[1], p[2], p[3], phase_g);
                const double err = std::fabs(table.node_E(node) - ref) / ref;
                ASSERT_TRUE(std::isfinite(err)) << "T " << p[0] << " g " << p[1] << " r " << p[2] << " S " << p[3];
                if (err > worst) std::copy(p, p + 4, worst_at);
                worst = std::max(worst, err);
            }
            std::printf("phase_g %5.2f %s: every node vs Boost: %.2e at T %g g %g r %g S %g\n", phase_g,
                        finite ? "E4" : "E3", worst, worst_at[0], worst_at[1], worst_at[2], worst_at[3]);
            EXPECT_LE(worst, 1e-9) << "phase_g " << phase_g << (finite ? " E4" : " E3");
            EXPECT_LE(t.accuracy.integration_max_rel, 1e-9);
        }
}

// A table survives its file: g read back, the same values.
TEST(AnisotropicNearLightTable, RoundTripKeepsPhaseG) {
    const Table &t = small_table(true, 0.95);
    const std::vector<uint8_t> bytes = scatterlut::encode_binary(t);
    const Table back = scatterlut::decode_binary(bytes.data(), bytes.size(), "round trip");
    const NearLightHgTable table(back);
    EXPECT_EQ(table.phase_g(), 0.95);
    EXPECT_EQ(back.values, t.values);
    Table wrong = t;
    wrong.extra.erase("phase.g");
    EXPECT_THROW(NearLightHgTable{wrong}, std::invalid_argument);
    wrong = t;
    wrong.extra["phase.g"] = "0.95x";
    EXPECT_THROW(NearLightHgTable{wrong}, std::invalid_argument);
    wrong.extra["phase.g"] = "1";
    EXPECT_THROW(NearLightHgTable{wrong}, std::invalid_argument);
    wrong = t;
    wrong.kind = scatterlut::kKindNearLightE4; // an isotropic kind is not an anisotropic table
    EXPECT_THROW(NearLightHgTable{wrong}, std::invalid_argument);
}

namespace {

// Random near-light queries whose (T, g, r, S) the table covers and whose attenuation (the
// isotropic E) is ≥ 1e-6: the normal +z, eye and light above the plane, σ set so that T and
// S fall inside the table's axes.
std::vector<NearLightQuery> covered_queries(const NearLightHgTable &table, size_t count, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Table &t = table.table();
    const double T_lo = t.axes[0].map.min, T_hi = t.axes[0].map.max;
    std::vector<NearLightQuery> out;
    for (size_t tries = 0; out.size() < count && tries < 100 * count; ++tries) {
        NearLightQuery q;
        const double view = std::acos(1.0 - unit(rng) * (1.0 - std::cos(1.0))); // ≤ 57°
        const double phi_e = 2 * M_PI * unit(rng), phi_l = 2 * M_PI * unit(rng);
        q.eye_dir[0] = std::sin(view) * std::cos(phi_e);
        q.eye_dir[1] = std::sin(view) * std::sin(phi_e);
        q.eye_dir[2] = std::cos(view);
        const double mu_l = 0.02 + 0.98 * unit(rng), sl = std::sqrt(1 - mu_l * mu_l);
        const double l = 0.5 + 4.5 * unit(rng);
        q.light_rel_m[0] = l * sl * std::cos(phi_l);
        q.light_rel_m[1] = l * sl * std::sin(phi_l);
        q.light_rel_m[2] = l * mu_l;
        const double T = T_lo * std::pow(T_hi / T_lo, unit(rng)), sigma_t = T / l, albedo = 0.2 + 0.8 * unit(rng);
        q.sigma_s_per_m = albedo * sigma_t;
        q.sigma_a_per_m = sigma_t - q.sigma_s_per_m;
        q.intensity_W_per_sr = 1 + 99 * unit(rng);
        if (table.thick_only()) q.length_m = HUGE_VAL;
        else {
            const double S_lo = t.axes[3].map.min, S_hi = t.axes[3].map.max;
            q.length_m = S_lo * std::pow(S_hi / S_lo, unit(rng)) / sigma_t;
        }
        const scatterlut::NearLightParams p = scatterlut::near_light_params(q);
        if (p.light_below || !table.covers(p.T, p.g, p.r, p.S)) continue;
        if (slut_nl_E(p.T, p.g, p.r, p.S) < 1e-6) continue;
        out.push_back(q);
    }
    return out;
}

} // namespace

namespace {

// Table radiance against the exact quadrature with the phase: 3000 random covered queries
// (attenuation ≥ 1e-6), the batch equal to the scalar call, never NaN or negative; the worst
// relative error.
double radiance_error(bool finite, double phase_g) {
    {
        {
            const NearLightHgTable table(radiance_table(finite, phase_g));
            const std::vector<NearLightQuery> qs = covered_queries(table, 3000, 7);
            EXPECT_GE(qs.size(), 1000u);
            std::vector<double> batch(qs.size());
            table.radiance(qs.data(), qs.size(), batch.data());
            double worst = 0;
            for (size_t k = 0; k < qs.size(); ++k) {
                const double exact = scatterlut::near_light_radiance_exact(qs[k], phase_g);
                const double L = table.radiance(qs[k]);
                if (!(L >= 0.0 && std::isfinite(L)) || !(exact > 0.0)) {
                    ADD_FAILURE() << "query " << k << ": table " << L << ", exact " << exact;
                    return HUGE_VAL;
                }
                EXPECT_NEAR(batch[k], L, 1e-12 * L) << k;
                worst = std::max(worst, std::fabs(L - exact) / exact);
            }
            std::printf("phase_g %5.2f %s: %zu queries, radiance vs exact max %.2e\n", phase_g, finite ? "E4" : "E3",
                        qs.size(), worst);
            return worst;
        }
    }
}

} // namespace

// The thick tables at the default counts: within the default scene's accepted error (1 %).
TEST(AnisotropicNearLightTable, ThickRadianceMatchesExact) {
    for (double phase_g : kPhaseGs) EXPECT_LE(radiance_error(false, phase_g), 1e-2) << "phase_g " << phase_g;
}

// The slab tables (E4_hg) at the default counts, one g per test (each generates its table,
// ~1-2 min on a loaded 2-core machine): the radiance at random covered queries and the hard
// corners (T, g, r at their ends as below; S at its ends and at the light's foot point)
// within the default scene's accepted error (1 %), never NaN. The slab divisor
// (slut_hg_nl_slab_divisor) carries the phase's mean along the path; with the entry point's
// phase alone they measured 1.7 % (g = 0.95) and 20 % (g = −0.9).
class AnisotropicNearLightSlab : public testing::TestWithParam<double> {};

TEST_P(AnisotropicNearLightSlab, SlabRadianceMatchesExact) {
    const double phase_g = GetParam();
    EXPECT_LE(radiance_error(true, phase_g), 1e-2) << "phase_g " << phase_g;
    const NearLightHgTable table(radiance_table(true, phase_g));
    const scatterlut::SamplingStats c = scatterlut::measure_nearlight_corners(table, 4000, 3);
    std::printf("phase_g %5.2f E4: corners max %.2e p99 %.2e (%zu points)\n", phase_g, c.max_rel, c.p99_rel, c.points);
    EXPECT_TRUE(std::isfinite(c.max_rel));
    EXPECT_LE(c.max_rel, 1e-2) << "phase_g " << phase_g << " worst at T " << c.worst_at[0] << " g " << c.worst_at[1]
                               << " r " << c.worst_at[2] << " S " << c.worst_at[3];
    EXPECT_GE(c.points, 1000u);
}

INSTANTIATE_TEST_SUITE_P(PerPhase, AnisotropicNearLightSlab, testing::ValuesIn(kPhaseGs));

// The hard corners (T at its ends, g at g_min, g_min + 1e-9 and 1, r at 0, 1e-12 and r_max)
// of the thick tables: within 1 % and never NaN, per g (the slab tables: above).
TEST(AnisotropicNearLightTable, HardCorners) {
    for (double phase_g : kPhaseGs) {
        const NearLightHgTable table(radiance_table(false, phase_g));
        const scatterlut::SamplingStats c = scatterlut::measure_nearlight_corners(table, 4000, 3);
        std::printf("phase_g %5.2f E3: corners max %.2e p99 %.2e (%zu points)\n", phase_g, c.max_rel, c.p99_rel, c.points);
        EXPECT_TRUE(std::isfinite(c.max_rel));
        EXPECT_LE(c.max_rel, 1e-2) << "phase_g " << phase_g << " worst at T " << c.worst_at[0] << " g "
                                   << c.worst_at[1] << " r " << c.worst_at[2] << " S " << c.worst_at[3];
        EXPECT_GE(c.points, 1000u);
    }
}

// r = 0 (the light in the plane of... the eye's cosine ≫ the light's) is the airlight with
// D = l, cos γ = −g and the same phase (kernels/slut_nearlight_hg.h): σ_t N_g(σ_t D, −cos γ,
// 0, ∞) = 4π/(σ_s I0) L_airlight,g. The quadrature to 1e-9, the table to its sampling error.
TEST(AnisotropicNearLightTable, ZeroRIsTheAirlight) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (double phase_g : kPhaseGs) {
        const NearLightHgTable table(radiance_table(false, phase_g));
        double worst_exact = 0, worst_table = 0;
        for (int k = 0; k < 200; ++k) {
            const double T = 0.02 * std::pow(400.0, unit(rng)), g = -0.98 + 1.98 * unit(rng);
            scatterlut::AirlightQuery a;
            a.sigma_s_per_m = 1.0; // σ_t = 1/m: D = T m
            a.intensity_W_per_sr = 1.0;
            a.distance_m = T;
            a.gamma_rad = std::acos(-g);
            a.length_m = HUGE_VAL;
            const double airlight = 4 * M_PI * scatterlut::airlight_radiance_exact(a, phase_g);
            const double H = slut_nl_H(T, g, HUGE_VAL);
            const double N_exact = slut_hg_nl_N(T, g, 0.0, HUGE_VAL, phase_g);
            const double N_table = table.E(T, g, 0.0, HUGE_VAL) * H;
            worst_exact = std::max(worst_exact, std::fabs(N_exact - airlight) / airlight);
            worst_table = std::max(worst_table, std::fabs(N_table - airlight) / airlight);
        }
        std::printf("phase_g %5.2f: r = 0 vs the airlight: quadrature %.2e, table %.2e\n", phase_g, worst_exact,
                    worst_table);
        EXPECT_LE(worst_exact, 1e-9);
        EXPECT_LE(worst_table, 1e-2);
    }
}

// RGB from one table: each channel is the single-channel radiance; a clear channel (σ_t = 0,
// outside every table) and a dense one are independent and exact/tabulated respectively.
TEST(AnisotropicNearLightTable, RgbOneTable) {
    const NearLightHgTable table(radiance_table(false, 0.8));
    const std::vector<NearLightQuery> qs = covered_queries(table, 50, 13);
    ASSERT_FALSE(qs.empty());
    for (const NearLightQuery &q : qs) {
        const double st = q.sigma_s_per_m + q.sigma_a_per_m;
        const scatterlut::Rgb s = {q.sigma_s_per_m, 0.0, 0.5 * q.sigma_s_per_m};
        const scatterlut::Rgb a = {q.sigma_a_per_m, 0.0, 0.5 * q.sigma_a_per_m + 0.5 * st};
        const scatterlut::Rgb L = table.radiance_rgb(q, s, a);
        EXPECT_EQ(L[0], table.radiance(q));
        EXPECT_EQ(L[1], 0.0); // σ_s = 0: nothing scattered
        NearLightQuery blue = q;
        blue.sigma_s_per_m = s[2];
        blue.sigma_a_per_m = a[2];
        EXPECT_EQ(L[2], table.radiance(blue));
        const scatterlut::Rgb exact = scatterlut::near_light_radiance_exact_rgb(q, s, a, 0.8);
        EXPECT_NEAR(L[0], exact[0], 1e-2 * exact[0]);
    }
    // A clear channel with scattering but no extinction to speak of (σ_t → 0): exact, finite.
    NearLightQuery q = qs[0];
    const scatterlut::Rgb L = table.radiance_rgb(q, {1e-300, q.sigma_s_per_m, 0.0}, {0.0, q.sigma_a_per_m, 0.0});
    EXPECT_TRUE(std::isfinite(L[0]) && L[0] >= 0.0);
    EXPECT_EQ(L[1], table.radiance(q));
    EXPECT_THROW(table.radiance_rgb(q, {-1.0, 0.0, 0.0}, {0.0, 0.0, 0.0}), std::invalid_argument);
}

// The closed forms with the phase: the distant form is exact as l → ∞ (every ray parallel),
// the thin form as σ_t s → 0; both reduce to the isotropic ones at g = 0 and are never negative.
TEST(AnisotropicNearLightClosedForms, Limits) {
    for (double phase_g : kPhaseGs) {
        NearLightQuery q;
        q.sigma_s_per_m = 0.5;
        q.sigma_a_per_m = 0.1;
        q.intensity_W_per_sr = 1.0;
        const double eye[3] = {0.3, 0.0, std::sqrt(1 - 0.09)};
        std::copy(eye, eye + 3, q.eye_dir);
        const double dir[3] = {-0.6, 0.2, std::sqrt(1 - 0.4)};
        q.length_m = 0.5;
        for (int k = 0; k < 3; ++k) q.light_rel_m[k] = 1e5 * dir[k]; // distant: l = 1e5 m ≫ s
        const double exact_far = scatterlut::near_light_radiance_exact(q, phase_g);
        const double distant = scatterlut::near_light_radiance_distant(q, phase_g);
        EXPECT_NEAR(distant, exact_far, 1e-4 * exact_far) << phase_g;
        for (int k = 0; k < 3; ++k) q.light_rel_m[k] = 2.0 * dir[k];
        q.length_m = 1e-5; // thin: σ_t s = 6e-6
        const double exact_thin = scatterlut::near_light_radiance_exact(q, phase_g);
        const double thin = scatterlut::near_light_radiance_thin(q, phase_g);
        EXPECT_NEAR(thin, exact_thin, 1e-4 * exact_thin) << phase_g;
        EXPECT_GE(thin, 0.0);
        EXPECT_GE(distant, 0.0);
    }
    NearLightQuery q;
    q.sigma_s_per_m = 0.5;
    q.intensity_W_per_sr = 1.0;
    q.length_m = 1.0;
    q.light_rel_m[0] = 1.0;
    EXPECT_EQ(scatterlut::near_light_radiance_thin(q, 0.0), scatterlut::near_light_radiance_thin(q));
    EXPECT_EQ(scatterlut::near_light_radiance_distant(q, 0.0), scatterlut::near_light_radiance_distant(q));
}

// The planner: isotropic media keep the isotropic kinds; a medium with phase_g gets the
// anisotropic kind with its g (and g_max for a backward phase); each distinct g its own table
// and file stem; media that differ only in σ share one.
TEST(AnisotropicNearLightPlan, DemandFollowsPhaseG) {
    // Three thick media seen from outside (σ in 1/m), one point light.
    auto medium = [](const char *name, int sigma_s, int sigma_a) {
        return "[[medium]]\nname = \"" + std::string(name) + "\"\nsigma_s_per_m = " + std::to_string(sigma_s) +
               "\nsigma_a_per_m = " + std::to_string(sigma_a) + "\nviewer_inside = false\nthick = true\n";
    };
    const std::string text = "name = \"two\"\n" + medium("wax", 90, 10) + medium("fog", 40, 10) +
                             medium("smoke", 30, 10) +
                             "[[light]]\nname = \"lamp\"\ntype = \"point\"\nintensity_W_per_sr = 1\n"
                             "distance_m = [0.01, 0.1]\n";
    scatterlut::Scene scene = scatterlut::parse_scene(text, "two.toml");
    {
        const scatterlut::ScenePlan p = scatterlut::derive_plan(scene, scatterlut::Storage::F32);
        ASSERT_EQ(p.tables.size(), 1u);
        EXPECT_STREQ(p.tables[0].name(), "near_light_E3");
    }
    scene.media[1].phase_g = -0.9; // fog
    scene.media[2].phase_g = 0.85; // smoke: a second g, a second table
    const scatterlut::ScenePlan p = scatterlut::derive_plan(scene, scatterlut::Storage::F32);
    ASSERT_EQ(p.tables.size(), 3u);
    EXPECT_STREQ(p.tables[0].name(), "near_light_E3");
    ASSERT_EQ(p.tables[0].requested_by.size(), 1u);
    EXPECT_EQ(p.tables[0].requested_by[0].medium, "wax");
    EXPECT_EQ(p.tables[0].plan_as<NearLightPlan>().phase_g, 0.0);
    const scatterlut::PlannedTable &hg = p.tables[1];
    EXPECT_EQ(hg.kind->name(), std::string(scatterlut::kKindNearLightE3Hg));
    EXPECT_STREQ(hg.name(), "near_light_E3_hg_g-0.9");
    EXPECT_EQ(hg.phase_g, -0.9);
    ASSERT_EQ(hg.requested_by.size(), 1u);
    EXPECT_EQ(hg.requested_by[0].medium, "fog");
    EXPECT_EQ(hg.plan_as<NearLightPlan>().phase_g, -0.9);
    EXPECT_EQ(hg.plan_as<NearLightPlan>().g_max, 0.85);
    // T = σ_t·l of the fog alone: 50·[0.01, 0.1].
    EXPECT_DOUBLE_EQ(hg.plan_as<NearLightPlan>().T_min, 0.5);
    const scatterlut::PlannedTable &smoke = p.tables[2];
    EXPECT_STREQ(smoke.name(), "near_light_E3_hg_g0.85");
    EXPECT_EQ(smoke.phase_g, 0.85);
    ASSERT_EQ(smoke.requested_by.size(), 1u);
    EXPECT_EQ(smoke.requested_by[0].medium, "smoke");
    EXPECT_EQ(smoke.plan_as<NearLightPlan>().phase_g, 0.85);
    EXPECT_EQ(smoke.plan_as<NearLightPlan>().g_max, 1.0);
    EXPECT_DOUBLE_EQ(smoke.plan_as<NearLightPlan>().T_min, 0.4); // 40·0.01
    // Media that differ only in σ share their g's table.
    scene.media[2].phase_g = -0.9;
    const scatterlut::ScenePlan shared = scatterlut::derive_plan(scene, scatterlut::Storage::F32);
    ASSERT_EQ(shared.tables.size(), 2u);
    EXPECT_EQ(shared.tables[1].requested_by.size(), 2u);
    EXPECT_DOUBLE_EQ(shared.tables[1].plan_as<NearLightPlan>().T_min, 0.4);
    const Table layout = scatterlut::make_nearlight_table_layout(hg.plan_as<NearLightPlan>());
    EXPECT_EQ(layout.extra.at("phase.g"), "-0.90000000000000002");
    EXPECT_EQ(scatterlut::near_light_hg_file_stem(false, 0.85), "near_light_E3_hg_g0.85");
    EXPECT_EQ(scatterlut::near_light_hg_file_stem(true, -0.5), "near_light_E4_hg_g-0.5");
}

// eval: a near_light query with "phase_g" takes "table" from a loaded anisotropic near-light
// table of exactly its g that covers it (per channel for RGB); another g, no phase_g, or a
// query outside the table: "table": null.
TEST(AnisotropicNearLightEval, TableOfTheSameG) {
    scatterlut::EvalTables tables;
    tables.add("thick_0.8", small_table(false, 0.8));
    tables.add("slab_-0.5", small_table(true, -0.5));
    const NearLightHgTable thick(small_table(false, 0.8)), slab(small_table(true, -0.5));
    auto json_of = [](const NearLightQuery &q, double phase_g) {
        nlohmann::json j = {{"quantity", "near_light"},
                            {"sigma_s", q.sigma_s_per_m},
                            {"sigma_a", q.sigma_a_per_m},
                            {"intensity", q.intensity_W_per_sr},
                            {"normal", {q.normal[0], q.normal[1], q.normal[2]}},
                            {"eye_dir", {q.eye_dir[0], q.eye_dir[1], q.eye_dir[2]}},
                            {"light_pos", {q.light_rel_m[0], q.light_rel_m[1], q.light_rel_m[2]}}};
        if (q.length_m > 1e300) j["length"] = "inf";
        else j["length"] = q.length_m;
        if (phase_g != 0.0) j["phase_g"] = phase_g;
        return j;
    };
    for (const auto &[table, g] : {std::make_pair(&thick, 0.8), std::make_pair(&slab, -0.5)}) {
        const std::vector<NearLightQuery> qs = covered_queries(*table, 20, 17);
        ASSERT_GE(qs.size(), 10u);
        for (const NearLightQuery &q : qs) {
            const nlohmann::json out = scatterlut::eval_query(json_of(q, g), tables);
            ASSERT_TRUE(out["table"].is_number()) << out.dump();
            EXPECT_EQ(out["table"].get<double>(), table->radiance(q)) << out.dump();
            EXPECT_EQ(out["exact"].get<double>(), scatterlut::near_light_radiance_exact(q, g));
            // The closed forms with the phase (thin: 0 for a thick table's infinite length).
            EXPECT_EQ(out["approx"].get<double>(), scatterlut::near_light_radiance_thin(q, g)) << out.dump();
            EXPECT_EQ(out["distant"].get<double>(), scatterlut::near_light_radiance_distant(q, g)) << out.dump();
            // Another g (the other loaded table's, or none loaded) and the isotropic query: no table.
            for (double other : {g == 0.8 ? -0.5 : 0.8, 0.3, 0.0})
                EXPECT_TRUE(scatterlut::eval_query(json_of(q, other), tables)["table"].is_null()) << other;
        }
        // Per channel: each channel's table value is its scalar query's.
        const NearLightQuery &q = qs[0];
        nlohmann::json rgb = json_of(q, g);
        rgb["sigma_s"] = {q.sigma_s_per_m, 0.0, 0.5 * q.sigma_s_per_m};
        rgb["sigma_a"] = {q.sigma_a_per_m, 0.0, q.sigma_a_per_m + 0.5 * q.sigma_s_per_m}; // channel 2: the same σ_t
        const nlohmann::json out = scatterlut::eval_query(rgb, tables);
        ASSERT_TRUE(out["table"].is_array()) << out.dump();
        const scatterlut::Rgb L = table->radiance_rgb(q, {q.sigma_s_per_m, 0.0, 0.5 * q.sigma_s_per_m},
                                                     {q.sigma_a_per_m, 0.0, q.sigma_a_per_m + 0.5 * q.sigma_s_per_m});
        EXPECT_EQ(out["table"][0].get<double>(), L[0]);
        EXPECT_EQ(out["table"][2].get<double>(), L[2]);
        // A query outside the table's T axis (σ_t far above): null, the exact answer still given.
        NearLightQuery far = q;
        far.sigma_s_per_m *= 1e4;
        far.sigma_a_per_m *= 1e4;
        const nlohmann::json outside = scatterlut::eval_query(json_of(far, g), tables);
        EXPECT_TRUE(outside["table"].is_null()) << outside.dump();
        EXPECT_TRUE(outside["exact"].is_number()) << outside.dump();
    }
}

// validate's independent check (Boost Gauss–Kronrod with the phase at the corners and random
// nodes, the sampling error at other points) passes on an anisotropic table file of each kind.
TEST(AnisotropicNearLightValidate, IndependentCheckPasses) {
    for (const auto &[finite, phase_g] : {std::make_pair(false, 0.8), std::make_pair(true, -0.5)}) {
        const std::string path = slut_test::temp_stem("validate_hg") + (finite ? "_E4" : "_E3") + ".slut";
        const std::vector<uint8_t> bytes = scatterlut::encode_binary(small_table(finite, phase_g));
        std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char *>(bytes.data()),
                                                    static_cast<std::streamsize>(bytes.size()));
        const slut_test::RunResult r = slut_test::run_scatterlut("validate " + path);
        EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
        EXPECT_NE(r.out.find("nodes:"), std::string::npos) << r.out;
        std::filesystem::remove(path);
    }
}
