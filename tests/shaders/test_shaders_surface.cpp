// The surface GPU snippets (scatterlut_surface.{glsl,hlsl,essl}, generated at build time)
// against the truth they must reproduce: the C++ runtime (scatterlut::SurfaceTable::G and
// scatterlut::surface_radiance, tables/src/surface_table.cpp and surface_radiance.cpp, tested
// against the quadrature in tests/runtime/test_surface_table.cpp and test_surface_radiance.cpp)
// on two surface_G tables filled by quadrature — the diffuse G0 (exponent 1, θ_s linear) and a
// Phong G_20 (θ_r log1p) — rounded to float and stacked in one R32F texture (G0 rows 0 … n−1,
// G_20 above), compared query by query with the double C++ code fed the same float-rounded
// inputs and the same float-rounded tables:
//   - G(T, θ) of each table inside its domain (points uniform in the warped unit coordinates,
//     the axis ends, θ = π/2, π) and beyond its T axis (the shader's clamped ratio times the
//     scale at the true T, against the C++ table's ratio at T_max times the same scale);
//   - the radiance terms from geometry (random normals, lights above and below the horizon,
//     viewers above it, σ, k_d, k_s): each of the four terms and their sum, where the C++
//     table covers T; the zero limits (viewer below the surface, I0 = 0, σ_s = 0).
// Both languages compile with glslang (GLSL 4.30 compute, Vulkan, HLSL; both snippets in one
// GLSL 3.30, GLSL ES 3.00 and HLSL pixel shader); the GLSL runs on Mesa llvmpipe through
// surfaceless EGL, the HLSL too (HLSL -> SPIR-V -> GLSL 4.30 by spirv-cross).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_harness.hpp"
#include "scatterlut/surface_radiance.hpp"
#include "scatterlut/surface_table.hpp"
#include "scatterlut/table.hpp"

extern "C" {
#include "slut_axes.h"
#include "slut_surface_table.h"
}

#include "wgsl_cases.hpp"

using namespace gpu_harness;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSpecularExponent = 20;
constexpr double kTMax = 8.0;
constexpr int kTCount = 16, kThetaCount = 17; // odd: G0's node at π/2

// ------------------------------------------------------------------------ the tables

// A table as the GPU sees it (its values rounded to float) and the C++ SurfaceTable on exactly
// those values (the reference).
struct GpuTable {
    scatterlut::Table rounded;
    std::unique_ptr<scatterlut::SurfaceTable> cpp;
    int row0 = 0;
};

struct Tables {
    GpuTable diffuse, specular;
    std::vector<float> texels; // width kTCount, height 2 kThetaCount: G0's rows, then G_20's
};

GpuTable make_gpu_table(scatterlut::Table t, int row0) {
    GpuTable g;
    for (double &v : t.values) v = static_cast<float>(v);
    g.rounded = t;
    g.cpp = std::make_unique<scatterlut::SurfaceTable>(std::move(t));
    g.row0 = row0;
    return g;
}

const Tables &tables() {
    static const Tables t = [] {
        Tables out;
        out.diffuse = make_gpu_table(scatterlut::surface_G_table_by_quadrature(1, kTMax, kTCount, kThetaCount), 0);
        out.specular = make_gpu_table(
            scatterlut::surface_G_table_by_quadrature(kSpecularExponent, kTMax, kTCount, kThetaCount), kThetaCount);
        for (const GpuTable *g : {&out.diffuse, &out.specular})
            for (double v : g->rounded.values) out.texels.push_back(static_cast<float>(v)); // axis 0 fastest: rows
        return out;
    }();
    return t;
}

// ---------------------------------------------------------------------- the queries

// One GPU query: 20 floats. mode 0: G of table [1] (0 diffuse, 1 specular) at T [2], θ [3];
// mode 1: radiance term [1] (0 the sum, 1 diffuse direct, 2 diffuse scattered, 3 specular
// direct, 4 specular scattered) of σ_s [2], σ_a [3], I0 [4], normal [5..7], light − P [8..10],
// viewer − P [11..13], k_d [14], k_s [15].
enum Mode { kG = 0, kRadiance = 1 };
constexpr int kQueryFloats = 20;

