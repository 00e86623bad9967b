// The airlight snippet's tiers (scatterlut_airlight.{glsl,hlsl,essl} with SLUT_TIER_FAST or
// SLUT_TIER_ACCURATE: tables/shaders/src/airlight.slsl and kernels/slut_airlight_rational.h,
// docs/SHADERS.md "Tiers") per query against the truths they must reproduce:
//   - the C++ double reference of the same algorithm on the same float-rounded table and
//     inputs (scatterlut::AirlightRationalTable::radiance): what the shader's float arithmetic
//     and, in the fast tier, the GPU's filter weights may add;
//   - the exact radiance (airlight_radiance_exact, quadrature ~1e-13) at each tier's stated
//     tolerance: (2G − 1) times the table's measured interpolation error (G =
//     SLUT_AIRLIGHT_RATIONAL_GAIN: the two ends' difference where it is used; the short
//     segment's rule is ~1e-7 there) plus the float arithmetic's;
// on the shader tests' airlight queries (airlight_gpu_test.hpp: every regime, σ_t D up to 85,
// γ at and near 0 and π, finite and infinite rays, the degenerate inputs) and from points.
// Never NaN, never negative; +∞ exactly where the ray runs through the light.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "generate_airlight_rational.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_rational.hpp"

extern "C" {
#include "slut_airlight_rational.h"
}

#include "airlight_gpu_test.hpp"
#include "wgsl_cases.hpp"

