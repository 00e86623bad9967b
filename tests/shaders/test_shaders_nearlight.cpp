// The near-light GPU snippets (scatterlut_nearlight.{glsl,hlsl}, generated at build time)
// against the truth they must reproduce: the C++ runtime (scatterlut::NearLightTable::E
// and ::radiance, near_light_radiance_thin / _distant; tables/src/nearlight.cpp, itself
// tested against Boost.Math in kernels/test_nearlight_math.cpp and kernels/test_nearlight_kernel.cpp) on
// the REAL tables of the default scene: `scatterlut generate` plans and writes
// near_light_E3 (now 48 x 40 x 32) and near_light_E4 (now 40 x 16 x 32 x 24, axes T, g, r,
// q) into the scratch directory, this test loads them,
// uploads them as R32F 3-D textures (E4: the S layers stacked along the height) and
// compares, query by query, with the double C++ code fed the same float-rounded inputs
// and the same float-rounded table:
//   - E(T, g, r[, S]) inside each table's domain (points uniform in the warped unit
//     coordinates, plus the axis ends and r = 0), and outside it, where the shader clamps
//     to the edge texels: there the reference is NearLightTable::E at the point clamped to
//     its axes (the edge value), since NearLightTable::E would integrate exactly outside;
//   - radiance from geometry (random normal, eye and light directions, sigma_t, eta with
//     and without Fresnel) wherever the C++ table covers the query, plus the zero limits
//     (light below the plane, sigma_s = 0, I0 = 0, length 0);
//   - the thin-medium and distant-light closed forms (no table).
// Both languages compile with glslang; the GLSL runs on Mesa llvmpipe through surfaceless
// EGL, the HLSL too (HLSL -> SPIR-V -> GLSL 4.30 by spirv-cross); both with and without
// SLUT_NEARLIGHT_HARDWARE_FILTER.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nearlight_gpu_test.hpp"
#include "scatterlut/io.hpp"
#include "wgsl_cases.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/table.hpp"

using namespace gpu_harness;
using namespace nearlight_gpu_test;