struct Query {
    std::array<float, kQueryFloats> gpu{};
    double reference = 0;
    double conditioning = 0; // the relative sensitivity to the float geometry (scales the tolerance)
    std::string label;
};

double log_uniform(std::mt19937_64 &rng, double lo, double hi) {
    return lo * std::pow(hi / lo, std::uniform_real_distribution<double>(0.0, 1.0)(rng));
}

using Vec = std::array<double, 3>;

// The unit vector at polar cosine `mu` and azimuth `phi` about the unit vector n, in the
// orthonormal basis (b1, b2, n) of Duff et al. 2017 ("Building an orthonormal basis, revisited").
Vec about(const Vec &n, double mu, double phi) {
    const double sign = std::copysign(1.0, n[2]), a = -1.0 / (sign + n[2]), b = n[0] * n[1] * a;
    const Vec b1{1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]}, b2{b, sign + n[1] * n[1] * a, -n[1]};
    const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu)), c = std::cos(phi), d = std::sin(phi);
    return {mu * n[0] + s * (c * b1[0] + d * b2[0]), mu * n[1] + s * (c * b1[1] + d * b2[1]),
            mu * n[2] + s * (c * b1[2] + d * b2[2])};
}

// The G the shader computes beyond the T axis: the ratio at the clamped T times the scale at
// the true T (slut_surface_G_scale in double).
double G_reference(const GpuTable &t, double T, double theta) {
    const double T_max = t.cpp->T_max();
    const int n = t.cpp->exponent();
    if (T <= T_max) return t.cpp->G(T, theta);
    return t.cpp->G(T_max, theta) / slut_surface_G_scale(n, T_max, theta) * slut_surface_G_scale(n, T, theta);
}

void add_G_queries(std::mt19937_64 &rng, std::vector<Query> &out) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int which = 0; which < 2; ++which) {
        const GpuTable &t = which ? tables().specular : tables().diffuse;
        const slut_axis &aT = t.rounded.axes[0].map, &ath = t.rounded.axes[1].map;
        for (int i = 0; i < 1200; ++i) {
            const bool outside = i >= 1000;
            double T = slut_param_from_unit(&aT, i % 10 == 0 ? 0.0 : i % 10 == 1 ? 1.0 : unit(rng));
            double theta = slut_param_from_unit(&ath, i % 7 == 0 ? 0.0 : i % 7 == 1 ? 1.0 : unit(rng));
            if (i % 13 == 0) theta = 0.5 * kPi;
            if (outside) T = kTMax * (1.0 + 2.0 * unit(rng));
            Query q;
            q.gpu[0] = kG;
            q.gpu[1] = static_cast<float>(which);
            q.gpu[2] = static_cast<float>(T);
            q.gpu[3] = static_cast<float>(theta);
            const double Tf = q.gpu[2], thf = std::min(double(q.gpu[3]), kPi);
            if (!outside && Tf > kTMax) continue;
            q.reference = G_reference(t, Tf, thf);
            q.label = outside ? "G_beyond" : "G";
            out.push_back(q);
        }
    }
}

// The C++ lighting of a radiance query's float inputs (the normal renormalised in double: the
// C++ check wants |n| = 1 to 1e-6; a change of ~6e-8, inside the noise).
scatterlut::SurfaceLighting cpp_lighting(const Query &q) {
    scatterlut::SurfaceLighting s;
    const double len = std::sqrt(double(q.gpu[5]) * q.gpu[5] + double(q.gpu[6]) * q.gpu[6] + double(q.gpu[7]) * q.gpu[7]);
    for (int k = 0; k < 3; ++k) {
        s.point_m[k] = 0.0;
        s.normal[k] = q.gpu[5 + k] / len;
        s.light_m[k] = q.gpu[8 + k];
        s.viewer_m[k] = q.gpu[11 + k];
    }
    s.intensity_W_per_sr = q.gpu[4];
    return s;
}

double term(const scatterlut::SurfaceRadiance &r, int component) {
    switch (component) {
    case 1: return r.diffuse_direct;
    case 2: return r.diffuse_scattered;
    case 3: return r.specular_direct;
    case 4: return r.specular_scattered;
    default: return r.total();
    }
}

const char *kTermLabel[5] = {"total", "diff_direct", "diff_scatt", "spec_direct", "spec_scatt"};

