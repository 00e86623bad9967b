// The anisotropic (Henyey-Greenstein) airlight GPU sampling snippets
// (scatterlut_airlight_hg.{glsl,hlsl,essl}, generated at build time from
// tables/shaders/src/airlight_hg.slsl and kernels/slut_airlight_hg.h, slut_phase.h compiled
// whole in float; docs/SHADERS.md) against the truths they must reproduce, at
// g in {-0.5, 0.85, 0.95, 0.99}, on the tables the generator lays out (its peak-warped w axis
// for g > 0):
//   - the table radiance, its RGB entry point and G~_g: the C++ runtime sampler
//     (scatterlut::AirlightHgTable, tables/src/airlight_hg.cpp) on the same table;
//   - the snippet's exact radiance (slut_airlight_hg_exact, no table): the double-precision
//     exact radiance (scatterlut::airlight_radiance_exact with phase_g, anisotropic.hpp);
//   - the thin-medium and distant-light closed forms with the phase (no table, every g):
//     scatterlut::airlight_hg_radiance_thin / _distant;
// both fed the same float-rounded inputs, with the float tolerances of the isotropic snippet's
// test (tests/shaders/test_shaders.cpp); G~_g also just beyond u_max at the forward peak, where
// Watson's series alone fails (docs/SHADERS.md). Also: the files share one body and are ASCII,
// glslang compiles GLSL (OpenGL, Vulkan, ES 3.00) and HLSL, and the queries exercise every
// regime and branch. A missing tool or EGL display skips, unless SCATTERLUT_REQUIRE_SHADER_TESTS.
//
// The queries and their tables: airlight_hg_gpu_queries.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/anisotropic.hpp"
#include "scatterlut/table.hpp"

extern "C" {
#include "slut_airlight_hg.h"
#include "slut_axes.h"
}

#include "airlight_gpu_test.hpp"
#include "wgsl_cases.hpp"

#include "airlight_hg_gpu_queries.hpp"

namespace {

using namespace airlight_gpu_test;

const std::string &snippet(const std::string &lang) {
    static std::map<std::string, std::string> texts;
    auto it = texts.find(lang);
    if (it == texts.end()) it = texts.emplace(lang, read_text(kShaderDir + "scatterlut_airlight_hg." + lang)).first;
    return it->second;
}

using namespace airlight_hg_gpu_test;

// ------------------------------------------------------------------ shader wrappers

// What each invocation of the compute shader evaluates (airlight_gpu_test's wrapper), once for
// both languages; the parameters (std140): u_max, u_scale, u_count, w_min, w_count, n_queries,
// phase_g, and the w axis's warp scale and id as the file records them.
const char *kParams = "    float u_max; float u_scale; int u_count; float w_min; int w_count; int n_queries; "
                      "float phase_g;\n    float w_scale; int w_warp;";
const char *kTestBody = R"slsl(
float test_eval(int i) {
    SlutAirlightHgTable t = slut_airlight_hg_table(
        slut_axis_make(0.0, u_max, u_scale, SLUT_WARP_LOG1P, u_count),
        slut_axis_make(w_min, SLUT_PIO2_HI, w_scale, w_warp, w_count), phase_g);
    int b = 16 * i;
    int mode = int(q[b]);
    if (mode == 0) return slut_airlight_hg_scaled_tail(SLUT_TEX_ARG(slut_test_table), t, q[b + 1], q[b + 2]);
    if (mode == 1)
        return slut_airlight_hg_radiance(SLUT_TEX_ARG(slut_test_table), t, q[b + 1], q[b + 2], q[b + 3], q[b + 4],
                                         q[b + 5], q[b + 6], q[b + 7]);
    if (mode == 2)
        return slut_airlight_hg_exact(q[b + 1], q[b + 2], q[b + 3], q[b + 4], q[b + 5], q[b + 6], q[b + 7], phase_g);
    if (mode == 3) {
        SLUT_FLOAT3 L = slut_airlight_hg_radiance_rgb(SLUT_TEX_ARG(slut_test_table), t,
                                                      SLUT_FLOAT3(q[b + 1], q[b + 2], q[b + 3]),
                                                      SLUT_FLOAT3(q[b + 4], q[b + 5], q[b + 6]), q[b + 7], q[b + 8],
                                                      q[b + 9], q[b + 10], q[b + 11]);
        int c = int(q[b + 12]);
        return c == 0 ? L.x : (c == 1 ? L.y : L.z);
    }
    if (mode == 5)
        return slut_airlight_hg_radiance_thin(q[b + 1], q[b + 2], q[b + 3], q[b + 4], q[b + 5], q[b + 6], q[b + 7],
                                              phase_g);
    if (mode == 6)
        return slut_airlight_hg_radiance_distant(q[b + 1], q[b + 2], q[b + 3], q[b + 4], q[b + 5], q[b + 6],
                                                 q[b + 7], phase_g);
    return slut_airlight_hg_radiance_points(SLUT_TEX_ARG(slut_test_table), t,
                                            SLUT_FLOAT3(q[b + 1], q[b + 2], q[b + 3]),
                                            SLUT_FLOAT3(q[b + 4], q[b + 5], q[b + 6]),
                                            SLUT_FLOAT3(q[b + 7], q[b + 8], q[b + 9]), q[b + 10], q[b + 11],
                                            q[b + 12], q[b + 13]);
}
)slsl";