namespace {

// ------------------------------------------------------------------------ the tables

// A table as the GPU sees it (nearlight_gpu_test::Texture: the values rounded to float, the
// texture), and the C++ NearLightTable on exactly those values (the reference).
struct GpuTable : Texture {
    std::unique_ptr<scatterlut::NearLightTable> cpp;
};

struct Tables {
    std::string error; // non-empty when generation failed
    GpuTable e3, e4;
};

GpuTable make_gpu_table(scatterlut::Table t) {
    GpuTable g;
    static_cast<Texture &>(g) = make_texture(std::move(t));
    g.cpp = std::make_unique<scatterlut::NearLightTable>(g.rounded);
    return g;
}

// The default tables as the scatterlut executable writes them (what a user ships): from
// $SLUT_NEARLIGHT_TABLES where CTest's fixture ShaderNearLightTables generated them once
// per run, else generated here (~10 s on 2 CPU cores).
const Tables &tables() {
    static const Tables t = [] {
        Tables out;
        std::string dir;
        if (const char *given = std::getenv("SLUT_NEARLIGHT_TABLES")) {
            dir = given;
        } else {
            dir = scratch_dir() + "/tables";
            const std::string command = gpu_harness::quoted(SLUT_BINARY) + " generate --format bin --n-u 16 --n-w 16 --out " + gpu_harness::quoted(dir);
            std::string output;
            if (run_command(command, &output) != 0) {
                out.error = command + "\n" + output;
                return out;
            }
        }
        out.e3 = make_gpu_table(scatterlut::load_table(dir + "/near_light_E3.slut"));
        out.e4 = make_gpu_table(scatterlut::load_table(dir + "/near_light_E4.slut"));
        return out;
    }();
    return t;
}

// ---------------------------------------------------------------------- the queries

// One GPU query (nearlight_gpu_test::Query, 20 floats). mode 0: E(T, g, r, S) [2..5]; modes
// 1-3: radiance from the table / thin closed form / distant closed form of the geometry in
// gpu[2..16] (nearlight_gpu_test::random_geometry).
enum Mode { kE = 0, kRadiance = 1, kThin = 2, kDistant = 3 };

// E queries inside the table (unit coordinates uniform per axis, 10 % at an axis end,
// r = 0 for 10 %) and outside it (one coordinate beyond its axis, clamped by the shader).
void add_E_queries(const GpuTable &t, bool thick, std::mt19937_64 &rng, std::vector<Query> &out) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const size_t n_axes = t.rounded.axes.size();
    for (int i = 0; i < 2500; ++i) {
        const bool outside = i >= 2000;
        double p[4] = {0, 0, 0, kInf};
        for (size_t a = 0; a < n_axes; ++a) {
            const slut_axis &m = t.rounded.axes[a].map;
            const double r = unit(rng);
            p[a] = slut_param_from_unit(&m, r < 0.05 ? 0.0 : r < 0.1 ? 1.0 : unit(rng));
        }
        if (unit(rng) < 0.1) p[2] = 0.0;
        if (outside) {
            const size_t a = static_cast<size_t>(i) % n_axes;
            const slut_axis &m = t.rounded.axes[a].map;
            if (a == 1) p[1] = -1.0 + (m.min + 1.0) * unit(rng);              // g below g_min
            else p[a] = (i % 2 ? m.max * (1.0 + 3.0 * unit(rng)) : m.min * unit(rng)); // beyond an end
            if (a == 2 && !(i % 2)) p[2] = m.max * (1.0 + unit(rng));          // r min is 0: beyond max
        }
        Query q;
        q.gpu[0] = kE;
        for (int k = 0; k < 4; ++k) q.gpu[2 + k] = static_cast<float>(p[k]);
        const double T = q.gpu[2], g = q.gpu[3], r = q.gpu[4], S = thick ? kInf : q.gpu[5];
        if (!outside) {
            if (!t.cpp->covers(T, g, r, S)) continue; // float rounding stepped out of an end
            q.reference = t.cpp->E(T, g, r, S);
            q.ln_E = std::log(q.reference);
            q.label = "E";
        } else {
            if (t.cpp->covers(T, g, r, S)) continue;
            // The edge value: the C++ table at the point clamped to its axes (inside it).
            const auto& ax = t.rounded.axes;
            const auto clamp = [&](size_t a, double x) { return std::min(std::max(x, ax[a].map.min), ax[a].map.max); };
            q.reference = t.cpp->E(clamp(0, T), clamp(1, g), clamp(2, r), thick ? kInf : clamp(3, S));
            q.ln_E = std::log(q.reference);
            q.label = "E_clamped";
        }
        out.push_back(q);
    }
}

// Radiance queries: random geometries (nearlight_gpu_test::random_geometry) with T over the
// table's T axis and S over its S axis (E4) or infinite (E3), kept where the C++ table covers
// the point.
void add_radiance_queries(const GpuTable &t, bool thick, std::mt19937_64 &rng, std::vector<Query> &out) {
    const slut_axis &aT = t.rounded.axes[0].map;
    int made = 0;
    for (int attempt = 0; attempt < 20000 && made < 1500; ++attempt) {
        Query q = random_geometry(rng, aT.min, aT.max, thick ? 0.0 : t.rounded.axes[3].map.min,
                                  thick ? 0.0 : t.rounded.axes[3].map.max);
        q.gpu[0] = kRadiance;
        const scatterlut::NearLightQuery c = cpp_query(q);
        const scatterlut::NearLightParams p = scatterlut::near_light_params(c);
        if (p.light_below || !t.cpp->covers(p.T, p.g, p.r, p.S)) continue;
        q.reference = t.cpp->radiance(c);
        q.ln_E = std::log(t.cpp->E(p.T, p.g, p.r, p.S));
        q.label = "radiance";
        out.push_back(q);
        ++made;
        // The same geometry through the closed forms (E3 pass only: no table involved).
        if (thick || made % 2) {
            Query thin = q, distant = q;
            thin.gpu[0] = kThin;
            thin.reference = scatterlut::near_light_radiance_thin(c);
            thin.label = "thin";
            distant.gpu[0] = kDistant;
            distant.reference = scatterlut::near_light_radiance_distant(c);
            distant.label = "distant";
            if (thin.reference > 1e-30) out.push_back(thin); // thick: E_thin = 0 exactly
            out.push_back(distant);
        }
    }
    // Zero limits on the last radiance query (nearlight_gpu_test::zero_limit).
    size_t last = out.size();
    while (last > 0 && out[last - 1].gpu[0] != kRadiance) --last;
    if (last == 0) return;
    for (int k = 0; k < 4; ++k) {
        Query z = zero_limit(out[last - 1], k);
        z.reference = t.cpp->radiance(cpp_query(z));
        out.push_back(z);
    }
}

