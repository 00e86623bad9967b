// The airlight GPU sampling snippets (scatterlut_airlight.{glsl,hlsl}, generated at build
// time from tables/shaders/src and the SLUT_SHADER regions of kernels/; docs/SHADERS.md)
// against the truth they must reproduce: the C++ runtime sampler (scatterlut::AirlightTable,
// tables/src/airlight.cpp, itself tested against Boost.Math in runtime/test_airlight_table.cpp) on the
// same table. The snippets run in single precision; these tests are what keeps them
// from drifting:
//   - ShaderSources: the GLSL and HLSL files agree outside their preludes, are ASCII, and their
//     constants (warp ids, regimes, Gauss-Legendre rule) equal kernels/slut_*.h;
//   - ShaderGlslang: both compile with glslang (GLSL for OpenGL and Vulkan, compute and
//     fragment; HLSL compute and pixel), with and without the hardware-filter option;
//   - GpuShaders: the GLSL runs for real (surfaceless EGL, OpenGL 4.3 core, Mesa llvmpipe
//     where there is no GPU) on a 128x64 table uploaded as R32F, and the HLSL too where
//     spirv-cross is installed (HLSL -> SPIR-V by glslang -> GLSL 4.30 by spirv-cross),
//     for ~5600 queries, compared with the double-precision C++ sampler fed the same
//     float-rounded inputs and float-rounded table;
//   - ShaderQueries: those queries exercise every regime and branch of the C++ code.
// Tools come from configure time (find_program); a missing tool or EGL display skips,
// unless SCATTERLUT_REQUIRE_SHADER_TESTS is set, which makes it a failure.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scatterlut/airlight.hpp"
#include "scatterlut/table.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_axes.h"
}

#include "airlight_gpu_test.hpp"
#include "wgsl_cases.hpp"

