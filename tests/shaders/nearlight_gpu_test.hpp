// What the near-light shader tests share (test_shaders_nearlight.cpp: the isotropic snippet,
// test_shaders_nearlight_hg.cpp: the Henyey-Greenstein one): the texture packing of a table
// (E4's S layers stacked along the height), the 20-float query record and its random
// geometries, the compute-shader wrapper around a snippet and the GPU run. The EGL/GL and
// tool plumbing is gpu_harness.hpp's.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "gpu_harness.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/table.hpp"

extern "C" {
#include "slut_axes.h"
}

namespace nearlight_gpu_test {

using namespace gpu_harness;

constexpr double kInf = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------------ the tables

// A table as the GPU sees it: its values rounded to float (`rounded`, what the C++ reference
// samples) and the texture as docs/SHADERS.md packs it: E3 the payload as it stands
// (nT x ng x nr); E4 its S layers stacked along the height (nT x ng*nS x nr, texel
// (iT, ig + ng*iS, ir)), what one glTexSubImage3D per layer at y offset ng*iS uploads.
struct Texture {
    scatterlut::Table rounded;
    std::vector<float> texels;
    int layers() const { return rounded.axes.size() == 4 ? rounded.axes[3].map.count : 1; }
};

inline Texture make_texture(scatterlut::Table t) {
    Texture g;
    for (double &v : t.values) v = static_cast<float>(v);
    g.texels.assign(t.values.begin(), t.values.end());
    if (t.axes.size() == 4) {
        const size_t nT = t.axes[0].map.count, ng = t.axes[1].map.count, nr = t.axes[2].map.count,
                     nS = t.axes[3].map.count;
        for (size_t iS = 0; iS < nS; ++iS)
            for (size_t ir = 0; ir < nr; ++ir)
                for (size_t ig = 0; ig < ng; ++ig)
                    for (size_t iT = 0; iT < nT; ++iT)
                        g.texels[iT + nT * ((ig + ng * iS) + ng * nS * ir)] =
                            static_cast<float>(t.values[iT + nT * (ig + ng * (ir + nr * iS))]);
    }
    g.rounded = std::move(t);
    return g;
}

// ---------------------------------------------------------------------- the queries

// One GPU query: 20 floats. gpu[0] the mode (the test's own); a geometry query carries
// (sigma_s, sigma_a, I0 [2..4], normal [5..7], eye_dir [8..10], light_rel [11..13], length [14],
// eta [15], fresnel [16]); the rest is the test's.
constexpr int kQueryFloats = 20;

struct Query {
    std::array<float, kQueryFloats> gpu{};
    double reference = 0;
    double ln_E = 0;         // ln of the table's E at the query (scales the tolerance)
    double conditioning = 0; // 1/mu_l + 1/mu_e of a geometry query (scales the tolerance)
    std::string label;       // category for the statistics
};

inline double log_uniform(std::mt19937_64 &rng, double lo, double hi) {
    return lo * std::pow(hi / lo, std::uniform_real_distribution<double>(0.0, 1.0)(rng));
}

inline std::array<double, 3> random_unit(std::mt19937_64 &rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    for (;;) {
        const std::array<double, 3> v = {n(rng), n(rng), n(rng)};
        const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (len > 1e-3) return {v[0] / len, v[1] / len, v[2] / len};
    }
}

// A unit vector at cosine mu to n (random azimuth).
inline std::array<double, 3> at_cosine(std::mt19937_64 &rng, const std::array<double, 3> &n, double mu) {
    std::array<double, 3> t;
    do {
        const std::array<double, 3> v = random_unit(rng);
        const double d = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
        t = {v[0] - d * n[0], v[1] - d * n[1], v[2] - d * n[2]};
    } while (t[0] * t[0] + t[1] * t[1] + t[2] * t[2] < 1e-6);
    const double tl = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    return {mu * n[0] + s * t[0] / tl, mu * n[1] + s * t[1] / tl, mu * n[2] + s * t[2] / tl};
}

// The float the GPU gets, and the double unit vector the C++ checks demand (|v| = 1 to
// 1e-9): the float vector renormalised in double (a change of ~6e-8, inside the noise).
inline std::array<double, 3> unit_of_floats(const float *f) {
    const double len = std::sqrt(double(f[0]) * f[0] + double(f[1]) * f[1] + double(f[2]) * f[2]);
    return {f[0] / len, f[1] / len, f[2] / len};
}

// The C++ query of a geometry query's gpu[2..16].
inline scatterlut::NearLightQuery cpp_query(const Query &q) {
    scatterlut::NearLightQuery c;
    c.sigma_s_per_m = q.gpu[2];
    c.sigma_a_per_m = q.gpu[3];
    c.intensity_W_per_sr = q.gpu[4];
    const auto n = unit_of_floats(&q.gpu[5]), e = unit_of_floats(&q.gpu[8]);
    for (int k = 0; k < 3; ++k) {
        c.normal[k] = n[k];
        c.eye_dir[k] = e[k];
        c.light_rel_m[k] = q.gpu[11 + k];
    }
    c.length_m = std::isinf(q.gpu[14]) ? kInf : q.gpu[14];
    c.eta = q.gpu[15];
    c.fresnel = q.gpu[16] != 0.0f;
    return c;
}

// A random geometry (gpu[2..16] and conditioning; gpu[0] left to the caller): random normal,
// eye at mu_e in [0.05, 1], light at mu_l in [1e-4, 1] (r from 1e-4 to 20) with T log-uniform
// over [max(T_min, 1e-3), T_max], sigma_t in [0.05, 50]/m, albedo in [0.05, 1], eta = 1 or in
// [0.75, 1.6], Fresnel on half of the refracted ones; S log-uniform over [S_min, S_max] (a slab)
// or infinite (S_max = 0: thick).
inline Query random_geometry(std::mt19937_64 &rng, double T_min, double T_max, double S_min, double S_max) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto n = random_unit(rng);
    const auto eye = at_cosine(rng, n, 0.05 + 0.95 * unit(rng));
    const auto ldir = at_cosine(rng, n, log_uniform(rng, 1e-4, 1.0));
    const double mu_e = eye[0] * n[0] + eye[1] * n[1] + eye[2] * n[2];
    const double mu_l = ldir[0] * n[0] + ldir[1] * n[1] + ldir[2] * n[2];
    const double sigma_t = log_uniform(rng, 0.05, 50.0), albedo = 0.05 + 0.95 * unit(rng);
    const double T = log_uniform(rng, std::max(T_min, 1e-3), T_max), l = T / sigma_t;
    double length = kInf;
    if (S_max > 0.0) length = log_uniform(rng, S_min, S_max) / sigma_t;
    const double r_eta = unit(rng);
    const double eta = r_eta < 0.5 ? 1.0 : r_eta < 0.6 ? 0.75 + 0.25 * unit(rng) : 1.0 + 0.6 * unit(rng);
    Query q;
    q.gpu[2] = static_cast<float>(albedo * sigma_t);
    q.gpu[3] = static_cast<float>((1.0 - albedo) * sigma_t);
    q.gpu[4] = static_cast<float>(log_uniform(rng, 0.1, 1e3));
    for (int k = 0; k < 3; ++k) {
        q.gpu[5 + k] = static_cast<float>(n[k]);
        q.gpu[8 + k] = static_cast<float>(eye[k]);
        q.gpu[11 + k] = static_cast<float>(l * ldir[k]);
    }
    q.gpu[14] = static_cast<float>(length);
    q.gpu[15] = static_cast<float>(eta);
    q.gpu[16] = (eta != 1.0 && unit(rng) < 0.5) ? 1.0f : 0.0f;
    q.conditioning = 1.0 / mu_l + 1.0 / mu_e;
    return q;
}