struct Run {
    std::vector<Query> queries;
    std::vector<double> reference;
};

const Run &queries(bool thick) {
    static const auto make = [](bool th) {
        Run run;
        if (!tables().error.empty()) return run;
        const GpuTable &t = th ? tables().e3 : tables().e4;
        std::mt19937_64 rng(th ? 20261201 : 20261202);
        add_E_queries(t, th, rng, run.queries);
        add_radiance_queries(t, th, rng, run.queries);
        for (const Query &q : run.queries) run.reference.push_back(q.reference);
        return run;
    };
    static const Run e3 = make(true), e4 = make(false);
    return thick ? e3 : e4;
}

// ------------------------------------------------------------------------- shaders

// The compute shader evaluating one pass of queries. Bindings as in gpu_harness:
// 0 the table, 1 the queries, 2 the results, 3 the parameters (std140: per axis
// (min, max, scale, -) and (warp, count, -, -); the number of layers; the query count).
std::string glsl_snippet() { return read_text(kShaderDir + "scatterlut_nearlight.glsl"); }
std::string hlsl_snippet() { return read_text(kShaderDir + "scatterlut_nearlight.hlsl"); }

// What each invocation evaluates, written once for both languages with the snippets'
// own prelude macros (SLUT_FLOAT3, SLUT_TEX_ARG): the test wrapper cannot drift between
// GLSL and HLSL either.
const char *kTestBody = R"slsl(
float test_eval(int i) {
    SlutNearLightTable t = test_table();
    int b = 20 * i;
    int mode = int(q[b]);
    TEST_GEOMETRY(b);
    if (mode == 0) return slut_near_light_E(SLUT_TEX_ARG(slut_test_table), t, q[b + 2], q[b + 3], q[b + 4], q[b + 5]);
    if (mode == 1)
        return slut_near_light_radiance(SLUT_TEX_ARG(slut_test_table), t, q[b + 2], q[b + 3], q[b + 4], n, e, l,
                                        q[b + 14], q[b + 15], fresnel);
    if (mode == 2)
        return slut_near_light_radiance_thin(q[b + 2], q[b + 3], q[b + 4], n, e, l, q[b + 14], q[b + 15], fresnel);
    return slut_near_light_radiance_distant(q[b + 2], q[b + 3], q[b + 4], n, e, l, q[b + 14], q[b + 15], fresnel);
}
)slsl";

// defines: "" (no tier), a tier's "#define SLUT_TIER_FAST\n" / "#define SLUT_TIER_ACCURATE\n", or the
// hardware-filter option.
std::string glsl_compute_source(const std::string &defines) {
    return nearlight_gpu_test::glsl_compute_source(glsl_snippet(), kTestBody, defines);
}
std::string glsl_compute_source(bool hardware_filter) {
    return glsl_compute_source(std::string(hardware_filter ? "#define SLUT_NEARLIGHT_HARDWARE_FILTER\n" : ""));
}

std::string hlsl_compute_source(bool hardware_filter) {
    return nearlight_gpu_test::hlsl_compute_source(hlsl_snippet(), kTestBody,
                                                   hardware_filter ? "#define SLUT_NEARLIGHT_HARDWARE_FILTER\n" : "");
}

// A fragment / pixel shader using both snippets together, as an engine would (compile
// checks: the shared part must be included once without clashes).
std::string glsl_fragment_source(bool es) {
    const std::string version = es ? "#version 300 es\nprecision highp float;\nprecision highp sampler3D;\n" : "#version 330\n";
    return version + "uniform sampler2D airlight_table;\nuniform sampler3D near_table;\n"
           "uniform vec3 light_pos;\nuniform vec3 medium;\nin vec3 world_pos;\nin vec3 eye_pos;\n"
           "in vec3 normal;\nout vec4 colour;\n" +
           read_text(kShaderDir + "scatterlut_airlight.glsl") + glsl_snippet() + R"glsl(
void main() {
    SlutNearLightTable t = slut_near_light_table_e3(
        slut_axis_make(1e-3, 20.0, 1.0, SLUT_WARP_LOGLIN, 96), slut_axis_make(-0.99, 1.0, 0.0, SLUT_WARP_SQRT1P, 80),
        slut_axis_make(0.0, 1e3, 1e-6, SLUT_WARP_LOG1P, 64));
    float L = slut_near_light_radiance(near_table, t, medium.x, medium.y, medium.z, normal,
                                       normalize(eye_pos - world_pos), light_pos - world_pos,
                                       1e30, 1.33, true);
    colour = vec4(vec3(L), 1.0);
}
)glsl";
}