namespace {

using namespace airlight_gpu_test;

const std::string &glsl_snippet() {
    static const std::string text = read_text(kShaderDir + "scatterlut_airlight.glsl");
    return text;
}
const std::string &hlsl_snippet() {
    static const std::string text = read_text(kShaderDir + "scatterlut_airlight.hlsl");
    return text;
}



// ------------------------------------------------------------------------ the table

// The airlight table as docs/AIRLIGHT.md defines it, laid out by the generator (u LOG1P scale
// 1e-7 on [0, 64], w ASINH_COT on [1e-3, pi/2], channel ln_Gs; airlight_gpu_test.hpp).
const scatterlut::AirlightTable &airlight_table() {
    static const scatterlut::AirlightTable table(airlight_test_table(0.0));
    return table;
}

// ---------------------------------------------------------------------- the queries

// One GPU query (airlight_gpu_test::Query, 16 floats). mode 0: Gs(u, w); 1: radiance(sigma_s,
// sigma_a, I0, D, sin gamma, cos gamma, s); 2: radiance from points (viewer, dir, light, s,
// sigma_s, sigma_a, I0).
enum Mode { kScaledTail = 0, kRadiance = 1, kPoints = 2 };

// A query's inputs for messages.
std::string describe_query(const std::array<float, kQueryFloats> &q) {
    return describe(q, q[0] == kScaledTail ? 3 : q[0] == kRadiance ? 8 : 14);
}

std::vector<Query> make_queries() {
    const scatterlut::AirlightTable &table = airlight_table();
    std::mt19937_64 rng(20240611);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Query> out;

    // Gs(u, w) in every regime: the table (points uniform in the warped coordinates),
    // u = 0, u around and beyond u_max (Watson), w below w_min (e^a E_n), w near pi/2.
    const slut_axis &au = table.table().axes[0].map;
    const slut_axis &aw = table.table().axes[1].map;
    for (int i = 0; i < 2000; ++i) {
        const auto [u, w] = random_scaled_tail_point(rng, au, aw);
        Query q;
        q.gpu[0] = kScaledTail;
        q.gpu[1] = static_cast<float>(u);
        q.gpu[2] = static_cast<float>(w);
        q.reference = table.scaled_tail(q.gpu[1], q.gpu[2]);
        q.label = "Gs";
        out.push_back(q);
    }

    // Radiance over the acceptance domain of docs/AIRLIGHT.md and beyond it
    // (airlight_gpu_test::random_geometry).
    for (int i = 0; i < 3000; ++i) {
        Query q = random_radiance_query(rng);
        q.reference = table.radiance(cpp_query(&q.gpu[1]));
        q.label = "radiance";
        out.push_back(q);
    }

    // Degenerate inputs (airlight_gpu_test::degenerate_radiance_inputs).
    for (const auto &d : degenerate_radiance_inputs()) {
        Query q;
        q.gpu[0] = kRadiance;
        std::copy(d.begin(), d.end(), q.gpu.begin() + 1);
        q.reference = table.radiance(cpp_query(d.data()));
        q.label = "radiance";
        out.push_back(q);
    }

    // Radiance from points (airlight_gpu_test::random_points): gamma in [0.1, pi - 0.1] (a float
    // cross product of nearly parallel vectors loses sin gamma's relative precision; that is the
    // caller's input, not the snippet's error) and a few exactly collinear rays both ways.
    for (int i = 0; i < 600; ++i) {
        const double D = log_uniform(rng, 0.01, 100.0);
        const double tau = log_uniform(rng, 1e-4, 13.8);
        const double sigma_t = tau / D, albedo = 0.05 + 0.95 * unit(rng);
        const double r = unit(rng);
        const bool collinear = r < 0.1;
        const double gamma = r < 0.05 ? 0.0 : r < 0.1 ? kPi : 0.1 + (kPi - 0.2) * unit(rng);
        const double s = unit(rng) < 0.15 ? std::numeric_limits<double>::infinity()
                                           : D * log_uniform(rng, 1e-5, 100.0);
        Query q;
        q.gpu[0] = kPoints;
        random_points(rng, D, gamma, collinear, &q);
        q.gpu[10] = static_cast<float>(s);
        q.gpu[11] = static_cast<float>(albedo * sigma_t);
        q.gpu[12] = static_cast<float>((1.0 - albedo) * sigma_t);
        q.gpu[13] = static_cast<float>(log_uniform(rng, 1.0, 1e4));
        const double v[3] = {q.gpu[1], q.gpu[2], q.gpu[3]}, d[3] = {q.gpu[4], q.gpu[5], q.gpu[6]},
                     l[3] = {q.gpu[7], q.gpu[8], q.gpu[9]};
        q.reference = table.radiance(
            scatterlut::airlight_query_from_points(v, d, l, q.gpu[10], q.gpu[11], q.gpu[12], q.gpu[13]));
        q.label = "points";
        out.push_back(q);
    }
    return out;
}

const std::vector<Query> &queries() {
    static const std::vector<Query> q = make_queries();
    return q;
}

// Which branches of the C++ radiance a radiance query takes (to prove the queries cover
// them all): the regime at each end, the theta-integral fallback, the limits.
struct Branches {
    bool zero = false, divergent = false, infinite_ray = false, fallback = false;
    int regime_viewer = -1, regime_far = -1;
};

Branches radiance_branches(const Query &q) {
    const scatterlut::AirlightTable &table = airlight_table();
    Branches b;
    const double gamma = std::atan2(static_cast<double>(q.gpu[5]), static_cast<double>(q.gpu[6]));
    const slut_airlight_geometry g =
        slut_airlight_setup(q.gpu[1], q.gpu[2], q.gpu[3], q.gpu[4], std::sin(gamma), std::cos(gamma), q.gpu[7]);
    b.zero = g.kind == 1;
    b.divergent = g.kind == 2;
    if (g.kind != 0) return b;
    b.infinite_ray = g.w1 == 0.0;
    b.regime_viewer = slut_gs_regime(g.u, g.w2, table.u_max(), table.w_min());
    const double gs2 = table.scaled_tail(g.u, g.w2, g.a2);
    double gs1 = 0.0;
    if (!b.infinite_ray) {
        b.regime_far = slut_gs_regime(g.u, g.w1, table.u_max(), table.w_min());
        gs1 = table.scaled_tail(g.u, g.w1, g.a1);
    }
    const double viewer_term = g.w2 / g.sin_gamma * gs2;
    const double far_term = b.infinite_ray ? 0.0 : g.far_attenuation * g.w1 / g.sin_gamma * gs1;
    b.fallback = far_term > 0.5 * viewer_term;
    return b;
}

// ------------------------------------------------------------------ shader wrappers

// What each invocation of the compute shader evaluates (airlight_gpu_test's wrapper), once for
// both languages; the parameters (std140): u_max, u_scale, u_count, w_min, w_count, n_queries.
const char *kParams = "    float u_max; float u_scale; int u_count; float w_min; int w_count; int n_queries;";
const char *kTestBody = R"slsl(
float test_eval(int i) {
    SlutAirlightTable t = slut_airlight_table(u_max, u_scale, u_count, w_min, w_count);
    int b = 16 * i;
    int mode = int(q[b]);
    if (mode == 0) return slut_airlight_scaled_tail_uw(SLUT_TEX_ARG(slut_test_table), t, q[b + 1], q[b + 2]);
    if (mode == 1)
        return slut_airlight_radiance(SLUT_TEX_ARG(slut_test_table), t, q[b + 1], q[b + 2], q[b + 3], q[b + 4],
                                      q[b + 5], q[b + 6], q[b + 7]);
    return slut_airlight_radiance_points(SLUT_TEX_ARG(slut_test_table), t, SLUT_FLOAT3(q[b + 1], q[b + 2], q[b + 3]),
                                         SLUT_FLOAT3(q[b + 4], q[b + 5], q[b + 6]),
                                         SLUT_FLOAT3(q[b + 7], q[b + 8], q[b + 9]), q[b + 10], q[b + 11], q[b + 12],
                                         q[b + 13]);
}
)slsl";