// The zero limits of a geometry query: the light strictly below the plane (light_rel =
// -l n), sigma_s = 0, I0 = 0, length 0 (k = 0 ... 3).
inline Query zero_limit(Query z, int k) {
    if (k == 0) {
        const float *v = &z.gpu[11];
        const double l = std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
        for (int c = 0; c < 3; ++c) z.gpu[11 + c] = static_cast<float>(-l * z.gpu[5 + c]);
    }
    if (k == 1) z.gpu[2] = 0.0f;
    if (k == 2) z.gpu[4] = 0.0f;
    if (k == 3) z.gpu[14] = 0.0f;
    z.label = "zero";
    return z;
}

// ------------------------------------------------------------------------- shaders

// The compute shader around a near-light snippet (gpu_harness::glsl_compute_source with a 3-D
// table): `body` may call test_axis(k) (axis k of the parameters), test_table() (the table of
// those axes) and test_vec(b) (three floats of the queries), declare a query's geometry with
// TEST_GEOMETRY(b), and read `layers` and `phase_g`;
// the parameters (std140) are Params of run_queries below.
inline const char *kTestAxis = R"slsl(
SlutAxis test_axis(int k) {
    return slut_axis_make(axis_f[k].x, axis_f[k].y, axis_f[k].z, axis_i[k].x, axis_i[k].y);
}
// The table of the parameters: E3 (one layer) or E4.
SlutNearLightTable test_table() {
    if (layers == 1) return slut_near_light_table_e3(test_axis(0), test_axis(1), test_axis(2));
    return slut_near_light_table_e4(test_axis(0), test_axis(1), test_axis(2), test_axis(3));
}
// The vector q[b], q[b + 1], q[b + 2].
SLUT_FLOAT3 test_vec(int b) { return SLUT_FLOAT3(q[b], q[b + 1], q[b + 2]); }
// The geometry of the query at q[b]: normal n, eye direction e, light l, fresnel.
#define TEST_GEOMETRY(b) \
    SLUT_FLOAT3 n = test_vec(b + 5); SLUT_FLOAT3 e = test_vec(b + 8); SLUT_FLOAT3 l = test_vec(b + 11); \
    bool fresnel = q[b + 16] != 0.0
)slsl";
// The fields of the parameters (GLSL; struct Params below holds them, std140).
inline const char *kParamsDecl = "    vec4 axis_f[4]; ivec4 axis_i[4]; int layers; int n_queries; float phase_g;";
inline std::string glsl_compute_source(const std::string &snippet, const std::string &body, const std::string &defines) {
    return gpu_harness::glsl_compute_source(snippet, kParamsDecl, kTestAxis + body, defines, true);
}
inline std::string hlsl_compute_source(const std::string &snippet, const std::string &body, const std::string &defines) {
    return gpu_harness::hlsl_compute_source(
        snippet, "    float4 axis_f[4]; int4 axis_i[4]; int layers; int n_queries; float phase_g;", kTestAxis + body,
        defines, true);
}