namespace {

using namespace airlight_gpu_test;

// The tiers' table: the airlight_rational layout at kCount² nodes, the node function's values
// rounded to float (what the generator's kernel computes, tests/commands and tests/runtime check
// that it does).
constexpr int kCount = 96;

const scatterlut::AirlightRationalTable &rational_table() {
    static const scatterlut::AirlightRationalTable table = [] {
        scatterlut::AirlightRationalPlan plan;
        plan.n_m = plan.n_t = kCount;
        scatterlut::Table t = scatterlut::make_airlight_rational_layout(plan);
        t.values.resize(static_cast<size_t>(kCount) * kCount);
        for (int j = 0; j < kCount; ++j)
            for (int i = 0; i < kCount; ++i)
                t.values[static_cast<size_t>(j) * kCount + i] = static_cast<float>(slut_airlight_rational_node(
                    static_cast<double>(i) / (kCount - 1), static_cast<double>(j) / (kCount - 1), 1.0));
        return scatterlut::AirlightRationalTable(t);
    }();
    return table;
}

// The table's interpolation error: max over random unit coordinates (the planner's measure).
double table_error() {
    static const double e = scatterlut::measure_airlight_rational_sampling(rational_table(), 20000, 7).max_rel;
    return e;
}

enum Mode { kRadiance = 1, kPoints = 2 };

struct TierQuery {
    Query q;          // gpu[0] the mode, then the inputs (airlight_gpu_test's layout)
    double exact = 0; // airlight_radiance_exact on the float inputs
    double cpp = 0;   // AirlightRationalTable::radiance on them
    double optical_distance = 0;
};

scatterlut::AirlightQuery points_query(const Query &q) {
    const double v[3] = {q.gpu[1], q.gpu[2], q.gpu[3]}, d[3] = {q.gpu[4], q.gpu[5], q.gpu[6]},
                 l[3] = {q.gpu[7], q.gpu[8], q.gpu[9]};
    return scatterlut::airlight_query_from_points(v, d, l, q.gpu[10], q.gpu[11], q.gpu[12], q.gpu[13]);
}

std::vector<TierQuery> make_queries() {
    std::mt19937_64 rng(20261204);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<TierQuery> out;
    auto add = [&](const Query &q) {
        TierQuery t;
        t.q = q;
        const scatterlut::AirlightQuery cq = q.gpu[0] == kRadiance ? cpp_query(&q.gpu[1]) : points_query(q);
        t.exact = scatterlut::airlight_radiance_exact(cq);
        t.cpp = rational_table().radiance(cq);
        t.optical_distance = (cq.sigma_s_per_m + cq.sigma_a_per_m) * cq.distance_m;
        out.push_back(t);
    };
    for (int i = 0; i < 3000; ++i) add(random_radiance_query(rng)); // random_geometry's: every regime
    // Degenerate inputs: zero radiance, γ = 0 short of and through the light, γ = π
    // (airlight_gpu_test), s → 0, σ → 0, u far beyond any table, grazing far ends (sin γ and
    // cos γ a consistent pair wherever the radiance is not 0: the snippet takes both as given,
    // the C++ query takes γ = atan2 of them).
    std::vector<std::array<float, 7>> degenerate = degenerate_radiance_inputs();
    const float inf = std::numeric_limits<float>::infinity();
    for (const std::array<float, 7> &d : std::vector<std::array<float, 7>>{
             {0.1f, 0.1f, 1.0f, 2.0f, 0.6f, 0.8f, 1e-6f},    {0.1f, 0.1f, 1.0f, 2.0f, 1e-4f, -1.0f, 1e-5f},
             {1e-12f, 0.0f, 1.0f, 2.0f, 0.6f, 0.8f, 3.0f},   {1e-12f, 1e-12f, 1.0f, 5.0f, 0.6f, -0.8f, inf},
             {40.0f, 2.0f, 1e15f, 2.0f, 1.0f, 0.0f, 5.0f},   {0.1f, 0.0f, 1.0f, 2.0f, 0.0f, 1.0f, 1.999f},
             {0.1f, 0.01f, 1.0f, 2.0f, 1e-7f, 1.0f, 2.5f},   {0.1f, 0.01f, 1.0f, 2.0f, 1e-7f, -1.0f, 1e4f},
             {0.5f, 0.01f, 1.0f, 2.0f, 0.999f, 0.0447f, 1e5f}})
        degenerate.push_back(d);
    for (const auto &d : degenerate) {
        Query q;
        q.gpu[0] = kRadiance;
        std::copy(d.begin(), d.end(), q.gpu.begin() + 1);
        add(q);
    }
    for (int i = 0; i < 600; ++i) { // from points (as test_shaders.cpp: γ away from 0 and π, collinear rays)
        const double D = log_uniform(rng, 0.01, 100.0), tau = log_uniform(rng, 1e-4, 13.8);
        const double sigma_t = tau / D, albedo = 0.05 + 0.95 * unit(rng), r = unit(rng);
        const double gamma = r < 0.05 ? 0.0 : r < 0.1 ? kPi : 0.1 + (kPi - 0.2) * unit(rng);
        Query q;
        q.gpu[0] = kPoints;
        random_points(rng, D, gamma, r < 0.1, &q);
        q.gpu[10] = static_cast<float>(unit(rng) < 0.15 ? std::numeric_limits<double>::infinity()
                                                        : D * log_uniform(rng, 1e-5, 100.0));
        q.gpu[11] = static_cast<float>(albedo * sigma_t);
        q.gpu[12] = static_cast<float>((1.0 - albedo) * sigma_t);
        q.gpu[13] = static_cast<float>(log_uniform(rng, 1.0, 1e4));
        add(q);
    }
    return out;
}

const std::vector<TierQuery> &queries() {
    static const std::vector<TierQuery> q = make_queries();
    return q;
}

const char *kParams = "    int m_count; int t_count; int n_queries;";
const char *kTestBody = R"slsl(
float test_eval(int i) {
    SlutAirlightTable t = slut_airlight_table(m_count, t_count);
    int b = 16 * i;
    if (int(q[b]) == 1)
        return slut_airlight_radiance(SLUT_TEX_ARG(slut_test_table), t, q[b + 1], q[b + 2], q[b + 3], q[b + 4],
                                      q[b + 5], q[b + 6], q[b + 7]);
    return slut_airlight_radiance_points(SLUT_TEX_ARG(slut_test_table), t, SLUT_FLOAT3(q[b + 1], q[b + 2], q[b + 3]),
                                         SLUT_FLOAT3(q[b + 4], q[b + 5], q[b + 6]),
                                         SLUT_FLOAT3(q[b + 7], q[b + 8], q[b + 9]), q[b + 10], q[b + 11], q[b + 12],
                                         q[b + 13]);
}
)slsl";

const std::string &snippet(const char *extension) {
    static std::string text[3];
    const int k = std::string(extension) == "glsl" ? 0 : std::string(extension) == "hlsl" ? 1 : 2;
    if (text[k].empty()) text[k] = read_text(kShaderDir + "scatterlut_airlight." + extension);
    return text[k];
}