std::string filter_define(bool hardware_filter) {
    return hardware_filter ? "#define SLUT_AIRLIGHT_HARDWARE_FILTER\n" : "";
}
std::string glsl_compute_source(bool hardware_filter) {
    return airlight_gpu_test::glsl_compute_source(glsl_snippet(), kParams, kTestBody, filter_define(hardware_filter));
}
std::string hlsl_compute_source(bool hardware_filter) {
    return airlight_gpu_test::hlsl_compute_source(hlsl_snippet(), kParams, kTestBody, filter_define(hardware_filter));
}

// A fragment / pixel shader using the snippet as an engine would (compile checks only).
std::string glsl_fragment_source(bool hardware_filter) {
    std::string s = "#version 330\n";
    if (hardware_filter) s += "#define SLUT_AIRLIGHT_HARDWARE_FILTER\n";
    s += "uniform sampler2D airlight_table;\nuniform vec4 table_meta; // u_max, u_scale, w_min, -\n"
         "uniform ivec2 table_counts;\nuniform vec3 light_pos;\nuniform vec3 medium; // sigma_s, sigma_a, I0\n"
         "in vec3 world_pos;\nin vec3 eye_pos;\nout vec4 colour;\n";
    s += glsl_snippet();
    s += R"glsl(
void main() {
    SlutAirlightTable t = slut_airlight_table(table_meta.x, table_meta.y, table_counts.x,
                                              table_meta.z, table_counts.y);
    float L = slut_airlight_radiance_points(airlight_table, t, eye_pos, world_pos - eye_pos,
                                            light_pos, length(world_pos - eye_pos),
                                            medium.x, medium.y, medium.z);
    colour = vec4(vec3(L), 1.0);
}
)glsl";
    return s;
}