// Radiance queries: random normal; light at cos θ_s uniform in [−1, 1] (10 % below the
// horizon within 0.01 rad of it), 0.3–20 m away; viewer above the surface at cos in
// [0.02, 1], 0.5–50 m away; σ_t 0.01–1 /m with albedo 0.05–1, kept where T lies in the
// tables; k_d, k_s in [0, 1]. Every term of each geometry.
void add_radiance_queries(std::mt19937_64 &rng, std::vector<Query> &out) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const scatterlut::SurfaceTables cpp_tables{tables().diffuse.cpp.get(), tables().specular.cpp.get()};
    int made = 0;
    for (int attempt = 0; attempt < 10000 && made < 800; ++attempt) {
        const Vec n = about({0.0, 0.0, 1.0}, 2.0 * unit(rng) - 1.0, 2.0 * kPi * unit(rng)); // uniform on the sphere
        const double cos_s = unit(rng) < 0.1 ? -0.01 * unit(rng) : 2.0 * unit(rng) - 1.0;
        const Vec ldir = about(n, cos_s, 2.0 * kPi * unit(rng));
        const Vec vdir = about(n, 0.02 + 0.98 * unit(rng), 2.0 * kPi * unit(rng));
        const double D = log_uniform(rng, 0.3, 20.0), Dv = log_uniform(rng, 0.5, 50.0);
        const double sigma_t = log_uniform(rng, 0.01, 1.0), albedo = 0.05 + 0.95 * unit(rng);
        Query q;
        q.gpu[0] = kRadiance;
        q.gpu[2] = static_cast<float>(albedo * sigma_t);
        q.gpu[3] = static_cast<float>((1.0 - albedo) * sigma_t);
        q.gpu[4] = static_cast<float>(log_uniform(rng, 1.0, 1e3));
        for (int k = 0; k < 3; ++k) {
            q.gpu[5 + k] = static_cast<float>(n[k]);
            q.gpu[8 + k] = static_cast<float>(D * ldir[k]);
            q.gpu[11 + k] = static_cast<float>(Dv * vdir[k]);
        }
        q.gpu[14] = static_cast<float>(unit(rng));
        q.gpu[15] = static_cast<float>(unit(rng));
        if ((double(q.gpu[2]) + q.gpu[3]) * D > 0.999 * kTMax) continue; // the C++ front-end would integrate there
        scatterlut::SurfaceMaterial m;
        m.diffuse_albedo = q.gpu[14];
        m.specular_per_sr = q.gpu[15];
        m.phong_exponent = kSpecularExponent;
        const scatterlut::SurfaceLighting s = cpp_lighting(q);
        const scatterlut::SurfaceRadiance r = scatterlut::surface_radiance(cpp_tables, s, q.gpu[2], q.gpu[3], m);
        // The float geometry: cosines to ~1e-7 absolute, so relative 1e-7/|cos θ_s| on E_d and
        // n·1e-7/cos θ_r on the lobe; σ_t D and σ_t D_v to ~1e-7 relative.
        const double vx = q.gpu[11], vy = q.gpu[12], vz = q.gpu[13];
        const double nv = (s.normal[0] * vx + s.normal[1] * vy + s.normal[2] * vz) / std::sqrt(vx * vx + vy * vy + vz * vz);
        for (int c = 0; c < 5; ++c) {
            Query t = q;
            t.gpu[1] = static_cast<float>(c);
            t.reference = term(r, c);
            t.conditioning = 1.0 / std::max(std::fabs(cos_s), 1e-4) + kSpecularExponent / std::max(nv, 1e-4) +
                             (double(q.gpu[2]) + q.gpu[3]) * (D + Dv) + kSpecularExponent;
            t.label = kTermLabel[c];
            out.push_back(t);
        }
        ++made;
    }
    // Zero limits on the last geometry: the viewer below the surface, I0 = 0, σ_s = 0 (the
    // scattered terms).
    Query z = out.back();
    z.gpu[1] = 0.0f;
    for (int k = 0; k < 3; ++k) z.gpu[11 + k] = -z.gpu[5 + k] * 3.0f;
    z.reference = 0.0;
    z.label = "zero";
    out.push_back(z);
    z = out[out.size() - 2];
    z.gpu[4] = 0.0f;
    z.reference = 0.0;
    z.label = "zero";
    out.push_back(z);
    z = out[out.size() - 3];
    z.gpu[1] = 2.0f;
    z.gpu[2] = 0.0f;
    z.reference = 0.0;
    z.label = "zero";
    out.push_back(z);
}