std::string define(const std::string &tier) { return "#define " + tier + "\n"; }

// Tolerances (relative):
//  - against the C++ tier (the same algorithm in double on the same float table and inputs):
//    1e-5 + 4e-7 σ_t D, as the airlight snippet's test (tests/shaders/test_shaders.cpp: the
//    float e^{−σ_t D} and arithmetic), plus, in the fast tier, the filter's weight error times
//    the largest cell jump of Ĥ, times 2G − 1 (the difference);
//  - against the exact radiance: that plus (2G − 1) times the table's interpolation error
//    (table_error) plus 1e-6 (the segment rule's truncation where it serves, G = 8:
//    (λ tan dv)^4/720 with λ tan dv ≤ 0.15).
constexpr double kTolFloat = 1e-5, kTolPerOpticalDistance = 4e-7, kTolSegmentRule = 1e-6;
const double kDifferenceGain = 2.0 * SLUT_AIRLIGHT_RATIONAL_GAIN - 1.0;

double max_cell_jump() {
    const scatterlut::Table &t = rational_table().table();
    double worst = 0;
    for (int j = 0; j + 1 < kCount; ++j)
        for (int i = 0; i + 1 < kCount; ++i) {
            const size_t k = static_cast<size_t>(j) * kCount + i;
            worst = std::max(worst, (std::fabs(t.values[k + 1] - t.values[k]) +
                                     std::fabs(t.values[k + kCount] - t.values[k])) / t.values[k]);
        }
    return worst;
}

// The uniform block of kParams (std140).
struct Params {
    int32_t m_count, t_count, n_queries, pad;
};
Params test_params() { return Params{kCount, kCount, static_cast<int32_t>(queries().size()), 0}; }

#if SLUT_HAVE_EGL
std::vector<float> run_tier(const std::string &source, std::string *error) {
    const scatterlut::Table &t = rational_table().table();
    const Params params = test_params();
    std::vector<Query> qs;
    for (const TierQuery &q : queries()) qs.push_back(q.q);
    return run_queries(source, t, qs, params, error);
}
#endif

// Both comparisons of one tier's results; filter_extra: the fast tier's filter term.
void expect_tier(const std::vector<float> &got, const std::string &run, double filter_extra, ::testing::Test *test) {
    ASSERT_EQ(got.size(), queries().size());
    const double table = kDifferenceGain * table_error();
    std::vector<double> cpp, exact;
    std::vector<size_t> all;
    for (size_t i = 0; i < queries().size(); ++i) {
        cpp.push_back(queries()[i].cpp);
        exact.push_back(queries()[i].exact);
        all.push_back(i);
    }
    const auto against_cpp = [&](size_t i) {
        return kTolFloat + kTolPerOpticalDistance * queries()[i].optical_distance + filter_extra;
    };
    const auto against_exact = [&](size_t i) { return against_cpp(i) + table + kTolSegmentRule; };
    for (int k = 0; k < 2; ++k) {
        const bool vs_exact = k == 1;
        const Stats st = vs_exact ? error_stats(got, exact, all, against_exact) : error_stats(got, cpp, all, against_cpp);
        const size_t w = st.worst_ratio;
        const double want = vs_exact ? exact[w] : cpp[w];
        std::printf("[ %s ] vs %-5s n=%zu  max %.3g  p99 %.3g  median %.3g  max error/tolerance %.2f "
                    "(table error %.3g x %.0f)\n",
                    run.c_str(), vs_exact ? "exact" : "C++", st.count, st.max, st.p99, st.median, st.max_ratio,
                    table_error(), kDifferenceGain);
        EXPECT_LE(st.max_ratio, 1.0) << run << (vs_exact ? " vs the exact radiance" : " vs the C++ tier") << ": query "
                                     << describe(queries()[w].q.gpu, 14) << " gave " << got[w] << ", want " << want
                                     << ": relative error " << rel_err(got[w], want) << " > tolerance "
                                     << (vs_exact ? against_exact(w) : against_cpp(w));
        test->RecordProperty(run + (vs_exact ? "_exact" : "_cpp") + "_max_rel_err", std::to_string(st.max));
        test->RecordProperty(run + (vs_exact ? "_exact" : "_cpp") + "_median_rel_err", std::to_string(st.median));
    }
    for (size_t i = 0; i < got.size(); ++i) {
        EXPECT_FALSE(std::isnan(got[i]) || got[i] < 0.0f) << run << ": " << got[i] << " at "
                                                           << describe(queries()[i].q.gpu, 14);
        EXPECT_EQ(std::isinf(got[i]), std::isinf(exact[i])) << run << ": " << got[i] << " against " << exact[i]
                                                             << " at " << describe(queries()[i].q.gpu, 14);
    }
}

} // namespace