std::string hlsl_pixel_source(bool hardware_filter) {
    std::string s;
    if (hardware_filter) s += "#define SLUT_AIRLIGHT_HARDWARE_FILTER\n";
    s += "Texture2D<float> airlight_table : register(t0);\nSamplerState airlight_sampler : register(s0);\n"
         "cbuffer Fog : register(b0) { float4 table_meta; int2 table_counts; float3 light_pos; float3 medium; };\n";
    s += hlsl_snippet();
    s += R"hlsl(
float4 main(float3 world_pos : TEXCOORD0, float3 eye_pos : TEXCOORD1) : SV_Target {
    SlutAirlightTable t = slut_airlight_table(table_meta.x, table_meta.y, table_counts.x,
                                              table_meta.z, table_counts.y);
    float L = slut_airlight_radiance_points(airlight_table, airlight_sampler, t, eye_pos,
                                            world_pos - eye_pos, light_pos,
                                            length(world_pos - eye_pos), medium.x, medium.y,
                                            medium.z);
    return float4(L, L, L, 1.0);
}
)hlsl";
    return s;
}

// ---------------------------------------------------------------------- comparisons

// Tolerances (relative, against the double C++ sampler on the same float-rounded table
// and inputs; measured on Mesa llvmpipe, see docs/SHADERS.md):
//  - Gs, texelFetch path: 1e-5 (measured 3e-6). The shader's float arithmetic: the texel
//    position x*(n - 1) carries ~1e-5 texel of rounding (the log of a ~20-unit warp over
//    127 cells) times |d ln Gs| per cell (<= 0.28 here), exp of an ln Gs down to ~-15
//    (~1e-6), and the asymptotic forms' float series (~1e-6).
//  - radiance: 1e-5 + 4e-7 * sigma_t D (measured 6e-6 for sigma_t D <= 13.8, 1.1e-5 at
//    82). The same Gs errors, at most doubled by the difference of the two ends (the
//    theta-integral takes over beyond a factor 2) and the float theta-integral (~1e-6);
//    then e^{-sigma_t D}: its float argument is rounded twice (sigma_s + sigma_a, times
//    D: 1.2e-7 * sigma_t D) and GLSL allows exp (3 + 2|x|) ulp (up to 2.4e-7 * |x|).
//  - hardware filter: the bilinear weights are the GPU's. Many GPUs use 8-bit fixed
//    point (a weight error up to 1/512): the filtered ln Gs is then off by up to that
//    error times the largest jump of ln Gs across a cell. The test measures the weight
//    error on the running GPU (hardware_filter_weight_error) and adds error x jump to
//    the tolerances above: llvmpipe filters R32F with float weights, so there the
//    hardware path is as good as the texelFetch one.
constexpr double kTolGs = 1e-5, kTolRadiance = 1e-5, kTolPerOpticalDistance = 4e-7;


// Relative errors of one category of queries (see gpu_harness::error_stats).
template <class Tolerance>
Stats stats_for(const std::vector<float> &got, const std::string &label, const Tolerance &tolerance) {
    std::vector<double> reference;
    std::vector<size_t> indices;
    for (size_t i = 0; i < queries().size(); ++i) {
        reference.push_back(queries()[i].reference);
        if (queries()[i].label == label) indices.push_back(i);
    }
    return error_stats(got, reference, indices, [&](size_t i) { return tolerance(queries()[i]); });
}

// sigma_t D of a radiance or points query (float's exp(-sigma_t D) error grows with it).
double optical_distance(const Query &q) {
    if (q.gpu[0] == kRadiance) return (static_cast<double>(q.gpu[1]) + q.gpu[2]) * q.gpu[4];
    if (q.gpu[0] == kPoints) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k) d2 += (static_cast<double>(q.gpu[7 + k]) - q.gpu[1 + k]) * (static_cast<double>(q.gpu[7 + k]) - q.gpu[1 + k]);
        return (static_cast<double>(q.gpu[11]) + q.gpu[12]) * std::sqrt(d2);
    }
    return 0.0;
}

// ------------------------------------------------------------------------- EGL / GL