std::string hlsl_pixel_source() {
    return "Texture3D<float> near_table : register(t0);\nSamplerState near_table_sampler : register(s0);\n"
           "cbuffer Slab : register(b0) { float3 light_pos; float3 medium; };\n" +
           read_text(kShaderDir + "scatterlut_airlight.hlsl") + hlsl_snippet() + R"hlsl(
float4 main(float3 world_pos : TEXCOORD0, float3 eye_pos : TEXCOORD1, float3 normal : NORMAL) : SV_Target {
    SlutNearLightTable t = slut_near_light_table_e3(
        slut_axis_make(1e-3, 20.0, 1.0, SLUT_WARP_LOGLIN, 96), slut_axis_make(-0.99, 1.0, 0.0, SLUT_WARP_SQRT1P, 80),
        slut_axis_make(0.0, 1e3, 1e-6, SLUT_WARP_LOG1P, 64));
    float L = slut_near_light_radiance(near_table, near_table_sampler, t, medium.x, medium.y, medium.z,
                                       normal, normalize(eye_pos - world_pos), light_pos - world_pos,
                                       1e30, 1.33, true);
    return float4(L, L, L, 1.0);
}
)hlsl";
}

// ---------------------------------------------------------------------- comparisons

// Tolerances (relative, against the double C++ code on the same float-rounded table and
// inputs; measured on Mesa llvmpipe, docs/SHADERS.md):
//  - E: 1e-5 + 2e-7·|ln E| (measured max 9e-6). The shader interpolates the stored ln E
//    in float: each texel position x·(n − 1) carries a few float ulps of its warp (log1p
//    over ~11 units of T, ~18 of r): ~1e-6 texel, times |Δ ln E| per cell (up to ~8 across
//    the r boundary layer); the interpolated ln E itself rounds to ~6e-8·|ln E|, and exp
//    adds (3 + 2|ln E|) ulp.
//  - radiance: the E tolerance, plus 1e-5 for T·H from the float closed form (the Cephes
//    atan and a few divisions, ~1e-6), refraction and Fresnel (~1e-6), plus
//    2e-7·(1/μ_l + 1/μ_e): the geometry's float dot products. μ_l = (light − O)·n/l of a
//    light near the plane cancels: its absolute error ~1e-7 is relative 1e-7/μ_l, and E,
//    T·H and the closed forms depend on r = μ_l/μ_e at most linearly (measured 3e-4 at
//    μ_l = 4e-5). The C++ reference computes those dot products in double from the
//    same float vectors, so this is the snippet's own float error, not a drift.
//  - thin / distant closed forms: 1e-5 + the same 2e-7·(1/μ_l + 1/μ_e) (a handful of
//    float operations on the same parameters, expm1 by its polynomial).
//  - the hardware filter adds, per filtered axis, (its weight error + 2^-24·n)·|Δ ln E|
//    per cell, times 1.5: the weights are the GPU's (measured on the running GPU by
//    gpu_harness::hardware_filter_weight_error), and the filter receives the position as
//    a normalised coordinate whose float ulp is 2^-24·n texels for an axis of n texels —
//    along E4's stacked height n = g count × q count (384 here, 1536 for the default plan):
//    ~2e-5 (~9e-5) texel.
constexpr double kTolE = 1e-5, kTolPerLnE = 2e-7, kTolRadiance = 1e-5, kTolClosedForm = 1e-5,
                 kTolPerConditioning = 2e-7;

// The hardware filter's extra error on one table: nearlight_gpu_test::hardware_filter_extra (see
// the tolerances above).

// A query's tolerance (its label's), filter_extra added where the table is sampled.
double tolerance_of(const Query &q, double filter_extra) {
    const double ln_e = std::fabs(q.ln_E);
    const double geometry = kTolPerConditioning * q.conditioning;
    if (q.label == "thin" || q.label == "distant") return kTolClosedForm + geometry;
    if (q.label == "radiance") return kTolRadiance + geometry + kTolE + kTolPerLnE * ln_e + filter_extra;
    return kTolE + kTolPerLnE * ln_e + filter_extra;
}