std::string filter_define(bool hardware_filter) {
    return hardware_filter ? "#define SLUT_AIRLIGHT_HARDWARE_FILTER\n" : "";
}
std::string glsl_compute_source(bool hardware_filter) {
    return airlight_gpu_test::glsl_compute_source(snippet("glsl"), kParams, kTestBody, filter_define(hardware_filter));
}
std::string hlsl_compute_source(bool hardware_filter) {
    return airlight_gpu_test::hlsl_compute_source(snippet("hlsl"), kParams, kTestBody, filter_define(hardware_filter));
}

// Fragment / pixel shaders as an engine would write them, RGB fog (compile checks only).
std::string glsl_fragment_source(const std::string &version, const std::string &lang) {
    std::string s = "#version " + version + "\n";
    s += snippet(lang); // first: the ES prelude declares the precisions the declarations below need
    s += "uniform sampler2D airlight_hg_table;\nuniform vec4 table_meta; // u_max, u_scale, w_min, phase_g\n"
         "uniform ivec2 table_counts;\nuniform vec3 light_pos;\nuniform vec3 sigma_s;\nuniform vec3 sigma_a;\n"
         "uniform float intensity;\nin vec3 world_pos;\nin vec3 eye_pos;\nout vec4 colour;\n";
    s += R"glsl(
void main() {
    SlutAirlightHgTable t = slut_airlight_hg_table_default(table_meta.x, table_meta.y, table_counts.x,
                                                           table_meta.z, table_counts.y, table_meta.w);
    vec3 L = slut_airlight_hg_radiance_points_rgb(airlight_hg_table, t, eye_pos, world_pos - eye_pos,
                                                  light_pos, length(world_pos - eye_pos), sigma_s, sigma_a,
                                                  intensity);
    colour = vec4(L, 1.0);
}
)glsl";
    return s;
}

std::string hlsl_pixel_source() {
    std::string s = "Texture2D<float> airlight_hg_table : register(t0);\nSamplerState airlight_hg_table_sampler : "
                    "register(s0);\ncbuffer Fog : register(b0) { float4 table_meta; int2 table_counts; float3 "
                    "light_pos; float3 sigma_s; float3 sigma_a; float intensity; };\n";
    s += snippet("hlsl");
    s += R"hlsl(
float4 main(float3 world_pos : TEXCOORD0, float3 eye_pos : TEXCOORD1) : SV_Target {
    SlutAirlightHgTable t = slut_airlight_hg_table_default(table_meta.x, table_meta.y, table_counts.x,
                                                           table_meta.z, table_counts.y, table_meta.w);
    float3 L = slut_airlight_hg_radiance_points_rgb(airlight_hg_table, airlight_hg_table_sampler, t, eye_pos,
                                                    world_pos - eye_pos, light_pos, length(world_pos - eye_pos),
                                                    sigma_s, sigma_a, intensity);
    return float4(L, 1.0);
}
)hlsl";
    return s;
}