// The uniform block of kParams (std140).
struct Params {
    float u_max, u_scale;
    int32_t u_count;
    float w_min;
    int32_t w_count, n_queries, pad[2];
};
Params test_params() {
    return Params{static_cast<float>(kUMax), static_cast<float>(kUScale), kCountU, static_cast<float>(kWMin),
                  kCountW, static_cast<int32_t>(queries().size()), {0, 0}};
}

#if SLUT_HAVE_EGL

// Every query through a compute shader built from glsl/hlsl_compute_source (or its
// spirv-cross translation), on the test table.
std::vector<float> run_on_gpu(const std::string &source, std::string *error) {
    return run_queries(source, airlight_table().table(), queries(), test_params(), error);
}

// The largest change of the stored ln Gs across one cell (u and w steps added): a filter
// weight error e moves the interpolated ln Gs, i.e. Gs relatively, by at most e times this.
double max_cell_jump() {
    const scatterlut::Table &t = airlight_table().table();
    double worst = 0;
    for (int j = 0; j + 1 < kCountW; ++j)
        for (int i = 0; i + 1 < kCountU; ++i) {
            const size_t k = static_cast<size_t>(j) * kCountU + i;
            worst = std::max(worst, std::fabs(t.values[k + 1] - t.values[k]) + std::fabs(t.values[k + kCountU] - t.values[k]));
        }
    return worst;
}

#endif // SLUT_HAVE_EGL

// Checks one run against the C++ sampler: Gs within tol_gs; radiance within
// tol_radiance + kTolPerOpticalDistance * sigma_t D. Per category the worst, p99 and
// median relative errors are printed and recorded as test properties.
void expect_agreement(const std::vector<float> &got, const std::string &run, double tol_gs, double tol_radiance,
                      ::testing::Test *test) {
    for (const std::string label : {"Gs", "radiance", "points"}) {
        const auto tolerance = [&](const Query &q) {
            return label == "Gs" ? tol_gs : tol_radiance + kTolPerOpticalDistance * optical_distance(q);
        };
        const Stats st = stats_for(got, label, tolerance);
        const Query &worst = queries()[st.worst];
        std::printf("[ %s ] %-8s n=%zu  max %.3g  p99 %.3g  median %.3g  (worst: %s -> gpu %.9g, C++ %.9g)\n",
                    run.c_str(), label.c_str(), st.count, st.max, st.p99, st.median, describe_query(worst.gpu).c_str(),
                    static_cast<double>(got[st.worst]), worst.reference);
        const Query &w = queries()[st.worst_ratio];
        EXPECT_LE(st.max_ratio, 1.0) << run << " " << label << ": query " << describe_query(w.gpu) << " gave "
                                     << got[st.worst_ratio] << ", the C++ sampler " << w.reference
                                     << ": relative error " << rel_err(got[st.worst_ratio], w.reference)
                                     << " > tolerance " << tolerance(w);
        test->RecordProperty(run + "_" + label + "_max_rel_err", std::to_string(st.max));
        test->RecordProperty(run + "_" + label + "_median_rel_err", std::to_string(st.median));
    }
    // Never NaN, never negative.
    size_t bad = 0;
    for (float v : got) bad += (std::isnan(v) || v < 0.0f) ? 1 : 0;
    EXPECT_EQ(bad, 0u) << run << ": NaN or negative results";
}

} // namespace

// ------------------------------------------------------------------------- sources

// The two files share one body, so that what runs as GLSL below is also what the HLSL
// users compile; only the preludes (texture access, infinity, constant arrays) differ.
TEST(ShaderSources, GlslAndHlslShareOneBody) {
    const std::string g = shared_body(glsl_snippet()), h = shared_body(hlsl_snippet());
    ASSERT_FALSE(g.empty()) << "SHARED BODY markers missing in scatterlut_airlight.glsl";
    ASSERT_FALSE(h.empty()) << "SHARED BODY markers missing in scatterlut_airlight.hlsl";
    if (g != h) {
        size_t k = 0;
        while (k < g.size() && k < h.size() && g[k] == h[k]) ++k;
        const size_t line = static_cast<size_t>(std::count(g.begin(), g.begin() + static_cast<long>(k), '\n')) + 1;
        FAIL() << "the shared bodies differ from body line " << line << ":\n  glsl: "
               << g.substr(k, 80) << "\n  hlsl: " << h.substr(k, 80);
    }
}