// The queries cover both of the tiers' paths (the two ends' difference, the segment rule),
// finite and infinite rays and the degenerate results.
TEST(AirlightTierQueries, CoverBothPathsAndTheLimits) {
    int difference = 0, segment = 0, infinite_ray = 0, zero = 0, divergent = 0;
    for (const TierQuery &t : queries()) {
        if (t.q.gpu[0] != kRadiance) continue;
        const float *a = &t.q.gpu[1];
        const slut_airlight_rational_setup r = slut_airlight_rational_setup_of(a[0], a[1], a[2], a[3], a[4], a[5], a[6]);
        if (r.kind == 1) ++zero;
        if (r.kind == 2) ++divergent;
        if (r.kind != 0) continue;
        if (!(a[6] < 1e18f)) ++infinite_ray;
        const double h2 = rational_table().sample(r.x_m2, r.x_t2), h1 = rational_table().sample(r.x_m1, r.x_t1);
        (r.weight1 * h1 <= (1.0 - 1.0 / SLUT_AIRLIGHT_RATIONAL_GAIN) * r.weight2 * h2) ? ++difference : ++segment;
    }
    std::printf("difference %d, segment rule %d, infinite rays %d, zero %d, divergent %d\n", difference, segment,
                infinite_ray, zero, divergent);
    EXPECT_GE(difference, 1000);
    EXPECT_GE(segment, 100);
    EXPECT_GE(infinite_ray, 100);
    EXPECT_GE(zero, 3);
    EXPECT_GE(divergent, 2);
}

TEST(AirlightTierGlslang, EveryTierCompilesInEveryLanguage) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    for (const std::string tier : {"SLUT_TIER_FAST", "SLUT_TIER_ACCURATE"}) {
        const std::string glsl = glsl_compute_source(snippet("glsl"), kParams, kTestBody, define(tier));
        EXPECT_EQ(glslang("tier_" + tier + ".comp", glsl, ""), "");
        const std::string hlsl = hlsl_compute_source(snippet("hlsl"), kParams, kTestBody, define(tier));
        EXPECT_EQ(glslang("tier_" + tier + ".hlsl", hlsl,
                          "-D -V -e main -S comp -o " + gpu_harness::quoted(scratch_dir() + "/tier.spv")),
                  "");
        const std::string essl = "#version 300 es\n" + define(tier) + snippet("essl") +
                                 "uniform sampler2D hn;\nuniform ivec2 counts;\nuniform vec3 eye, light;\nin vec3 p;\n"
                                 "out vec4 colour;\nvoid main() {\n    float L = slut_airlight_radiance_points(hn, "
                                 "slut_airlight_table(counts.x, counts.y), eye, p - eye, light, length(p - eye), 0.04, "
                                 "0.01, 100.0);\n    colour = vec4(vec3(L), 1.0);\n}\n";
        EXPECT_EQ(glslang("tier_" + tier + "_es.frag", essl, ""), "");
    }
}

class GpuAirlightTiers : public gpu_harness::GpuTest {};

TEST_F(GpuAirlightTiers, AccurateMatchesTheCppTierAndTheExactRadiance) {
#if SLUT_HAVE_EGL
    std::string error;
    const std::vector<float> got =
        run_tier(glsl_compute_source(snippet("glsl"), kParams, kTestBody, define("SLUT_TIER_ACCURATE")), &error);
    ASSERT_EQ(error, "");
    expect_tier(got, "accurate", 0.0, this);
#endif
}