// ---------------------------------------------------------------------- comparisons

// The isotropic snippet's tolerances (tests/shaders/test_shaders.cpp, where they are derived):
// Gs 1e-5; radiance 1e-5 + 4e-7 * sigma_t D (float's exp(-sigma_t D)). Their Gs part holds the
// float texel position x*(n - 1), ~1e-5 texel of rounding, times |d ln Gs| per cell, which is
// <= 0.28 on the isotropic table; the forward peak of g = 0.95 (width (1 - g)/(1 + g) = 0.026
// in tan v) makes ln Gs_g change by up to ~4 across one w cell of this table, so that term is
// added here per query: kTexelRounding times the cell's jump (twice for the radiance, a
// difference of two samples).
constexpr double kTolGs = 1e-5, kTolRadiance = 1e-5, kTolPerOpticalDistance = 4e-7;
constexpr double kTexelRounding = 1e-5;
// The closed forms with the phase (no table: cell_jump 0) take the radiance's tolerance: the
// distant form's float error is its e^{-sigma_t D} (formed in logarithms: ~ulp(sigma_t D)), the
// thin form has no exponential (optical_distance 0: 1e-5 alone). Its largest error is the
// float rounding of phase_g itself near the forward peak, d ln psi/dg = 1/(1 + g) + 2/(1 - g)
// = 200 at g = 0.99 times |float(0.99) - 0.99| = 9.5e-9: 1.9e-6 (measured 2.05e-6, at gamma = 0).

// The uniform block of kParams (std140) for the table of g.
struct Params {
    float u_max, u_scale;
    int32_t u_count;
    float w_min;
    int32_t w_count, n_queries;
    float phase_g, w_scale;
    int32_t w_warp, pad[3];
};
Params test_params(double g) {
    const slut_axis &w = table_for(g).table().axes[1].map;
    return Params{static_cast<float>(kUMax), static_cast<float>(kUScale), kCountU, static_cast<float>(kWMin),
                  kCountW, static_cast<int32_t>(queries(g).size()), static_cast<float>(g), static_cast<float>(w.scale),
                  w.warp, {0, 0, 0}};
}

#if SLUT_HAVE_EGL
std::vector<float> run_on_gpu(const std::string &source, double g, std::string *error) {
    return run_queries(source, table_for(g).table(), queries(g), test_params(g), error);
}
#endif

// A query's tolerance (its label's, above); filter_weight_error: the fast tier's (SLUT_TIER_FAST:
// the hardware filter), which moves the filtered ln G~_g by that error times the cell's jump
// (twice that on the radiance: two samples).
double tolerance_of(const Query &q, double filter_weight_error = 0.0) {
    return q.label == "Gs" ? kTolGs + (kTexelRounding + filter_weight_error) * q.cell_jump + q.own_tolerance
                           : kTolRadiance + kTolPerOpticalDistance * q.optical_distance +
                                 2.0 * (kTexelRounding + filter_weight_error) * q.cell_jump;
}