// ASCII only: GLSL before 4.20 and some HLSL toolchains reject other bytes even in comments.
TEST(ShaderSources, AreAscii) {
    for (const std::string *text : {&glsl_snippet(), &hlsl_snippet()}) {
        const auto it = std::find_if(text->begin(), text->end(), [](char c) { return static_cast<unsigned char>(c) > 127; });
        EXPECT_EQ(it, text->end()) << "non-ASCII byte at offset " << (it - text->begin());
    }
}

// Warp ids and regimes as in kernels/slut_axes.h and slut_airlight.h (ids are stored in
// files), and the Gauss-Legendre rule as the C header's rounded to float.
TEST(ShaderSources, ConstantsMatchTheCHeaders) {
    const std::string body = shared_body(glsl_snippet());
    const std::vector<std::pair<std::string, int>> ids = {
        {"SLUT_WARP_LINEAR", SLUT_WARP_LINEAR}, {"SLUT_WARP_LOG", SLUT_WARP_LOG},
        {"SLUT_WARP_LOG1P", SLUT_WARP_LOG1P},   {"SLUT_WARP_ASINH_COT", SLUT_WARP_ASINH_COT},
        {"SLUT_WARP_SQRT1P", SLUT_WARP_SQRT1P}, {"SLUT_WARP_LOGLIN", SLUT_WARP_LOGLIN},
        {"SLUT_WARP_NL_QODDS", SLUT_WARP_NL_QODDS}, {"SLUT_GS_TABLE", SLUT_GS_TABLE},
        {"SLUT_GS_LARGE_U", SLUT_GS_LARGE_U},   {"SLUT_GS_SMALL_W", SLUT_GS_SMALL_W}};
    for (const auto &[name, value] : ids) {
        std::smatch m;
        const std::regex re("#define " + name + " (-?[0-9]+)\\s");
        ASSERT_TRUE(std::regex_search(body, m, re)) << name << " is not defined in the shared body";
        EXPECT_EQ(std::stoi(m[1]), value) << name;
    }
    for (const std::string *text : {&glsl_snippet(), &hlsl_snippet()}) {
        for (const char *array : {"slut_gl16_x", "slut_gl16_w"}) {
            const std::string head = "SLUT_CONST_ARRAY8(" + std::string(array) + ",";
            const size_t at = text->find(head);
            ASSERT_NE(at, std::string::npos) << array;
            const std::string list = text->substr(at + head.size(), 400);
            std::vector<double> values;
            const std::regex number("[0-9]+\\.[0-9]+");
            for (auto it = std::sregex_iterator(list.begin(), list.end(), number);
                 it != std::sregex_iterator() && values.size() < 8; ++it)
                values.push_back(std::stod(it->str()));
            ASSERT_EQ(values.size(), 8u) << array;
            for (int k = 0; k < 8; ++k) {
                const double want = std::string(array) == "slut_gl16_x" ? slut_gl16_x[k] : slut_gl16_w[k];
                EXPECT_EQ(static_cast<float>(values[k]), static_cast<float>(want)) << array << "[" << k << "]";
            }
        }
    }
}