struct Run {
    std::vector<Query> queries;
    std::vector<double> reference;
};

const Run &queries() {
    static const Run run = [] {
        Run r;
        std::mt19937_64 rng(20261202);
        add_G_queries(rng, r.queries);
        add_radiance_queries(rng, r.queries);
        for (const Query &q : r.queries) r.reference.push_back(q.reference);
        return r;
    }();
    return run;
}

// ------------------------------------------------------------------------- shaders

std::string glsl_snippet() { return read_text(kShaderDir + "scatterlut_surface.glsl"); }
std::string hlsl_snippet() { return read_text(kShaderDir + "scatterlut_surface.hlsl"); }
std::string essl_snippet() { return read_text(kShaderDir + "scatterlut_surface.essl"); }

// What each invocation evaluates, once for both languages (the snippets' own prelude macros).
const char *kTestBody = R"slsl(
SlutSurfaceTable test_table(int k) {
    return slut_surface_table(slut_axis_make(axis_f[2 * k].x, axis_f[2 * k].y, axis_f[2 * k].z, axis_i[2 * k].x,
                                             axis_i[2 * k].y),
                              slut_axis_make(axis_f[2 * k + 1].x, axis_f[2 * k + 1].y, axis_f[2 * k + 1].z,
                                             axis_i[2 * k + 1].x, axis_i[2 * k + 1].y),
                              table_i[k].x, table_i[k].y);
}
float test_eval(int i) {
    int b = 20 * i;
    int mode = int(q[b]);
    int which = int(q[b + 1]);
    SlutSurfaceTable diffuse = test_table(0);
    SlutSurfaceTable specular = test_table(1);
    if (mode == 0)
        return slut_surface_G(SLUT_TEX_ARG(slut_test_table), which == 0 ? diffuse : specular, q[b + 2], q[b + 3]);
    SLUT_FLOAT3 n = SLUT_FLOAT3(q[b + 5], q[b + 6], q[b + 7]);
    SLUT_FLOAT3 l = SLUT_FLOAT3(q[b + 8], q[b + 9], q[b + 10]);
    SLUT_FLOAT3 v = SLUT_FLOAT3(q[b + 11], q[b + 12], q[b + 13]);
    slut_surface_terms t = slut_surface_radiance_terms(SLUT_TEX_ARG(slut_test_table), diffuse, specular, q[b + 2],
                                                       q[b + 3], q[b + 4], n, l, v, q[b + 14], q[b + 15]);
    if (which == 1) return t.diffuse_direct;
    if (which == 2) return t.diffuse_scattered;
    if (which == 3) return t.specular_direct;
    if (which == 4) return t.specular_scattered;
    return slut_surface_radiance(SLUT_TEX_ARG(slut_test_table), diffuse, specular, q[b + 2], q[b + 3], q[b + 4], n, l,
                                 v, q[b + 14], q[b + 15]);
}
)slsl";

// The compute shaders around the snippet (gpu_harness's wrappers): the uniform block holds per
// table its two axes (min, max, scale, -) and (warp, count, -, -) and (exponent, row0, -, -).
// defines: "" (no tier, as SLUT_TIER_ACCURATE) or "#define SLUT_TIER_FAST\n" (one filtered fetch).
// The uniform block's fields (GLSL; struct Params below holds them, std140).
const char *kParamsDecl = "    vec4 axis_f[4]; ivec4 axis_i[4]; ivec4 table_i[2]; int n_queries;";
std::string glsl_compute_source(const std::string &defines = "") {
    return gpu_harness::glsl_compute_source(glsl_snippet(), kParamsDecl, kTestBody, defines, false);
}

std::string hlsl_compute_source() {
    return gpu_harness::hlsl_compute_source(hlsl_snippet(),
                                            "    float4 axis_f[4]; int4 axis_i[4]; int4 table_i[2]; int n_queries;",
                                            kTestBody, "", false);
}