void expect_agreement(const std::vector<float> &got, double g, const std::string &run, ::testing::Test *test,
                      double filter_weight_error = 0.0) {
    const std::vector<Query> &qs = queries(g);
    ASSERT_EQ(got.size(), qs.size());
    std::vector<double> reference;
    for (const Query &q : qs) reference.push_back(q.reference);
    for (const std::string label : {"Gs", "radiance", "exact", "rgb", "points", "thin", "distant"}) {
        std::vector<size_t> indices;
        for (size_t i = 0; i < qs.size(); ++i)
            if (qs[i].label == label) indices.push_back(i);
        if (indices.empty()) continue; // kPeakOnlyG: G~_g only
        const auto tolerance = [&](size_t i) { return tolerance_of(qs[i], filter_weight_error); };
        const Stats st = error_stats(got, reference, indices, tolerance);
        double jump = 0;
        for (size_t i : indices) jump = std::max(jump, qs[i].cell_jump);
        std::printf("[ %s g=%g ] %-8s n=%zu  max %.3g  p99 %.3g  median %.3g  max cell jump %.3g  (worst: %s -> gpu "
                    "%.9g, C++ %.9g)\n",
                    run.c_str(), g, label.c_str(), st.count, st.max, st.p99, st.median, jump,
                    describe(qs[st.worst].gpu).c_str(), static_cast<double>(got[st.worst]), qs[st.worst].reference);
        const Query &w = qs[st.worst_ratio];
        EXPECT_LE(st.max_ratio, 1.0) << run << " g=" << g << " " << label << ": query " << describe(w.gpu) << " gave "
                                     << got[st.worst_ratio] << ", C++ " << w.reference << ": relative error "
                                     << rel_err(got[st.worst_ratio], w.reference) << " > tolerance "
                                     << tolerance(st.worst_ratio);
        char name[64];
        std::snprintf(name, sizeof name, "%s_g%g_%s_max_rel_err", run.c_str(), g, label.c_str());
        test->RecordProperty(name, std::to_string(st.max));
    }
    size_t bad = 0, first_bad = 0;
    for (size_t k = 0; k < got.size(); ++k)
        if (std::isnan(got[k]) || got[k] < 0.0f) first_bad = (bad++ == 0) ? k : first_bad;
    EXPECT_EQ(bad, 0u) << run << " g=" << g << ": NaN or negative results, the first: query "
                       << (bad ? describe(qs[first_bad].gpu) : std::string()) << " gave " << (bad ? got[first_bad] : 0.0f);
}

} // namespace

// ------------------------------------------------------------------------- sources

TEST(ShaderAirlightHgSources, AllLanguagesShareOneBodyAndAreAscii) {
    const std::string g = shared_body(snippet("glsl"));
    ASSERT_FALSE(g.empty()) << "SHARED BODY markers missing in scatterlut_airlight_hg.glsl";
    for (const std::string lang : {"hlsl", "essl"}) {
        EXPECT_EQ(shared_body(snippet(lang)), g) << "the " << lang << " body differs from the GLSL one";
    }
    // The shared part (prelude, float math, kernels/) is the isotropic snippet's, so that both
    // can go into one shader.
    const std::string common_begin = "#ifndef SLUT_SHADER_COMMON", common_end = "#endif // SLUT_SHADER_COMMON";
    const std::string iso = read_text(kShaderDir + "scatterlut_airlight.glsl");
    const std::string &hg = snippet("glsl");
    const auto common = [&](const std::string &t) {
        const size_t b = t.find(common_begin), e = t.find(common_end);
        return (b == std::string::npos || e == std::string::npos) ? std::string() : t.substr(b, e - b);
    };
    EXPECT_FALSE(common(hg).empty());
    EXPECT_EQ(common(hg), common(iso));
    for (const std::string lang : {"glsl", "hlsl", "essl"}) {
        const std::string &text = snippet(lang);
        const auto it = std::find_if(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) > 127; });
        EXPECT_EQ(it, text.end()) << lang << ": non-ASCII byte at offset " << (it - text.begin());
    }
}