// The comparison below is only as good as its queries: each regime of Gs and each
// branch of the radiance must be exercised (at least 20 times).
TEST(ShaderQueries, CoverEveryRegimeAndBranch) {
    const scatterlut::AirlightTable &table = airlight_table();
    int gs_regime[3] = {0, 0, 0}, viewer_regime[3] = {0, 0, 0}, far_regime[3] = {0, 0, 0};
    int zero = 0, divergent = 0, infinite_ray = 0, fallback = 0, u_zero = 0;
    for (const Query &q : queries()) {
        if (q.label == "Gs") {
            ++gs_regime[slut_gs_regime(q.gpu[1], q.gpu[2], table.u_max(), table.w_min())];
            u_zero += q.gpu[1] == 0.0f;
        } else if (q.label == "radiance") {
            const Branches b = radiance_branches(q);
            zero += b.zero;
            divergent += b.divergent;
            infinite_ray += b.infinite_ray;
            fallback += b.fallback;
            if (b.regime_viewer >= 0) ++viewer_regime[b.regime_viewer];
            if (b.regime_far >= 0) ++far_regime[b.regime_far];
        }
    }
    std::printf("Gs: table %d, large u %d, small w %d, u = 0 %d | radiance: viewer end table/large-u/small-w "
                "%d/%d/%d, far end %d/%d/%d, infinite %d, theta-integral %d, zero %d, divergent %d\n",
                gs_regime[0], gs_regime[1], gs_regime[2], u_zero, viewer_regime[0], viewer_regime[1],
                viewer_regime[2], far_regime[0], far_regime[1], far_regime[2], infinite_ray, fallback, zero,
                divergent);
    for (int r = 0; r < 3; ++r) {
        EXPECT_GE(gs_regime[r], 20) << "Gs regime " << r;
        EXPECT_GE(viewer_regime[r], 20) << "viewer-end regime " << r;
        EXPECT_GE(far_regime[r], 20) << "far-end regime " << r;
    }
    EXPECT_GE(u_zero, 20);
    EXPECT_GE(infinite_ray, 20);
    EXPECT_GE(fallback, 20);
    EXPECT_GE(zero, 3);
    EXPECT_GE(divergent, 20);
}

// ------------------------------------------------------------------------- glslang

TEST(ShaderGlslang, GlslCompilesForOpenGLAndVulkan) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    for (bool hw : {false, true}) {
        SCOPED_TRACE(hw ? "SLUT_AIRLIGHT_HARDWARE_FILTER" : "texelFetch path");
        const std::string tag = hw ? "_hw" : "";
        EXPECT_EQ(glslang("compute" + tag + ".comp", glsl_compute_source(hw), ""), "");
        EXPECT_EQ(glslang("vk_compute" + tag + ".comp", glsl_compute_source(hw),
                          "-V -o " + quoted(scratch_dir() + "/vk_compute" + tag + ".spv")),
                  "");
        EXPECT_EQ(glslang("fragment" + tag + ".frag", glsl_fragment_source(hw), ""), "");
    }
}

TEST(ShaderGlslang, HlslCompilesAsComputeAndPixelShaders) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    for (bool hw : {false, true}) {
        SCOPED_TRACE(hw ? "SLUT_AIRLIGHT_HARDWARE_FILTER" : "Load path");
        const std::string tag = hw ? "_hw" : "";
        EXPECT_EQ(glslang("compute" + tag + ".hlsl", hlsl_compute_source(hw),
                          "-D -V -e main -S comp -o " + quoted(scratch_dir() + "/compute_hlsl" + tag + ".spv")),
                  "");
        EXPECT_EQ(glslang("pixel" + tag + ".hlsl", hlsl_pixel_source(hw),
                          "-D -V -e main -S frag -o " + quoted(scratch_dir() + "/pixel_hlsl" + tag + ".spv")),
                  "");
    }
}

// ----------------------------------------------------------------------------- GPU

class GpuShaders : public GpuTest {};

TEST_F(GpuShaders, GlslMatchesTheCppSampler) {
#if SLUT_HAVE_EGL
    std::string error;
    const std::vector<float> got = run_on_gpu(glsl_compute_source(false), &error);
    ASSERT_EQ(error, "");
    expect_agreement(got, "glsl", kTolGs, kTolRadiance, this);
#endif
}