// A fragment / pixel shader with the airlight and the surface snippets together, as an engine
// would shade a lit wall in fog (compile checks: the shared part included once, no clashes).
std::string glsl_fragment_source(bool es) {
    const std::string version = es ? "#version 300 es\nprecision highp float;\nprecision highp sampler2D;\n"
                                   : "#version 330\n";
    const std::string ext = es ? "essl" : "glsl"; // (the .essl snippets: GLSL ES 3.00, WebGL2)
    return version + "uniform sampler2D airlight_table;\nuniform sampler2D surface_tables;\n"
           "uniform vec3 light_pos;\nuniform vec3 medium;\nin vec3 world_pos;\nin vec3 eye_pos;\n"
           "in vec3 normal;\nout vec4 colour;\n" +
           read_text(kShaderDir + "scatterlut_airlight." + ext) + read_text(kShaderDir + "scatterlut_surface." + ext) +
           R"glsl(
void main() {
    SlutSurfaceTable g0 = slut_surface_table(slut_axis_make(0.0, 8.0, 0.1, SLUT_WARP_LOG1P, 16),
                                             slut_axis_make(0.0, 3.14159265, 1.0, SLUT_WARP_LINEAR, 17), 1, 0);
    SlutSurfaceTable g20 = slut_surface_table(slut_axis_make(0.0, 8.0, 0.1, SLUT_WARP_LOG1P, 16),
                                              slut_axis_make(0.0, 3.14159265, 0.218, SLUT_WARP_LOG1P, 17), 20, 17);
    SlutAirlightTable air = slut_airlight_table(64.0, 1e-7, 512, 1e-3, 256);
    vec3 to_eye = eye_pos - world_pos;
    float L = slut_surface_radiance(surface_tables, g0, g20, medium.x, medium.y, 100.0, normal, light_pos - world_pos,
                                    to_eye, 0.5, 0.3) +
              slut_airlight_radiance_points(airlight_table, air, eye_pos, -to_eye, light_pos, length(to_eye),
                                            medium.x, medium.y, 100.0);
    colour = vec4(vec3(L), 1.0);
}
)glsl";
}

std::string hlsl_pixel_source() {
    return "Texture2D<float> surface_tables : register(t0);\nSamplerState surface_tables_sampler : register(s0);\n"
           "cbuffer Street : register(b0) { float3 light_pos; float3 medium; float3 eye_pos; };\n" +
           read_text(kShaderDir + "scatterlut_airlight.hlsl") + hlsl_snippet() + R"hlsl(
float4 main(float3 world_pos : TEXCOORD0, float3 normal : NORMAL) : SV_Target {
    SlutSurfaceTable g0 = slut_surface_table(slut_axis_make(0.0, 8.0, 0.1, SLUT_WARP_LOG1P, 16),
                                             slut_axis_make(0.0, 3.14159265, 1.0, SLUT_WARP_LINEAR, 17), 1, 0);
    SlutSurfaceTable g20 = slut_surface_table(slut_axis_make(0.0, 8.0, 0.1, SLUT_WARP_LOG1P, 16),
                                              slut_axis_make(0.0, 3.14159265, 0.218, SLUT_WARP_LOG1P, 17), 20, 17);
    float L = slut_surface_radiance(surface_tables, surface_tables_sampler, g0, g20, medium.x, medium.y, 100.0,
                                    normal, light_pos - world_pos, eye_pos - world_pos, 0.5, 0.3);
    return float4(L, L, L, 1.0);
}
)hlsl";
}

// ---------------------------------------------------------------------- comparisons

// Tolerances (relative, against the double C++ code on the same float-rounded tables and
// inputs; measured on Mesa llvmpipe, printed below):
//  - G: 2e-5. The float ln ratio interpolated at a position carrying a few float ulps of the
//    axis warp (log1p of T and, for n > 1, of θ_r), exp (3 + 2|ln| ulp), and the scale in float
//    (kernels/slut_surface_table.h: e^{−T}, E(sin θ) by the AGM, the lobe's Bessel form).
//  - radiance terms: 5e-5 plus 2e-7 per unit of conditioning: the float geometry (the cosines
//    to ~1e-7 absolute, relative 1e-7/|cos θ_s| on E_d and n·1e-7/cos on the lobe; e^{−σ_t D}
//    and e^{−σ_t D_v} to σ_t (D + D_v)·1e-7; the lobe's G_n moves by n·δθ near θ_r = 0).
constexpr double kTolG = 2e-5, kTolRadiance = 5e-5, kTolPerConditioning = 2e-7;