void expect_agreement(const std::vector<float> &got, bool thick, const std::string &run, double filter_extra,
                      ::testing::Test *test) {
    const Run &r = queries(thick);
    ASSERT_EQ(got.size(), r.queries.size());
    for (const std::string label : {"E", "E_clamped", "radiance", "thin", "distant", "zero"}) {
        std::vector<size_t> idx;
        for (size_t i = 0; i < r.queries.size(); ++i)
            if (r.queries[i].label == label) idx.push_back(i);
        if (idx.empty()) continue;
        const auto tolerance = [&](size_t i) { return tolerance_of(r.queries[i], filter_extra); };
        const Stats st = error_stats(got, r.reference, idx, tolerance);
        std::printf("[ %s %s ] %-9s n=%zu  max %.3g  p99 %.3g  median %.3g  (worst: gpu %.9g, C++ %.9g)  "
                    "max error/tolerance %.2f\n",
                    run.c_str(), thick ? "E3" : "E4", label.c_str(), st.count, st.max, st.p99, st.median,
                    static_cast<double>(got[st.worst]), r.reference[st.worst], st.max_ratio);
        if (label == "radiance" || label == "thin" || label == "distant") {
            // The same over the well-conditioned geometries (mu_l, mu_e >= ~0.1).
            std::vector<size_t> well;
            for (size_t i : idx)
                if (r.queries[i].conditioning <= 20.0) well.push_back(i);
            const Stats sw = error_stats(got, r.reference, well, tolerance);
            std::printf("[ %s %s ] %-9s n=%zu  max %.3g  p99 %.3g  median %.3g  where 1/mu_l + 1/mu_e <= 20\n",
                        run.c_str(), thick ? "E3" : "E4", label.c_str(), sw.count, sw.max, sw.p99, sw.median);
        }
        const Query &w = r.queries[st.worst_ratio];
        std::string inputs;
        for (int k = 0; k < 17; ++k) inputs += std::to_string(w.gpu[k]) + " ";
        EXPECT_LE(st.max_ratio, 1.0) << run << " " << label << ": query [" << inputs << "] gave " << got[st.worst_ratio]
                                     << ", the C++ code " << w.reference << ": relative error "
                                     << rel_err(got[st.worst_ratio], w.reference) << " > tolerance "
                                     << tolerance(st.worst_ratio);
        test->RecordProperty(run + (thick ? "_E3_" : "_E4_") + label + "_max_rel_err", std::to_string(st.max));
    }
}

#if SLUT_HAVE_EGL
std::vector<float> run_on_gpu(const std::string &source, bool thick, std::string *error) {
    return run_queries(source, thick ? tables().e3 : tables().e4, queries(thick).queries, 0.0, error);
}
#endif

} // namespace

// The comparison is only as good as its queries: enough of each kind in both tables, and
// the domain's far corners (r = 0, the axis ends, the refracted and Fresnel paths).
TEST(NearLightShaderQueries, CoverTheDomainAndEveryPath) {
    ASSERT_EQ(tables().error, "") << "generating the default tables failed";
    for (bool thick : {true, false}) {
        int count[6] = {0, 0, 0, 0, 0, 0}, r_zero = 0, refracted = 0, fresnel = 0;
        for (const Query &q : queries(thick).queries) {
            const std::string &l = q.label;
            ++count[l == "E" ? 0 : l == "E_clamped" ? 1 : l == "radiance" ? 2 : l == "thin" ? 3 : l == "distant" ? 4 : 5];
            r_zero += (l == "E" && q.gpu[4] == 0.0f);
            refracted += (l == "radiance" && q.gpu[15] != 1.0f);
            fresnel += (l == "radiance" && q.gpu[16] != 0.0f);
        }
        std::printf("%s: E %d, E clamped %d, radiance %d (refracted %d, Fresnel %d), thin %d, distant %d, zero %d, r = 0 %d\n",
                    thick ? "E3" : "E4", count[0], count[1], count[2], refracted, fresnel, count[3], count[4], count[5], r_zero);
        EXPECT_GE(count[0], 1500);
        EXPECT_GE(count[1], 300);
        EXPECT_GE(count[2], 1000);
        EXPECT_GE(count[4], 300);
        EXPECT_GE(count[5], 3);
        EXPECT_GE(r_zero, 100);
        EXPECT_GE(refracted, 300);
        EXPECT_GE(fresnel, 100);
        if (!thick) {
            EXPECT_GE(count[3], 300); // the thin form is 0 for a thick medium
        }
    }
}