// The filter's weight precision on this GPU (reported; the hardware-path tolerances
// follow from it). Any GPU worth using has at least 8 fractional bits.
TEST_F(GpuShaders, MeasuresTheHardwareFilterWeights) {
#if SLUT_HAVE_EGL
    const double e = hardware_filter_weight_error();
    ASSERT_GE(e, 0.0) << "the ramp shader failed";
    std::printf("[ filter ] GL_LINEAR weight error %.3g (%.1f bits); max |d ln Gs| per cell %.3g\n", e,
                e > 0 ? -std::log2(2.0 * e) : 24.0, max_cell_jump());
    RecordProperty("filter_weight_error", std::to_string(e));
    RecordProperty("max_ln_gs_jump_per_cell", std::to_string(max_cell_jump()));
    EXPECT_LE(e, 1.0 / 256.0);
#endif
}

#if SLUT_HAVE_EGL
double hardware_tol_gs() { return kTolGs + 1.5 * hardware_filter_weight_error() * max_cell_jump(); }
double hardware_tol_radiance() { return kTolRadiance + 3.0 * hardware_filter_weight_error() * max_cell_jump(); }
#endif

// The one-fetch path, GL_LINEAR on the ln values: the same up to the filter's weights.
TEST_F(GpuShaders, GlslHardwareFilterAgreesToTheFilterPrecision) {
#if SLUT_HAVE_EGL
    ASSERT_GE(hardware_filter_weight_error(), 0.0);
    std::string error;
    const std::vector<float> got = run_on_gpu(glsl_compute_source(true), &error);
    ASSERT_EQ(error, "");
    expect_agreement(got, "glsl_hw", hardware_tol_gs(), hardware_tol_radiance(), this);
#endif
}

TEST_F(GpuShaders, HlslMatchesTheCppSampler) {
#if SLUT_HAVE_EGL
    if (kGlslang.empty() || kSpirvCross.empty())
        SLUT_SKIP_OR_FAIL("running the HLSL needs glslangValidator and spirv-cross (Debian: glslang-tools, spirv-cross)");
    for (bool hw : {false, true}) {
        std::string error;
        const std::string glsl = hlsl_compute_to_glsl(hw ? "hw" : "fetch", hlsl_compute_source(hw), &error);
        ASSERT_EQ(error, "");
        const std::vector<float> got = run_on_gpu(glsl, &error);
        ASSERT_EQ(error, "");
        if (hw)
            expect_agreement(got, "hlsl_hw", hardware_tol_gs(), hardware_tol_radiance(), this);
        else
            expect_agreement(got, "hlsl", kTolGs, kTolRadiance, this);
    }
#endif
}

// ------------------------------------------------------------------ the WebGPU test's cases
// (tests/shaders/wgsl_cases.hpp; ctest WebGPUSnippets runs the WGSL snippets on them.)

namespace {

std::vector<wgsl_cases::CaseSet> write_wgsl_cases() {
    std::vector<wgsl_cases::CaseSet> sets;
    // The snippet without a tier: the airlight_F table, every query of the GLSL test (its tiers:
    // test_shaders_airlight_tiers.cpp).
    wgsl_cases::CaseSet c;
    c.name = "airlight";
    c.snippet = "airlight";
    const scatterlut::Table &t = airlight_table().table();
    c.width = t.axes[0].map.count;
    c.height = t.axes[1].map.count;
    c.texels.assign(t.values.begin(), t.values.end());
    c.params_decl = kParams;
    c.params = wgsl_cases::bytes_of(test_params());
    c.body = kTestBody;
    c.query_floats = kQueryFloats;
    wgsl_cases::Tier none;
    for (const Query &q : queries()) {
        c.queries.insert(c.queries.end(), q.gpu.begin(), q.gpu.end());
        c.labels.push_back(q.label);
        c.reference.push_back(q.reference);
        none.tol.push_back(q.label == "Gs" ? kTolGs : kTolRadiance + kTolPerOpticalDistance * optical_distance(q));
    }
    c.tiers.push_back(none);
    sets.push_back(c);

    return sets;
}

} // namespace

SLUT_WGSL_CASES(write_wgsl_cases);