// extra: added to every tolerance (the fast tier's filter weights: weight error times the
// largest jump of the stored ln ratio across a cell, which moves G and every term relatively).
double tolerance_of(const Query &q, double extra) {
    if (q.label == "G" || q.label == "G_beyond") return kTolG + extra;
    return kTolRadiance + kTolPerConditioning * q.conditioning + extra;
}

// The largest jump of the stored ln ratio across a cell of either table (the fast tier's filter
// moves G by its weight error times this).
double max_cell_jump() {
    double jump = 0;
    for (const GpuTable *t : {&tables().diffuse, &tables().specular}) {
        const int nT = t->rounded.axes[0].map.count, nth = t->rounded.axes[1].map.count;
        for (int j = 0; j < nth; ++j)
            for (int i = 0; i < nT; ++i) {
                const double v = t->rounded.values[static_cast<size_t>(j) * nT + i];
                double step = 0;
                if (i + 1 < nT) step += std::fabs(t->rounded.values[static_cast<size_t>(j) * nT + i + 1] - v);
                if (j + 1 < nth) step += std::fabs(t->rounded.values[static_cast<size_t>(j + 1) * nT + i] - v);
                jump = std::max(jump, step);
            }
    }
    return jump;
}

void expect_agreement(const std::vector<float> &got, const std::string &run, ::testing::Test *test,
                      double extra = 0.0) {
    const Run &r = queries();
    ASSERT_EQ(got.size(), r.queries.size());
    for (const std::string label : {"G", "G_beyond", "total", "diff_direct", "diff_scatt", "spec_direct", "spec_scatt",
                                    "zero"}) {
        std::vector<size_t> idx;
        for (size_t i = 0; i < r.queries.size(); ++i)
            if (r.queries[i].label == label) idx.push_back(i);
        if (idx.empty()) continue;
        const auto tolerance = [&](size_t i) { return tolerance_of(r.queries[i], extra); };
        const Stats st = error_stats(got, r.reference, idx, tolerance);
        std::printf("[ %s ] %-11s n=%zu  max %.3g  p99 %.3g  median %.3g  (worst: gpu %.9g, C++ %.9g)  "
                    "max error/tolerance %.2f\n",
                    run.c_str(), label.c_str(), st.count, st.max, st.p99, st.median, static_cast<double>(got[st.worst]),
                    r.reference[st.worst], st.max_ratio);
        const Query &w = r.queries[st.worst_ratio];
        std::string inputs;
        for (int k = 0; k < 16; ++k) inputs += std::to_string(w.gpu[k]) + " ";
        EXPECT_LE(st.max_ratio, 1.0) << run << " " << label << ": query [" << inputs << "] gave " << got[st.worst_ratio]
                                     << ", the C++ code " << w.reference << ": relative error "
                                     << rel_err(got[st.worst_ratio], w.reference) << " > tolerance "
                                     << tolerance(st.worst_ratio);
        for (size_t i : idx) {
            ASSERT_FALSE(std::isnan(got[i])) << run << " " << label << ": NaN at query " << i;
            ASSERT_GE(got[i], 0.0f) << run << " " << label << ": negative at query " << i;
        }
        test->RecordProperty(run + "_" + label + "_max_rel_err", std::to_string(st.max));
    }
}

// The uniform block of the compute shaders (std140).
struct Params {
    float axis_f[4][4];
    int32_t axis_i[4][4];
    int32_t table_i[2][4];
    int32_t n_queries, pad[3];
};

Params test_params() {
    const Run &r = queries();
    Params params{};
    const GpuTable *ts[2] = {&tables().diffuse, &tables().specular};
    for (int k = 0; k < 2; ++k) {
        for (int a = 0; a < 2; ++a) {
            const slut_axis &m = ts[k]->rounded.axes[static_cast<size_t>(a)].map;
            params.axis_f[2 * k + a][0] = static_cast<float>(m.min);
            params.axis_f[2 * k + a][1] = static_cast<float>(m.max);
            params.axis_f[2 * k + a][2] = static_cast<float>(m.scale);
            params.axis_i[2 * k + a][0] = m.warp;
            params.axis_i[2 * k + a][1] = m.count;
        }
        params.table_i[k][0] = ts[k]->cpp->exponent();
        params.table_i[k][1] = ts[k]->row0;
    }
    params.n_queries = static_cast<int32_t>(r.queries.size());
    return params;
}