// The fast tier samples with the hardware filter: its weights (llvmpipe: float; many GPUs: 8
// bits, measured by hardware_filter_weight_error) move a sample by the weight error times the
// largest relative jump of Ĥ across a cell, which the difference amplifies by up to 2G − 1.
TEST_F(GpuAirlightTiers, FastMatchesTheCppTierAndTheExactRadiance) {
#if SLUT_HAVE_EGL
    const double weight_error = hardware_filter_weight_error();
    ASSERT_GE(weight_error, 0.0) << "the ramp shader failed";
    const double extra = kDifferenceGain * weight_error * max_cell_jump();
    std::printf("[ filter ] weight error %.3g, largest cell jump %.3g: extra tolerance %.3g\n", weight_error,
                max_cell_jump(), extra);
    std::string error;
    const std::vector<float> got =
        run_tier(glsl_compute_source(snippet("glsl"), kParams, kTestBody, define("SLUT_TIER_FAST")), &error);
    ASSERT_EQ(error, "");
    expect_tier(got, "fast", extra, this);
#endif
}

TEST_F(GpuAirlightTiers, HlslTiersMatchTheCppTier) {
#if SLUT_HAVE_EGL
    if (kGlslang.empty() || kSpirvCross.empty())
        SLUT_SKIP_OR_FAIL("running the HLSL needs glslangValidator and spirv-cross (Debian: glslang-tools, spirv-cross)");
    const double extra = kDifferenceGain * std::max(hardware_filter_weight_error(), 0.0) * max_cell_jump();
    for (const std::string tier : {"SLUT_TIER_FAST", "SLUT_TIER_ACCURATE"}) {
        std::string error;
        const std::string glsl = hlsl_compute_to_glsl(
            "tier_" + tier, hlsl_compute_source(snippet("hlsl"), kParams, kTestBody, define(tier)), &error);
        ASSERT_EQ(error, "");
        const std::vector<float> got = run_tier(glsl, &error);
        ASSERT_EQ(error, "");
        expect_tier(got, tier == "SLUT_TIER_FAST" ? "hlsl_fast" : "hlsl_accurate",
                    tier == "SLUT_TIER_FAST" ? extra : 0.0, this);
    }
#endif
}

// ------------------------------------------------------------------ the WebGPU test's cases
// (tests/shaders/wgsl_cases.hpp; ctest WebGPUSnippets runs the WGSL snippets on them): both tiers
// on every query above, once against the C++ tier and once against the exact radiance, at the
// tolerances above (the fast tier's filter term linear in the weight error the test measures).
namespace {

std::vector<wgsl_cases::CaseSet> write_wgsl_cases() {
    std::vector<wgsl_cases::CaseSet> sets;
    const double table = kDifferenceGain * table_error(), per_weight_error = kDifferenceGain * max_cell_jump();
    for (bool vs_exact : {false, true}) {
        wgsl_cases::CaseSet c;
        c.name = vs_exact ? "airlight tiers vs the exact radiance" : "airlight tiers vs the C++ tier";
        c.snippet = "airlight";
        const scatterlut::Table &t = rational_table().table();
        c.width = t.axes[0].map.count;
        c.height = t.axes[1].map.count;
        c.texels.assign(t.values.begin(), t.values.end());
        c.params_decl = kParams;
        c.params = wgsl_cases::bytes_of(test_params());
        c.body = kTestBody;
        c.query_floats = kQueryFloats;
        wgsl_cases::Tier accurate, fast;
        accurate.name = "accurate";
        fast.name = "fast";
        for (const TierQuery &q : queries()) {
            c.queries.insert(c.queries.end(), q.q.gpu.begin(), q.q.gpu.end());
            c.labels.push_back(q.q.gpu[0] == kRadiance ? "radiance" : "points");
            c.reference.push_back(vs_exact ? q.exact : q.cpp);
            const double tol = kTolFloat + kTolPerOpticalDistance * q.optical_distance +
                               (vs_exact ? table + kTolSegmentRule : 0.0);
            accurate.tol.push_back(tol);
            fast.tol.push_back(tol);
            fast.tol_per_weight_error.push_back(per_weight_error);
        }
        c.tiers = {accurate, fast};
        sets.push_back(c);
    }
    return sets;
}

} // namespace

SLUT_WGSL_CASES(write_wgsl_cases);