// Generated from one source: the GLSL and HLSL files agree outside their preludes, are
// ASCII, and carry the kernels/ regions verbatim (the axis maps, the closed-form H, E4's
// slab coordinate and value base, refraction and Fresnel).
TEST(NearLightShaderSources, OneBodyFromTheCHeaders) {
    const std::string g = shared_body(glsl_snippet()), h = shared_body(hlsl_snippet());
    ASSERT_FALSE(g.empty()) << "SHARED BODY markers missing in scatterlut_nearlight.glsl";
    EXPECT_TRUE(g == h) << "the GLSL and HLSL near-light snippets differ outside their preludes";
    for (const std::string &text : {glsl_snippet(), hlsl_snippet()}) {
        const auto it = std::find_if(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) > 127; });
        EXPECT_EQ(it, text.end()) << "non-ASCII byte at offset " << (it - text.begin());
    }
    for (const char *function : {"SLUT_FN double slut_warp_forward(int warp, double p, double p_min, double scale)",
                                 "SLUT_FN double slut_nl_H_scaled(double g, double S_over_T)",
                                 "SLUT_FN double slut_nl_E_thin(double r, double S)",
                                 "SLUT_FN double slut_nl_depth_odds(double T, double g, double S)",
                                 "SLUT_FN double slut_nl_unit_from_S_between(double T, double g, double S, double S_min, double S_max)",
                                 "SLUT_FN double slut_nl_E_base(double T, double r, double S)",
                                 "SLUT_FN double slut_refracted_cos(double mu_e, double eta)",
                                 "SLUT_FN double slut_fresnel_transmittance(double cos_i, double cos_t, double eta)"}) {
        EXPECT_NE(g.find(function), std::string::npos) << function << " is not copied from kernels/";
    }
}

TEST(NearLightShaderGlslang, GlslAndHlslCompile) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    expect_compute_shaders_compile("nl", [](bool hw) { return glsl_compute_source(hw); },
                                   [](bool hw) { return hlsl_compute_source(hw); });
    // Both snippets in one shader (the shared part once): GLSL 3.30, GLSL ES 3.00 and an
    // HLSL pixel shader.
    expect_engine_shaders_compile("nl", glsl_fragment_source(false), glsl_fragment_source(true), hlsl_pixel_source());
}

class NearLightGpu : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        ASSERT_EQ(tables().error, "") << "generating the default tables failed";
    }
};

// The packing fits every GPU: each dimension of both textures within the OpenGL 4.x and
// D3D11 minimum of GL_MAX_3D_TEXTURE_SIZE (2048), and within the running GPU's own limit.
// (The library's default E4 plan, 80 x 32 x 64 x 48, is 80 x 1536 x 64 so; stacked along the
// depth it would be 64 x 48 = 3072 deep, beyond 2048.)
TEST_F(NearLightGpu, TexturesFitTheThreeDimensionalTextureLimit) {
#if SLUT_HAVE_EGL
    GLint limit = 0;
    gpu().gl.glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &limit);
    std::printf("[ limit ] GL_MAX_3D_TEXTURE_SIZE %d\n", limit);
    for (const GpuTable *t : {&tables().e3, &tables().e4}) {
        const auto &ax = t->rounded.axes;
        for (int n : {ax[0].map.count, ax[1].map.count * t->layers(), ax[2].map.count}) {
            EXPECT_LE(n, 2048) << t->rounded.kind;
            EXPECT_LE(n, limit) << t->rounded.kind;
        }
    }
#endif
}

// Without a tier and in the accurate tier (SLUT_TIER_ACCURATE: the same texel fetches).
TEST_F(NearLightGpu, GlslMatchesTheCppSampler) {
#if SLUT_HAVE_EGL
    for (const std::string tier : {"", "SLUT_TIER_ACCURATE"}) {
        for (bool thick : {true, false}) {
            std::string error;
            const std::vector<float> got =
                run_on_gpu(glsl_compute_source(tier.empty() ? "" : "#define " + tier + "\n"), thick, &error);
            ASSERT_EQ(error, "");
            expect_agreement(got, thick, tier.empty() ? "glsl" : "glsl_accurate", 0.0, this);
        }
    }
#endif
}