// The queries exercise every regime of Gs_g and every branch of the radiance (at least 20
// times each, per g): the table, large u and small w at both ends, the two-sample bracket and
// its fallback to the segment's integral, infinite rays, zero and divergent limits, clear channels.
TEST(ShaderAirlightHgQueries, CoverEveryRegimeAndBranch) {
    for (double g : kPhaseGs) {
        SCOPED_TRACE("g = " + std::to_string(g));
        const scatterlut::AirlightHgTable &table = table_for(g);
        const auto regime = [&](double u, double w) { return w < table.w_min() ? 2 : (u > table.u_max() ? 1 : 0); };
        int gs[3] = {0, 0, 0}, viewer[3] = {0, 0, 0}, far[3] = {0, 0, 0};
        int two_samples = 0, fallback = 0, infinite = 0, zero = 0, divergent = 0, clear = 0;
        for (const Query &q : queries(g)) {
            if (q.label == "Gs") ++gs[regime(q.gpu[1], q.gpu[2])];
            if (q.label == "rgb" && q.gpu[1 + static_cast<int>(q.gpu[12])] == 0.0f) ++clear;
            if (q.label != "radiance") continue;
            if (std::isinf(q.reference)) ++divergent;
            if (q.reference == 0.0) ++zero;
            const double sigma_t = static_cast<double>(q.gpu[1]) + q.gpu[2];
            const double gamma = std::atan2(static_cast<double>(q.gpu[5]), static_cast<double>(q.gpu[6]));
            const double s_over_D = std::isinf(q.gpu[7]) ? HUGE_VAL : q.gpu[7] / static_cast<double>(q.gpu[4]);
            const slut_hg_airlight_ends e =
                slut_hg_airlight_setup_ends(sigma_t * q.gpu[4], std::sin(gamma), std::cos(gamma), s_over_D);
            if (!(q.gpu[1] > 0.0f) || !(q.gpu[3] > 0.0f) || !(q.gpu[7] > 0.0f)) continue;
            infinite += std::isinf(q.gpu[7]);
            if (e.samples == 0) {
                ++fallback;
                continue;
            }
            ++viewer[regime(e.u, e.w2)];
            const double a = e.w2 * table.scaled_tail(e.u, e.w2);
            double b = 0.0;
            if (e.w1 > 0.0) {
                ++far[regime(e.u, e.w1)];
                b = e.far_attenuation * e.w1 * table.scaled_tail(e.u, e.w1);
            }
            (b <= 0.5 * a && a > 0.0) ? ++two_samples : ++fallback;
        }
        std::printf("g=%g  Gs: table/large-u/small-w %d/%d/%d | radiance: viewer end %d/%d/%d, far end %d/%d/%d, "
                    "two samples %d, segment integral %d, infinite %d, zero %d, divergent %d | rgb clear %d\n",
                    g, gs[0], gs[1], gs[2], viewer[0], viewer[1], viewer[2], far[0], far[1], far[2], two_samples,
                    fallback, infinite, zero, divergent, clear);
        for (int r = 0; r < 3; ++r) {
            EXPECT_GE(gs[r], 20) << "Gs regime " << r;
            EXPECT_GE(viewer[r], 20) << "viewer-end regime " << r;
            EXPECT_GE(far[r], 20) << "far-end regime " << r;
        }
        EXPECT_GE(two_samples, 20);
        EXPECT_GE(fallback, 20);
        EXPECT_GE(infinite, 20);
        EXPECT_GE(zero, 3);
        EXPECT_GE(divergent, 20);
        EXPECT_GE(clear, 20);
    }
}

// ------------------------------------------------------------------------- glslang

TEST(ShaderAirlightHgGlslang, GlslEsslAndHlslCompile) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    expect_compute_shaders_compile("hg", [](bool hw) { return glsl_compute_source(hw); },
                                   [](bool hw) { return hlsl_compute_source(hw); });
    expect_engine_shaders_compile("hg", glsl_fragment_source("330", "glsl"), glsl_fragment_source("300 es", "essl"),
                                  hlsl_pixel_source());
}

// ----------------------------------------------------------------------------- GPU

class GpuAirlightHg : public GpuTest {};