// The uniform block of the wrappers above (std140): per axis (min, max, scale, -) and (warp,
// count, -, -), the number of layers, the query count, phase_g.
struct Params {
    float axis_f[4][4];
    int32_t axis_i[4][4];
    int32_t layers, n_queries;
    float phase_g;
    int32_t pad;
};

inline Params make_params(const Texture &t, size_t n_queries, double phase_g) {
    Params params{};
    for (size_t a = 0; a < t.rounded.axes.size(); ++a) {
        const slut_axis &m = t.rounded.axes[a].map;
        params.axis_f[a][0] = static_cast<float>(m.min);
        params.axis_f[a][1] = static_cast<float>(m.max);
        params.axis_f[a][2] = static_cast<float>(m.scale);
        params.axis_i[a][0] = m.warp;
        params.axis_i[a][1] = m.count;
    }
    params.layers = t.layers();
    params.n_queries = static_cast<int32_t>(n_queries);
    params.phase_g = static_cast<float>(phase_g);
    return params;
}

#if SLUT_HAVE_EGL
// Every query through a compute shader built by the functions above (or its spirv-cross
// translation) on texture t, with the table's axes and layers, and phase_g, as parameters.
inline std::vector<float> run_queries(const std::string &source, const Texture &t, const std::vector<Query> &qs,
                                      double phase_g, std::string *error) {
    std::vector<float> packed;
    for (const Query &q : qs) packed.insert(packed.end(), q.gpu.begin(), q.gpu.end());
    const Params params = make_params(t, qs.size(), phase_g);
    const auto &ax = t.rounded.axes;
    return run_compute(source, t.texels, ax[0].map.count, ax[1].map.count * t.layers(), ax[2].map.count, packed,
                       qs.size(), &params, sizeof params, error);
}
#endif

// The hardware filter's extra error on one table (the fast tier; test_shaders_nearlight.cpp
// derives it): per filtered axis the largest |d ln E| between neighbouring texels (layer seams
// included) times (weight error + 2^-24 texels), times 1.5.
inline double hardware_filter_extra(const Texture &t, double weight_error) {
    const auto &ax = t.rounded.axes;
    const size_t n[3] = {static_cast<size_t>(ax[0].map.count), static_cast<size_t>(ax[1].map.count) * t.layers(),
                         static_cast<size_t>(ax[2].map.count)};
    const size_t stride[3] = {1, n[0], n[0] * n[1]};
    double jump[3] = {0, 0, 0};
    for (size_t k = 0; k < n[2]; ++k)
        for (size_t j = 0; j < n[1]; ++j)
            for (size_t i = 0; i < n[0]; ++i) {
                const size_t at = (k * n[1] + j) * n[0] + i, idx[3] = {i, j, k};
                for (int a = 0; a < 3; ++a)
                    if (idx[a] + 1 < n[a])
                        jump[a] = std::max(jump[a], double{std::fabs(t.texels[at + stride[a]] - t.texels[at])});
            }
    double extra = 0;
    for (int a = 0; a < 3; ++a) extra += jump[a] * (weight_error + std::ldexp(static_cast<double>(n[a]), -24));
    return 1.5 * extra;
}

} // namespace nearlight_gpu_test