#if SLUT_HAVE_EGL
std::vector<float> run_on_gpu(const std::string &source, std::string *error) {
    const Run &r = queries();
    std::vector<float> packed;
    for (const Query &q : r.queries) packed.insert(packed.end(), q.gpu.begin(), q.gpu.end());
    const Params params = test_params();
    return run_compute(source, tables().texels, kTCount, 2 * kThetaCount, 0, packed, r.queries.size(), &params,
                       sizeof params, error);
}
#endif

} // namespace

// The comparison is only as good as its queries: enough of each kind, the light below the
// horizon, grazing viewers.
TEST(SurfaceShaderQueries, CoverTheDomainAndEveryPath) {
    int count[8] = {0, 0, 0, 0, 0, 0, 0, 0}, below = 0;
    const char *labels[8] = {"G", "G_beyond", "total", "diff_direct", "diff_scatt", "spec_direct", "spec_scatt", "zero"};
    for (const Query &q : queries().queries) {
        for (int k = 0; k < 8; ++k)
            if (q.label == labels[k]) ++count[k];
        if (q.label == "total") {
            const double n_dot_l = double(q.gpu[5]) * q.gpu[8] + double(q.gpu[6]) * q.gpu[9] + double(q.gpu[7]) * q.gpu[10];
            below += n_dot_l < 0.0;
        }
    }
    std::printf("G %d, G beyond T_max %d, radiance geometries %d (light below the horizon %d), zero %d\n", count[0],
                count[1], count[2], below, count[7]);
    EXPECT_GE(count[0], 1800);
    EXPECT_GE(count[1], 300);
    EXPECT_GE(count[2], 600);
    EXPECT_GE(below, 200);
    EXPECT_EQ(count[7], 3);
}

// Generated from one source: the GLSL, GLSL ES and HLSL files agree outside their preludes,
// are ASCII, and carry the kernels/ code verbatim (the scale the table decodes with, the
// front-end's geometry and assembly).
TEST(SurfaceShaderSources, OneBodyFromTheCHeaders) {
    const std::string g = shared_body(glsl_snippet()), h = shared_body(hlsl_snippet()), e = shared_body(essl_snippet());
    ASSERT_FALSE(g.empty()) << "SHARED BODY markers missing in scatterlut_surface.glsl";
    EXPECT_TRUE(g == h) << "the GLSL and HLSL surface snippets differ outside their preludes";
    EXPECT_TRUE(g == e) << "the GLSL and GLSL ES surface snippets differ outside their preludes";
    for (const std::string &text : {glsl_snippet(), hlsl_snippet(), essl_snippet()}) {
        const auto it = std::find_if(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) > 127; });
        EXPECT_EQ(it, text.end()) << "non-ASCII byte at offset " << (it - text.begin());
    }
    for (const char *function :
         {"SLUT_FN double slut_surface_G_scale(int exponent, double optical_distance, double theta)",
          "SLUT_FN slut_surface_geometry slut_surface_geometry_make(slut_vec3 normal, slut_vec3 light_rel_m,",
          "SLUT_FN slut_surface_terms slut_surface_assemble(slut_surface_geometry g, double sigma_s_per_m, double "
          "sigma_a_per_m,"}) {
        EXPECT_NE(g.find(function), std::string::npos) << function << " is not copied from kernels/";
    }
}

TEST(SurfaceShaderGlslang, GlslAndHlslCompile) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    EXPECT_EQ(glslang("surf_compute.comp", glsl_compute_source(), ""), "");
    EXPECT_EQ(glslang("surf_vk_compute.comp", glsl_compute_source(),
                      "-V -o " + gpu_harness::quoted(scratch_dir() + "/surf_vk_compute.spv")),
              "");
    EXPECT_EQ(glslang("surf_compute.hlsl", hlsl_compute_source(),
                      "-D -V -e main -S comp -o " + gpu_harness::quoted(scratch_dir() + "/surf_compute_hlsl.spv")),
              "");
    EXPECT_EQ(glslang("surf_fragment.frag", glsl_fragment_source(false), ""), "");
    EXPECT_EQ(glslang("surf_fragment_es.frag", glsl_fragment_source(true), ""), "");
    EXPECT_EQ(glslang("surf_pixel.hlsl", hlsl_pixel_source(),
                      "-D -V -e main -S frag -o " + gpu_harness::quoted(scratch_dir() + "/surf_pixel.spv")),
              "");
}