TEST_F(GpuAirlightHg, GlslMatchesTheCppSamplerAndTheExactRadiance) {
#if SLUT_HAVE_EGL
    for (double g : all_phase_gs()) {
        std::string error;
        const std::vector<float> got = run_on_gpu(glsl_compute_source(false), g, &error);
        ASSERT_EQ(error, "");
        expect_agreement(got, g, "glsl", this);
    }
#endif
}

// The fast tier (SLUT_TIER_FAST: one hardware-filtered fetch per sample), at the filter's
// measured weight error on top of the tolerances above.
TEST_F(GpuAirlightHg, GlslFastTierMatchesTheCppSampler) {
#if SLUT_HAVE_EGL
    const double weight_error = hardware_filter_weight_error();
    ASSERT_GE(weight_error, 0.0) << "the ramp shader failed";
    for (double g : all_phase_gs()) {
        std::string error;
        const std::vector<float> got = run_on_gpu(
            airlight_gpu_test::glsl_compute_source(snippet("glsl"), kParams, kTestBody, "#define SLUT_TIER_FAST\n"), g,
            &error);
        ASSERT_EQ(error, "");
        expect_agreement(got, g, "glsl_fast", this, weight_error);
    }
#endif
}

TEST_F(GpuAirlightHg, HlslMatchesTheCppSamplerAndTheExactRadiance) {
#if SLUT_HAVE_EGL
    if (kGlslang.empty() || kSpirvCross.empty())
        SLUT_SKIP_OR_FAIL("running the HLSL needs glslangValidator and spirv-cross (Debian: glslang-tools, spirv-cross)");
    std::string error;
    const std::string glsl = hlsl_compute_to_glsl("hg_fetch", hlsl_compute_source(false), &error);
    ASSERT_EQ(error, "");
    for (double g : all_phase_gs()) {
        const std::vector<float> got = run_on_gpu(glsl, g, &error);
        ASSERT_EQ(error, "");
        expect_agreement(got, g, "hlsl", this);
    }
#endif
}

// ------------------------------------------------------------------ the WebGPU test's cases
// (tests/shaders/wgsl_cases.hpp; ctest WebGPUSnippets runs the WGSL snippets on them): per g every
// query above, no tier and the accurate tier at the tolerances above, the fast tier with the
// filter's weight error as GlslFastTierMatchesTheCppSampler takes it (tolerance_of).
namespace {

std::vector<wgsl_cases::CaseSet> write_wgsl_cases() {
    std::vector<wgsl_cases::CaseSet> sets;
    for (double g : all_phase_gs()) {
        const scatterlut::Table &t = table_for(g).table();
        const std::vector<Query> &qs = queries(g);
        wgsl_cases::CaseSet c;
        char name[48];
        std::snprintf(name, sizeof name, "airlight_hg g=%g", g);
        c.name = name;
        c.snippet = "airlight_hg";
        c.width = t.axes[0].map.count;
        c.height = t.axes[1].map.count;
        c.texels.assign(t.values.begin(), t.values.end());
        c.params_decl = kParams;
        c.params = wgsl_cases::bytes_of(test_params(g));
        c.body = kTestBody;
        c.query_floats = kQueryFloats;
        wgsl_cases::Tier none, accurate, fast;
        accurate.name = "accurate";
        fast.name = "fast";
        for (const Query &q : qs) {
            c.queries.insert(c.queries.end(), q.gpu.begin(), q.gpu.end());
            c.labels.push_back(q.label);
            c.reference.push_back(q.reference);
            none.tol.push_back(tolerance_of(q));
            accurate.tol.push_back(tolerance_of(q));
            fast.tol.push_back(tolerance_of(q));
            fast.tol_per_weight_error.push_back(tolerance_of(q, 1.0) - tolerance_of(q));
        }
        c.tiers = {none, accurate, fast};
        sets.push_back(c);
    }
    return sets;
}

} // namespace

SLUT_WGSL_CASES(write_wgsl_cases);