TEST_F(NearLightGpu, GlslHardwareFilterAgreesToTheFilterPrecision) {
#if SLUT_HAVE_EGL
    const double weight_error = hardware_filter_weight_error();
    ASSERT_GE(weight_error, 0.0) << "the ramp shader failed";
    for (bool thick : {true, false}) {
        const double extra = hardware_filter_extra(thick ? tables().e3 : tables().e4, weight_error);
        std::printf("[ filter ] weight error %.3g: extra tolerance %.3g\n", weight_error, extra);
        // The option and the fast tier (SLUT_TIER_FAST: the hardware filter).
        for (const std::string defines : {"#define SLUT_NEARLIGHT_HARDWARE_FILTER\n", "#define SLUT_TIER_FAST\n"}) {
            std::string error;
            const std::vector<float> got = run_on_gpu(glsl_compute_source(defines), thick, &error);
            ASSERT_EQ(error, "");
            expect_agreement(got, thick, defines.find("FAST") != std::string::npos ? "glsl_fast" : "glsl_hw", extra, this);
        }
    }
#endif
}

TEST_F(NearLightGpu, HlslMatchesTheCppSampler) {
#if SLUT_HAVE_EGL
    if (kGlslang.empty() || kSpirvCross.empty())
        SLUT_SKIP_OR_FAIL("running the HLSL needs glslangValidator and spirv-cross (Debian: glslang-tools, spirv-cross)");
    std::string error;
    const std::string glsl = hlsl_compute_to_glsl("nl", hlsl_compute_source(false), &error);
    ASSERT_EQ(error, "");
    for (bool thick : {true, false}) {
        const std::vector<float> got = run_on_gpu(glsl, thick, &error);
        ASSERT_EQ(error, "");
        expect_agreement(got, thick, "hlsl", 0.0, this);
    }
#endif
}

// ------------------------------------------------------------------ the WebGPU test's cases
// (tests/shaders/wgsl_cases.hpp; ctest WebGPUSnippets runs the WGSL snippets on them): per table
// every query above, no tier and the accurate tier at the tolerances above, the fast tier with
// the filter's extra (linear in the weight error).
namespace {

std::vector<wgsl_cases::CaseSet> write_wgsl_cases() {
    if (!tables().error.empty()) throw std::runtime_error("generating the default tables failed: " + tables().error);
    std::vector<wgsl_cases::CaseSet> sets;
    for (bool thick : {true, false}) {
        const GpuTable &t = thick ? tables().e3 : tables().e4;
        const Run &r = queries(thick);
        wgsl_cases::CaseSet c;
        c.name = thick ? "nearlight E3" : "nearlight E4";
        c.snippet = "nearlight";
        c.texture = "3d";
        const auto &ax = t.rounded.axes;
        c.width = ax[0].map.count;
        c.height = ax[1].map.count * t.layers();
        c.depth = ax[2].map.count;
        c.texels = t.texels;
        c.params_decl = kParamsDecl;
        c.params = wgsl_cases::bytes_of(make_params(t, r.queries.size(), 0.0));
        c.body = std::string(kTestAxis) + kTestBody;
        c.query_floats = kQueryFloats;
        const double extra0 = hardware_filter_extra(t, 0.0), extra_per_w = hardware_filter_extra(t, 1.0) - extra0;
        wgsl_cases::Tier none, accurate, fast;
        accurate.name = "accurate";
        fast.name = "fast";
        for (const Query &q : r.queries) {
            c.queries.insert(c.queries.end(), q.gpu.begin(), q.gpu.end());
            c.labels.push_back(q.label);
            c.reference.push_back(q.reference);
            none.tol.push_back(tolerance_of(q, 0.0));
            accurate.tol.push_back(tolerance_of(q, 0.0));
            fast.tol.push_back(tolerance_of(q, extra0));
            fast.tol_per_weight_error.push_back(tolerance_of(q, extra0 + extra_per_w) - tolerance_of(q, extra0));
        }
        c.tiers = {none, accurate, fast};
        sets.push_back(c);
    }
    return sets;
}

} // namespace

SLUT_WGSL_CASES(write_wgsl_cases);