class SurfaceGpu : public gpu_harness::GpuTest {};

TEST_F(SurfaceGpu, GlslMatchesTheCppFrontEnd) {
#if SLUT_HAVE_EGL
    std::string error;
    const std::vector<float> got = run_on_gpu(glsl_compute_source(), &error);
    ASSERT_EQ(error, "");
    expect_agreement(got, "glsl", this);
#endif
}

// The fast tier (SLUT_TIER_FAST): one hardware-filtered fetch per table, so the filter's
// weights (llvmpipe: float; many GPUs: 8 bits) add their error times the largest jump of the
// stored ln ratio across a cell of the two stacked tables (rows of one table, never across
// the seam: the theta position is clamped to the table's rows).
TEST_F(SurfaceGpu, GlslFastTierAgreesToTheFilterPrecision) {
#if SLUT_HAVE_EGL
    const double weight_error = hardware_filter_weight_error();
    ASSERT_GE(weight_error, 0.0) << "the ramp shader failed";
    const double jump = max_cell_jump();
    const double extra = 2.0 * weight_error * jump;
    std::printf("[ filter ] weight error %.3g, largest cell jump %.3g: extra tolerance %.3g\n", weight_error, jump, extra);
    std::string error;
    const std::vector<float> got = run_on_gpu(glsl_compute_source("#define SLUT_TIER_FAST\n"), &error);
    ASSERT_EQ(error, "");
    expect_agreement(got, "glsl_fast", this, extra);
#endif
}

TEST_F(SurfaceGpu, HlslMatchesTheCppFrontEnd) {
#if SLUT_HAVE_EGL
    if (kGlslang.empty() || kSpirvCross.empty())
        SLUT_SKIP_OR_FAIL("running the HLSL needs glslangValidator and spirv-cross (Debian: glslang-tools, spirv-cross)");
    std::string error;
    const std::string glsl = hlsl_compute_to_glsl("surf", hlsl_compute_source(), &error);
    ASSERT_EQ(error, "");
    const std::vector<float> got = run_on_gpu(glsl, &error);
    ASSERT_EQ(error, "");
    expect_agreement(got, "hlsl", this);
#endif
}

// ------------------------------------------------------------------ the WebGPU test's cases
// (tests/shaders/wgsl_cases.hpp; ctest WebGPUSnippets runs the WGSL snippets on them): every query
// above, no tier and the accurate tier at the tolerances above, the fast tier with the filter's
// extra 2 x weight error x the largest cell jump, as GlslFastTierAgreesToTheFilterPrecision.
namespace {

std::vector<wgsl_cases::CaseSet> write_wgsl_cases() {
    const Run &r = queries();
    wgsl_cases::CaseSet c;
    c.name = "surface";
    c.snippet = "surface";
    c.width = kTCount;
    c.height = 2 * kThetaCount;
    c.texels = tables().texels;
    c.params_decl = kParamsDecl;
    c.params = wgsl_cases::bytes_of(test_params());
    c.body = kTestBody;
    c.query_floats = kQueryFloats;
    const double per_weight_error = 2.0 * max_cell_jump();
    wgsl_cases::Tier none, accurate, fast;
    accurate.name = "accurate";
    fast.name = "fast";
    for (const Query &q : r.queries) {
        c.queries.insert(c.queries.end(), q.gpu.begin(), q.gpu.end());
        c.labels.push_back(q.label);
        c.reference.push_back(q.reference);
        none.tol.push_back(tolerance_of(q, 0.0));
        accurate.tol.push_back(tolerance_of(q, 0.0));
        fast.tol.push_back(tolerance_of(q, 0.0));
        fast.tol_per_weight_error.push_back(per_weight_error);
    }
    c.tiers = {none, accurate, fast};
    return {c};
}

} // namespace

SLUT_WGSL_CASES(write_wgsl_cases);
